"""Names with control characters, empty or blank are refused where they enter (a scenario file's
`name`, `variant` and its parts' names, `export --name`, `compare --label`, a swept point's keys
and values), each in one line and exit 2: a newline never makes a line of the name's making, an
escape sequence never reaches the terminal raw, and what is drawn stays well-formed XML."""

from __future__ import annotations

import xml.etree.ElementTree as ElementTree
from pathlib import Path

import pytest

from reports.cli.main import main
from scenarios.names import MAX_NAME_LENGTH

EXAMPLE = Path(__file__).resolve().parents[3] / "examples" / "slider_crank.toml"
HOSTILE = {
    "newline": "crank\nmbxval: error: a line of the name's making",
    "window title": "crank\x1b]0;owned\x07",
    "clear screen": "crank\x1b[2J",
    "bidi override": "crank\u202eknarc",
    "nul": "crank\x00",
    "empty": "",
    "blank": "   ",
    "over-long": "c" * (MAX_NAME_LENGTH + 1),
}


def _toml_string(text: str) -> str:
    """`text` as a TOML basic string (control characters as \\u escapes, as TOML requires)."""
    return '"' + "".join(c if c.isprintable() else f"\\u{ord(c):04x}" for c in text) + '"'


def _refused(capsys: pytest.CaptureFixture[str], argv: list[str], *words: str) -> str:
    code = main(argv)
    captured = capsys.readouterr()
    err = captured.err
    assert code == 2 and err.startswith("mbxval: error: ") and err.count("\n") == 1, err
    assert captured.out == "" and "\x1b" not in err and "\x00" not in err and "\u202e" not in err
    for word in words:
        assert word in err, err
    return err


@pytest.mark.parametrize("case", HOSTILE)
@pytest.mark.parametrize("where", ['name = "slider_crank"', 'name = "crank"', 'name = "O"'])
def test_a_scenario_file_with_such_a_name_is_refused(
    case: str, where: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    text = EXAMPLE.read_text()
    assert where in text
    key = where.split(" = ")[0]
    path = tmp_path / "hostile.toml"
    path.write_text(text.replace(where, f"{key} = {_toml_string(HOSTILE[case])}", 1))
    out = tmp_path / "out"
    argv = ["run", "--scenario", str(path), "--engine", "reference", "--out", str(out), "--quiet"]
    err = _refused(capsys, argv, f"{path}: ")
    assert "a line of the name's making" not in err and not out.exists()


@pytest.mark.parametrize("name", ["slider_crank[offset=0.05]", "a/b", "x.toml", "a=b"])
def test_a_file_name_that_reads_as_another_scenario_is_refused_as_export_refuses_it(
    name: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    path = tmp_path / "point.toml"
    path.write_text(EXAMPLE.read_text().replace('name = "slider_crank"', f'name = "{name}"', 1))
    file_err = _refused(capsys, ["solve", str(path)], "must be a plain name, without '/', '.toml' or any of")
    export_err = _refused(
        capsys,
        ["export", "slider_crank", "--format", "toml", "--name", name, "--out", str(tmp_path / "e.toml")],
    )
    assert file_err.split("must be a plain name")[1] == export_err.split("must be a plain name")[1]


@pytest.mark.parametrize("case", HOSTILE)
def test_export_name_and_compare_label_refuse_it(case: str, tmp_path: Path, capsys) -> None:
    name = HOSTILE[case]
    _refused(
        capsys,
        ["export", "slider_crank", "--format", "toml", "--name", name, "--out", str(tmp_path / "e.toml")],
    )
    assert not (tmp_path / "e.toml").exists()
    csv = tmp_path / "t.csv"
    assert main(["solve", "slider_crank", "--set", "steps=10", "--out", str(csv)]) == 0
    _refused(capsys, ["compare", "slider_crank", str(csv), "--set", "steps=10", "--label", name], "--label")


@pytest.mark.parametrize(
    "point", ["slider_crank[offset=0.05\x1b[2J]", "slider_crank[offset\n=0.05]", "slider_crank[ =0.05]"]
)
def test_a_swept_point_with_such_a_key_or_value_is_refused(point: str, capsys) -> None:
    _refused(capsys, ["solve", point])


def test_an_error_quoting_an_argument_escapes_its_control_characters(capsys) -> None:
    err = _refused(capsys, ["solve", "no_such\x1b]0;owned\x07"], "\\x1b]0;owned\\x07")
    assert "\x07" not in err


def test_a_drawing_stays_well_formed_xml_for_any_name_it_takes(tmp_path: Path, capsys) -> None:
    text = EXAMPLE.read_text().replace('name = "crank"', 'name = "<cr&nk \\"\'>"', 1)
    text = text.replace('body = "crank"', 'body = "<cr&nk \\"\'>"')
    text = text.replace('name = "slider_crank"', 'name = "<slider & crank>"', 1)
    path, svg = tmp_path / "marked.toml", tmp_path / "d.svg"
    path.write_text(text)
    assert main(["draw", str(path), "--out", str(svg)]) == 0, capsys.readouterr().err
    root = ElementTree.parse(svg).getroot()
    assert "<cr&nk \"'>" in "".join(root.itertext())


def test_a_trajectory_file_whose_stem_is_no_name_needs_a_label(tmp_path: Path, capsys) -> None:
    csv = tmp_path / "mine\x1b[2J.csv"
    assert main(["solve", "slider_crank", "--set", "steps=10", "--out", str(csv)]) == 0
    _refused(
        capsys, ["compare", "slider_crank", str(csv), "--set", "steps=10"], "the file's stem unless --label"
    )
    assert main(["compare", "slider_crank", str(csv), "--set", "steps=10", "--label", "mine"]) == 0
