"""A store edited by hand and committed again with fresh checksums (so it verifies) still renders:
a `sweep` cell that is not the JSON object of parameter values a run writes makes its row an
unswept one (drawn among the plain rows, out of the map), and a stored engine colour that cannot be
drawn gives that engine a palette colour; never a traceback after the rows were stored."""

from __future__ import annotations

import shutil
from pathlib import Path
from typing import Any

import pandas as pd
import pytest

import adapters
from reports.cli.main import main
from reports.render import plots
from reports.render.report_data import ReportData, swept_point
from reports.render.swept_map import swept_maps
from reports.store.results_store import ResultsStore
from tests.support.stores import doctor

POINTS = ("0", "0.02", "0.05")


@pytest.fixture(scope="module")
def swept(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A sweep of three offsets of the slider-crank by the native engine."""
    out = tmp_path_factory.mktemp("swept") / "store"
    argv = ["run", "--suite", "quick", "--scenario", "slider_crank", "--engine", "reference"]
    argv += ["--steps", "20", "--sweep", f"offset={','.join(POINTS)}", "--out", str(out), "--quiet"]
    assert main(argv) == 0
    return out


# a cell as a hand may leave it: none is the object of names to values a run writes
BAD_SWEEPS = {
    "not JSON": "{offset: 0.02",
    "an array": '["offset", "0.02"]',
    "a number": "5",
    "null": "null",
    "an empty object": "{}",
    "a nested value": '{"offset": [0.02]}',
    "a table value": '{"offset": {"a": 1}}',
    "a boolean value": '{"offset": true}',
    "deeply nested": "[" * 100_000 + "]" * 100_000,
    "markup": "<b>&amp;</b>",
}


def with_sweep_cell(source: Path, target: Path, cell: str) -> Path:
    """A copy of the store whose first swept row's `sweep` cell holds `cell`, committed."""

    def edit(frame: pd.DataFrame) -> None:
        frame.at[frame.index[0], "sweep"] = cell

    return doctor(source, target, edit)


@pytest.mark.parametrize("case", BAD_SWEEPS)
def test_a_bad_sweep_cell_renders_its_row_unswept(
    case: str, swept: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    copy = with_sweep_cell(swept, tmp_path / "copy", BAD_SWEEPS[case])
    capsys.readouterr()
    assert main(["report", str(copy)]) == 0, capsys.readouterr().err
    assert capsys.readouterr().err == ""
    (only,) = swept_maps(ReportData.load(copy))
    assert len(only.cells) == len(POINTS) - 1  # the map of the two rows that read; the third apart
    assert (copy / "index.html").stat().st_size > 0


# (column, value) of a swept row's verdict that no run stores: each cell is drawn in the colour of
# verdicts without one of their own, under its text in the legend
BAD_VERDICTS = {
    "an unknown verdict": ("verdict", "<b>&amp;$x$</b>"),
    "a long verdict": ("verdict", "x" * 5000),
    "no verdict": ("verdict", ""),
    "a missing verdict": ("verdict", None),
    "ok without an error": ("verdict_error", None),
    "ok with an error of NaN": ("verdict_error", float("nan")),
}


@pytest.mark.parametrize("case", BAD_VERDICTS)
def test_a_swept_row_with_a_verdict_no_run_stores_is_drawn(
    case: str, swept: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    column, value = BAD_VERDICTS[case]

    def edit(frame: pd.DataFrame) -> None:
        frame[column] = frame[column].astype(object)
        frame.at[frame.index[0], column] = value

    copy = doctor(swept, tmp_path / "copy", edit)
    capsys.readouterr()
    assert main(["report", str(copy)]) == 0, capsys.readouterr().err
    (only,) = swept_maps(ReportData.load(copy))
    assert len(only.cells) == len(POINTS)


@pytest.mark.parametrize(
    ("cell", "values"),
    [
        ('{"offset": "0.02"}', {"offset": "0.02"}),
        ('{"offset": 0.02, "omega": 5}', {"offset": "0.02", "omega": "5"}),
        ("", None),
        (None, None),
        (float("nan"), None),
        *((cell, None) for cell in BAD_SWEEPS.values()),
    ],
)
def test_a_sweep_cell_is_its_values_or_none(cell: Any, values: dict[str, str] | None) -> None:
    assert swept_point(cell) == values


@pytest.mark.parametrize(
    "colours",
    [
        {"reference": "not-a-colour"},
        {"reference": '#12"><script>'},
        {"reference": 5},
        {"reference": None},
        ["#ffffff"],
        "#ffffff",
    ],
)
def test_a_stored_colour_that_cannot_be_drawn_gives_a_palette_colour(
    colours: object, swept: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    copy = tmp_path / "copy"
    shutil.copytree(swept, copy, symlinks=True)
    store = ResultsStore(copy)
    store.save({**store.meta, "engine_colours": colours})
    assert main(["report", str(copy)]) == 0, capsys.readouterr().err
    ReportData.load(copy)
    assert plots.colour("reference") in plots.PALETTE


def test_a_stored_colour_that_can_be_drawn_is_kept(swept: Path) -> None:
    ReportData.load(swept)
    assert plots.colour("reference") == adapters.adapter_class("reference").colour  # as the run stored it


# sidecar fields of another shape than a run writes: the page says '?' or nothing there
BAD_SIDECARS = {
    "engines a number": ("engines", 5),
    "engines a text": ("engines", "x"),
    "engines null": ("engines", None),
    "packages a list": ("packages", ["numpy"]),
    "machine a text": ("machine", "x"),
    "revisions a number": ("revisions", 5),
    "timeout a text": ("timeout", "abc"),
    "repeats a table": ("repeats", {"a": 1}),
    "warmup a list": ("warmup", [1]),
}


@pytest.mark.parametrize("case", BAD_SIDECARS)
def test_a_sidecar_field_of_another_shape_is_left_out(
    case: str, swept: Path, tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    key, value = BAD_SIDECARS[case]
    copy = tmp_path / "copy"
    shutil.copytree(swept, copy, symlinks=True)
    store = ResultsStore(copy)
    store.save({**store.meta, key: value})
    capsys.readouterr()
    assert main(["report", str(copy)]) == 0, capsys.readouterr().err
    assert key not in ReportData.load(copy).meta
