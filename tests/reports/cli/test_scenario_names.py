"""Two mechanisms never share a scenario name in one store: a file whose `name` is taken in the
store by a different mechanism (another file, or this file before an edit), or by another file of
the same run, is refused in one line before anything runs; the same mechanism (a file identical to
a family) shares its name's rows."""

from __future__ import annotations

import shutil
from pathlib import Path

import pandas as pd
import pytest

import scenarios
from reports.cli.main import main
from reports.store.results_store import read_results
from reports.store.scenario_identity import digest
from scenarios.files import read_scenario, scenario_toml

EXAMPLES = Path(__file__).resolve().parents[3] / "examples"


def _file(path: Path, mass: float = 0.01) -> Path:
    """A small spur-gear file named `gears` with the given gear mass."""
    scenario = scenarios.build("spur_gears", overrides={"steps": 10})
    text = scenario_toml(scenario).replace('name = "spur_gears"', 'name = "gears"', 1)
    path.write_text(_with_mass(text, mass))
    return path


def _with_mass(text: str, mass: float) -> str:
    old = f"mass = {scenarios.build('spur_gears').bodies[0].mass!r}\n"
    assert old in text
    return text.replace(old, f"mass = {mass!r}\n", 1)


def _run(
    capsys: pytest.CaptureFixture[str], out: Path, *scenarios_: str, rerun: bool = False
) -> tuple[int, str]:
    argv = ["run", "--out", str(out), "--quiet", "--engine", "reference", "--repeats", "1"]
    for name in scenarios_:
        argv += ["--scenario", name]
    code = main(argv + (["--rerun"] if rerun else []))
    return code, capsys.readouterr().err


def test_digest_is_the_mechanism_not_the_path(tmp_path: Path) -> None:
    a, b, c = _file(tmp_path / "a.toml"), _file(tmp_path / "b.toml"), _file(tmp_path / "c.toml", 0.3)
    assert digest(read_scenario(a)) == digest(read_scenario(b)) != digest(read_scenario(c))
    assert digest(read_scenario(EXAMPLES / "slider_crank.toml")) == digest(scenarios.build("slider_crank"))


def test_two_files_of_one_name_in_one_run_are_refused(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    a, c = _file(tmp_path / "a.toml"), _file(tmp_path / "c.toml", 0.3)
    code, err = _run(capsys, tmp_path / "out", str(a), str(c))
    assert code == 2 and err.count("\n") == 1
    assert f"{a} and {c} both name their scenario 'gears' but describe different mechanisms" in err
    assert not (tmp_path / "out").exists()


def test_an_edited_file_is_refused_by_the_store_until_rerun(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    out, file = tmp_path / "out", _file(tmp_path / "gears.toml")
    assert _run(capsys, out, str(file))[0] == 0
    before = read_results(out)[0]
    _file(file, 0.3)  # the user edits the file
    code, err = _run(capsys, out, str(file))
    assert code == 2 and f"{out} holds results of another mechanism named 'gears'" in err
    assert "or add --rerun to replace those results" in err
    assert read_results(out)[0].equals(before)  # nothing changed
    other = _file(tmp_path / "other.toml", 0.3)  # another file of the same name: the same refusal
    assert _run(capsys, out, str(other))[0] == 2
    code, err = _run(capsys, out, str(file), rerun=True)
    assert code == 0, err
    assert set(read_results(out)[0]["scenario_digest"]) == {digest(read_scenario(file))}


def test_the_same_mechanism_shares_its_rows(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out, file = tmp_path / "out", _file(tmp_path / "gears.toml")
    assert _run(capsys, out, str(file))[0] == 0
    copy = shutil.copy(file, tmp_path / "copy.toml")
    assert _run(capsys, out, str(copy))[0] == 0  # identical content: resumed, not refused


def test_compare_refuses_a_store_holding_another_mechanism(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    out, file = tmp_path / "out", _file(tmp_path / "gears.toml")
    assert _run(capsys, out, str(file))[0] == 0
    csv = tmp_path / "t.csv"
    assert main(["solve", str(file), "--out", str(csv)]) == 0
    edited = _file(tmp_path / "edited.toml", 0.3)
    capsys.readouterr()
    assert main(["compare", str(edited), str(csv), "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert f"{out} holds results of another mechanism named 'gears'" in err and "--rerun" not in err
    assert main(["compare", str(file), str(csv), "--out", str(out)]) == 0


# --- a family and a file of its name are two mechanisms, in either order -------------------------
def _lengthened(path: Path) -> Path:
    """The shipped slider-crank file with its rod lengthened and its name kept: another mechanism."""
    text = (EXAMPLES / "slider_crank.toml").read_text()
    old = 'name = "rod"\nguess = [0.3888719440661749, 0.029552020666133955, -0.14830313118757033]\n'
    assert old in text and "length = 0.4\n" in text
    path.write_text(text.replace("length = 0.4\n", "length = 0.45\n", 1))
    return path


def _digests(file: Path) -> tuple[str, str]:
    mine, family = digest(read_scenario(file)), digest(scenarios.build("slider_crank"))
    assert mine != family
    return mine, family


def _in_order(order: str, tmp_path: Path) -> tuple[Path, Path, str, str]:
    """The results folder, a slider-crank file of other lengths, and the two names (the file's and
    the family's) in `order`."""
    out, file = tmp_path / "out", _lengthened(tmp_path / "longer.toml")
    first, second = (str(file), "slider_crank") if order == "file first" else ("slider_crank", str(file))
    return out, file, first, second


def _refused_as_another_mechanism(err: str, out: Path, file: Path, before: pd.DataFrame) -> None:
    """One error line naming the stored mechanism and both digests; the stored results unchanged."""
    assert err.count("\n") == 1, err
    assert f"{out} holds results of another mechanism named 'slider_crank'" in err
    assert all(d in err for d in _digests(file)), err
    assert read_results(out)[0].equals(before)


@pytest.mark.parametrize("order", ["file first", "family first"])
def test_run_refuses_a_family_and_a_file_of_its_name_in_either_order(
    order: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    out, file, first, second = _in_order(order, tmp_path)
    code, err = _run(capsys, out, first)
    assert code == 0, err
    before = read_results(out)[0]
    code, err = _run(capsys, out, second)
    assert code == 2, err
    _refused_as_another_mechanism(err, out, file, before)


@pytest.mark.parametrize("order", ["file first", "family first"])
def test_compare_out_refuses_a_family_and_a_file_of_its_name_in_either_order(
    order: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    out, file, stored, compared = _in_order(order, tmp_path)
    assert _run(capsys, out, stored)[0] == 0
    before = read_results(out)[0]
    csv = tmp_path / "t.csv"
    assert main(["solve", compared, "--out", str(csv)]) == 0
    capsys.readouterr()
    assert main(["compare", compared, str(csv), "--out", str(out), "--label", "mine"]) == 2
    _refused_as_another_mechanism(capsys.readouterr().err, out, file, before)


def test_report_refuses_a_store_holding_two_mechanisms_under_one_name(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    from tests.support.stores import doctor

    out, file = tmp_path / "out", _lengthened(tmp_path / "longer.toml")
    assert _run(capsys, out, "slider_crank")[0] == 0
    mine, family = _digests(file)

    def borrow(frame) -> None:  # type: ignore[no-untyped-def]
        frame.loc[frame.index[0], "scenario_digest"] = mine  # as a store written before the rule holds

    mixed = doctor(out, tmp_path / "mixed", borrow)
    assert main(["report", str(mixed), "--out", str(tmp_path / "page")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "more than one mechanism named 'slider_crank'" in err
    assert mine in err and family in err
    assert not (tmp_path / "page").exists()
