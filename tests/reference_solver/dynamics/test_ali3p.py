"""ALI3-P, the second native forward-dynamics method: the same motion as the partitioned method where
that one works (second order in the step, so halving the step divides its distance by 4 and the
Richardson combination of the two agrees far closer), and IFToMM A02 through its singular passages,
judged against the chain's own one-degree-of-freedom equation (every rocker turns with the crank,
couplers translate: I theta'' = -c cos theta, I = (N + 1)/3 + N, c = g ((N + 1)/2 + N) for links
of 1 m and 1 kg), which also gives the passage times (theta a multiple of pi)."""

from __future__ import annotations

import re
from dataclasses import replace

import numpy as np
import pytest

import scenarios
from reference_solver.compiled_system import constraint_system
from reference_solver.dynamics import DynamicAnalysis, ali3p, ali3p_grid, simulate, tangent
from reference_solver.dynamics.ali3p import PENALTY, Ali3p, StepState
from reference_solver.dynamics.forward import initial_state
from reference_solver.dynamics.loads import Loads
from reference_solver.dynamics.mass import mass_diagonal
from reference_solver.errors import ConvergenceError, SolverError
from scenarios import Point
from scenarios.drivers import AbsoluteDriver
from scenarios.forces import AppliedTorque, RotationalSpringDamper, SpringDamper
from scenarios.joints import Revolute
from scenarios.motions import ConstantSpeed
from tests.support.a02_chain import FACTOR, a02_chain, a02_errors, steps_alike_in_metres_and_kilometres
from tests.support.measured import A02_SPEC

SHORT = {
    # scenario: (t_end, steps, step h), and the measured distance to the partitioned method at h/2
    # per level (positions over the characteristic length, rates in SI, multipliers over their
    # largest); the distances of the Richardson combination (4 x_{h/2} - x_h) / 3 are all far smaller
    "four_bar_gravity": (0.1, 2, 2.5e-4, (9.12e-07, 4.87e-07, 2.38e-05, 3.89e-08)),
    "compound_pendulum": (0.2, 2, 5e-4, (3.77e-07, 7.04e-07, 2.06e-05, 1.96e-07)),
    "slider_crank_spring": (0.05, 2, 2.5e-4, (1.13e-05, 3.38e-05, 1.97e-03, 1.37e-06)),
    "andrews_squeezer": (0.0005, 1, 5e-6, (1.49e-08, 8.50e-07, 9.42e-05, 1.49e-10)),
}
RICHARDSON = {
    "four_bar_gravity": (1.08e-09, 1.23e-09, 3.93e-08, 4.48e-09),
    "compound_pendulum": (1.29e-10, 8.00e-10, 1.05e-08, 1.54e-09),
    "slider_crank_spring": (8.21e-09, 1.22e-07, 4.87e-06, 2.40e-09),
    "andrews_squeezer": (4.38e-13, 1.16e-10, 3.84e-06, 1.15e-12),
}
ORDER_WINDOW = np.array([0.1, 0.1, 0.1, 0.15])
"""How far the observed order may be from 2 per level. The output multipliers carry the projection's
round-off, alpha times that of C_q x (dynamics.projection: PENALTY EPSILON, about 4e-9 of their
largest on four_bar_gravity, measured as their change when C's rows changed their order of
summation), a tenth of their distance at h/2 there: order 2.10 measured, 2.01 before that change."""
A02_REDUCED = (8.58e-08, 5.44e-13, 4.55e-08)
"""2 loops over 0.8 s (one passage) at h = 1e-4: energy drift over the largest kinetic energy, the
largest rocker-to-crank angle, the crank's distance to the reduced equation (rad)."""


def _distances(
    scenario: scenarios.Scenario, ref: DynamicAnalysis, levels: tuple[np.ndarray, ...]
) -> np.ndarray:
    q, qd, qdd, lam = levels
    return np.array(
        [
            np.max(np.abs(q - ref.q)) / scenario.characteristic_length,
            np.max(np.abs(qd - ref.qd)),
            np.max(np.abs(qdd - ref.qdd)),
            np.max(np.abs(lam - ref.lam)) / np.max(np.abs(ref.lam)),
        ]
    )


@pytest.mark.parametrize("name", sorted(SHORT))
def test_the_same_motion_as_the_partitioned_method_to_second_order(name: str) -> None:
    t_end, steps, h, measured = SHORT[name]
    scenario = scenarios.build(name, overrides={"t_end": t_end, "steps": steps})
    ref = simulate(scenario, rtol=1e-12, compiled=True)
    coarse = simulate(scenario, method="ali3p", step=h, compiled=True)
    fine = simulate(scenario, method="ali3p", step=h / 2, compiled=True)
    levels = ("q", "qd", "qdd", "lam")
    far = _distances(scenario, ref, tuple(getattr(coarse, k) for k in levels))
    near = _distances(scenario, ref, tuple(getattr(fine, k) for k in levels))
    order = np.log2(far / near)
    assert np.all(np.abs(order - 2) < ORDER_WINDOW), f"observed order {order}"
    assert np.all(near < FACTOR * np.array(measured)), near
    assert np.all(near > np.array(measured) / FACTOR), near
    extrapolated = tuple((4 * getattr(fine, k) - getattr(coarse, k)) / 3 for k in levels)
    assert np.all(_distances(scenario, ref, extrapolated) < FACTOR * np.array(RICHARDSON[name]))


def test_constraints_hold_to_round_off_and_the_energy_balance_closes_to_second_order() -> None:
    scenario = scenarios.build("slider_crank_spring", overrides={"t_end": 0.05, "steps": 2})
    balances = []
    for h in (2.5e-4, 1.25e-4):
        analysis = simulate(scenario, method="ali3p", step=h, compiled=True)
        assert np.max(analysis.motion.residual) < 1e-14
        balances.append(np.max(np.abs(analysis.extras["energy.balance"])))
    assert 3.6 < balances[0] / balances[1] < 4.4, balances


def test_a_reduced_a02_passes_its_singular_position_at_second_order() -> None:
    scenario, grid, reduced = a02_chain(2, 0.8)
    assert len(reduced.t_events[0]) == 1  # type: ignore[attr-defined]
    coarse = a02_errors(simulate(scenario, grid, method="ali3p", step=2e-4, compiled=True), reduced)
    fine = a02_errors(simulate(scenario, grid, method="ali3p", step=1e-4, compiled=True), reduced)
    order = np.log2(np.array(coarse[::2]) / np.array(fine[::2]))  # energy drift and crank angle
    assert np.all((order > 1.8) & (order < 2.3)), order
    measured = np.array(A02_REDUCED)
    assert np.all((np.array(fine) < FACTOR * measured) & (np.array(fine) > measured / FACTOR)), fine


@pytest.mark.parametrize(
    ("count", "plain", "compiled"), [(8000, 6.05e-13, 5.44e-13), (8005, 3.60e-9, 7.19e-12)]
)
def test_the_rockers_leave_the_crank_by_what_the_step_s_phase_at_the_passage_allows(
    count: int, plain: float, compiled: float, monkeypatch: pytest.MonkeyPatch
) -> None:
    """The rocker-to-crank angle is not a smooth function of h: it depends on where the singular
    instant falls within a step. 8000 steps over 0.8 s put it at 0.55 of a step, 8005 steps at 0.02
    (a step ends next to the singular configuration, where C_q holds the chain's extra freedoms only
    to second order). The plain step stops there at its stalled augmented Lagrangian: measured
    6.0e-13 and 3.6e-9 (before C's rows summed positions apart, 1.4e-12 and 3.6e-9). The compiled
    step continues through the Schur complement (compiled.ali3p_kernel): measured 5.4e-13 and 7.2e-12
    (2.2e-12 and 1.0e-10 before)."""
    scenario, grid, reduced = a02_chain(2, 0.8)
    step = 0.8 / count * (1 + 1e-9)
    analysis = simulate(scenario, grid, method="ali3p", step=step, compiled=True)
    assert compiled / FACTOR < a02_errors(analysis, reduced)[1] < FACTOR * compiled
    monkeypatch.setattr(ali3p_grid, "ali3p_stepper", Ali3p)  # the plain step on the same rows
    analysis = simulate(scenario, grid, method="ali3p", step=step, compiled=True)
    assert plain / FACTOR < a02_errors(analysis, reduced)[1] < FACTOR * plain


def test_unknown_method_and_bad_step_are_refused() -> None:
    scenario = scenarios.build("compound_pendulum", overrides={"t_end": 0.01, "steps": 1})
    with pytest.raises(SolverError, match="ali3p"):
        simulate(scenario, method="ali3")
    with pytest.raises(SolverError, match="positive"):
        simulate(scenario, method="ali3p", step=0.0)


def _stepper(scenario: scenarios.Scenario, h: float) -> tuple[Ali3p, StepState]:
    """The plain step of `scenario` at h and its initial state."""
    system = constraint_system(scenario, compiled=False)
    mass = mass_diagonal(scenario, system.layout)
    loads = Loads(scenario, system.layout, mass)
    start = initial_state(system, mass, loads, 0.0)
    stepper = Ali3p(system, mass, loads, h)
    return stepper, StepState(start.t, start.q, start.qd, start.qdd, start.lam.copy(), start.jac)


SPRING, TORSION, TORSION_DAMPING, DAMPING = 50.0, 7.0, 0.5, 3.0
BODY_MASS, BODY_INERTIA = 2.0, 0.1


def _sprung_body(damping: float, torque: bool = False, scale: float = 1.0) -> scenarios.Scenario:
    """A free body at (0.3, 0.4, 0.2), turning at 0.5 rad/s, held by a spring of free length 0 from
    the ground's origin to its centre (force -k r: linear; a damper c along the line) and a torsion
    spring-damper to the ground (T = -k_t theta - c_t omega); no gravity. `torque` adds a torque
    0.2 + t (time-dependent, the same at every q and q'). `scale` is the unit of length: the centre at
    (0.3, 0.4) scale, the characteristic length scale."""
    body = scenarios.Body(
        "b", (0.3 * scale, 0.4 * scale, 0.2), mass=BODY_MASS, inertia=BODY_INERTIA, rate=(0.0, 0.0, 0.5)
    )
    forces = (
        SpringDamper("s", Point("ground"), Point("b"), SPRING, damping),
        RotationalSpringDamper("t", "ground", "b", TORSION, TORSION_DAMPING),
        *((AppliedTorque("motor", "b", ConstantSpeed(0.2, 1.0)),) if torque else ()),
    )
    return scenarios.Scenario(
        "sprung", "default", (body,), (), (), 1.0, 10, scale, forces=forces, analysis="dynamic"
    )


@pytest.mark.parametrize("scale", [1.0, 1e3])
def test_the_tangent_s_stiffness_and_damping_are_the_force_elements_derivatives(scale: float) -> None:
    """K = -dQ_e/dq = diag(k, k, k_t) (the damper's direction moves with r, but the body's centre is
    at rest, so its force does not change); D = -dQ_e/dq' = c e e^T with e = (0.6, 0.8), and c_t;
    and P = M + h/2 D + h^2/4 K, the weight of the projections, at the predictor: r (1 - h^2 k / 2m)
    moving at v = -h k r / m, both along e, where the damper's force -c (e . v) e turns with e and
    adds c (e . v) (I - e e^T) / l to K. In metres and in a unit of 1 km: the differences' steps are
    relative to the column scales (absolute steps of 1e-10 would lose a km-sized Q_e's digits)."""
    h = 0.01
    stepper, start = _stepper(_sprung_body(DAMPING, torque=True, scale=scale), h)
    stiffness, damping = stepper._load_derivatives(start.q, start.qd, 0.3)
    e = np.array([0.6, 0.8])
    k_expected = np.diag([SPRING, SPRING, TORSION])
    d_expected = np.zeros((3, 3))
    d_expected[:2, :2], d_expected[2, 2] = DAMPING * np.outer(e, e), TORSION_DAMPING
    np.testing.assert_allclose(stiffness, k_expected, rtol=0, atol=1e-6)
    np.testing.assert_allclose(damping, d_expected, rtol=0, atol=1e-7)
    stepper.step(start)
    r = np.array([0.3, 0.4]) * scale
    length = float(np.hypot(*r)) * (1 - h * h * SPRING / (2 * BODY_MASS))
    rate = float(e @ (-h * SPRING * r / BODY_MASS))
    k_expected[:2, :2] += DAMPING * rate * (np.eye(2) - np.outer(e, e)) / length
    weight = np.diag([BODY_MASS, BODY_MASS, BODY_INERTIA]) + h / 2 * d_expected + h * h / 4 * k_expected
    np.testing.assert_allclose(stepper.weight, weight, rtol=0, atol=1e-9)
    x = np.array([1.0, -2.0, 3.0])
    np.testing.assert_allclose(stepper.weigh(x), weight @ x, rtol=0, atol=1e-8)


def test_a_step_of_a_linear_oscillator_is_the_trapezoidal_rule_s() -> None:
    """Without the translational damper every coordinate is a linear oscillator m x'' = -k x - c x',
    and the trapezoidal rule's step y1 = (I - h/2 A)^-1 (I + h/2 A) y0, y = (x, x'), A = [[0, 1],
    [-k/m, -c/m]], is what ALI3-P's Newton must reach (no constraints, nothing to project); x'' is
    the equation's at the new state."""
    h = 0.01
    stepper, s = _stepper(_sprung_body(0.0), h)
    assert stepper.stiff
    for k, m, c, column in (
        (SPRING, BODY_MASS, 0.0, 0),
        (SPRING, BODY_MASS, 0.0, 1),
        (TORSION, BODY_INERTIA, TORSION_DAMPING, 2),
    ):
        a = np.array([[0.0, 1.0], [-k / m, -c / m]])
        y = np.array([s.q[column], s.qd[column]])
        for _ in range(3):
            y = np.linalg.solve(np.eye(2) - h / 2 * a, (np.eye(2) + h / 2 * a) @ y)
        column_expected = (y[0], y[1], (-k * y[0] - c * y[1]) / m)
        steps = s
        for _ in range(3):
            steps = stepper.step(steps)
        assert steps.t == pytest.approx(3 * h, abs=1e-15)
        got = (steps.q[column], steps.qd[column], steps.qdd[column])
        # the tangent is exact (K and D of linear elements): the first update lands, the second confirms
        assert steps.iterations == 2
        np.testing.assert_allclose(got, column_expected, rtol=0, atol=1e-10)


@pytest.mark.parametrize("mass", [1.0, 1e9])
def test_the_penalties_give_each_row_a_unit_penalty_diagonal(mass: float) -> None:
    """alpha_i = PENALTY 4/h^2 / (C_q M^-1 C_q^T)_ii at the first step's predictor, fixed after;
    for links of 1 kg and of 1e9 kg (row inertias about 1e-9: the floor for vanishing rows, 1e-12
    of the largest, stays below them)."""
    h = 1e-3
    overrides = {"t_end": 0.01, "steps": 2, "link_mass": mass}
    scenario = scenarios.build("compound_pendulum", overrides=overrides)
    stepper, s = _stepper(scenario, h)
    predictor = s.q + h * s.qd + h * h / 2 * s.qdd
    jac = stepper.system.jacobian(predictor, h)
    inertia = np.einsum("ij,j,ij->i", jac, 1 / stepper.mass, jac)
    s = stepper.step(s)
    np.testing.assert_allclose(h * h / 4 * stepper.alpha * inertia, PENALTY, rtol=1e-12)
    first = stepper.alpha.copy()
    stepper.step(s)
    np.testing.assert_array_equal(stepper.alpha, first)


def test_a_step_newton_cannot_finish_is_refused_with_where_and_how_far(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """One Newton iteration allowed: the residual is measured before the update, at the predictor,
    which misses the pendulum's pin by O(h^3), so the step cannot be accepted."""
    scenario = scenarios.build("compound_pendulum", overrides={"t_end": 0.01, "steps": 2})
    stepper, s = _stepper(scenario, 1e-3)
    monkeypatch.setattr(ali3p, "NEWTON_STEPS", 1)
    with pytest.raises(ConvergenceError) as caught:
        stepper.step(s)
    message = str(caught.value)
    assert re.fullmatch(
        r"compound_pendulum: ALI3-P's Newton iteration did not converge at t=0\.001 "
        r"\(update \S+, constraint residual \S+\)",
        message,
    ), message
    violation = float(re.search(r"constraint residual (\S+)\)", message).group(1))  # type: ignore[union-attr]
    assert 0 < violation < 1e-6
    assert caught.value.time == pytest.approx(1e-3, abs=1e-18)
    assert caught.value.q is not None and caught.value.q.shape == s.q.shape


@pytest.mark.parametrize("spring", [False, True])
def test_a_rod_hanging_at_rest_carries_its_weight_at_the_pin(spring: bool) -> None:
    """A rod of mass 2 pinned at its top end, hanging straight down at rest under g = 9.81: the pin's
    multipliers are its weight: C_q^T lambda = Q_e with C = p - (r + A s) (the ground's point first),
    so lambda = (0, m g). With a
    torsion spring-damper at its free angle (no torque at rest) the stiff branch (least squares)
    gives the same."""
    m, g = 2.0, 9.81
    rod = scenarios.Body("rod", (0.0, -0.5, -np.pi / 2), mass=m, inertia=0.2, length=1.0)
    pin = Revolute("pin", Point("ground", (0.0, 0.0)), Point("rod", (-0.5, 0.0)))
    forces = (RotationalSpringDamper("t", "ground", "rod", 5.0, 1.0, -np.pi / 2),) if spring else ()
    scenario = scenarios.Scenario(
        "rod",
        "default",
        (rod,),
        (pin,),
        (),
        1.0,
        10,
        1.0,
        gravity=(0.0, -g),
        forces=forces,
        analysis="dynamic",
    )
    stepper, s = _stepper(scenario, 1e-3)
    assert stepper.stiff is spring
    np.testing.assert_allclose(s.qd, 0.0, atol=1e-15)
    stepper.step(s)  # the penalties and W, which the projection of M^-1 Q_e uses, are set by a step
    rest = StepState(0.0, s.q, s.qd, np.zeros(3), s.multipliers, s.jac)
    lam = stepper.multipliers(rest, stepper.loads(s.q, s.qd, 0.0).generalized)
    np.testing.assert_allclose(lam, [0.0, m * g], rtol=0, atol=1e-12)


def test_the_step_is_the_same_in_any_unit_of_length() -> None:
    """The compound double pendulum with links of 1 m under g = 9.81 and of 1 km under g = 9.81e3
    (lengths and g scaled alike, so the angles move the same in time): every step takes as many
    Newton iterations and gives the same angles, and lengths a thousand times (the stopping rule
    measures updates over the column scales and residuals over the row scales)."""
    steps_alike_in_metres_and_kilometres(_stepper)


def test_a_chain_long_enough_for_the_banded_tangent_steps_as_with_the_dense_one(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """A02 with 7 loops (45 coordinates, W banded) from its start: one step with W banded and with W
    dense (tangent.BANDED_FROM raised) are the same to round-off."""
    scenario = scenarios.build("n_four_bar", overrides={"loops": 7, "t_end": 0.01, "steps": 2})
    banded, s = _stepper(scenario, 1e-3)
    assert banded.tangent.banded
    a = banded.step(s)
    monkeypatch.setattr(tangent, "BANDED_FROM", 1000)
    dense, _ = _stepper(scenario, 1e-3)
    assert not dense.tangent.banded
    b = dense.step(s)
    np.testing.assert_allclose(a.q, b.q, rtol=0, atol=1e-13)
    np.testing.assert_allclose(a.qd, b.qd, rtol=0, atol=1e-9)


def test_a_driven_rod_s_rates_are_the_driver_s_after_the_projection() -> None:
    """A rod of 1 m pinned at its end and turned by a driver at theta = -pi/2 + 2 t: after a step,
    theta = -pi/2 + 2 h and theta' = 2 exactly (C_q q' = -C_t), and its centre, 0.5 (cos, sin)(theta)
    from the pin, moves at 0.5 theta' (-sin, cos)(theta)."""
    rod = scenarios.Body("rod", (0.0, -0.5, -np.pi / 2), mass=2.0, inertia=0.2, length=1.0)
    pin = Revolute("pin", Point("ground", (0.0, 0.0)), Point("rod", (-0.5, 0.0)))
    turn = AbsoluteDriver("turn", "rod", "theta", ConstantSpeed(-np.pi / 2, 2.0))
    scenario = scenarios.Scenario(
        "rod", "default", (rod,), (pin,), (turn,), 1.0, 10, 1.0, gravity=(0.0, -9.81), analysis="dynamic"
    )
    h = 1e-3
    stepper, s = _stepper(scenario, h)
    s = stepper.step(s)
    theta = -np.pi / 2 + 2 * h
    assert s.q[2] == pytest.approx(theta, abs=1e-14)
    np.testing.assert_allclose(s.q[:2], 0.5 * np.array([np.cos(theta), np.sin(theta)]), rtol=0, atol=1e-14)
    assert s.qd[2] == pytest.approx(2.0, abs=1e-9)
    np.testing.assert_allclose(s.qd[:2], np.array([-np.sin(theta), np.cos(theta)]), rtol=0, atol=1e-9)


def test_a_chain_with_force_elements_keeps_its_tangent_dense() -> None:
    """With force elements P is dense (K and D couple every coordinate): W is not banded even on
    45 coordinates, and the step runs."""
    scenario = scenarios.build("n_four_bar", overrides={"loops": 7, "t_end": 0.01, "steps": 2})
    body = scenario.bodies[0].name
    scenario = replace(scenario, forces=(RotationalSpringDamper("t", "ground", body, 1.0, 0.1),))
    stepper, s = _stepper(scenario, 1e-3)
    assert stepper.stiff and not stepper.tangent.banded
    assert stepper.step(s).t == pytest.approx(1e-3, abs=1e-18)


SPEC_FLOOR = 10.0
"""The spec test's lower bounds are the measured values over this (its upper ones FACTOR times them)."""


@pytest.mark.slow
def test_a02_as_specified_passes_every_singular_position() -> None:
    scenario = scenarios.build("n_four_bar/spec", overrides={"steps": 400})
    _, _, reduced = a02_chain(40, scenario.t_end)
    passages = reduced.t_events[0]  # type: ignore[attr-defined]
    assert len(passages) == 20
    analysis = simulate(
        scenario, np.union1d(scenario.times(), passages), method="ali3p", step=2e-5, compiled=True
    )
    errors = np.array(a02_errors(analysis, reduced))
    measured = np.array(A02_SPEC)
    assert np.all((errors < FACTOR * measured) & (errors > measured / SPEC_FLOOR)), errors
    assert errors[0] < 1e-8 and errors[1] < 1e-10  # the bounds on the energy and the rockers
