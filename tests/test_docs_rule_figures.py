"""docs/settings-rule.md, docs/a02.md and the MuJoCo page's time-constant sweep state their measured
figures as the tables the engines' tests hold give them (tests.support.rule_figures,
tests.support.measured): each phrase below is made from those tables and must be on its page, so a
page cannot keep a figure the engines no longer give."""

from __future__ import annotations

import math

import pytest

from tests.support import rule_figures as f
from tests.support.doc_pages import figure, page_text, triple
from tests.support.measured import DYNAMIC_DEFAULTS, FLOORS, KINEMATIC_DEFAULTS, MUJOCO_FORCES

RULE, A02 = "settings-rule.md", "a02.md"


def plain(value: float) -> str:
    """A figure near 1 as the pages write it: 0.79, 3."""
    return f"{value:.2f}" if value < 1 else f"{value:.2g}"


def accelerations(table: dict, keys: list) -> list[str]:
    return [figure(table[key][2]) for key in keys]


def mujoco() -> list[tuple[str, str]]:
    own, scaled, free, cam = f.MUJOCO_OWN_TC, f.MUJOCO_SCALED_TC, f.MUJOCO_FREE_TC, f.MUJOCO_SPLINE_CAM
    crank = accelerations(scaled, [("slider_crank", k) for k in (64.0, 128.0, 256.0)])
    four_bar = accelerations(scaled, [("four_bar", k) for k in (64.0, 128.0, 256.0)])
    gravity = accelerations(free, [("four_bar_gravity", k) for k in (128.0, 256.0, 512.0, 1024.0, 2048.0)])
    andrews = accelerations(
        free, [("andrews_squeezer", k) for k in (128.0, 256.0, 512.0, 1024.0, 2048.0, 1e4)]
    )
    singular = f.MUJOCO_SINGULAR_TC
    return [
        (
            "own regulariser",
            f"slider-crank accelerations {figure(own[2.0][2])} at tc = 2 steps, {figure(own[4.0][2])} at 4",
        ),
        (
            "own regulariser past 4 steps",
            f"at 8 steps the slider-crank's positions rise from {figure(own[4.0][0])} to "
            f"{figure(own[8.0][0])}, "
            f"and past 8 its accelerations stop near {figure(own[8.0][2])} to {figure(own[16.0][2])}",
        ),
        (
            "scaled time constants",
            f"tc = 64 / 128 / 256 steps give slider-crank accelerations {' / '.join(crank)} and four-bar "
            f"{' / '.join(four_bar)}",
        ),
        (
            "the default",
            f"accelerations {figure(KINEMATIC_DEFAULTS[('slider_crank', 'mujoco')][2])} (slider-crank) and "
            f"{figure(KINEMATIC_DEFAULTS[('four_bar', 'mujoco')][2])} (four-bar), forces "
            f"{figure(MUJOCO_FORCES['slider_crank'][0])} and {figure(MUJOCO_FORCES['four_bar'][0])}",
        ),
        ("the 1e-6 rung", f"sags to {figure(f.MUJOCO_SINGULAR_SAG)} m"),
        (
            "direct form",
            f"four_bar_gravity {triple(free[('four_bar_gravity', 128.0)])} in both at 128 steps, "
            f"{triple(free[('four_bar_gravity', 1024.0)])} in both at 1024",
        ),
        (
            "free time constants",
            "four_bar_gravity {} at 128 steps, {} at 256, {} at 512, {} at 1024, {} at 2048; "
            "andrews_squeezer {}, {}, {}, {}, {}, and {} at 1e4".format(*gravity, *andrews),
        ),
        (
            "singular passages",
            f"the accelerations are {figure(singular[1024.0][2])} at 1024 steps, "
            f"{figure(singular[128.0][2])} at 128 (the driven scenes' time constant), "
            f"{figure(singular[64.0][2])} at 64 and "
            f"{figure(singular[32.0][2])} at 32 (positions {figure(singular[32.0][0])})",
        ),
        (
            "singular weights",
            f"brings them to {figure(f.MUJOCO_SINGULAR_WEIGHTS[1e-10][2])} and "
            f"{figure(f.MUJOCO_SINGULAR_WEIGHTS[1e-12][2])} at 1024 steps",
        ),
        ("off its branch", f"(1e-10: positions {plain(f.MUJOCO_OFF_BRANCH)})"),
        (
            "spline cam",
            f"({plain(cam[(512, 4.0)][2])} at the default, relative)",
        ),
        (
            "spline cam filtered",
            f"(16 steps: {plain(cam[(512, 16.0)][2])}, positions {figure(cam[(512, 16.0)][0])}), 2048 facets "
            f"with it {plain(cam[(2048, 16.0)][2])}",
        ),
        (
            "spline cam best",
            f"the default 512 facets at 4 steps {figure(cam[(512, 4.0)][0])} / "
            f"{figure(cam[(512, 4.0)][1])} / "
            f"{plain(cam[(512, 4.0)][2])}): 1024 facets at 8 and 16 steps {plain(cam[(1024, 8.0)][2])} and "
            f"{plain(cam[(1024, 16.0)][2])}; 2048 at 8 and 16 steps {plain(cam[(2048, 8.0)][2])} and "
            f"{plain(cam[(2048, 16.0)][2])}",
        ),
        (
            "spline cam ringing",
            "with {}, {} or {} the follower rings on the vertices (accelerations above {:g})".format(
                *(f"{pieces} facets at {steps:g} steps" for pieces, steps in f.MUJOCO_SPLINE_CAM_RINGING),
                f.RINGING,
            ),
        ),
        (
            "compound pendulum",
            "(the 9-link compound pendulum "
            f"{triple(DYNAMIC_DEFAULTS[('compound_pendulum', 'mujoco')])} with the rule's RK4)",
        ),
        (
            "free dynamics against 128 steps",
            f"accelerations are {figure(DYNAMIC_DEFAULTS[('four_bar_gravity', 'mujoco')][2])} and "
            f"{figure(DYNAMIC_DEFAULTS[('andrews_squeezer', 'mujoco')][2])} by default, against "
            f"{figure(free[('four_bar_gravity', 128.0)][2])} and "
            f"{figure(free[('andrews_squeezer', 128.0)][2])} at the driven scenes' 128 steps",
        ),
        (
            "out of reach",
            f"below about {figure(FLOORS[('slider_crank', 'mujoco')][2])} in accelerations on driven scenes "
            f"(RK4's error on the constraint mode at the ladder's longest time constant, 256 steps) and "
            f"{figure(FLOORS[('four_bar_gravity', 'mujoco')][2])} in free dynamics",
        ),
    ]


def lasts(steps: float) -> str:
    return "no transient" if steps == 0 else f"for {steps:.0f} steps"


def exudyn() -> list[tuple[str, str]]:
    r = f.EXUDYN_REMEDIES
    rows = [
        ("none (ρ∞ 0.9, exact start)", r["none"]),
        ("ρ∞ 0.5", r["rho 0.5"]),
        ("ρ∞ 0.6", r["rho 0.6"]),
        ("ρ∞ 0", (None, *f.EXUDYN_RHO_ZERO)),
        ("ρ∞ 0.99", r["rho 0.99"]),
        ("run-in of 50 steps at ρ∞ 0.9", r["run-in 50"]),
        ("run-in of 200 steps at ρ∞ 0.9", r["run-in 200"]),
        ("run-in of 50 steps at ρ∞ 0.5", r["run-in 50 rho 0.5"]),
        ("run-in of 50 steps at ρ∞ 0.6", r["run-in 50 rho 0.6"]),
        ("run-in of 50 steps at ρ∞ 0", r["run-in 50 rho 0"]),
    ]
    position, acceleration = f.EXUDYN_INDEX_2
    start = f.EXUDYN_EXACT_START
    return [
        *[(label, f"| {label} | {figure(a)}, {lasts(steps)} |") for label, (_, a, steps) in rows],
        ("index 2", f"| {figure(acceleration)}, no transient | positions drift, {figure(position)} |"),
        (
            "settled",
            "largest acceleration error; settled error "
            f"{figure(KINEMATIC_DEFAULTS[('four_bar', 'exudyn')][2])})",
        ),
        ("run-in", f"({f.EXUDYN_RUN_IN_STEPS})"),
        (
            "free excess",
            f"(start-up excess {plain(f.EXUDYN_FREE_EXCESS['four_bar_gravity'])} on `four_bar_gravity`, "
            f"{plain(f.EXUDYN_FREE_EXCESS['andrews_squeezer'])} on `andrews_squeezer`)",
        ),
        ("spline knots", f"(cam_roller/spline {figure(f.EXUDYN_SPLINE_KNOTS)})"),
        (
            "exact start",
            ", ".join(
                f"`{name}` {excess:.0f} for {figure(time)} s" for name, (excess, time) in start.items()
            ),
        ),
        (
            "the floor",
            f"(slider-crank {figure(KINEMATIC_DEFAULTS[('slider_crank', 'exudyn')][2])} at 2000 steps "
            "per period, "
            f"{figure(FLOORS[('slider_crank', 'exudyn')][2])} at 20000)",
        ),
    ]


def a02() -> list[tuple[str, str]]:
    def step(bodies: int) -> str:
        """The rule's step for a chain of `bodies` links of 1 m, three digits."""
        mantissa, exponent = f"{2 * math.pi / (2 * math.sqrt(bodies * 9.81)) / 1000:.2e}".split("e")
        return f"{mantissa}e{int(exponent)}"

    labels = {
        ("n_four_bar", None): f"N = 2, 10 s | {step(5)} s (default)",
        ("n_four_bar", 1e-4): "N = 2, 10 s | 1e-4 s",
        ("n_four_bar", 1e-3): "N = 2, 10 s | 1e-3 s",
        ("n_four_bar/spec", None): f"N = 40, 20 s | {step(81)} s (default)",
    }
    out = [
        ("steps", f"{step(5)} s for N = 2, {step(81)} s for N = 40"),
        ("rockers", f"at round-off in every case, below {f.A02_ROCKERS:g} rad"),
    ]
    for key, (benchmark, energy) in f.A02_TABLE.items():
        fails = " (fails 1e-3)" if benchmark > 1e-3 else ""
        out.append((str(key), f"| {labels[key]} | {figure(benchmark)}{fails} | {figure(energy)} |"))
    return out


def mujoco_page() -> list[tuple[str, str]]:
    free = f.MUJOCO_FREE_TC
    return [
        (
            "free dynamics at 128 steps",
            f"128 steps {figure(free[('four_bar_gravity', 128.0)][2])} and "
            f"{figure(free[('andrews_squeezer', 128.0)][2])} in accelerations",
        )
    ]


STATED = (
    [(RULE, *p) for p in mujoco() + exudyn()]
    + [(A02, *p) for p in a02()]
    + [("engines/mujoco.md", *p) for p in mujoco_page()]
)


@pytest.mark.parametrize(("page", "what", "words"), STATED, ids=[f"{p}:{w}" for p, w, _ in STATED])
def test_the_page_states_the_held_figure(page: str, what: str, words: str) -> None:
    assert words in page_text(page), f"docs/{page} does not say '{words}' ({what})"


def test_the_settings_rule_states_no_timing() -> None:
    """CPU times are noisy and belong to generated pages (engine-accuracy.md, performance.md)."""
    assert "µs" not in page_text(RULE)
