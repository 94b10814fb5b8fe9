"""Pinocchio's kinematic solver off the happy path: the unknowns' sizes (a slide's coordinate is a
length, sized by the characteristic length, an angle 1 rad; they scale the Newton rows and the branch
guard's distances, so a wrong size changes no converged answer on the catalogue), and its refusals
with their messages and times: a singular Jacobian where the links lie in line, a non-finite guess."""

from __future__ import annotations

import numpy as np
import pytest

import scenarios
from adapters.base import EngineFailure, Singular
from adapters.pinocchio.constraint_rows import ConstraintRows
from adapters.pinocchio.kinematics import KinematicSolver
from adapters.pinocchio.model import build_model
from adapters.pinocchio.tree import plan


def test_a_slide_s_coordinate_is_sized_by_the_characteristic_length_and_an_angle_by_one() -> None:
    scenario = scenarios.build("slider_crank")
    pm = build_model(scenario, plan(scenario))
    solver = KinematicSolver(pm, ConstraintRows.of(scenario, pm), length=0.37)
    slides = [pm.q_index(edge.name) for edge in pm.tree.edges if edge.kind == "prismatic"]
    assert len(slides) == 1 and slides[0] is not None
    expected = np.ones(pm.model.nq)
    expected[slides[0]] = 0.37
    assert (solver.sizes == expected).all()


def _solver(name: str) -> tuple[KinematicSolver, int]:
    scenario = scenarios.build(name)
    pm = build_model(scenario, plan(scenario))
    solver = KinematicSolver(pm, ConstraintRows.of(scenario, pm), length=scenario.characteristic_length)
    return solver, pm.model.nq


def test_a_guess_with_every_link_in_line_is_a_singular_jacobian_at_its_time() -> None:
    """Every joint coordinate 0 lays the links along one line: the four-bar folded flat, the
    slider-driven crank at its dead centre. Both lose a rank there; Newton cannot take a step."""
    for name in ("four_bar", "slider_crank/slider_drive"):
        solver, nq = _solver(name)
        with pytest.raises(Singular) as caught:
            solver.position(np.zeros(nq), 0.125)
        assert str(caught.value) == "singular constraint Jacobian at t = 0.125" and caught.value.time == 0.125


def test_a_non_finite_guess_is_refused_with_its_time_and_assembly_says_so() -> None:
    solver, nq = _solver("slider_crank")
    with pytest.raises(EngineFailure) as caught:
        solver.position(np.full(nq, np.nan), 0.25)
    assert str(caught.value) == "non-finite constraint residual at t = 0.25" and caught.value.time == 0.25
    with pytest.raises(EngineFailure) as assembly:
        solver.assemble(np.full(nq, np.nan), 0.25)
    assert str(assembly.value) == "cannot assemble at t = 0.25: non-finite constraint residual at t = 0.25"
    assert assembly.value.time == 0.25
