"""ALI3-P's iteration matrix W = P + f C_q^T diag(alpha) C_q: its solve against a dense solve of the
same matrix written out here, on the dense and the banded factorization, and which one a system takes
(banded from 40 coordinates when the half-bandwidth is at most a quarter of them)."""

from __future__ import annotations

import numpy as np
import pytest

import scenarios
from reference_solver.dynamics.tangent import Tangent
from reference_solver.layout import Layout
from reference_solver.system import ConstraintSystem
from scenarios import Body, Point, Scenario
from scenarios.joints import Revolute


def chain(loops: int) -> ConstraintSystem:
    return ConstraintSystem(scenarios.build("n_four_bar", overrides={"loops": loops}))


def pattern_width(jac: np.ndarray) -> int:
    """The half-bandwidth of C_q^T C_q: the widest spread of one row's nonzero columns."""
    return max(int(np.ptp(np.flatnonzero(row))) for row in jac if np.any(row))


def random_state(
    system: ConstraintSystem, rng: np.random.Generator
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """C_q at a random configuration (every entry of the pattern nonzero), random positive masses
    and penalties."""
    q = rng.uniform(-1.0, 1.0, system.unknowns)
    return system.jacobian(q, 0.3), rng.uniform(0.5, 2.0, system.unknowns), rng.uniform(0.5, 3.0, system.size)


@pytest.mark.parametrize(("loops", "banded"), [(6, False), (7, True)])
def test_w_solves_as_the_dense_matrix_does_on_either_factorization(loops: int, banded: bool) -> None:
    rng = np.random.default_rng(28)
    system = chain(loops)
    tangent = Tangent(system, dense_weight=False)
    jac, mass, alpha = random_state(system, rng)
    assert tangent.banded is banded and tangent.n == system.unknowns
    assert tangent.width == pattern_width(jac) == 5
    factor = 0.37
    w = np.diag(mass) + factor * jac.T @ np.diag(alpha) @ jac
    tangent.factor(mass if banded else np.diag(mass), jac, alpha, factor)
    rhs = rng.uniform(-1.0, 1.0, system.unknowns)
    np.testing.assert_allclose(w @ tangent.solve(rhs), rhs, rtol=0, atol=1e-12)


def test_a_dense_weight_is_factored_densely_and_with_its_off_diagonal_terms() -> None:
    """Force elements (K, D) may couple any two bodies: W's weight is then a full matrix."""
    rng = np.random.default_rng(28)
    system = chain(7)
    tangent = Tangent(system, dense_weight=True)
    assert not tangent.banded
    jac, mass, alpha = random_state(system, rng)
    coupling = rng.uniform(-0.1, 0.1, (system.unknowns, system.unknowns))
    weight = np.diag(mass) + coupling @ coupling.T
    w = weight + 2.5 * jac.T @ np.diag(alpha) @ jac
    tangent.factor(weight, jac, alpha, 2.5)
    rhs = rng.uniform(-1.0, 1.0, system.unknowns)
    np.testing.assert_allclose(w @ tangent.solve(rhs), rhs, rtol=0, atol=1e-12)


def test_unconstrained_bodies_have_a_diagonal_w_on_the_banded_path() -> None:
    """14 free bodies: 42 coordinates and no constraint rows, so the half-bandwidth is 0."""
    rng = np.random.default_rng(28)
    bodies = tuple(Body(f"b{k}", (float(k), 0.0, 0.0)) for k in range(14))
    system = ConstraintSystem(Scenario("free", "default", bodies, (), (), 1.0, 1, 1.0))
    tangent = Tangent(system, dense_weight=False)
    assert tangent.banded and tangent.width == 0 and Layout.of(system.scenario).size == 42
    mass = rng.uniform(0.5, 2.0, 42)
    tangent.factor(mass, np.zeros((0, 42)), np.zeros(0), 0.25)
    rhs = rng.uniform(-1.0, 1.0, 42)
    np.testing.assert_allclose(tangent.solve(rhs), rhs / mass, rtol=1e-15)


def test_a_singular_banded_w_is_refused_with_lapack_s_pivot() -> None:
    """No mass and no penalty on the first coordinate: W's first column is 0, dgbtrf's first pivot."""
    system = chain(7)
    tangent = Tangent(system, dense_weight=False)
    jac = random_state(system, np.random.default_rng(28))[0]
    with pytest.raises(np.linalg.LinAlgError) as raised:
        tangent.factor(np.zeros(system.unknowns), jac, np.zeros(system.size), 1.0)
    assert str(raised.value) == "ALI3-P's iteration matrix is singular (LAPACK dgbtrf info 1)"


@pytest.mark.parametrize(("bodies", "banded"), [(14, False), (15, True)])
def test_the_band_is_taken_when_four_half_bandwidths_fit_in_the_size(bodies: int, banded: bool) -> None:
    """Free bodies and one pin between the first and the fourth: columns 0 to 2 and 9 to 11 share a
    row, a half-bandwidth of 11; 4 x 11 = 44 fits in 45 coordinates, not in 42."""
    rng = np.random.default_rng(28)
    free = tuple(Body(f"b{k}", (float(k), 0.0, 0.0)) for k in range(bodies))
    pin = Revolute("pin", Point("b0", (0.5, 0.0)), Point("b3", (-2.5, 0.0)))
    system = ConstraintSystem(Scenario("pinned", "default", free, (pin,), (), 1.0, 1, 1.0))
    tangent = Tangent(system, dense_weight=False)
    assert (tangent.width, tangent.banded) == (11, banded)
    jac, mass, alpha = random_state(system, rng)
    tangent.factor(mass if banded else np.diag(mass), jac, alpha, 0.5)
    rhs = rng.uniform(-1.0, 1.0, system.unknowns)
    w = np.diag(mass) + 0.5 * jac.T @ np.diag(alpha) @ jac
    np.testing.assert_allclose(w @ tangent.solve(rhs), rhs, rtol=0, atol=1e-12)
