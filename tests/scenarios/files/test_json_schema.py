"""The JSON Schema of the scenario file (`mbxval schema`): a valid draft 2020-12 schema that accepts
every example file and every file the writer makes, and rejects broken files the reader rejects."""

from __future__ import annotations

import json
import tomllib
from pathlib import Path

import jsonschema
import pytest

from reports.cli.main import main
from scenarios import catalogue, load
from scenarios.files import ScenarioFileError, parse_scenario, scenario_toml

EXAMPLES = sorted((Path(__file__).resolve().parents[3] / "examples").glob("*.toml"))


@pytest.fixture(scope="module")
def validator(tmp_path_factory: pytest.TempPathFactory) -> jsonschema.Draft202012Validator:
    """The schema as the command line prints it, checked against the metaschema."""
    path = tmp_path_factory.mktemp("schema") / "scenario.schema.json"
    assert main(["schema", "--out", str(path)]) == 0
    schema = json.loads(path.read_text())
    jsonschema.Draft202012Validator.check_schema(schema)
    return jsonschema.Draft202012Validator(schema)


@pytest.mark.parametrize("path", EXAMPLES, ids=lambda p: p.name)
def test_every_example_file_is_valid(validator, path: Path) -> None:
    errors = [e.message for e in validator.iter_errors(tomllib.loads(path.read_text()))]
    assert errors == []


def test_every_file_the_writer_makes_is_valid(validator) -> None:
    names = catalogue(include_dynamic=True)
    assert len(names) > 20
    for name in names:
        document = tomllib.loads(scenario_toml(load(name)))
        assert [e.message for e in validator.iter_errors(document)] == [], name


BROKEN = {
    "a misspelt key": ("t_end = ", "t_ende = "),
    "an unknown joint kind": ('kind = "revolute"', 'kind = "revolut"'),
    "steps not positive": ("steps = 200", "steps = 0"),
    "a point without its body": (
        'p_i = { body = "ground", local = [0.0, 0.0] }',
        "p_i = { local = [0.0, 0.0] }",
    ),
    "a pose of two numbers": (
        "guess = [0.09553364891256061, 0.029552020666133955, 0.3]",
        "guess = [0.1, 0.2]",
    ),
}


@pytest.mark.parametrize("what", BROKEN)
def test_a_broken_file_is_rejected_by_the_schema_and_the_reader(validator, what: str) -> None:
    text = (EXAMPLES[0].parent / "slider_crank.toml").read_text()
    old, new = BROKEN[what]
    assert old in text
    broken = text.replace(old, new, 1)
    assert not validator.is_valid(tomllib.loads(broken))
    with pytest.raises(ScenarioFileError):
        parse_scenario(broken)
