"""ALI3-P's steps around a singular passage (dynamics.ali3p_schedule): the steps the compiled
stepper is asked for on the 10-loop chain through its first passage (tests.support.a02_chain),
recorded as they are taken, against what the module promises: equal steps of h on the grid t0 + k h,
except three placed steps from t_j to t_{j+3}, each 0.5 to 1.5 h long, the middle one across the
singular instant (from the chain's one-degree-of-freedom solution) and no step ending within half a
step of it; careful steps exactly where the scaled smallest singular value s of C_q is small (a
dense SVD at each step's start), and a placement never past the span's end."""

from __future__ import annotations

import math

import numpy as np
import pytest

from reference_solver.compiled_system import constraint_system
from reference_solver.dynamics.ali3p import PENALTY, StepState
from reference_solver.dynamics.ali3p_grid import integrate
from reference_solver.dynamics.compiled_ali3p import CompiledAli3p
from reference_solver.dynamics.forward import initial_state
from reference_solver.dynamics.loads import Loads
from reference_solver.dynamics.mass import mass_diagonal
from reference_solver.dynamics.passage import CAREFUL, END_VALUE, FIRST, Watch
from tests.support.a02_chain import a02_chain
from tests.support.ali3p_rod import swinging_rod
from tests.support.passage_spies import compiled_schedule, fail_when_careful

H = 0.77 / 38500
"""The step of test_passage's chain at the instant's phase 0.41 (t* = 36015.41 h)."""

Call = tuple[float, int, float, bool, float, float]
"""A call of CompiledAli3p.run: its start time, step count, step length, care, s at its start and
the time it returns."""


def _record(
    monkeypatch: pytest.MonkeyPatch, loops: int, t_end: float, t0: float = 0.0, h: float = H
) -> tuple[list[Call], float, float]:
    """The chain over t_end at the step h from time t0 (no drivers: the same motion, t0 later),
    its stepper's calls recorded; with t* and the span's end. The watch reads s first at t0 and
    then FIRST steps on (passage.FIRST)."""
    scenario, grid, reduced = a02_chain(loops, t_end)
    system = constraint_system(scenario)
    mass = mass_diagonal(scenario, system.layout)
    loads = Loads(scenario, system.layout, mass)
    calls: list[Call] = []
    run = CompiledAli3p.run

    def spied(
        self: CompiledAli3p, s: StepState, count: int, power: np.ndarray, work: np.ndarray
    ) -> tuple[StepState, np.ndarray, np.ndarray]:
        scaled = s.jac / np.sqrt(mass)
        scaled /= np.linalg.norm(scaled, axis=1)[:, None]
        smallest = float(np.linalg.svd(scaled, compute_uv=False)[-1])
        length, careful = float(self.params[self.kernels.P_H]), self.careful
        out = run(self, s, count, power, work)
        calls.append((s.t, count, length, careful, smallest, out[0].t))
        return out

    monkeypatch.setattr(CompiledAli3p, "run", spied)
    read = Watch.read

    def reading(self: Watch, t: float, jac: np.ndarray) -> float:
        readings.append(t)
        return read(self, t, jac)

    readings: list[float] = []
    monkeypatch.setattr(Watch, "read", reading)
    start = initial_state(system, mass, loads, t0)
    states, _, _ = integrate(system, mass, loads, start, t0 + grid, h * (1 + 1e-9))
    end = float(t0 + grid[-1])
    assert states[-1].t == end
    assert readings[:2] == [t0, pytest.approx(t0 + FIRST * h, abs=1e-12)]  # passage.FIRST
    return calls, t0 + float(reduced.t_events[0][0]), end  # type: ignore[attr-defined]


def _ends(calls: list[Call]) -> list[float]:
    """Every step's end, checking that each call starts where the last ended and ends count steps
    of its length on."""
    ends = [calls[0][0]]
    for start, count, length, _, _, stop in calls:
        assert start == ends[-1]
        assert stop == pytest.approx(start + count * length, abs=1e-12)
        ends.extend([*(start + k * length for k in range(1, count)), stop])
    return ends[1:]


def _placed(calls: list[Call], instant: float, h: float = H) -> list[Call]:
    """The calls next to the one whose step holds the instant, and it, if each is a single step
    and some is not h long; every other call's steps are h long."""
    i = next(k for k, c in enumerate(calls) if c[0] < instant < c[5])
    around = calls[i - 1 : i + 2]
    others = calls[: i - 1] + calls[i + 2 :]
    assert all(c[2] == pytest.approx(h, rel=1e-9) for c in others)
    if all(c[1] == 1 for c in around) and any(c[2] != pytest.approx(h, rel=1e-9) for c in around):
        return around
    assert all(c[2] == pytest.approx(h, rel=1e-9) for c in around)
    return []


@pytest.mark.parametrize("t0", [0.0, 0.25])
def test_the_steps_around_a_chain_s_passage(t0: float, monkeypatch: pytest.MonkeyPatch) -> None:
    """10 loops over 0.77 s (the passage at t* = 0.7203 s after the start), started at t0 = 0 and
    0.25: from t0 to the end without a gap; every step h long except three, which start on a grid
    point t0 + j h and end on t0 + (j + 3) h, each 0.5 to 1.5 h, the middle one with t* inside, at
    least 0.45 h from either end (the prediction is within 0.01 h, test_passage); no other step ends
    within half a step of t*. The steps are careful where s < sqrt(CAREFUL / PENALTY) = 2e-4 (read
    every NEAR steps: s moves by 1.3e-5 in between, so careful wherever s < 0.8 of that and not
    wherever s > 1.2 of it), the three placed ones among them; none before t* - 100 h or after
    t* + 100 h."""
    calls, instant, end = _record(monkeypatch, 10, 0.77, t0)
    ends = _ends(calls)
    assert calls[0][0] == t0 and ends[-1] == pytest.approx(end, abs=1e-12)
    placed = _placed(calls, instant)
    assert len(placed) == 3
    first, middle, last = placed
    j = round((first[0] - t0) / H)
    assert first[0] == pytest.approx(t0 + j * H, abs=1e-12)
    assert last[0] + last[2] == pytest.approx(t0 + (j + 3) * H, abs=1e-12)
    assert all(0.5 * H <= c[2] <= 1.5 * H for c in placed)
    assert min(instant - middle[0], middle[0] + middle[2] - instant) >= 0.45 * H
    assert min(abs(t - instant) for t in ends) >= 0.45 * H
    threshold = math.sqrt(CAREFUL / PENALTY)
    assert all(c[3] for c in placed)
    assert all(c[3] for c in calls if c[4] < 0.8 * threshold)
    assert not any(c[3] for c in calls if c[4] > 1.2 * threshold)
    assert not any(c[3] for c in calls if abs(c[0] - instant) > 100 * H)
    assert sum(c[3] for c in calls) >= 5


@pytest.mark.parametrize("last", [36017, 36016])
def test_a_placement_ends_on_the_span_s_end_or_is_not_made(
    last: int, monkeypatch: pytest.MonkeyPatch
) -> None:
    """The chain stopped just after its passage (t* = 36015.41 h): at 36017 h the placed steps
    resume on the grid exactly at the span's end (the third ends on it, not a round-off away); at
    36016 h there is no room for them (they would end past it), so the steps stay equal, careful
    next to t*, and the last ends on the span's end."""
    calls, instant, end = _record(monkeypatch, 10, last * H)
    assert instant / H == pytest.approx(36015.41, abs=0.01)
    ends = _ends(calls)
    assert ends[-1] == pytest.approx(end, abs=1e-12)
    placed = _placed(calls, instant)
    if last == 36017:
        assert len(placed) == 3 and calls[-1] is placed[-1]
        assert placed[-1][5] == end
    else:
        assert placed == [] and calls[-1][3]


def test_an_output_within_a_step_s_round_off_of_the_start_is_the_start() -> None:
    """A grid whose first output is 1e-14 s after the start (within SAME_TIME of a step of 1e-3):
    no step is taken for it, and the output is the start state itself with no work done; the next
    output, a step on, is a step's state."""
    scenario = swinging_rod()
    system = constraint_system(scenario)
    mass = mass_diagonal(scenario, system.layout)
    loads = Loads(scenario, system.layout, mass)
    start = initial_state(system, mass, loads, 0.0)
    states, works, _ = integrate(system, mass, loads, start, np.array([0.0, 1e-14, 1e-3]), 1e-3)
    np.testing.assert_array_equal(states[1].q, start.q)
    np.testing.assert_array_equal(states[1].qd, start.qd)
    assert works[1].tolist() == [0.0, 0.0, 0.0]
    assert states[2].t == 1e-3 and not np.array_equal(states[2].q, start.q)


def test_the_step_across_a_slow_passage_is_longer_than_a_step() -> None:
    """At h = 4e-6 (192500 steps over 0.77 s) the chain's s falls slower than 2 END_VALUE / h per
    second (0.63 / s), so the step across the instant is 2 END_VALUE / slope long, not h: s is
    END_VALUE at both its ends (measured 0.99987 and 1.00022 of it, by a dense SVD at each step's
    start), and it is 1.26 h long (measured); the steps beside it 0.5 to 1.5 h. 12 s."""
    h = 0.77 / 192500
    with pytest.MonkeyPatch.context() as monkeypatch:
        calls, instant, _ = _record(monkeypatch, 10, 0.77, h=h)
    first, middle, last = _placed(calls, instant, h)
    assert middle[2] > 1.1 * h and all(0.5 * h <= c[2] <= 1.5 * h for c in (first, last))
    assert middle[4] == pytest.approx(END_VALUE, rel=0.02) and last[4] == pytest.approx(END_VALUE, rel=0.02)


def test_a_placed_careful_step_that_fails_is_retaken_at_its_length(monkeypatch: pytest.MonkeyPatch) -> None:
    """As test_passage's retry, for a placed step (another length than h): the careful step that
    raises is taken again without care at the same length, giving the state the uncareful step of
    that length gives (the time h/2 on, the same q)."""
    stepper, first, schedule = compiled_schedule(swinging_rod())
    expected, _, _ = stepper.run_length(first, 5e-4, np.zeros(3), np.zeros(3))
    fail_when_careful(monkeypatch, stepper, 5e-4)
    schedule._take(1, 5e-4)
    assert not stepper.careful and schedule.state.t == expected.t == 5e-4
    np.testing.assert_array_equal(schedule.state.q, expected.q)
