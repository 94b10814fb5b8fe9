"""A group's runs in warm workers kept from group to group: one fork serves every group of an
engine, each group's runs are measured against that group's own scenario and truth, and a crash
costs its own row, the next run being sent its group again in a new worker."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from adapters.base import Setting
from reports.run.group_runs import RunConfig, Workers, run_group
from reports.run.planning import plan_engine
from reports.scoring.assembly import consistent_start
from reports.scoring.truth import NamedTruth
from scenarios import load as build_scenario
from tests.support.fake_engine import GOOD, FakeAdapter, fake_truth

CONFIG = RunConfig(repeats=1, warmup=0, timeout=10.0)


def crash_between(scenario, adapter):  # type: ignore[no-untyped-def]
    return [GOOD[0], Setting.of("crash"), GOOD[1]]


def test_one_worker_serves_every_group_of_an_engine(tmp_path: Path) -> None:
    adapter = FakeAdapter(tmp_path / "log")
    groups = []
    for name in ("slider_crank", "four_bar", "slider_crank[offset=0.05]"):  # other bodies, grids
        scenario = consistent_start(build_scenario(name))
        groups.append(plan_engine(scenario, "fake", adapter, True, crash_between))
    with Workers(CONFIG, None) as workers:
        made = []
        for group in groups:
            truth = NamedTruth(fake_truth(group.scenario, np.asarray(group.scenario.times())), "fake")
            made += run_group(group, group.jobs, truth, CONFIG, None, workers=workers)
        (worker,) = workers.workers.values()
        assert worker.forks == 1 + len(groups)  # the first, then one after each crash
    statuses = [row["status"] for row, _ in made]
    assert statuses == ["ok", "failed", "ok"] * len(groups)
    for row, _ in made:
        if row["status"] == "ok":  # measured against its own group's truth: the fake's error, dt
            assert np.isclose(row["position_length_max"], float(row["setting"].split("=")[1]), rtol=1e-12)
        else:
            assert "SIGSEGV" in row["message"]
    assert [row["scenario"] for row, _ in made][::3] == [g.scenario.name for g in groups]


def test_only_a_kept_trajectory_comes_back_from_the_worker(tmp_path: Path) -> None:
    """A run's trajectory crosses the pipe only when the row keeps it (the default setting's):
    the others' errors are measured in the child, and their trajectories stay there."""
    adapter = FakeAdapter(tmp_path / "log")
    scenario = consistent_start(build_scenario("four_bar"))
    group = plan_engine(scenario, "fake", adapter, True, None)
    truth = NamedTruth(fake_truth(scenario, np.asarray(scenario.times())), "fake")
    with Workers(CONFIG, None) as workers:
        kept = workers.measure(group, truth, GOOD[1], keep=True)
        dropped = workers.measure(group, truth, GOOD[0], keep=False)
    assert kept.kind == dropped.kind == "ok" and kept.value is not None and dropped.value is not None
    assert kept.value[0].trajectory is not None and dropped.value[0].trajectory is None
    assert np.isclose(dropped.value[2]["position_length_max"], 0.01, rtol=1e-12)  # measured all the same


class UntunedFake(FakeAdapter):
    """The fake with its own defaults declared apart from its ladder: dt = 0.1."""

    def untuned_setting(self, scenario):  # type: ignore[no-untyped-def]
        return Setting.of("good", dt=0.1)

    def ladder(self, scenario):  # type: ignore[no-untyped-def]
        return list(GOOD)


def test_the_untuned_setting_runs_beside_the_ladder_and_its_row_says_so(tmp_path: Path) -> None:
    scenario = consistent_start(build_scenario("four_bar"))
    group = plan_engine(scenario, "fake", UntunedFake(tmp_path / "log"), True, None)
    assert [s.label for s, _ in group.jobs] == [*(s.label for s in GOOD), "good dt=0.1"]
    truth = NamedTruth(fake_truth(scenario, np.asarray(scenario.times())), "fake")
    rows = [row for row, _ in run_group(group, group.jobs, truth, CONFIG, None)]
    assert [row["is_untuned"] for row in rows] == [False, False, True]
    assert np.isclose(rows[2]["position_length_max"], 0.1, rtol=1e-12)  # the fake's error is its dt
    quick = plan_engine(scenario, "fake", UntunedFake(tmp_path / "log"), False, None)
    assert [s for s, _ in quick.jobs] == [GOOD[1]]  # the quick suite runs the default alone
