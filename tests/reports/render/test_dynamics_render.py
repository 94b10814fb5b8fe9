"""The dynamics section of a report made by a real (narrow) dynamics run of the native engine."""

from __future__ import annotations

from pathlib import Path

import pytest

from reports.cli.main import main
from reports.render.report_data import ReportData, map_cell_rows

SCENARIOS = ["compound_pendulum/small_oscillation", "stiff_spring/k1e2_dt1e-2", "stiff_spring/k1e4_dt1e-2"]


@pytest.fixture(scope="module")
def results(tmp_path_factory: pytest.TempPathFactory) -> Path:
    out = tmp_path_factory.mktemp("dynamics")
    args = ["run", "--suite", "dynamics", "--engine", "reference", "--out", str(out), "--quiet"]
    for name in SCENARIOS:
        args += ["--scenario", name]
    assert main(args) == 0
    return Path(out)


@pytest.fixture(scope="module")
def page(results: Path) -> str:
    return (results / "index.html").read_text()


def test_the_page_says_dynamics_and_has_its_section(page: str) -> None:
    assert "planar multibody dynamics across engines" in page
    for heading in ("Dynamics: drift and stability", "Stability map", "Energy drift over time"):
        assert heading in page
    assert 'aria-label="stability map"' in page and 'aria-label="energy drift"' in page


def test_the_native_runs_are_stable_in_every_cell(results: Path) -> None:
    cells = map_cell_rows(ReportData.load(results).frame)
    assert len(cells) == 2 and set(cells["verdict"]) == {"stable"}
