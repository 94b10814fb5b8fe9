"""A table's `kind` is a string: a table, an array, a number or a boolean in its place, in the file
or through `--set`, is one ScenarioFileError naming the key and the type it got (a table there was
a raw `TypeError: unhashable type: 'dict'`)."""

from __future__ import annotations

import pytest

import scenarios
from scenarios.files import ScenarioFileError, parse_scenario, scenario_toml

SLIDER_CRANK = scenario_toml(scenarios.build("slider_crank"))
CAM = scenario_toml(scenarios.build("cam_roller"))
JOINT, MOTION = 'kind = "revolute"', 'kind = "constant_speed"'
PROFILE = 'kind = "eccentric_disc"'
VALUES = {"table": "{ a = 1 }", "array": '["revolute"]', "integer": "5", "boolean": "true", "float": "0.5"}

# (base file, the kind's text, its key path) for every table selected by a kind
KINDS = {
    "joint": (SLIDER_CRANK, JOINT, "joints[0].kind"),
    "motion": (SLIDER_CRANK, MOTION, "drivers[0].motion.kind"),
    "profile": (CAM, PROFILE, "joints[2].profile.kind"),
}
# (where, the --set path) of the same keys, by name or index
OVERRIDES = {
    "joint": "joints.O.kind",
    "motion": "drivers.crank_drive.motion.kind",
    "profile": "joints.2.profile.kind",
}


@pytest.mark.parametrize("kind", KINDS)
@pytest.mark.parametrize("toml_type", VALUES)
def test_a_kind_of_another_type_in_the_file(kind: str, toml_type: str) -> None:
    base, text, path = KINDS[kind]
    assert text in base
    with pytest.raises(ScenarioFileError) as raised:
        parse_scenario(base.replace(text, f"kind = {VALUES[toml_type]}", 1), "my.toml")
    assert str(raised.value).startswith(f"my.toml: {path}: expected a string, got {toml_type}")


@pytest.mark.parametrize("kind", OVERRIDES)
@pytest.mark.parametrize("toml_type", VALUES)
def test_a_kind_of_another_type_through_set(kind: str, toml_type: str) -> None:
    base, _, path = KINDS[kind]
    with pytest.raises(ScenarioFileError) as raised:
        parse_scenario(base, "my.toml", overrides={OVERRIDES[kind]: VALUES[toml_type]})
    assert str(raised.value).startswith(f"my.toml: {path}: expected a string, got {toml_type}")
