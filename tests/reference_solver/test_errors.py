"""The solver's errors carry what they were given, and nothing they were not: an error raised
without a rank report (a Newton failure at a regular configuration, an assembly miss) lost no rank
and names no rows."""

from __future__ import annotations

import numpy as np
import pytest

from reference_solver.errors import (
    AssemblyError,
    ConvergenceError,
    MobilityError,
    SingularConfigurationError,
    SolverError,
)


@pytest.mark.parametrize(
    "kind", [SolverError, MobilityError, AssemblyError, SingularConfigurationError, ConvergenceError]
)
def test_an_error_without_a_rank_report_lost_no_rank(kind: type[SolverError]) -> None:
    error = kind("Newton-Raphson did not converge")
    assert isinstance(error, SolverError) and str(error) == "Newton-Raphson did not converge"
    assert error.time is None and error.q is None
    assert error.rank_deficiency == 0 and error.dependent_rows == ()


def test_an_error_keeps_where_and_why_it_failed() -> None:
    q = np.array([0.1, 0.2, 0.3])
    error = SingularConfigurationError("dead centre", 0.25, q, 1, ("crank.x", "rod.y"))
    assert (str(error), error.time, error.q, error.rank_deficiency) == ("dead centre", 0.25, q, 1)
    assert error.dependent_rows == ("crank.x", "rod.y")
