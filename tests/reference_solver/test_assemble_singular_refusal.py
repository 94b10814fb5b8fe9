"""analysis.assemble's refusal where Newton meets the constraints but C_q is singular there: the
whole message, with the residual it reports read
back and held below the tolerance, so that no word of the explanation and no default of the numbers
in it can change unseen."""

from __future__ import annotations

import dataclasses
import re

import numpy as np
import pytest

import scenarios
from reference_solver.analysis import analyse
from reference_solver.errors import AssemblyError
from reference_solver.system import ConstraintSystem
from scenarios import AbsoluteDriver, Constant
from tests.support.a02_chain import moved_along_x

HELD = re.compile(
    r"slider_crank: the mechanism cannot assemble at t=0: the constraints hold \(to (?P<miss>\S+)\) but "
    r"C_q is singular there, rank deficiency 1, dependent rows: slide\.angle, slide\.normal, slider_y\.y: "
    r"a constraint the others already hold at this configuration \(independent elsewhere, so the "
    r"mobility check passed it\)"
)


def test_a_driver_the_joints_hold_is_refused_with_the_whole_explanation() -> None:
    """The slider-crank driven at its slider's y (test_analysis.py's case): the rows the rank report
    names, and a residual below Newton's tolerance 1e-12 (the constraints do hold)."""
    base = scenarios.build("slider_crank")
    held = AbsoluteDriver("slider_y", "slider", "y", Constant(0.0))
    with pytest.raises(AssemblyError) as caught:
        analyse(dataclasses.replace(base, drivers=(held,)))
    match = HELD.fullmatch(str(caught.value))
    assert match is not None, str(caught.value)
    assert 0.0 <= float(match["miss"]) < 1e-12


FLOORED = re.compile(
    r"four_bar: the mechanism cannot assemble at t=0: Newton-Raphson stopped with the constraints missing "
    r"by up to (?P<miss>\S+), above the tolerance 1e-12, where C_q is regular: the round-off of coordinates "
    r"as large as (?P<largest>\S+) is about (?P<floor>\S+) \(relative to the characteristic length 0\.05\)"
)


def test_an_assembly_stopped_by_round_off_is_not_called_singular() -> None:
    """The four-bar (L = 0.05 m) moved 1000 m along x: the plain rows sum coordinates of 1000 m,
    whose round-off, eps 1000 / L = 4.4e-12 of the length, floors the residual above the tolerance
    1e-12 and within ten of it, while C_q is regular: the refusal names the round-off floor, never
    "C_q is singular there, rank deficiency 0"."""
    scenario = moved_along_x(scenarios.build("four_bar"), 1000.0)
    with pytest.raises(AssemblyError) as caught:
        analyse(scenario, compiled=False)
    match = FLOORED.fullmatch(str(caught.value))
    assert match is not None, str(caught.value)
    assert caught.value.rank_deficiency == 0
    q = caught.value.q
    assert q is not None
    system = ConstraintSystem(scenario)
    miss = np.max(np.abs(system.residual(q, 0.0) / system.row_scales))
    assert 1e-12 < miss < 1e-11 and float(match["miss"]) == pytest.approx(miss, rel=1e-2)
    largest = np.max(np.abs(q))
    assert 1000.0 < largest < 1000.1 and float(match["largest"]) == pytest.approx(largest, rel=1e-2)
    assert float(match["floor"]) == pytest.approx(np.finfo(float).eps * largest / 0.05, rel=1e-2)
