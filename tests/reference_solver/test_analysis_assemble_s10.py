"""analysis.assemble's refusal where Newton meets the constraints but C_q is singular there (added
after session 8's mutation pass of assemble): the whole message, with the residual it reports read
back and held below the tolerance, so that no word of the explanation and no default of the numbers
in it can change unseen."""

from __future__ import annotations

import dataclasses
import re

import pytest

import scenarios
from reference_solver.analysis import analyse
from reference_solver.errors import AssemblyError
from scenarios import AbsoluteDriver, Constant

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
