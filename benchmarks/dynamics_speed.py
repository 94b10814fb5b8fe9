"""The native forward dynamics' cost per output time point, plain and compiled constraints side by
side, beside the kinematic analysis of the same mechanism (the kinematic family it was released
from) on the same grid.

    python -m benchmarks.dynamics_speed [--repeats N]      (or: mbxval bench dynamics)

Right-hand sides per second are printed for the plain path (`simulate`'s default) and the compiled
one (`compiled=True`: reference_solver.compiled_system's constraints, the whole right-hand side in one
numba call, reference_solver.dynamics.compiled_rates), with their ratio; the two take turns in each
repeat, so that the ratio is measured side by side; the dynamics column is the compiled path.
Those rates divide the whole integration by its right-hand sides, scipy's own step included; the
`call` columns time the right-hand-side call alone, plain and compiled in turns, over the calls of
one integration replayed (benchmarks.rhs_replay), and their ratio.

Forward dynamics: coordinate partitioning with DOP853 at rtol 1e-12 (truth quality); its cost per
point depends on how many integrator steps fall between output points, so the right-hand-side
evaluations per point are printed too. Kinematic: the plain (uncompiled) Newton loop at tolerance
1e-12, and the compiled path where it applies. Every time is the best of the repeats.
"""

from __future__ import annotations

import argparse
import time
from collections.abc import Callable
from functools import partial

import scenarios
from benchmarks.rhs_replay import rhs_seconds
from reference_solver import analyse
from reference_solver.dynamics import simulate

PAIRS = (
    ("compound_pendulum", None),
    ("four_bar_gravity", "four_bar"),
    ("slider_crank_spring", "slider_crank"),
    ("andrews_squeezer", None),
    ("n_four_bar", "four_bar_chain"),
    ("stiff_spring", None),
)
POINTS = 50


def best(run: Callable[[], object], repeats: int) -> float:
    return min(interleaved([run], repeats)[0])


def interleaved(runs: list[Callable[[], object]], repeats: int) -> list[list[float]]:
    """The CPU time of each run in each round (the harness's clock, adapters.timing), the runs
    taking turns within a round, so that a burst of load on a shared machine falls on both sides of
    a ratio alike."""
    times: list[list[float]] = [[] for _ in runs]
    for _ in range(repeats):
        for run, kept in zip(runs, times, strict=True):
            start = time.process_time()
            run()
            kept.append(time.process_time() - start)
    return times


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args(argv)
    print(f"microseconds per output point ({POINTS} points over each horizon); best of {args.repeats}")
    header = (
        f"{'scenario':<22}{'n':>4}{'dynamics':>12}{'evals/pt':>10}{'rhs/s plain':>13}{'compiled':>10}"
        f"{'ratio':>7}{'call us plain':>15}{'compiled':>10}{'ratio':>7}{'kinematic':>12}{'compiled':>10}"
    )
    print(header + "  (kinematic family)")
    for name, kinematic in PAIRS:
        scenario = scenarios.build(name, overrides={"steps": POINTS} if name != "stiff_spring" else {})
        grid = scenario.times(steps=POINTS)
        evaluations = simulate(scenario, grid, compiled=True).evaluations
        compiled, plain_runs = interleaved(
            [partial(simulate, scenario, grid, compiled=True), partial(simulate, scenario, grid)],
            args.repeats,
        )
        dynamic, unfast = min(compiled) / (POINTS + 1), min(plain_runs) / (POINTS + 1)
        per_point = evaluations / (POINTS + 1)
        rates = f"{per_point / unfast:13.0f}{per_point / dynamic:10.0f}{unfast / dynamic:7.1f}"
        slow_call, fast_call = rhs_seconds(scenario, grid, args.repeats)
        calls = f"{1e6 * slow_call:15.0f}{1e6 * fast_call:10.1f}{slow_call / fast_call:7.0f}"
        plain = compiled_cell = "-"
        if kinematic is not None:
            driven = scenarios.build(kinematic)
            kgrid = driven.times(steps=POINTS)
            slow = best(partial(analyse, driven, kgrid, compiled=False), args.repeats)
            quick = best(partial(analyse, driven, kgrid), args.repeats)
            plain, compiled_cell = f"{1e6 * slow / (POINTS + 1):12.0f}", f"{1e6 * quick / (POINTS + 1):10.0f}"
        size = 3 * len(scenario.bodies)
        print(
            f"{name:<22}{size:>4}{1e6 * dynamic:12.0f}{per_point:10.1f}{rates}{calls}"
            f"{plain:>12}{compiled_cell:>10}  ({kinematic or '-'})"
        )


if __name__ == "__main__":
    main()
