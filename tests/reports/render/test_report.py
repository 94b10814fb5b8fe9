"""The report, rendered from stored results alone: a self-contained HTML page with its plots, and a
Markdown summary; plus the same page opened in a real headless Chromium when one is installed."""

from __future__ import annotations

import html
import os
import re
import shutil
import subprocess
import xml.etree.ElementTree as ElementTree
from pathlib import Path

import pandas as pd
import pytest

from reports.cli.main import main
from reports.store.results_store import read_results

SCENARIOS = ("slider_crank", "cam_roller/stress_undercut")
CHROMIUM = Path("/usr/bin/chromium")


@pytest.fixture(scope="module")
def results(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A real small run: MuJoCo over its sweep (it does not support the lobed cam), timed once."""
    out = tmp_path_factory.mktemp("run")
    args = ["run", "--out", str(out), "--quiet", "--engine", "mujoco"]
    args += ["--repeats", "1", "--warmup", "0"]
    for name in SCENARIOS:
        args += ["--scenario", name]
    assert main(args) == 0
    return out


def test_run_writes_the_documented_files(results: Path) -> None:
    for name in ("index.html", "summary.md", "results.json"):
        assert (results / name).is_file(), name
    for name in ("results.parquet", "trajectories.parquet"):  # a folder of Parquet parts each
        assert (results / name).is_dir() and list((results / name).glob("part-*.parquet")), name
    assert len(pd.read_parquet(results / "results.parquet")) == len(read_results(results)[0])


def test_html_is_self_contained_with_its_plots(results: Path) -> None:
    page = (results / "index.html").read_text()
    assert not re.search(r'(src|href)="(https?:|//)', page), "the page must not load anything from outside"
    images = re.findall(r'<svg class="plot" .*?</svg>', page, flags=re.DOTALL)
    kinds = [re.search(r'aria-label="([^"]+)"', image).group(1) for image in images]  # type: ignore[union-attr]
    # the suite overview; slider_crank: work-precision and deviations; the lobed cam: nothing ran
    assert kinds == ["overview of error against run time", "work-precision plot", "deviations"]
    assert "no work-precision plot: no successful run to draw" in page
    assert "no stored truth trajectory: no deviations" in page
    assert 'title="truth: closed form"' in page  # the slider-crank's truth, named in the matrix
    assert "Stability map" not in page  # the stress suite's, never the default report's
    for image in images:  # crisp at any zoom: vector paths and text as text, no raster inside
        root = ElementTree.fromstring(image)
        assert root.findall(".//{http://www.w3.org/2000/svg}text") and "<image" not in image
    _, meta = read_results(results)
    assert f"<th>engine mujoco</th><td>{meta['engines']['mujoco']}</td>" in page
    assert 'class="unsupported"' in page  # MuJoCo and the lobed cam, in the matrix
    assert html.escape(meta["scales"]) in page


def test_markdown_summary_has_the_matrix_and_each_scenario(results: Path) -> None:
    text = (results / "summary.md").read_text()
    assert "| scenario | mujoco |" in text
    frame, _ = read_results(results)
    for name in SCENARIOS:
        assert f"\n## {name}\n" in text
    unsupported = frame[frame["status"] == "unsupported"]
    assert len(unsupported) == 1 and unsupported["scenario"].item() == "cam_roller/stress_undercut"
    assert "| cam_roller/stress_undercut | unsupported |" in text and "| slider_crank | ok " in text


def test_report_rerenders_from_stored_files_alone(results: Path, tmp_path: Path) -> None:
    copy = tmp_path / "stored"
    copy.mkdir()
    for name in (".generations", "current", "results.parquet", "results.json", "trajectories.parquet"):
        if (results / name).is_symlink():
            shutil.copy(results / name, copy / name, follow_symlinks=False)
        else:
            shutil.copytree(results / name, copy / name, symlinks=True)
    assert main(["report", str(copy / "results.parquet")]) == 0
    assert (copy / "index.html").read_text().count('<svg class="plot"') == 3
    assert (copy / "summary.md").read_text() == (results / "summary.md").read_text()


def test_report_of_nothing_is_a_one_line_error(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["report", str(tmp_path)]) == 2
    error = capsys.readouterr().err
    assert error.startswith("mbxval: error: no results.parquet in") and error.count("\n") == 1


def test_the_page_loads_in_a_real_browser(results: Path) -> None:
    """Headless Chromium opens the page; the page's own script counts the plots that decoded. CI
    installs Chromium (.ci/run), so there a missing browser is a failure, not a skip."""
    if not CHROMIUM.exists():
        message = "Chromium is not installed (apt-get install chromium)"
        if os.environ.get("CI"):
            pytest.fail(f"{message}: CI must run the browser test")
        pytest.skip(message)
    done = subprocess.run(
        [
            str(CHROMIUM),
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--disable-background-networking",
            "--disable-component-update",
            "--no-first-run",
            "--dump-dom",
            (results / "index.html").as_uri(),
        ],
        capture_output=True,
        text=True,
        timeout=120,
    )
    loaded = re.search(r'data-plots-loaded="(\d+)/(\d+)"', done.stdout)
    assert loaded, done.stderr[-2000:]
    assert loaded.group(1) == loaded.group(2) == "3"


def test_the_page_says_what_each_mode_measures(results: Path) -> None:
    """Every engine-mode that ran has its `measures` text in the modes table, as its rows say."""
    page = (results / "index.html").read_text()
    frame, _ = read_results(results)
    measured = frame[frame["measures"].astype(str) != ""].drop_duplicates(["engine", "mode"])
    assert not measured.empty
    for _, row in measured.iterrows():
        assert html.escape(str(row["measures"]), quote=False) in page, row["mode"]
