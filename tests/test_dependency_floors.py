"""The floors pyproject.toml declares are the versions CI's oldest-versions step installs: every
package `.ci/oldest.txt` pins `==` and pyproject lists must carry that version as its `>=` floor,
and the engines and numerics whose floors the project claims must all be pinned there."""

from __future__ import annotations

import re
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
CLAIMED = ("mujoco", "exudyn", "pin", "numpy", "scipy", "pandas")
REQUIREMENT = re.compile(r"^\s*([A-Za-z0-9_.-]+)\s*(?:\[[^\]]*\])?\s*(==|>=)\s*([^\s,;#]+)")


def canonical(name: str) -> str:
    """PEP 503 name, so `Foo_Bar` and `foo-bar` compare equal."""
    return re.sub(r"[-_.]+", "-", name).lower()


def parsed(lines: list[str], operator: str) -> dict[str, str]:
    """Package -> version for each requirement written with `operator` (other lines are skipped)."""
    found = {}
    for line in lines:
        match = REQUIREMENT.match(line)
        if match and match.group(2) == operator:
            found[canonical(match.group(1))] = match.group(3)
    return found


def pyproject_floors() -> dict[str, str]:
    project = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]
    return parsed(project["dependencies"], ">=")


def oldest_pins() -> dict[str, str]:
    lines = (ROOT / ".ci" / "oldest.txt").read_text().splitlines()
    return parsed([line for line in lines if not line.lstrip().startswith("#")], "==")


def test_every_pinned_dependency_has_its_pin_as_floor() -> None:
    floors, pins = pyproject_floors(), oldest_pins()
    disagree = {
        name: (floors[name], pin) for name, pin in pins.items() if name in floors and floors[name] != pin
    }
    assert not disagree, f"pyproject floor != .ci/oldest.txt pin (floor, pin): {disagree}"


def test_the_claimed_floors_are_pinned() -> None:
    floors, pins = pyproject_floors(), oldest_pins()
    assert all(name in floors for name in CLAIMED), sorted(set(CLAIMED) - set(floors))
    assert all(name in pins for name in CLAIMED), sorted(set(CLAIMED) - set(pins))


def test_the_parser_reads_what_the_test_compares() -> None:
    lines = ["Foo_Bar >= 1.2 ; python_version > '3'", "dask[distributed]>=2024.1", "baz==3.0", "qux"]
    assert parsed(lines, ">=") == {"foo-bar": "1.2", "dask": "2024.1"}
    assert parsed(lines, "==") == {"baz": "3.0"}
