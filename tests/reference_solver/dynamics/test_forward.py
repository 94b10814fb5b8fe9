"""Forward dynamics on a system with no constraint rows: a free body falls as y = -g t^2 / 2."""

from __future__ import annotations

import numpy as np
import pytest

from reference_solver.dynamics.forward import simulate
from scenarios import Body, Scenario

G = 9.81


@pytest.mark.parametrize(("method", "fast"), [("DOP853", False), ("DOP853", True), ("ali3p", False)])
def test_a_free_body_falls_as_the_closed_form(method: str, fast: bool) -> None:
    """Each method used to end in a crash (the largest residual of no rows) after integrating."""
    body = Body("b", (0.3, 0.0, 0.2), mass=2.0, inertia=0.1)
    scenario = Scenario(
        "free", "default", (body,), (), (), 1.0, 10, 1.0, gravity=(0.0, -G), analysis="dynamic"
    )
    result = simulate(scenario, method=method, fast=fast, step=1e-2 if method == "ali3p" else None)
    t = np.linspace(0.0, 1.0, 11)
    np.testing.assert_allclose(result.q[:, 1], -0.5 * G * t**2, rtol=0, atol=1e-12)
    np.testing.assert_allclose(result.q[:, [0, 2]], np.tile([0.3, 0.2], (11, 1)), rtol=0, atol=1e-15)
    # ALI3-P derives q'' from rate differences over its step: round-off 3.2e-12 relative, measured
    np.testing.assert_allclose(result.qdd[:, 1], -G, rtol=1e-11)
    assert np.all(result.motion.residual == 0.0) and result.lam.shape == (11, 0)
