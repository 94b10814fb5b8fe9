"""The documentation's measured figures are the tests' measured figures: each figure below is stated
on its page exactly as the table that the engine's test holds two-sided (tests.support.measured)
gives it, so neither the code nor the docs can drift from the other without a failure."""

from __future__ import annotations

import pytest

from tests.support.doc_pages import figure, page_text, triple
from tests.support.measured import (
    A02_SPEC,
    DYNAMIC_DEFAULTS,
    EXUDYN_FORCES,
    FLOORS,
    KINEMATIC_DEFAULTS,
    MUJOCO_FORCES,
)

ENGINE_PAGES = {engine: f"engines/{engine}.md" for engine in ("mujoco", "exudyn", "pinocchio")}


def stated() -> list[tuple[str, str, str]]:
    """(what, the page, the words the page must contain)."""
    out = []
    for (name, engine), values in DYNAMIC_DEFAULTS.items():
        label = "the 9-link compound pendulum" if name == "compound_pendulum" else name
        out.append((f"{engine} default on {name}", ENGINE_PAGES[engine], f"{label} {triple(values)}"))
    for name in ("slider_crank", "four_bar"):
        words = f"{name.replace('_', '-')} {figure(KINEMATIC_DEFAULTS[(name, 'mujoco')][2])}"
        out.append((f"mujoco default on {name}", ENGINE_PAGES["mujoco"], words))
    acceleration = figure(KINEMATIC_DEFAULTS[("slider_crank", "exudyn")][2])
    floor = figure(FLOORS[("slider_crank", "exudyn")][2])
    out.append(
        ("exudyn on the slider-crank", ENGINE_PAGES["exudyn"], f"slider-crank {acceleration} at 2000 steps")
    )
    out.append(("exudyn floor on the slider-crank", ENGINE_PAGES["exudyn"], f"{floor} at 20000"))
    mujoco_floor = figure(FLOORS[("slider_crank", "mujoco")][2])
    out.append(("mujoco floor on the slider-crank", ENGINE_PAGES["mujoco"], f"slider-crank {mujoco_floor}"))
    pinocchio_floor = figure(FLOORS[("andrews_squeezer", "pinocchio")][2])
    out.append(("pinocchio floor on andrews_squeezer", ENGINE_PAGES["pinocchio"], f"best {pinocchio_floor}"))
    crank, four_bar = MUJOCO_FORCES["slider_crank"], MUJOCO_FORCES["four_bar"]  # (default, own regulariser)
    out.append(
        (
            "mujoco forces",
            ENGINE_PAGES["mujoco"],
            f"slider-crank {figure(crank[0])}, four-bar {figure(four_bar[0])}; with MuJoCo's own regulariser "
            f"(time constant 4 steps) {figure(crank[1])} and {figure(four_bar[1])}",
        )
    )
    ga3, tr2 = (
        [EXUDYN_FORCES[(name, mode)] for name in ("slider_crank", "four_bar")] for mode in ("GA3", "TR2")
    )
    out.append(
        (
            "exudyn forces",
            ENGINE_PAGES["exudyn"],
            "slider-crank {}, four-bar {}; TR2 at the same step gives {} and {}".format(
                *map(figure, (*ga3, *tr2))
            ),
        )
    )
    for name in ("slider_crank", "four_bar"):
        label = name.replace("_", "-")
        out.append(
            (
                f"forces at the defaults on {name}",
                "dynamics.md",
                f"{label} MuJoCo {figure(MUJOCO_FORCES[name][0])}, Exudyn GA3 "
                f"{figure(EXUDYN_FORCES[(name, 'GA3')])}",
            )
        )
    energy, rockers, crank_angle = A02_SPEC
    out.append(
        (
            "A02 as specified at h = 2e-5",
            "dynamics.md",
            f"| {figure(energy)} | {figure(rockers)} rad at a passage (6.4e-12 to {figure(rockers)} over "
            f"the 20; 2.5e-13 elsewhere) | {figure(crank_angle)} rad |",
        )
    )
    return out


@pytest.mark.parametrize(("what", "page", "words"), stated(), ids=[what for what, _, _ in stated()])
def test_the_docs_state_the_measured_figure(what: str, page: str, words: str) -> None:
    assert words in page_text(page), f"docs/{page} does not say '{words}' ({what}, from the test's table)"
