"""`mbxval list --engine NAME`: the engine's modes, options and accuracy knobs, one line each, from
its declarations; an unknown engine is one error line and exit 2; docs/engine-knobs.md is what the
generator writes from the same declarations (reports.cli.knobs_page)."""

from __future__ import annotations

from pathlib import Path

import pytest

import adapters
from reports.cli.knobs_page import knobs_document
from reports.cli.main import main

PAGE = Path(__file__).resolve().parents[3] / "docs" / "engine-knobs.md"


def run(capsys, *argv: str) -> tuple[int, str, str]:  # type: ignore[no-untyped-def]
    try:
        code = main(list(argv))
    except SystemExit as stop:
        code = int(stop.code or 0)
    out, err = capsys.readouterr()
    return code, out, err


def test_an_engine_lists_every_mode_option_and_knob(capsys) -> None:  # type: ignore[no-untyped-def]
    code, out, err = run(capsys, "list", "--engine", "exudyn")
    assert code == 0 and err == ""
    lines = out.splitlines()
    kind = adapters.adapter_class("exudyn")
    for mode in kind.measured:
        assert f"  {mode.name}: {mode.measures}" in lines
    assert "  rho: a float in [0, 1]: spectral radius of generalized-alpha" in lines
    for knob in kind.knobs:
        assert f"  {knob.name}: {knob.treatment}: {knob.why}" in lines
    assert lines.index("options:") < lines.index("knobs:")


def test_a_markdown_listing_has_one_row_per_knob(capsys) -> None:  # type: ignore[no-untyped-def]
    code, out, _ = run(capsys, "list", "--engine", "pinocchio", "--format", "markdown")
    assert code == 0
    rows = [line for line in out.splitlines() if line.startswith("| ") and " swept " in f"{line} "]
    swept = [knob for knob in adapters.adapter_class("pinocchio").knobs if knob.treatment == "swept"]
    assert len(rows) >= len(swept) > 0
    assert "| `kp` | a float in [0, 1e+12] | Baumgarte position gain |" in out


@pytest.mark.parametrize(
    ("argv", "says"),
    [
        (("list", "--engine", "nosuch"), "unknown engine 'nosuch'"),
        (("list", "--format", "markdown"), "--format applies to --engine NAME only"),
        (("list", "four_bar", "--engine", "mujoco"), "give it without scenarios"),
    ],
)
def test_bad_input_is_one_line_and_exit_2(capsys, argv: tuple[str, ...], says: str) -> None:  # type: ignore[no-untyped-def]
    code, out, err = run(capsys, *argv)
    assert code == 2 and out == ""
    assert err.count("\n") == 1 and err.startswith("mbxval: error: ") and says in err


def test_list_without_engine_still_lists_the_scenarios(capsys) -> None:  # type: ignore[no-untyped-def]
    code, out, _ = run(capsys, "list", "four_bar")
    listed = [line for line in out.splitlines() if not line.startswith("engine ")]  # one not installed
    assert code == 0 and listed[0].startswith("engines: ") and "\nfour_bar " in out and "knobs:" not in out


def test_the_knobs_page_is_what_the_generator_writes() -> None:
    try:
        expected = knobs_document()
    except adapters.EngineUnavailable as error:
        pytest.skip(f"every engine is needed to write the page: {error}")
    assert PAGE.read_text(encoding="utf-8") == expected, (
        "docs/engine-knobs.md is stale: python -m reports.cli.knobs_page > docs/engine-knobs.md"
    )
