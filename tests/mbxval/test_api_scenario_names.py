"""A Scenario built in Python and handed to the API (mbxval.solve, mbxval.compare) has its names
checked as a scenario file's are (scenarios.names.check_scenario_names): a control or format
character, an empty or blank name, a separator or the point syntax in the scenario's own name, an
over-long name are one ScenarioError naming where, before any work and without echoing the name."""

from __future__ import annotations

import dataclasses

import pandas as pd
import pytest

import mbxval
from scenarios.names import MAX_NAME_LENGTH

BAD_NAMES = {
    "newline": "crank\nmbxval: error: forged",
    "escape sequence": "\x1b]0;title\x07crank",
    "bidirectional override": "crank\u202ekcab",
    "NUL": "cr\x00ank",
    "empty": "",
    "blank": " \t ",
    "over-long": "c" * (MAX_NAME_LENGTH + 1),
}
SCENARIO_ONLY = {  # refused in the scenario's own name and variant, as `export --name` refuses them
    "separator": "slider/crank",
    "point syntax": "slider_crank[offset=0.05]",
    "file name": "mine.toml",
}


def _renamed(where: str, bad: str) -> mbxval.Scenario:
    scenario = mbxval.load_scenario("slider_crank")
    if where == "family":
        return dataclasses.replace(scenario, family=bad)
    if where == "variant":
        return dataclasses.replace(scenario, variant=bad)
    field = {"body": "bodies", "joint": "joints", "driver": "drivers"}[where]
    items = list(getattr(scenario, field))
    items[0] = dataclasses.replace(items[0], name=bad)
    return dataclasses.replace(scenario, **{field: tuple(items)})


CASES = [(where, kind) for where in ("family", "variant", "body", "joint", "driver") for kind in BAD_NAMES]
CASES += [(where, kind) for where in ("family", "variant") for kind in SCENARIO_ONLY]


def _frame() -> pd.DataFrame:
    return mbxval.solve("slider_crank", steps=8)


@pytest.mark.parametrize(("where", "kind"), CASES)
@pytest.mark.parametrize("entry", ["solve", "compare"])
def test_a_built_scenario_with_a_bad_name_is_refused(entry: str, where: str, kind: str) -> None:
    bad = {**BAD_NAMES, **SCENARIO_ONLY}[kind]
    scenario = _renamed(where, bad)
    with pytest.raises(mbxval.ScenarioError) as refused:
        if entry == "solve":
            mbxval.solve(scenario, steps=8)
        else:
            mbxval.compare(scenario, FRAME)
    message = str(refused.value)
    assert "\n" not in message and "\x1b" not in message and "\u202e" not in message, message
    assert bad not in message or not bad.strip(), message  # the name is never echoed
    label = {"family": "name", "variant": "variant", "body": "bodies[0]", "joint": "joints[0]"}
    assert label.get(where, "drivers[0]") in message, message


FRAME = _frame()


@pytest.mark.parametrize("entry", ["solve", "compare"])
def test_a_built_scenario_with_good_names_is_taken(entry: str) -> None:
    """The checks refuse only what they should: unusual but valid names (spaces inside, accents,
    a name of exactly the longest length) solve and score."""
    scenario = dataclasses.replace(mbxval.load_scenario("slider_crank"), family="Kurbel Schieber é", steps=8)
    joints = list(scenario.joints)
    joints[0] = dataclasses.replace(joints[0], name="j" * MAX_NAME_LENGTH)
    scenario = dataclasses.replace(scenario, joints=tuple(joints))
    frame = mbxval.solve(scenario)
    assert len(frame) == 9
    if entry == "compare":
        assert len(mbxval.compare(scenario, frame)) == 1
