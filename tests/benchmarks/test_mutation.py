"""`mbxval bench mutation` on a small module: every mutant of the level errors is killed by their
tests or explained as equivalent (the habit kept cheap: about 20 s on one worker)."""

from __future__ import annotations

import pytest

from benchmarks.mutation import EXPLAINED, MODULES, run


@pytest.mark.slow
def test_every_mutant_of_the_level_errors_is_killed_or_explained() -> None:
    outcome = run("reports/harness/level_error.py")
    assert outcome.total > 50 and outcome.timeout == 0 and outcome.other == 0
    assert outcome.unexplained == ()
    assert outcome.killed == outcome.total - len(outcome.survivors)


def test_an_unknown_module_is_refused_by_name() -> None:
    with pytest.raises(ValueError, match=r"no mutation setup for reports/nowhere\.py"):
        run("reports/nowhere.py")
    assert all(tests for tests in MODULES.values()) and all(EXPLAINED.values())
