"""One start for all engines: a dynamic file whose coupler guess is 1 mm off starts every engine from
the native assembly (measured before: MuJoCo and Pinocchio 3.3e-3 m from the native start)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import adapters
from reports.scoring.assembly import consistent_start
from scenarios import load
from scenarios.files.writer import scenario_toml
from tests.support.engines import COMPARED


@pytest.fixture(scope="module")
def off_by_a_millimetre(tmp_path_factory: pytest.TempPathFactory) -> Path:
    scenario = load("four_bar_gravity", {"t_end": 0.05, "steps": 5})
    path = tmp_path_factory.mktemp("start") / "off.toml"
    text = scenario_toml(scenario)
    coupler = next(b for b in scenario.bodies if b.name == "coupler")
    x = coupler.guess[0]
    path.write_text(text.replace(repr(x), repr(x + 1e-3), 1), encoding="utf-8")
    return path


def test_a_consistent_start_is_kept_as_written() -> None:
    scenario = load("four_bar_gravity")
    assert consistent_start(scenario) is scenario
    kinematic = load("four_bar")
    assert consistent_start(kinematic) is kinematic


@pytest.mark.parametrize("engine", COMPARED)
def test_every_engine_starts_from_the_native_assembly(off_by_a_millimetre: Path, engine: str) -> None:
    written = load(str(off_by_a_millimetre))
    scenario = consistent_start(written)
    assert scenario is not written
    times = np.asarray(scenario.times())
    native = adapters.load("reference").run(scenario, None, times).trajectory
    adapter = adapters.load(engine)
    if adapter.supports(scenario) is not None:
        pytest.skip(f"{engine}: {adapter.supports(scenario)}")
    run = adapter.run(scenario, None, times)
    assert run.status == "ok" and run.trajectory is not None and native is not None
    gap = np.max(np.abs(run.trajectory.position[0] - native.position[0]))
    assert gap < 1e-10 * scenario.characteristic_length
