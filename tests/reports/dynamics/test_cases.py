"""The dynamics suite's scenarios, truth tolerances and settings."""

from __future__ import annotations

import math

import adapters
from reports.dynamics.cases import (
    JUDGED_MARGIN,
    LEFT_OUT,
    TRUTH_RTOL,
    map_cells,
    scenario_names,
    settings,
    truth_rtol,
)
from reports.suites import get
from scenarios import load
from scenarios.registry import all_families
from tests.support.engines import COMPARED


def test_the_suite_runs_every_dynamic_scenario_and_no_kinematic_one() -> None:
    names = scenario_names()
    assert get("dynamics").scenarios() == names
    assert all(load(n).analysis == "dynamic" for n in names)
    families = {n.partition("/")[0] for n in names}
    assert families == {name for name, family in all_families().items() if family.dynamic}
    assert set(map_cells()) <= set(names)
    assert not set(LEFT_OUT) & set(names)


def test_map_cells_span_stiffness_and_step() -> None:
    for name, values in map_cells().items():
        scenario = load(name)
        assert float(scenario.parameter("stiffness")) == values["stiffness"]
        assert math.isclose(scenario.t_end / scenario.steps, values["dt"], rel_tol=1e-12)
    assert len({v["stiffness"] for v in map_cells().values()}) >= 3
    assert len({v["dt"] for v in map_cells().values()}) >= 3


def test_the_native_engine_is_never_judged_by_a_truth_as_loose_as_itself() -> None:
    reference = adapters.load("reference")
    for name in ("four_bar_gravity", "n_four_bar", "andrews_squeezer"):
        scenario = load(name)
        chosen = settings(scenario, reference)
        assert chosen, name
        tolerances = [float(s["rtol"]) for s in chosen if s.get("rtol") is not None]
        assert all(rtol >= JUDGED_MARGIN * truth_rtol(scenario) for rtol in tolerances)
        # the rest step at a fixed dt (ALI3-P, the default through singular passages)
        assert all(s.get("dt") is not None for s in chosen if s.get("rtol") is None)
        assert len(tolerances) >= len(chosen) - 1
    assert truth_rtol(load("four_bar_gravity")) == TRUTH_RTOL
    assert truth_rtol(load("n_four_bar")) > TRUTH_RTOL  # the singular passage


def test_a_map_cell_runs_every_mode_at_its_step() -> None:
    for engine in COMPARED:
        adapter = adapters.load(engine)
        if not adapter.dynamics:
            continue
        for name, values in map_cells().items():
            chosen = settings(load(name), adapter)
            assert chosen is not None and chosen[0].mode == adapter.default_setting(load(name)).mode
            assert all(math.isclose(float(s["dt"]), values["dt"]) for s in chosen), (engine, name)
            assert len({s.mode for s in chosen}) == len(chosen) >= min(2, len(adapter.modes))
