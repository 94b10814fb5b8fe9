"""A row's scenario digest is computed once per scenario, and is the digest scenarios.identity gives."""

from __future__ import annotations

import dataclasses

from reports.run.rows import scenario_digest
from reports.scoring.assembly import consistent_start
from scenarios import load as build_scenario
from scenarios.identity import digest


def test_the_digest_is_the_scenario_s_and_computed_once() -> None:
    names = ("four_bar", "cam_roller/spline", "four_bar[omega=20]", "four_bar[omega=30]")
    scenarios = [consistent_start(build_scenario(name)) for name in names]
    before = scenario_digest.cache_info()  # type: ignore[attr-defined]
    for scenario in scenarios * 3:
        assert scenario_digest(scenario) == digest(scenario)
    after = scenario_digest.cache_info()  # type: ignore[attr-defined]
    assert after.misses - before.misses <= len(scenarios)
    assert after.hits - before.hits >= 2 * len(scenarios)
    swept, other = scenarios[2:]
    assert scenario_digest(swept) != scenario_digest(other)  # the point's parameters are in the file
    renamed = dataclasses.replace(swept, point=())
    assert scenario_digest(renamed) == scenario_digest(swept)  # the point's name tag is not
