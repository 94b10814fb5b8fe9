"""ALI3-P's projection of the rates onto C_q x = b against the P-orthogonal projection in closed form,
x = r - P^-1 C_q^T mu with mu = (C_q P^-1 C_q^T)^-1 (C_q r - b), on a hand-built step (a dense P,
W = P + h^2/4 C_q^T diag(alpha) C_q solved directly, every solve counted)."""

from __future__ import annotations

import numpy as np
import pytest

from reference_solver.dynamics.projection import PROJECTION_STEPS, project

N, H = 6, 0.01


class DenseStep:
    """A time step of P = `weight` and penalties alpha_i = penalty 4/h^2 / (C_q P^-1 C_q^T)_ii (as
    ALI3-P sets them, so the iteration contracts by about 1/(1 + penalty) per pass)."""

    def __init__(self, weight: np.ndarray, jac: np.ndarray, penalty: float) -> None:
        self.h = H
        inertia = np.einsum("ij,ji->i", jac, np.linalg.solve(weight, jac.T))
        self.alpha = penalty * 4 / (H * H) / inertia
        self.weight = weight
        self.w = weight + H * H / 4 * jac.T @ np.diag(self.alpha) @ jac
        self.solves = 0

    def weigh(self, x: np.ndarray) -> np.ndarray:
        return self.weight @ x  # type: ignore[no-any-return]

    def solve(self, rhs: np.ndarray) -> np.ndarray:
        self.solves += 1
        return np.linalg.solve(self.w, rhs)  # type: ignore[no-any-return]


def spd(rng: np.random.Generator, n: int) -> np.ndarray:
    a = rng.uniform(-1.0, 1.0, (n, n))
    return a @ a.T + n * np.eye(n)  # type: ignore[no-any-return]


def closed_form(weight: np.ndarray, jac: np.ndarray, rates: np.ndarray, target: np.ndarray):  # type: ignore[no-untyped-def]
    inverse_ct = np.linalg.solve(weight, jac.T)
    mu = np.linalg.solve(jac @ inverse_ct, jac @ rates - target)
    return rates - inverse_ct @ mu, mu


@pytest.mark.parametrize("penalty", [1e8, 1e3, 30.0])
def test_the_projection_is_the_p_orthogonal_one_with_its_multipliers(penalty: float) -> None:
    rng = np.random.default_rng(281)
    weight, jac = spd(rng, N), rng.uniform(-1.0, 1.0, (2, N))
    rates, target = rng.uniform(-1.0, 1.0, N), rng.uniform(-1.0, 1.0, 2)
    step = DenseStep(weight, jac, penalty)
    given = rates.copy()
    x, mu = project(step, jac, rates, target)
    expected_x, expected_mu = closed_form(weight, jac, given, target)
    np.testing.assert_allclose(x, expected_x, rtol=0, atol=1e-13)
    # mu = h^2/4 sigma carries alpha times C's round-off: about 1e-16 penalty relative
    np.testing.assert_allclose(mu, expected_mu, rtol=max(1e-15 * penalty, 1e-12))
    np.testing.assert_allclose(jac @ x, target, rtol=0, atol=1e-14)
    np.testing.assert_array_equal(rates, given)  # the rates given are left as they were
    # Each pass shrinks the constraint's error by about 1/(1 + penalty): it is settled (a move below
    # 1e-15 of the rates) after about 15 / log10(1 + penalty) passes, plus the first and the last.
    assert 2 <= step.solves <= np.ceil(15 / np.log10(1 + penalty)) + 2 < PROJECTION_STEPS


def test_rates_already_on_the_constraint_are_returned_after_one_solve() -> None:
    rng = np.random.default_rng(281)
    weight, jac = spd(rng, N), rng.uniform(-1.0, 1.0, (3, N))
    rates = rng.uniform(-1.0, 1.0, N)
    step = DenseStep(weight, jac, 1e8)
    x, mu = project(step, jac, rates, jac @ rates)
    np.testing.assert_allclose(x, rates, rtol=0, atol=1e-15)
    np.testing.assert_allclose(mu, 0.0, atol=1e-12)
    assert step.solves == 1


def test_zero_rates_project_onto_the_target() -> None:
    """x = P^-1 C^T (C P^-1 C^T)^-1 b from x* = 0 (the relative move then has no scale of its own)."""
    rng = np.random.default_rng(281)
    weight, jac = spd(rng, N), rng.uniform(-1.0, 1.0, (2, N))
    target = np.array([0.5, -2.0])
    x, mu = project(DenseStep(weight, jac, 1e4), jac, np.zeros(N), target)
    expected_x, expected_mu = closed_form(weight, jac, np.zeros(N), target)
    np.testing.assert_allclose(x, expected_x, rtol=0, atol=1e-13)
    np.testing.assert_allclose(mu, expected_mu, rtol=1e-11)


def test_a_repeated_row_still_gives_the_projection_and_multipliers_that_balance_it() -> None:
    """C_q without full rank (a row repeated, its target too): x is the projection onto the distinct
    rows, and P (x - x*) + C_q^T mu = 0 for the mu returned (which splits between the two copies)."""
    rng = np.random.default_rng(281)
    weight, distinct = spd(rng, N), rng.uniform(-1.0, 1.0, (2, N))
    jac = np.vstack([distinct, distinct[:1]])
    rates, target = rng.uniform(-1.0, 1.0, N), rng.uniform(-1.0, 1.0, 2)
    x, mu = project(DenseStep(weight, jac, 1e4), jac, rates, np.append(target, target[0]))
    expected_x, expected_mu = closed_form(weight, distinct, rates, target)
    np.testing.assert_allclose(x, expected_x, rtol=0, atol=1e-12)
    np.testing.assert_allclose(weight @ (x - rates) + jac.T @ mu, 0.0, atol=3e-11)  # measured 8.2e-12
    np.testing.assert_allclose([mu[0] + mu[2], mu[1]], expected_mu, rtol=1e-11)


def test_the_stopping_rule_is_relative_to_the_rates() -> None:
    """Rates and target of order 1e-9 are projected to the same relative accuracy as those of order 1."""
    rng = np.random.default_rng(281)
    weight, jac = spd(rng, N), rng.uniform(-1.0, 1.0, (2, N))
    rates, target = 1e-9 * rng.uniform(-1.0, 1.0, N), 1e-9 * rng.uniform(-1.0, 1.0, 2)
    x, _ = project(DenseStep(weight, jac, 1e3), jac, rates, target)
    expected_x, _ = closed_form(weight, jac, rates, target)
    np.testing.assert_allclose(x, expected_x, rtol=0, atol=1e-22)


def test_a_projection_that_cannot_settle_stops_after_its_thirty_passes() -> None:
    """A penalty of 0.5 contracts the error by only about 1/(1 + 0.5 s^2) per pass: still moving
    after PROJECTION_STEPS (30) passes, it stops there, nearer the constraint than it started."""
    rng = np.random.default_rng(281)
    weight, jac = spd(rng, N), rng.uniform(-1.0, 1.0, (2, N))
    rates, target = rng.uniform(-1.0, 1.0, N), rng.uniform(-1.0, 1.0, 2)
    step = DenseStep(weight, jac, 0.5)
    x, _ = project(step, jac, rates, target)
    assert step.solves == PROJECTION_STEPS == 30
    gap = np.max(np.abs(jac @ x - target))
    assert 1e-12 < gap < 1e-3 * np.max(np.abs(jac @ rates - target))


def test_rates_a_round_off_away_from_the_constraint_take_two_passes() -> None:
    """Rates 1e-14 (relative) off the constraint: the first move, below STALLED but above SETTLED,
    has no earlier move to be compared with; the second is settled."""
    rng = np.random.default_rng(281)
    weight, jac = spd(rng, N), rng.uniform(-1.0, 1.0, (2, N))
    on, _ = closed_form(weight, jac, rng.uniform(-1.0, 1.0, N), rng.uniform(-1.0, 1.0, 2))
    rates = on + 1e-14 * rng.uniform(-1.0, 1.0, N)
    step = DenseStep(weight, jac, 1e8)
    x, _ = project(step, jac, rates, jac @ on)
    np.testing.assert_allclose(x, on, rtol=0, atol=1e-14)
    assert step.solves == 2


class RecordedStep(DenseStep):
    """A DenseStep that keeps the size of every move it solves for."""

    def __init__(self, weight: np.ndarray, jac: np.ndarray, penalty: float) -> None:
        super().__init__(weight, jac, penalty)
        self.moves: list[float] = []

    def solve(self, rhs: np.ndarray) -> np.ndarray:
        move = super().solve(rhs)
        self.moves.append(float(np.max(np.abs(move))))
        return move


def test_the_projection_stops_at_the_first_move_that_is_settled_or_stalled() -> None:
    """The documented rule, on the moves observed: stop at the first move below SETTLED (1e-15) of
    the rates, or below STALLED (1e-13) and more than half the one before. On this draw (penalty 1e8,
    three rows) the moves reach round-off above SETTLED (measured 2.4, 8.7e-8, 3.4e-15, 1.1e-15,
    1.1e-15 relative): the stall ends it."""
    rng = np.random.default_rng(0)
    a = rng.uniform(-1.0, 1.0, (N, N))
    weight, jac = a @ a.T + N * np.eye(N), rng.uniform(-1.0, 1.0, (3, N))
    rates, target = rng.uniform(-1.0, 1.0, N), rng.uniform(-1.0, 1.0, 3)
    step = RecordedStep(weight, jac, 1e8)
    x, _ = project(step, jac, rates, target)
    np.testing.assert_allclose(x, closed_form(weight, jac, rates, target)[0], rtol=0, atol=1e-14)
    sizes = np.array(step.moves) / np.max(np.abs(rates))
    stops = [
        k
        for k, size in enumerate(sizes)
        if size <= 1e-15 or (size < 1e-13 and size > 0.5 * (sizes[k - 1] if k else np.inf))
    ]
    assert stops and stops[0] == len(sizes) - 1
