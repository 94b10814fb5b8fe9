"""The dynamics suite's regression baseline (made from a real `mbxval run --suite dynamics`): it covers
every scenario of the suite on every engine, and the gate sees a regression in it."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pandas as pd
import pytest

import adapters
from reports.dynamics.cases import scenario_names
from reports.gate import baselines, gate

BASELINE = baselines.resolve("dynamics")
ROOT = Path(__file__).resolve().parents[3]


def test_every_scenario_of_the_suite_has_a_default_cell_per_engine() -> None:
    cells = gate.read_baseline(BASELINE)
    defaults = {(c["scenario"], c["engine"]) for c in cells if c["is_default"]}
    missing = [(s, e) for s in scenario_names() for e in _dynamic_engines() if (s, e) not in defaults]
    assert not missing, missing
    # every engine that runs free dynamics has a supported default cell
    assert not [c for c in cells if c["is_default"] and c["status"] == "unsupported"]


def test_the_gate_sees_an_engine_losing_accuracy_in_dynamics() -> None:
    cells = gate.read_baseline(BASELINE)
    frame = pd.DataFrame(cells)
    assert gate.judge(cells, frame, gate.DEFAULT_FACTOR).passed
    worse = frame.copy()
    k = worse.index[
        (worse["engine"] == "mujoco") & (worse["scenario"] == "four_bar_gravity") & worse["is_default"]
    ][0]
    worse.loc[k, "error_position"] = 100.0 * float(worse.loc[k, "error_position"])
    verdict = gate.judge(cells, worse, gate.DEFAULT_FACTOR)
    assert [(r.scenario, r.engine) for r in verdict.regressions] == [("four_bar_gravity", "mujoco")]


def _dynamic_engines() -> list[str]:
    """The installed engines that run forward dynamics (Drake's adapter does not yet)."""
    found = []
    for name in adapters.names():
        try:
            if adapters.load(name).dynamics:
                found.append(name)
        except adapters.EngineUnavailable:
            continue
    return found


@pytest.mark.slow
def test_the_shipped_dynamics_gate_passes_as_a_newcomer_runs_it(tmp_path: Path) -> None:
    """`mbxval check --suite dynamics --baseline dynamics`, as on a fresh clone: from a directory
    of its own, the suite run into a temporary store and compared with the shipped baseline."""
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    argv = ["check", "--suite", "dynamics", "--baseline", "dynamics", "--quiet"]
    done = subprocess.run(
        [sys.executable, "-m", "mbxval", *argv],
        cwd=tmp_path,
        env=env,
        capture_output=True,
        text=True,
        timeout=1800,
    )
    assert done.returncode == 0, done.stdout[-3000:] + done.stderr[-3000:]
    assert "no regressions" in done.stdout, done.stdout[-3000:]
    assert list(tmp_path.iterdir()) == []  # the suite's store was a temporary one, removed
