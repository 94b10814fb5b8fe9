"""A row's ranks (where the report lists it) are read from the registry once per process, and
still follow a change of the registry (an engine added by its one line)."""

from __future__ import annotations

import pytest

import adapters
from reports.run.rows import ranks
from scenarios import catalogue


def test_ranks_are_the_places_in_the_catalogue_and_the_registry() -> None:
    listed = catalogue(include_stress=True, include_dynamic=True)
    found = ranks("slider_crank", "mujoco")
    assert found == {"scenario_rank": listed.index("slider_crank"), "engine_rank": 1}
    assert ranks("no_such_scenario", "no_such_engine") == {"scenario_rank": -1, "engine_rank": -1}


def test_an_engine_added_to_the_registry_gets_its_place(monkeypatch: pytest.MonkeyPatch) -> None:
    assert ranks("four_bar", "toy")["engine_rank"] == -1
    monkeypatch.setitem(adapters.ENGINES, "toy", ("tests.support.toy_engine", "ToyAdapter"))
    assert ranks("four_bar", "toy")["engine_rank"] == 5  # after the five built-in engines
