"""An exported scenario file is the mechanism: no inert [parameters] table, a name of the user's
(`export --name`), its scales declared (`characteristic_length`, `characteristic_rate`) and printed
by `list FILE`; a file identical to a family keeps the family's identity (digest); older files with a
[parameters] table still read, scaled as before."""

from __future__ import annotations

import math
import tomllib
from pathlib import Path

import pytest

import scenarios
from reports.cli.main import main
from reports.scoring.level_error import characteristic_rate
from reports.store.scenario_identity import digest
from scenarios.files import read_scenario

EXAMPLES = Path(__file__).resolve().parents[3] / "examples"


def export(tmp_path: Path, capsys, *argv: str) -> Path:  # type: ignore[no-untyped-def]
    target = tmp_path / "out.toml"
    assert main(["export", *argv, "--format", "toml", "--out", str(target)]) == 0, capsys.readouterr().err
    capsys.readouterr()
    return target


def test_an_export_has_no_parameters_table_and_declares_its_scales(tmp_path: Path, capsys) -> None:
    path = export(tmp_path, capsys, "four_bar", "--set", "omega=-7.5", "--set", "revolutions=2")
    document = tomllib.loads(path.read_text())
    assert "parameters" not in document
    assert document["characteristic_rate"] == 7.5  # |omega|: the family's drive speed, as before
    assert document["characteristic_length"] == scenarios.build("four_bar").characteristic_length
    family = scenarios.build("four_bar", overrides={"omega": "-7.5", "revolutions": "2"})
    assert digest(read_scenario(path)) == digest(family)  # identical to the family: the same identity
    assert characteristic_rate(read_scenario(path)) == characteristic_rate(family) == 7.5


def test_a_dynamic_family_declares_one_cycle_over_its_run(tmp_path: Path, capsys) -> None:
    path = export(tmp_path, capsys, "compound_pendulum", "--set", "t_end=4")
    assert tomllib.loads(path.read_text())["characteristic_rate"] == pytest.approx(2 * math.pi / 4)


def test_export_name_sets_the_files_name(tmp_path: Path, capsys) -> None:
    path = export(tmp_path, capsys, "slider_crank/offset", "--name", "my_crank")
    scenario = read_scenario(path)
    assert (scenario.name, scenario.variant) == ("my_crank", "default")
    family = scenarios.build("slider_crank/offset")
    assert scenario.bodies == family.bodies and scenario.joints == family.joints


@pytest.mark.parametrize(
    ("name", "rule"),
    [
        ("", "must not be empty"),
        ("a/b", "must be a plain name"),
        ("a[b=1]", "must be a plain name"),
        ("x.toml", "must be a plain name"),
    ],
)
def test_a_name_that_is_not_plain_is_one_error_line(tmp_path: Path, capsys, name: str, rule: str) -> None:
    target = tmp_path / "out.toml"
    assert main(["export", "four_bar", "--format", "toml", "--name", name, "--out", str(target)]) == 2
    assert capsys.readouterr().err.startswith(f"mbxval: error: --name {rule}")
    assert not target.exists()


def test_a_declared_rate_scales_the_errors_and_list_prints_it(tmp_path: Path, capsys) -> None:
    path = export(tmp_path, capsys, "slider_crank")
    scaled = tmp_path / "scaled.toml"
    scaled.write_text(path.read_text().replace("characteristic_rate = 50.0", "characteristic_rate = 5.0"))
    assert characteristic_rate(read_scenario(scaled)) == 5.0
    assert main(["list", str(scaled)]) == 0
    out = capsys.readouterr().out
    assert f"{scaled}: characteristic_length = 0.2 m, characteristic_rate = 5 rad/s" in out


def test_an_older_file_with_a_parameters_table_reads_as_before(capsys, tmp_path) -> None:
    """A file written before exports dropped the table (and before characteristic_rate was a key)."""
    text = (EXAMPLES / "slider_crank.toml").read_text().replace("characteristic_rate = 50.0\n", "")
    older = tmp_path / "slider_crank.toml"
    older.write_text(text + "\n[parameters]\ncrank_length = 0.2\nrod_length = 0.4\nomega = 50.0\n")
    scenario = read_scenario(older)
    assert characteristic_rate(scenario) == 50.0  # its omega, as it was scaled before
    assert digest(scenario) == digest(scenarios.build("slider_crank"))
