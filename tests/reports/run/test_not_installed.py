"""An engine whose package is not installed (an optional extra such as Drake) is said once on stderr
and in the report's engines line, and makes no row; an engine whose own module is broken still
fails with a row per scenario, as before."""

from __future__ import annotations

from pathlib import Path

import pytest

import adapters
from adapters.base import Adapter
from reports.run.runner import RunConfig, Runner, not_installed
from reports.store.results_store import ResultsStore, read_results
from tests.support.fake_engine import fake_loader, fake_truth

QUICK = RunConfig(ladder=False, repeats=1, warmup=0, timeout=5.0)


def loader_missing(log: Path, missing: str):  # type: ignore[no-untyped-def]
    """The fake engine, and 'optional' whose import fails on module `missing` as adapters.load says it."""
    fake = fake_loader(log)

    def load(name: str) -> Adapter:
        if name != "optional":
            return fake(name)  # type: ignore[no-any-return]
        try:
            raise ModuleNotFoundError(f"No module named '{missing}'", name=missing)
        except ModuleNotFoundError as error:
            raise adapters.EngineUnavailable(f"engine 'optional' is not available: {error}") from error

    return load


def run(tmp_path: Path, missing: str):  # type: ignore[no-untyped-def]
    store = ResultsStore(tmp_path)
    loader = loader_missing(tmp_path / "calls.log", missing)
    runner = Runner(store, ["fake", "optional"], QUICK, loader=loader, truth=fake_truth, progress=False)
    runner.run(["slider_crank", "four_bar"])
    frame, _ = read_results(tmp_path)
    return runner, frame


def test_an_engine_not_installed_is_said_once_and_makes_no_row(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    runner, frame = run(tmp_path, "pyengine")
    assert "optional" not in set(frame["engine"])
    assert set(frame["engine"]) == {"fake"}
    said = [line for line in capsys.readouterr().err.splitlines() if "optional" in line]
    assert said == ["mbxval: engine optional is not installed (no module named pyengine): no runs of it"]
    assert runner.adapters["optional"] == "not installed"


def test_a_missing_module_of_ours_is_a_failure_per_scenario(tmp_path: Path) -> None:
    _, frame = run(tmp_path, "adapters.optional.model")
    rows = frame[frame["engine"] == "optional"]
    assert len(rows) == 2 and set(rows["status"]) == {"failed"}


def test_not_installed_reads_the_cause() -> None:
    assert not_installed(RuntimeError("no cause")) == ""
    assert not_installed(ModuleNotFoundError("x", name="pydrake.all")) == "no module named pydrake.all"
