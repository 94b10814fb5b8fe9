"""Pinocchio's kinematic solver off the happy path: the unknowns' sizes (a slide's coordinate is a
length, sized by the characteristic length, an angle 1 rad; they scale the Newton rows and the branch
guard's distances, so a wrong size changes no converged answer on the catalogue), and its refusals
with their messages and times: a singular Jacobian where the links lie in line, a non-finite guess."""

from __future__ import annotations

import numpy as np
import pytest

import scenarios
from adapters.base import EngineFailure, Singular
from adapters.pinocchio import PinocchioAdapter
from adapters.pinocchio.constraint_rows import ConstraintRows
from adapters.pinocchio.kinematics import KinematicSolver, body_motion
from adapters.pinocchio.model import build_model
from adapters.pinocchio.tree import plan
from scenarios.closed_form import exact


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


def test_a_row_null_at_the_first_configuration_is_sized_one_and_later_solves_converge() -> None:
    """The four-bar folded flat (every joint coordinate 0) has a loop-closure row whose Jacobian
    entries are all zero: its size is 1, not 0 (a zero size would divide its residual by zero in
    every later solve). The sizes are kept, so the same solver must still run the four-bar from
    its assembled start and match the closed form."""
    scenario = scenarios.build("four_bar", overrides={"steps": 10})
    solver, nq = _solver("four_bar")
    flat = np.zeros(nq)
    rows, _ = solver._system(flat, 0.0)
    null = np.flatnonzero(np.all(rows.jac == 0.0, axis=1))
    assert null.size == 1
    with pytest.raises(Singular):
        solver.position(flat, 0.0)
    assert solver.row_sizes(rows.jac)[null[0]] == 1.0
    adapter = PinocchioAdapter()
    start = adapter.build(scenario, adapter.default_setting(scenario)).start
    assert start is not None
    times = np.asarray(scenario.times())
    z, z_rate, z_acc = solver.run(start[1], times)
    data = solver.pm.model.createData()
    bodies = scenario.output_bodies
    found = np.stack(
        [body_motion(solver.pm, data, (z[k], z_rate[k], z_acc[k]), bodies) for k in range(times.size)]
    )
    truth = exact(scenario, times).select(bodies)
    assert np.abs(found[:, 0] - truth.position).max() < 1e-12
    assert np.abs(found[:, 1] - truth.velocity).max() < 1e-10
