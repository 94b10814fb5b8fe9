"""The command line with scenario files: export --format toml, solve a file, --set by key path,
bad files as one error line with exit status 2 and no output."""

from __future__ import annotations

import io
from pathlib import Path

import pandas as pd
import pytest

import scenarios
from reports.cli.main import main
from scenarios.files import read_scenario
from scenarios.files.writer import read_back
from tests.support.engines import ENGINES

EXAMPLES = Path(__file__).resolve().parents[3] / "examples"


def run(capsys, *argv: str) -> tuple[int, str, str]:  # type: ignore[no-untyped-def]
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def test_export_toml_then_solve_is_the_family(tmp_path: Path, capsys) -> None:  # type: ignore[no-untyped-def]
    target = tmp_path / "offset.toml"
    code, out, err = run(
        capsys, "export", "slider_crank", "--set", "offset=0.05", "--format", "toml", "--out", str(target)
    )
    assert (code, err) == (0, "") and "wrote" in out
    assert read_scenario(target) == read_back(scenarios.build("slider_crank", overrides={"offset": 0.05}))
    code, from_file, _ = run(capsys, "solve", str(target), "--steps", "20")
    assert code == 0
    code, from_family, _ = run(capsys, "solve", "slider_crank", "--set", "offset=0.05", "--steps", "20")
    assert code == 0 and from_file == from_family


def test_export_toml_of_a_file_round_trips(tmp_path: Path, capsys) -> None:  # type: ignore[no-untyped-def]
    target = tmp_path / "copy.toml"
    source = EXAMPLES / "peaucellier_lipkin.toml"
    code, _, _ = run(
        capsys, "export", str(source), "--set", "steps=10", "--format", "toml", "--out", str(target)
    )
    assert code == 0
    assert read_scenario(target) == read_back(read_scenario(source, {"steps": "10"}))


def test_set_overrides_a_file_value(capsys) -> None:  # type: ignore[no-untyped-def]
    example = str(EXAMPLES / "whitworth_quick_return.toml")
    code, out, _ = run(
        capsys, "solve", example, "--set", "drivers.crank_drive.motion.rate=20", "--set", "steps=4"
    )
    assert code == 0
    frame = pd.read_csv(io.StringIO(out))
    assert len(frame) == 5
    assert frame["crank.omega"].tolist() == [20.0] * 5


@pytest.mark.parametrize(
    ("edit", "expected"),
    [
        (("mass = 0.1", "mas = 0.1"), "bodies[0].mas: unknown key (did you mean 'mass'?)"),
        (
            ('body = "crank", local = [0.1', 'body = "crnk", local = [0.1'),
            "joints[1].p_i.body: unknown body (did you mean 'crank'?)",
        ),
        (("steps = 200", "steps = -3"), "steps: must be positive, got -3"),
    ],
)
def test_bad_file_one_line_exit_2_no_output(tmp_path: Path, capsys, edit, expected) -> None:  # type: ignore[no-untyped-def]
    text = (EXAMPLES / "whitworth_quick_return.toml").read_text()
    assert edit[0] in text
    bad = tmp_path / "bad.toml"
    bad.write_text(text.replace(edit[0], edit[1], 1))
    target = tmp_path / "out.csv"
    code, out, err = run(capsys, "solve", str(bad), "--out", str(target))
    assert code == 2 and out == ""
    assert err.startswith(f"mbxval: error: {bad}: {expected}") and err.count("\n") == 1
    assert not target.exists()


def test_mobility_errors_name_the_files_constraints(tmp_path: Path, capsys) -> None:  # type: ignore[no-untyped-def]
    """A second driver on the crank over-drives the mechanism: the message names both drivers."""
    text = (EXAMPLES / "whitworth_quick_return.toml").read_text()
    extra = '\n[[drivers]]\nkind = "absolute"\nname = "slot_drive"\nbody = "slotted_link"\n'
    extra += 'coordinate = "theta"\nmotion = { kind = "constant", value = 0.46 }\n'
    bad = tmp_path / "overdriven.toml"
    bad.write_text(text + extra)
    code, out, err = run(capsys, "solve", str(bad))
    assert code == 2 and out == ""
    assert err.count("\n") == 1
    assert "whitworth_quick_return: over-driven" in err and "crank_drive, slot_drive" in err


def test_missing_file(capsys) -> None:  # type: ignore[no-untyped-def]
    code, out, err = run(capsys, "solve", "no/such/file.toml")
    assert code == 2 and out == "" and err.startswith("mbxval: error: no/such/file.toml: cannot read")


def test_list_takes_files_and_names(capsys) -> None:  # type: ignore[no-untyped-def]
    example = str(EXAMPLES / "watt_six_bar.toml")
    code, out, _ = run(capsys, "list", example, "four_bar")
    assert code == 0
    rows = [line.split()[0] for line in out.splitlines() if line.startswith((example, "four_bar"))]
    assert rows == [example, "four_bar"]
    assert "parameters (defaults)" not in out


def test_list_survives_an_adapter_whose_supports_raises(capsys, monkeypatch) -> None:  # type: ignore[no-untyped-def]
    """A broken adapter costs its own cell: the table says why it cannot tell, the others stand."""
    from adapters.pinocchio import PinocchioAdapter

    def broken(self, scenario):  # type: ignore[no-untyped-def]
        raise ValueError("need at least one array to concatenate")

    monkeypatch.setattr(PinocchioAdapter, "supports", broken)
    example = str(EXAMPLES / "damped_oscillators.toml")
    code, out, _ = run(capsys, "list", example)
    assert code == 0
    assert f"pinocchio on {example}: cannot tell: its supports() failed: ValueError: need at" in out
    cells: list[str] = []
    for word in next(line.split()[1:] for line in out.splitlines() if line.startswith(example)):
        cells += [f"{cells.pop()} {word}"] if word.startswith("[") else [word]  # a cell's note number
    assert dict(zip(ENGINES, cells, strict=True)) == {
        e: "no [1]" if e == "pinocchio" else "yes" for e in ENGINES
    }
