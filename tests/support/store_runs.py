"""Runs into a results store with a fake engine, and the checks the store's tests share: the rows
stored, a copy of a store, and the one-line error a refused command prints."""

from __future__ import annotations

from pathlib import Path

import pandas as pd
import pytest

from reports.run.runner import RunConfig, Runner
from reports.store.results_store import ResultsStore, read_results
from tests.support.fake_engine import GOOD, FakeAdapter, fake_truth

ROOT = Path(__file__).resolve().parents[2]
SCENARIO = "slider_crank"
CONFIG = RunConfig(repeats=1, warmup=0, timeout=10.0)


class QuickFake(FakeAdapter):
    """The fake engine with two good settings and one that raises (no slow modes)."""

    def ladder(self, scenario):  # type: ignore[no-untyped-def]
        from adapters.base import Setting

        return [*GOOD, Setting.of("raise")]


def fake_run(directory: Path, config: RunConfig = CONFIG, loader=None, version: str | None = None) -> Runner:  # type: ignore[no-untyped-def]
    log = directory.parent / "calls.log"

    def load(name: str) -> FakeAdapter:
        adapter = QuickFake(log)
        if version is not None:
            adapter.version = lambda: version  # type: ignore[method-assign]
        return adapter

    runner = Runner(
        ResultsStore(directory), ["fake"], config, loader=loader or load, truth=fake_truth, progress=False
    )
    runner.run([SCENARIO])
    return runner


def stored_run(factory: pytest.TempPathFactory, name: str) -> Path:
    """A new results folder `out` in a fresh temporary folder `name`, holding one fake run."""
    directory = factory.mktemp(name) / "out"
    fake_run(directory)
    return directory


def copy(source: Path, target: Path) -> Path:
    import shutil

    shutil.copytree(source, target, symlinks=True)
    return target


def one_line_error(capsys: pytest.CaptureFixture[str], *words: str) -> str:
    err = capsys.readouterr().err
    assert err.startswith("mbxval: error: ") and err.count("\n") == 1, err
    for word in words:
        assert word in err, err
    return err


def rows(directory: Path) -> pd.DataFrame:
    return read_results(directory)[0].set_index(["scenario", "engine", "setting"]).sort_index()
