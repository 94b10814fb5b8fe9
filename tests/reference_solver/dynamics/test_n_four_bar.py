"""IFToMM A02, the N-four-bar under gravity, through its singular horizontal position: the motion
must stay on the parallelogram branch (every rocker at the crank's angle, every coupler level) and
keep its energy, which no frictionless mechanism may lose at a singular configuration."""

from __future__ import annotations

import numpy as np

import scenarios
from reference_solver.dynamics import simulate


def test_the_chain_passes_the_horizontal_position_on_the_parallelogram_branch() -> None:
    analysis = simulate(scenarios.build("n_four_bar", overrides={"t_end": 1.0, "steps": 20}))
    layout = analysis.layout
    angle = {b: analysis.q[:, layout.bodies.index(b) * 3 + 2] for b in layout.bodies}
    crank = angle["crank"]
    assert crank[0] > 0 > crank[-1]  # it went through the horizontal position
    for body, theta in angle.items():
        expected = crank if body.startswith("rocker") or body == "crank" else np.zeros_like(crank)
        np.testing.assert_allclose(theta, expected, rtol=0, atol=1e-12)
    extras = analysis.extras
    energy = extras["energy.kinetic"] + extras["energy.potential"]
    assert np.max(np.abs(energy - energy[0])) < 1e-8 * np.max(extras["energy.kinetic"])
