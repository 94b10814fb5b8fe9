"""`mbxval draw`: a scenario or file drawn to an SVG file, a still or an animation; bad input is one
line, exit status 2 and no file (an existing one left as it was)."""

from __future__ import annotations

import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from reports.cli.main import main

ROOT = Path(__file__).resolve().parents[3]
SVG = "{http://www.w3.org/2000/svg}"


def status(argv: list[str]) -> int:
    """main's exit status, whether it returns it or argparse exits with it."""
    try:
        return main(argv)
    except SystemExit as stop:
        return int(stop.code or 0)


def frames_of(path: Path) -> list[ET.Element]:
    root = ET.parse(path).getroot()
    return [g for g in root.iter(f"{SVG}g") if g.get("class") == "frame"]


def test_a_family_with_a_parameter_set_drawn_at_a_time(tmp_path: Path, capsys) -> None:
    out = tmp_path / "sc.svg"
    assert status(["draw", "slider_crank", "--set", "offset=0.05", "--t", "0.05", "--out", str(out)]) == 0
    assert capsys.readouterr().out.strip() == f"wrote {out}"
    (frame,) = frames_of(out)
    assert float(frame.get("data-t", "nan")) == 0.05
    assert ET.parse(out).getroot().findtext(f"{SVG}title") == "slider_crank at t = 0.05 s"


def test_a_scenario_file_animated_over_one_cycle(tmp_path: Path) -> None:
    out = tmp_path / "w.svg"
    example = str(ROOT / "examples" / "whitworth_quick_return.toml")
    assert status(["draw", example, "--frames", "12", "--out", str(out)]) == 0
    assert len(frames_of(out)) == 12


@pytest.mark.parametrize(
    ("argv", "words"),
    [
        (["draw", "fourbar"], "unknown scenario 'fourbar'"),
        (["draw", "four_bar", "--t", "1.0"], "t must be in [0, 0.125664] s"),
        (["draw", "four_bar", "--t", "-0.01"], "t must be in [0, 0.125664] s"),
        (["draw", "four_bar", "--frames", "241"], "--frames: must be in [1, 240]"),
        (["draw", "four_bar", "--frames", "0"], "--frames: must be in [1, 240]"),
        (["draw", "four_bar", "--frames", "two"], "--frames: must be a whole number"),
        (["draw", "four_bar", "--t", "0.01", "--frames", "4"], "--t draws one instant"),
        (["draw", "four_bar", "--set", "crank_length=-1"], "crank_length"),
    ],
)
def test_bad_input_is_one_line_exit_2_and_no_file(
    tmp_path: Path, capsys, argv: list[str], words: str
) -> None:
    out = tmp_path / "fig.svg"
    assert status([*argv, "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.startswith("mbxval: error: ") and err.count("\n") == 1, err
    assert words in err, err
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("target", ["missing/fig.svg", "fig.png", "a_directory.svg"])
def test_a_bad_out_path_is_refused_before_solving(tmp_path: Path, capsys, target: str) -> None:
    (tmp_path / "a_directory.svg").mkdir()
    before = sorted(p.name for p in tmp_path.iterdir())
    assert status(["draw", "four_bar", "--out", str(tmp_path / target)]) == 2
    err = capsys.readouterr().err
    assert err.startswith("mbxval: error: ") and err.count("\n") == 1, err
    assert sorted(p.name for p in tmp_path.iterdir()) == before


def test_an_existing_file_is_left_as_it_was_on_bad_input(tmp_path: Path) -> None:
    out = tmp_path / "fig.svg"
    out.write_text("before")
    assert status(["draw", "four_bar", "--t", "9", "--out", str(out)]) == 2
    assert out.read_text() == "before"
