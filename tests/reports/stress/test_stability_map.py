"""The stability map: each stored row's verdict, time, error and residual, from stored results alone,
and its HTML and Markdown renderings."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

import scenarios
from adapters.base import RunResult, Setting
from reference_solver import constraint_residual, solve
from reports.render.report_data import ReportData
from reports.render.stability_render import html_fragment, markdown_section
from reports.render.stored_verdicts import Judgement, judgements, stress_rows
from reports.run.rows import failure_row, result_row
from reports.scoring.comparison import measure
from reports.store.results_store import ResultsStore
from reports.stress.recording import record
from reports.stress.truth import stress_truth
from scenarios.trajectory import Trajectory

SETTING = Setting.of("test")
FAILURES = {
    # engine: (status, message, failure time)
    "stops": ("singular", "constraint Jacobian is singular", 0.0568),
    "early": ("singular", "det changed sign", 0.03),
    "newton": ("failed", "Newton did not converge at t = 0.05 (residual 1e-3)", 0.05),
    "crash": ("failed", "RuntimeError: boom", math.nan),
    "slow": ("timeout", "no result within the time limit of 60 s", math.nan),
    "blows": ("diverged", "became unstable", 0.06),
    "cannot": ("unsupported", "no such joint", math.nan),
}


def _ok(
    store: ResultsStore, scenario: scenarios.Scenario, engine: str, run: Trajectory, truth: Trajectory
) -> None:
    result = RunResult(engine, "test", SETTING, "ok", trajectory=run, run_time=0.01, build_time=0.0)
    metrics, levels, note = measure(scenario, result, truth, constraint_residual)
    store.add(result_row(scenario, result, True, 1, 0, metrics, levels, note), run)


def _joined(first: Trajectory, rest: Trajectory, times: np.ndarray) -> Trajectory:
    return Trajectory(times, first.bodies, position=np.concatenate([first.position, rest.position]))


def positions(trajectory: Trajectory) -> np.ndarray:
    assert trajectory.position is not None
    return trajectory.position


@pytest.fixture(scope="module")
def stored(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """Results of made-up engines on the nominal four-bar and the change-point case."""
    out = tmp_path_factory.mktemp("stress")
    store = ResultsStore(out)
    nominal = scenarios.build("four_bar")
    truth = solve(nominal)
    store.put_truth(nominal.name, "tolerance=1e-12", truth)
    _ok(store, nominal, "exact", truth, truth)
    _ok(store, nominal, "mirror", solve(scenarios.build("four_bar/crossed"), nominal.times()), truth)
    lifted = positions(truth).copy()
    lifted[100:, :, 1] += nominal.characteristic_length  # from t[100] on, a crank length up
    _ok(store, nominal, "lifted", Trajectory(truth.times, truth.bodies, position=lifted), truth)

    case = scenarios.build("four_bar/stress_change_point")
    times = np.asarray(case.times())
    partial = stress_truth(case, times)
    store.put_truth(case.name, "tolerance=1e-12", partial)
    end = int(np.count_nonzero(np.all(np.isfinite(positions(partial)), axis=(1, 2))))
    later = times[end:]
    start = {"theta0": 0.3 + 50.0 * later[0], "branch": -1}
    crossed = solve(scenarios.build(case.name, overrides=start), later - later[0])
    _ok(store, case, "through", _joined(solve(case, times[:end]), crossed, times), partial)
    for engine, (status, message, when) in FAILURES.items():
        row = failure_row(case, engine, "test", SETTING, True, status, message)  # type: ignore[arg-type]
        row["failure_time"] = when
        store.add(row)
    record(store, "stress")
    store.save({"suite": "stress"})
    return out


@pytest.fixture(scope="module")
def found(stored: Path) -> dict[tuple[str, str], Judgement]:
    return {(v.scenario, v.engine): v for v in judgements(stress_rows(ReportData.load(stored).frame))}


def test_a_run_on_the_truth_is_ok(found) -> None:  # type: ignore[no-untyped-def]
    v = found[("four_bar", "exact")]
    assert v.verdict == "ok" and v.error == 0.0 and v.residual < 1e-14 and math.isnan(v.time)


def test_a_mirrored_run_is_a_wrong_branch_at_its_start(found) -> None:  # type: ignore[no-untyped-def]
    v = found[("four_bar", "mirror")]
    assert v.verdict == "wrong branch" and v.time == 0.0 and "mirrored" in v.detail
    assert v.error > 0.5 and v.residual < 1e-12  # a valid closure: only its error gives it away


def test_a_run_off_the_mechanism_has_drifted_from_when_it_left(found) -> None:  # type: ignore[no-untyped-def]
    v = found[("four_bar", "lifted")]
    times = scenarios.build("four_bar").times()
    assert v.verdict == "drifted" and v.time == pytest.approx(times[100]) and v.error == pytest.approx(1.0)


def test_a_run_through_the_singular_configuration_picked_the_mirrored_branch(found) -> None:  # type: ignore[no-untyped-def]
    v = found[("four_bar/stress_change_point", "through")]
    singular = (math.pi - 0.3) / 50.0
    assert v.verdict == "picked a branch" and "mirrored" in v.detail
    assert singular < v.time < singular + 0.13 / 200  # the first grid time past it
    assert 0.0 < v.error < 1.2e-14  # the native solve's round-off against the closed form (4.0e-15)


def test_engine_failures_keep_their_status_and_time(found) -> None:  # type: ignore[no-untyped-def]
    name = "four_bar/stress_change_point"
    expected = {
        "stops": "singular detected",
        "early": "singular detected",
        "newton": "failed to converge",
        "crash": "failed",
        "slow": "timeout",
        "blows": "diverged",
        "cannot": "unsupported",
    }
    for engine, verdict in expected.items():
        v = found[(name, engine)]
        assert v.verdict == verdict, engine
        when = FAILURES[engine][2]
        assert (math.isnan(v.time) and math.isnan(when)) or v.time == when, engine
    assert "no such joint" in found[(name, "cannot")].detail


def test_a_singular_verdict_where_the_truth_goes_on_is_marked(found) -> None:  # type: ignore[no-untyped-def]
    """'early' stops at 0.03 s where the truth is regular (to 0.05655 s); 'stops' at 0.0568 s,
    past the truth's end."""
    early = found[("four_bar/stress_change_point", "early")]
    assert early.verdict == "singular detected" and "truth goes on regular past 0.03 s" in early.detail
    assert "truth goes on" not in found[("four_bar/stress_change_point", "stops")].detail


def test_markdown_and_html_show_the_map(stored: Path) -> None:
    data = ReportData.load(stored)
    text = markdown_section(data)
    assert text.startswith("## Stability map")
    line = next(s for s in text.splitlines() if s.startswith("| four_bar/stress_change_point |"))
    assert "singular @0.05683 s" in line  # the closed form
    assert "picked a branch @" in line and "(mirrored)" in line
    assert "failed to converge @0.05 s" in line and "timeout" in line
    page = html_fragment(data)
    assert 'id="stability-map"' in page and 'class="sm-bad">wrong branch @0 s' in page
    assert 'class="sm-branch">picked a branch' in page


def test_no_stress_results_no_section(tmp_path: Path) -> None:
    store = ResultsStore(tmp_path)
    scenario = scenarios.build("four_bar/crossed")
    store.add(failure_row(scenario, "x", "test", SETTING, True, "unsupported", "no"))
    store.save({})
    data = ReportData.load(tmp_path)
    assert markdown_section(data) == "" and html_fragment(data) == ""
