"""The suites' timing rule: every suite that reports timings over a ladder times each run as the
minimum of its repeats after one untimed warm-up (a run over the grid's first interval, so it costs
little); only the one-setting suites (quick, stress) run once without one."""

from __future__ import annotations

from reports.suites import SUITES


def test_the_ladder_suites_warm_up_once_before_their_repeats() -> None:
    for name in ("default", "dynamics"):
        suite = SUITES[name]
        assert suite.ladder and suite.warmup == 1 and suite.repeats == 3, name


def test_the_one_setting_suites_time_one_run_without_a_warm_up() -> None:
    for name in ("quick", "stress"):
        suite = SUITES[name]
        assert not suite.ladder and suite.warmup == 0 and suite.repeats == 1, name
