"""How far apart the timed repeats of one run are, and what stopping them where two agree costs in
accuracy and saves in time (the AGREE rule of reports.run.group_runs).

    python -m benchmarks.repeat_noise [--low 0.03] [--high 0.3] [--repeats 5] [--engine NAME ...]

For every run of the default suite's plan (each engine's whole settings ladder) whose first timed
repeat takes between --low and --high seconds (the runs the rule touches: shorter ones cost little,
longer ones are timed once), the simulation is built, warmed as the harness warms it, and timed
--repeats times on the process's CPU clock (the harness's), each repeat apart. Printed: the load;
how far apart the first two repeats are (median, 90th percentile, the share within AGREE); the
minimum the rule finds (repeats stop where one agrees with the best before it to AGREE, at most
three, one above LONG_RUN, none past REPEATS_BUDGET) against the minimum of three and of all; and
the timed seconds of the rule against three repeats each.
"""

from __future__ import annotations

import argparse
import math
import os
import time

import numpy as np

import adapters
from adapters.timing import enough, over_budget
from reports import suites
from reports.run.group_runs import AGREE, LONG_RUN, REPEATS_BUDGET
from reports.run.planning import plan_engine
from reports.scoring.assembly import consistent_start
from scenarios import load as build_scenario


def repeat_times(engines: list[str], low: float, high: float, repeats: int) -> list[list[float]]:
    """Each selected run's `repeats` timed seconds, in order."""
    found = []
    loaded = {engine: adapters.load(engine) for engine in engines}
    for name in suites.main_scenarios():
        scenario = consistent_start(build_scenario(name))
        grid = np.asarray(scenario.times(), dtype=float)
        for engine, adapter in loaded.items():
            for setting, _ in plan_engine(scenario, engine, adapter, True, None).jobs:
                model = adapter.build(scenario, adapter.check_setting(setting))
                adapter._warm_up(model, grid)()
                each: list[float] = []
                for _ in range(repeats):
                    start = time.process_time()
                    adapter.simulate(model, grid)
                    each.append(time.process_time() - start)
                    if not low <= each[0] <= high:
                        break
                if len(each) == repeats:
                    found.append(each)
    return found


def by_the_rule(each: list[float]) -> tuple[float, float]:
    """(the minimum, the timed seconds) of the harness's rule (at most three repeats, within
    REPEATS_BUDGET) on these repeat times."""
    best, spent = math.inf, 0.0
    for latest in each[:3]:
        spent += latest
        done = enough(latest, best, LONG_RUN, AGREE) or over_budget(
            spent, min(best, latest), 1, REPEATS_BUDGET
        )
        best = min(best, latest)
        if done:
            break
    return best, spent


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(prog="repeat_noise", description=__doc__.splitlines()[0])
    parser.add_argument("--low", type=float, default=0.03, help="shortest first repeat, seconds")
    parser.add_argument("--high", type=float, default=LONG_RUN, help="longest first repeat, seconds")
    parser.add_argument("--repeats", type=int, default=5, help="repeats timed per run (at least 3)")
    parser.add_argument("--engine", action="append", help="engines (default mujoco, exudyn, pinocchio)")
    args = parser.parse_args(argv)
    if args.repeats < 3 or not 0 < args.low < args.high:
        parser.error("--repeats must be at least 3 and 0 < --low < --high")
    load = os.getloadavg()[0]
    runs = repeat_times(args.engine or ["mujoco", "exudyn", "pinocchio"], args.low, args.high, args.repeats)
    if not runs:
        parser.error("no run of the default suite took between --low and --high seconds")
    apart = np.array([abs(e[1] - e[0]) / min(e[:2]) for e in runs])
    rule = np.array([by_the_rule(e) for e in runs])
    of_three = np.array([min(e[:3]) for e in runs])
    of_all = np.array([min(e) for e in runs])
    above = rule[:, 0] / of_three - 1
    print(f"{len(runs)} runs, load {load:.2f} at the start, {os.getloadavg()[0]:.2f} at the end")
    print(
        f"first two repeats apart: median {np.median(apart):.2%}, 90th percentile "
        f"{np.quantile(apart, 0.9):.2%}, within {AGREE:.0%}: {np.mean(apart <= AGREE):.0%}"
    )
    print(
        f"the rule's minimum above the minimum of 3: median {np.median(above):.2%}, 90th percentile "
        f"{np.quantile(above, 0.9):.2%}, largest {above.max():.2%}; the minimum of 3 above the "
        f"minimum of {args.repeats}: median {np.median(of_three / of_all - 1):.2%}"
    )
    three, ruled = sum(sum(e[:3]) for e in runs), float(rule[:, 1].sum())
    print(f"timed seconds: the rule {ruled:.1f}, three repeats {three:.1f} (ratio {ruled / three:.2f})")


if __name__ == "__main__":
    main()
