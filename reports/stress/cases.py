"""The stress suite's cases: what each stress variant probes and what it needs to be judged.

Each case names a scenario (a `stress...` variant of a family, or a nominal scenario it is compared
with) and declares:
- `probes`: what it stresses, in a few words (shown in the stability map);
- `singular`: the closed-form time of its first singular configuration, where it has one;
- `similar`: the nominal scenario it is an exact similarity of (lengths scaled by `length`, time run
  `speed` times faster), against whose errors the map sets its errors (its truth, like every
  family mechanism's, is the closed form: reports.stress.truth);
- `refine`: the truth is solved on a grid this many times finer (near-singular cases, where the
  solver's predictor could jump to another branch on the scenario's own grid);
- `settings`: each engine's settings for the case (the first is the default), or None for the
  engine's own default; what an engine runs for a probe is the engine's to say (probing);
- `drift`: a long horizon, whose report compares the first and the last revolution.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

from adapters.base import Adapter, Setting
from adapters.probes import MASS, STIFFNESS, Probe
from adapters.step_rule import at_step
from scenarios import build
from scenarios.scenario import Scenario

Settings = Callable[[Scenario, Adapter], list[Setting] | None]
NOMINAL_SPEED = 50.0
"""The nominal slider-crank's crank speed (rad/s), against which the speed cases are scaled."""


@dataclass(frozen=True)
class Similar:
    """The case is `nominal` at time speed * t, lengths times `length`."""

    nominal: str
    length: float = 1.0
    speed: float = 1.0


@dataclass(frozen=True)
class StressCase:
    name: str
    probes: str
    singular: Callable[[Scenario], float] | None = None
    similar: Similar | None = None
    refine: int = 1
    settings: Settings | None = None
    drift: bool = False

    def singular_time(self) -> float | None:
        return None if self.singular is None else self.singular(build(self.name))


def _p(s: Scenario, *names: str) -> list[float]:
    return [float(s.parameter(n)) for n in names]


def dead_centre(s: Scenario) -> float:
    """x = mean + half sin(omega t) reaches the outer dead centre when f sin(omega t) = 1."""
    fraction, omega = _p(s, "stroke_fraction", "omega")
    return math.asin(1.0 / fraction) / abs(omega)


def crank_at_right_angle(s: Scenario) -> float:
    """Crank and rod of equal length, no offset: cos th3 = 0 when th2 reaches pi / 2."""
    theta0, omega = _p(s, "theta0", "omega")
    return (math.pi / 2 - theta0) / omega


def aligned(s: Scenario) -> float:
    """The change-point four-bar with g + a = b + c lines up when the crank points back, th2 = pi."""
    theta0, omega = _p(s, "theta0", "omega")
    return (math.pi - theta0) / omega


def toggle(s: Scenario) -> float:
    """Coupler and rocker stretch into line when |A - O4| = b + c."""
    g, a, b, c, theta0, omega = _p(
        s, "ground_length", "crank_length", "coupler_length", "rocker_length", "theta0", "omega"
    )
    return (math.acos((a * a + g * g - (b + c) ** 2) / (2 * a * g)) - theta0) / omega


def per_revolution(speed: float) -> Settings:
    """Each engine at its nominal steps per revolution: a time step (and MuJoCo's time constant) of
    its default on the nominal scenario stretched by the speed ratio (the rule's default step,
    adapters.step_rule, does the same)."""

    def settings(scenario: Scenario, adapter: Adapter) -> list[Setting] | None:
        nominal = adapter.default_setting(build("slider_crank"))
        dt = nominal.get("dt")
        return None if dt is None else [at_step(nominal, float(dt) * NOMINAL_SPEED / speed)]

    return settings


def probing(probe: Probe) -> Settings:
    """Each engine's own settings for a case that probes `probe` (Adapter.probe_settings): the
    constraint stiffness against the step, or the masses; None keeps the engine's default."""

    def settings(scenario: Scenario, adapter: Adapter) -> list[Setting] | None:
        return adapter.probe_settings(probe, scenario)

    return settings


def _cases() -> tuple[StressCase, ...]:
    """The stress suite's cases in the order the report shows them: a table of data, long because
    there are 32 cases, not because it decides anything."""
    speeds = [(1e-3, "1e-3"), (1e-1, "1e-1"), (1e1, "1e1"), (1e3, "1e3"), (1e4, "1e4")]
    fixed = [(1e-3, "1e-3"), (1e2, "1e2"), (1e3, "1e3"), (1e4, "1e4")]
    scales = [(1e-4, "1e-4"), (1e-2, "1e-2"), (1e1, "1e1"), (1e3, "1e3")]
    sc = "slider_crank"
    return (
        StressCase(sc, "nominal slider-crank (the scale and speed cases' reference point)"),
        StressCase(
            "four_bar", "nominal four-bar (the mass-ratio cases' reference point)", settings=probing(MASS)
        ),
        StressCase(f"{sc}/stress_dead_centre", "slider-driven through the outer dead centre", dead_centre),
        StressCase(f"{sc}/stress_equal_links", "crank = rod, through th2 = pi/2", crank_at_right_angle),
        StressCase(
            "four_bar/stress_change_point", "change-point four-bar through its aligned position", aligned
        ),
        StressCase("four_bar/stress_toggle", "crank driven into the coupler-rocker toggle", toggle),
        StressCase(
            "four_bar/stress_near_change_point",
            "1e-6 m short of a change point: the branches pass 1e-6 apart",
            refine=4,
        ),
        *(
            StressCase(
                f"{sc}/stress_speed_{label}",
                f"crank at {label} rad/s, 200 steps per revolution",
                similar=Similar(sc, speed=w / NOMINAL_SPEED),
                settings=per_revolution(w),
            )
            for w, label in speeds
        ),
        *(
            StressCase(
                f"{sc}/stress_fixed_step_{label}",
                f"crank at {label} rad/s, the nominal grid step 6.3e-4 s",
                similar=Similar(sc, speed=w / NOMINAL_SPEED),
            )
            for w, label in fixed
        ),
        *(
            StressCase(
                f"{sc}/stress_scale_{label}",
                f"the nominal mechanism scaled to a {label} m crank",
                similar=Similar(sc, length=s / 0.2),
            )
            for s, label in scales
        ),
        StressCase(f"{sc}/stress_link_ratio_1e-3", "crank 1e-3 of the rod"),
        StressCase("four_bar/stress_link_ratio_1e-3", "crank 1e-3 of the other links"),
        StressCase("spur_gears/stress_ratio_1000", "gear ratio 1:1000"),
        StressCase("four_bar/stress_mass_1e3", "coupler 1e3 times heavier", settings=probing(MASS)),
        StressCase("four_bar/stress_mass_1e6", "coupler 1e6 times heavier", settings=probing(MASS)),
        StressCase(f"{sc}/stress_long", "1000 revolutions at 20 steps per revolution", drift=True),
        StressCase(
            f"{sc}/stress_stiffness", "constraint stiffness against the step", settings=probing(STIFFNESS)
        ),
        StressCase("cam_knife_edge/stress_steep", "eccentric disc, pressure angle up to 64 deg"),
        StressCase("cam_roller/stress_steep", "eccentric disc, pressure angle up to 35 deg"),
        StressCase("cam_knife_edge/stress_few_knots", "spline profile through 6 knots"),
        StressCase("cam_roller/stress_few_knots", "spline profile through 6 knots"),
        StressCase(
            "cam_roller/stress_undercut",
            "roller radius 0.95 of the lobed cam's smallest concave radius of curvature",
            refine=4,
        ),
    )


CASES: dict[str, StressCase] = {case.name: case for case in _cases()}


def case(name: str) -> StressCase:
    """The declaration of scenario `name` (a bare one for a scenario the catalogue does not list)."""
    return CASES.get(name, StressCase(name, ""))


def scenario_names() -> list[str]:
    return list(CASES)


def stress_settings(scenario: Scenario, adapter: Adapter) -> list[Setting] | None:
    """The settings hook of the stress suite (see reports.suites)."""
    settings = case(scenario.name).settings
    return None if settings is None else settings(scenario, adapter)
