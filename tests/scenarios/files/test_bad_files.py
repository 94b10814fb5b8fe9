"""Every kind of bad scenario file gives one ScenarioFileError naming the file, the key path and
what is wrong; nothing is built."""

from __future__ import annotations

import tomllib
from pathlib import Path

import pytest

import scenarios
from scenarios.files import ScenarioFileError, parse_scenario, read_scenario, scenario_toml
from scenarios.files.writer import read_back

BASES = {
    name: scenario_toml(scenarios.build(name))
    for name in ("slider_crank", "cam_roller", "spur_gears", "andrews_squeezer", "compound_pendulum")
}
SLIDER_CRANK, CAM = BASES["slider_crank"], BASES["cam_roller"]
ROLLER = 'profile = { kind = "eccentric_disc", radius = 0.05, eccentricity = 0.01 }'
# Each case edits a built-in scenario's file: (base, old text, new text, expected message start).
CASES = {
    case["name"]: (BASES[case["base"]], case["old"], case["new"], case["expected"])
    for case in tomllib.loads((Path(__file__).parent / "bad_files.toml").read_text())["case"]
}


@pytest.mark.parametrize("case", CASES)
def test_bad_file_is_one_line_naming_file_and_key(case: str) -> None:
    base, old, new, expected = CASES[case]
    assert base.count(old) >= 1, "the case must change the file"
    with pytest.raises(ScenarioFileError) as error:
        parse_scenario(base.replace(old, new, 1), "my.toml")
    message = str(error.value)
    assert "\n" not in message
    assert message.startswith(f"my.toml: {expected}"), message


def test_the_unchanged_bases_are_good() -> None:
    for base in BASES.values():
        parse_scenario(base, "my.toml")


def test_spline_profile_from_a_csv_file_relative_to_the_scenario(tmp_path: Path) -> None:
    spline = scenarios.build("cam_roller/spline")
    profile = spline.joints[2].profile  # type: ignore[union-attr]
    (tmp_path / "profiles").mkdir()
    (tmp_path / "profiles" / "cam.csv").write_text(
        "radius\n" + "\n".join(repr(r) for r in profile.table) + "\n"
    )
    inline = f"table = {list(profile.table)!r}"
    text = scenario_toml(spline).replace(
        inline.replace("[", "[").replace("]", "]"), 'csv = "profiles/cam.csv"'
    )
    assert 'csv = "profiles/cam.csv"' in text
    (tmp_path / "cam.toml").write_text(text)
    assert read_scenario(tmp_path / "cam.toml") == read_back(spline)


def test_bad_csv_line(tmp_path: Path) -> None:
    (tmp_path / "cam.csv").write_text("radius\n0.05\nabc\n0.05\n")
    (tmp_path / "cam.toml").write_text(CAM.replace(ROLLER, 'profile = { kind = "spline", csv = "cam.csv" }'))
    with pytest.raises(
        ScenarioFileError, match=r"cam.toml: joints\[2\]\.profile\.csv: .*cam.csv line 3: not a number"
    ):
        read_scenario(tmp_path / "cam.toml")


def test_unreadable_file(tmp_path: Path) -> None:
    with pytest.raises(ScenarioFileError, match=r"missing.toml: cannot read"):
        read_scenario(tmp_path / "missing.toml")


@pytest.mark.parametrize(
    ("path", "expected"),
    [
        ("bodies.crnk.mass", "--set bodies.crnk.mass: no element 'crnk' (did you mean 'crank'?)"),
        ("stepz", "stepz: unknown key (did you mean 'steps'?)"),
        (
            "drivers.crank_drive.motoin.rate",
            "--set drivers.crank_drive.motoin.rate: no key 'motoin' (did you mean 'motion'?)",
        ),
        ("t_end.x", "--set t_end.x: 't_end' holds a value, not a table"),
    ],
)
def test_bad_override_paths(path: str, expected: str) -> None:
    with pytest.raises(ScenarioFileError) as error:
        parse_scenario(SLIDER_CRANK, "my.toml", overrides={path: "1"})
    assert str(error.value).startswith(f"my.toml: {expected}"), str(error.value)


def test_overrides_set_values_by_dotted_path() -> None:
    scenario = parse_scenario(
        SLIDER_CRANK,
        overrides={
            "steps": "40",
            "bodies.rod.mass": "2.5",
            "bodies.0.guess": "[0.1, 0.03, 0.3]",
            "drivers.crank_drive.motion.rate": "-20",
            "joints.slide.axis": "[1.0, 0.0]",
            "description": "my variant",
        },
    )
    assert scenario.steps == 40
    assert scenario.body("rod").mass == 2.5
    assert scenario.body("crank").guess == (0.1, 0.03, 0.3)
    assert scenario.drivers[0].motion.rate == -20.0  # type: ignore[union-attr]
    assert scenario.description == "my variant"
    with pytest.raises(ScenarioFileError, match=r"bodies\[1\]\.mass: must be a positive number"):
        parse_scenario(SLIDER_CRANK, "my.toml", overrides={"bodies.rod.mass": "-1"})
