"""The README's measured figures are the tests' measured figures: each figure below is stated in the
README exactly as the table of the test that holds it (two-sided, tests.support.bounds) gives it,
so neither the code nor the README can drift from the other without a failure."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from tests.adapters import test_defaults_and_floors as defaults
from tests.adapters.exudyn import test_forces as exudyn_forces
from tests.adapters.mujoco import test_forces as mujoco_forces
from tests.reference_solver.dynamics import test_ali3p as ali3p

README = Path(__file__).resolve().parent.parent / "README.md"


def figure(value: float) -> str:
    """A figure as the README writes it: two digits, no padded exponent (7.9e-8)."""
    mantissa, exponent = f"{value:.1e}".split("e")
    return f"{mantissa}e{int(exponent)}"


def triple(values: tuple[float, ...]) -> str:
    return " / ".join(figure(v) for v in values)


def readme_text() -> str:
    return re.sub(r"\s+", " ", README.read_text(encoding="utf-8"))


def stated() -> list[tuple[str, str]]:
    """(what, the words the README must contain)."""
    out = []
    pendulum = "the 9-link compound pendulum"
    for (name, engine), values in defaults.DYNAMIC_DEFAULTS.items():
        label = pendulum if name == "compound_pendulum" else name
        out.append((f"{engine} default on {name}", f"{label} {triple(values)}"))
    for name, values in defaults.KINEMATIC_DEFAULTS.items():
        if name == ("slider_crank", "exudyn"):
            out.append(
                ("exudyn default on the slider-crank", f"slider-crank {figure(values[2])} at 2000 steps")
            )
    out.append(
        (
            "exudyn floor on the slider-crank",
            f"{figure(defaults.FLOORS[('slider_crank', 'exudyn')][2])} at 20000",
        )
    )
    out.append(
        (
            "mujoco floor on the slider-crank",
            f"slider-crank {figure(defaults.FLOORS[('slider_crank', 'mujoco')][2])}",
        )
    )
    out.append(
        (
            "pinocchio floor on andrews_squeezer",
            f"best {figure(defaults.FLOORS[('andrews_squeezer', 'pinocchio')][2])}",
        )
    )
    mujoco = mujoco_forces.MEASURED
    exudyn = exudyn_forces.MEASURED
    out.append(
        (
            "forces at the defaults",
            f"slider-crank MuJoCo {figure(mujoco['slider_crank'][0])}, Exudyn GA3 "
            f"{figure(exudyn[('slider_crank', 'GA3')])}",
        )
    )
    out.append(
        (
            "four-bar forces at the defaults",
            f"four-bar MuJoCo {figure(mujoco['four_bar'][0])}, Exudyn GA3 "
            f"{figure(exudyn[('four_bar', 'GA3')])}",
        )
    )
    out.append(
        (
            "Exudyn TR2 forces",
            f"gives {figure(exudyn[('slider_crank', 'TR2')])} and {figure(exudyn[('four_bar', 'TR2')])}",
        )
    )
    out.append(
        (
            "MuJoCo forces with its own regulariser",
            f"4 steps) {figure(mujoco['slider_crank'][1])} and {figure(mujoco['four_bar'][1])}",
        )
    )
    energy, rockers, crank = ali3p.A02_SPEC
    out.append(
        (
            "A02 as specified at h = 2e-5",
            f"| {figure(energy)} | {figure(rockers)} rad at a passage (6.4e-12 to {figure(rockers)} over "
            f"the 20; 2.5e-13 elsewhere) | {figure(crank)} rad |",
        )
    )
    return out


@pytest.mark.parametrize(("what", "words"), stated(), ids=[what for what, _ in stated()])
def test_the_readme_states_the_measured_figure(what: str, words: str) -> None:
    assert words in readme_text(), f"README does not say '{words}' ({what}, from the test's table)"
