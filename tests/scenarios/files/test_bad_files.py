"""Every kind of bad scenario file gives one ScenarioFileError naming the file, the key path and
what is wrong; nothing is built."""

from __future__ import annotations

from pathlib import Path

import pytest

import scenarios
from scenarios.files import ScenarioFileError, parse_scenario, read_scenario, scenario_toml

SLIDER_CRANK = scenario_toml(scenarios.build("slider_crank"))
CAM = scenario_toml(scenarios.build("cam_roller"))
GEARS = scenario_toml(scenarios.build("spur_gears"))
DRIVE = 'motion = { kind = "constant_speed", start = 0.3, rate = 50.0 }'
TABULATED = 'motion = { kind = "tabulated", times = [0.0, 1.0, 2.0]'
ROLLER = 'profile = { kind = "eccentric_disc", radius = 0.05, eccentricity = 0.01 }'

# (base text, text replaced, replacement, expected message after "my.toml: ")
CASES = {
    "invalid TOML": (SLIDER_CRANK, "steps = 200\n", "steps = = 200\n", "not valid TOML: "),
    "unknown top-level key": (
        SLIDER_CRANK,
        "steps = 200\n",
        "step = 200\n",
        "step: unknown key (did you mean 'steps'?)",
    ),
    "unknown body key": (
        SLIDER_CRANK,
        "mass = 0.2\n",
        "mas = 0.2\n",
        "bodies[0].mas: unknown key (did you mean 'mass'?)",
    ),
    "unknown point key": (
        SLIDER_CRANK,
        'p_j = { body = "crank", local',
        'p_j = { body = "crank", locl',
        "joints[0].p_j.locl: unknown key (did you mean 'local'?)",
    ),
    "unknown motion key": (
        SLIDER_CRANK,
        DRIVE,
        DRIVE.replace("rate", "rat"),
        "drivers[0].motion.rat: unknown key (did you mean 'rate'?)",
    ),
    "unknown joint kind": (
        SLIDER_CRANK,
        'kind = "prismatic"',
        'kind = "prismatc"',
        "joints[3].kind: unknown kind 'prismatc' (did you mean 'prismatic'?)",
    ),
    "unknown motion law": (
        SLIDER_CRANK,
        DRIVE,
        DRIVE.replace('"constant_speed"', '"constant_sped"'),
        "drivers[0].motion.kind: unknown kind 'constant_sped' (did you mean 'constant_speed'?)",
    ),
    "missing top-level field": (SLIDER_CRANK, "t_end = 0.12566370614359174\n", "", "t_end: missing"),
    "missing format": (SLIDER_CRANK, "format = 1\n", "", "format: missing"),
    "newer format": (SLIDER_CRANK, "format = 1\n", "format = 2\n", "format: format 2 is newer than this"),
    "missing body guess": (
        SLIDER_CRANK,
        "guess = [0.5866765903072286, 0.0, 0.0]\n",
        "",
        "bodies[2].guess: missing",
    ),
    "missing joint point": (
        SLIDER_CRANK,
        'p_j = { body = "slider", local = [0.0, 0.0] }\n',
        "",
        "joints[2].p_j: missing",
    ),
    "missing motion value": (
        SLIDER_CRANK,
        DRIVE,
        DRIVE.replace(", rate = 50.0", ""),
        "drivers[0].motion.rate: missing",
    ),
    "missing kind": (SLIDER_CRANK, 'kind = "prismatic"\n', "", "joints[3].kind: missing"),
    "unknown body in a point": (
        SLIDER_CRANK,
        'p_i = { body = "rod", local = [0.2, 0.0] }',
        'p_i = { body = "rdo", local = [0.2, 0.0] }',
        "joints[2].p_i.body: unknown body 'rdo' (did you mean 'rod'?)",
    ),
    "unknown driven body": (
        SLIDER_CRANK,
        'body = "crank"\ncoordinate',
        'body = "cranks"\ncoordinate',
        "drivers[0].body: unknown body 'cranks' (did you mean 'crank'?)",
    ),
    "driving the ground": (
        SLIDER_CRANK,
        'body = "crank"\ncoordinate',
        'body = "ground"\ncoordinate',
        "drivers[0].body: unknown moving body (not the ground) 'ground'",
    ),
    "unknown gear": (
        GEARS,
        'gear_j = "gear_out"',
        'gear_j = "gear_ot"',
        "joints[2].gear_j: unknown body 'gear_ot'",
    ),
    "unknown output": (
        SLIDER_CRANK,
        "characteristic_length = 0.2\n",
        'characteristic_length = 0.2\noutputs = ["slidr"]\n',
        "outputs[0]: unknown body 'slidr' (did you mean 'slider'?)",
    ),
    "unknown level": (
        SLIDER_CRANK,
        "characteristic_length = 0.2\n",
        'characteristic_length = 0.2\nlevels = ["position", "jerk"]\n',
        "levels[1]: unknown level 'jerk'",
    ),
    "unknown coordinate": (
        SLIDER_CRANK,
        'coordinate = "theta"',
        'coordinate = "phi"',
        "drivers[0].coordinate: unknown value 'phi'; expected one of x, y, theta",
    ),
    "string for a number": (
        SLIDER_CRANK,
        "mass = 0.2\n",
        'mass = "heavy"\n',
        "bodies[0].mass: expected a number, got string 'heavy'",
    ),
    "float for an integer": (
        SLIDER_CRANK,
        "steps = 200\n",
        "steps = 200.5\n",
        "steps: expected an integer, got float 200.5",
    ),
    "short pose": (
        SLIDER_CRANK,
        "guess = [0.5866765903072286, 0.0, 0.0]",
        "guess = [0.58, 0.0]",
        "bodies[2].guess: expected 3 numbers, got 2",
    ),
    "string in a vector": (
        SLIDER_CRANK,
        'p_j = { body = "slider", local = [0.0, 0.0] }',
        'p_j = { body = "slider", local = [0.0, "a"] }',
        "joints[2].p_j.local[1]: expected a number, got string 'a'",
    ),
    "table expected": (
        SLIDER_CRANK,
        DRIVE,
        "motion = 50.0",
        "drivers[0].motion: expected a table, got float",
    ),
    "boolean expected": (
        GEARS,
        "radius_j = 0.15\n",
        "radius_j = 0.15\ninternal = 1\n",
        "joints[2].internal: expected true or false, got integer 1",
    ),
    "negative mass": (
        SLIDER_CRANK,
        "mass = 0.2\n",
        "mass = -0.2\n",
        "bodies[0].mass: must be a positive number, got -0.2",
    ),
    "zero end time": (
        SLIDER_CRANK,
        "t_end = 0.12566370614359174\n",
        "t_end = 0.0\n",
        "t_end: must be a positive number",
    ),
    "infinite value": (
        SLIDER_CRANK,
        DRIVE,
        DRIVE.replace("50.0", "inf"),
        "drivers[0].motion.rate: must be finite, got inf",
    ),
    "nan value": (
        SLIDER_CRANK,
        "guess = [0.5866765903072286, 0.0, 0.0]",
        "guess = [nan, 0.0, 0.0]",
        "bodies[2].guess[0]: must be finite",
    ),
    "negative drawing length": (
        SLIDER_CRANK,
        "\nlength = 0.2\n",
        "\nlength = -0.2\n",
        "bodies[0].length: must be a nonnegative number",
    ),
    "zero axis": (
        CAM,
        "axis = [0.0, 1.0]",
        "axis = [0.0, 0.0]",
        "joints[1].axis: must not be the zero vector",
    ),
    "zero roller": (
        CAM,
        "roller_radius = 0.02\nphi",
        "roller_radius = 0.0\nphi",
        "joints[2].roller_radius: must be a positive number",
    ),
    "disc eccentricity beyond radius": (
        CAM,
        ROLLER,
        ROLLER.replace("0.01", "0.06"),
        "joints[2].profile.eccentricity: must be below the radius 0.05, got 0.06",
    ),
    "lobes not an integer": (
        CAM,
        ROLLER,
        'profile = { kind = "lobed", radius = 0.05, amplitude = 0.01, lobes = 2.5 }',
        "joints[2].profile.lobes: expected an integer, got float 2.5",
    ),
    "non-positive spline radius": (
        CAM,
        ROLLER,
        'profile = { kind = "spline", table = [0.05, 0.0, 0.05, 0.04] }',
        "joints[2].profile.table: radii must be positive",
    ),
    "duplicate body": (
        SLIDER_CRANK,
        'name = "rod"',
        'name = "crank"',
        "bodies[1].name: 'crank' is already taken",
    ),
    "body called ground": (
        SLIDER_CRANK,
        'name = "slider"',
        'name = "ground"',
        "bodies[2].name: 'ground' is already taken",
    ),
    "duplicate constraint name": (
        SLIDER_CRANK,
        'name = "crank_drive"',
        'name = "slide"',
        "drivers[0].name: 'slide' names another constraint already",
    ),
    "joint to itself": (
        SLIDER_CRANK,
        'p_j = { body = "rod", local = [-0.2, 0.0] }',
        'p_j = { body = "crank", local = [-0.2, 0.0] }',
        "joints[1].p_j.body: joins body 'crank' to itself",
    ),
    "tabulated times not increasing": (
        SLIDER_CRANK,
        DRIVE,
        'motion = { kind = "tabulated", times = [0.0, 1.0, 1.0, 2.0], values = [0.0, 1.0, 2.0, 3.0] }',
        "drivers[0].motion.times: must increase strictly",
    ),
    "tabulated values and times differ in length": (
        SLIDER_CRANK,
        DRIVE,
        TABULATED + ", values = [0.0, 1.0, 2.0, 3.0] }",
        "drivers[0].motion.values: has 4 entries for 3 times",
    ),
    "periodic law that does not close": (
        SLIDER_CRANK,
        DRIVE,
        TABULATED + ', values = [0.0, 1.0, 0.5], ends = "periodic" }',
        "drivers[0].motion.values: a periodic law must end where it starts",
    ),
    "unknown spline end condition": (
        SLIDER_CRANK,
        DRIVE,
        TABULATED + ', values = [0.0, 1.0, 0.0], ends = "natural" }',
        "drivers[0].motion.ends: unknown value 'natural'",
    ),
    "missing profile csv": (
        CAM,
        ROLLER,
        'profile = { kind = "spline", csv = "nowhere.csv" }',
        "joints[2].profile.csv: cannot read ",
    ),
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
    for base in (SLIDER_CRANK, CAM, GEARS):
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
    assert read_scenario(tmp_path / "cam.toml") == spline


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
