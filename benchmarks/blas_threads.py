"""The native solver's CPU and wall time with BLAS held to one thread (what every mbxval process
does, adapters.threads) beside the BLAS library's own default (a thread per core), side by side in
one process, the two taking turns so that a burst of load falls on both alike.

    python -m benchmarks.blas_threads [--repeats 3] [--loops 40]

Cases: IFToMM A02 with two loops over 10 s by ALI3-P (`mbxval solve n_four_bar --set t_end=10
--mode ali3p`) and by its default path (timed up to its end or its failure), and the largest
kinematic scene, the chain of --loops four-bar loops (6 N + 3
unknowns: 243 at N = 40) on its default path. Each run is the engine run `mbxval solve` makes
(adapters.base.Adapter.run): its CPU time counts every thread of the process, which is what a
BLAS thread pool spends spinning on small systems.
"""

from __future__ import annotations

import argparse
import os

from threadpoolctl import threadpool_info, threadpool_limits

import adapters
from adapters.base import Setting
from adapters.threads import one_blas_thread
from adapters.timing import Instant, now
from scenarios import Scenario
from scenarios import build as build_scenario


def cases(loops: int) -> list[tuple[str, Scenario, Setting | None]]:
    """(label, scenario, setting: None for the engine's default) of each case."""
    a02 = build_scenario("n_four_bar", overrides={"t_end": 10.0})
    chain = build_scenario("four_bar_chain", overrides={"loops": loops})
    return [
        ("A02 N=2 over 10 s, ALI3-P", a02, Setting.of("ali3p")),
        ("A02 N=2 over 10 s, its default path", a02, None),
        (f"four_bar_chain N={loops} ({6 * loops + 3} unknowns)", chain, None),
    ]


def spent(scenario: Scenario, setting: Setting | None) -> Instant:
    """CPU and wall seconds of one native engine run, build included, up to its end or its failure
    (a default path that fails part-way is timed as far as it goes; its status is printed)."""
    engine = adapters.load(adapters.NATIVE)
    start = now()
    result = engine.run(scenario, setting)
    took = now() - start
    said = f"  ({scenario.name}: {result.status} at t = {result.failure_time}: timed up to there)"
    if result.status != "ok" and said not in _SAID:
        _SAID.add(said)
        print(said)
    return took


_SAID: set[str] = set()
"""The failures printed so far (each once)."""


def default_threads() -> int:
    """The threads the BLAS libraries start with here (their own default, before any limit)."""
    return max(int(info["num_threads"]) for info in threadpool_info() if info["user_api"] == "blas")


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(prog="blas_threads", description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=3, help="turns of each side (default 3)")
    parser.add_argument("--loops", type=int, default=40, help="loops of the kinematic chain (default 40)")
    args = parser.parse_args(argv)
    import scipy.linalg  # noqa: F401  (both BLAS libraries loaded before their default is read)

    own = default_threads()
    print(f"BLAS threads by default here: {own}; cores: {os.cpu_count()}; load {_load()}")
    print(
        f"{'case':<42}{'1 thread CPU':>13}{'wall':>8}{f'{own} threads CPU':>15}{'wall':>8}{'CPU ratio':>10}"
    )
    for label, scenario, setting in cases(args.loops):
        spent(scenario, setting)  # the compiled kernels loaded before either side is timed
        single: list[Instant] = []
        default: list[Instant] = []
        for _ in range(max(1, args.repeats)):
            with threadpool_limits(limits=own, user_api="blas"):
                default.append(spent(scenario, setting))
            with threadpool_limits(limits=1, user_api="blas"):
                single.append(spent(scenario, setting))
        one, many = min(single, key=lambda i: i.cpu), min(default, key=lambda i: i.cpu)
        print(
            f"{label:<42}{one.cpu:13.3f}{one.wall:8.3f}{many.cpu:15.3f}{many.wall:8.3f}"
            f"{many.cpu / one.cpu:10.2f}"
        )
    one_blas_thread()
    print(f"seconds, best of {args.repeats} by CPU; load {_load()}")


def _load() -> str:
    with open("/proc/loadavg") as loadavg:
        return loadavg.read().split()[0]


if __name__ == "__main__":
    main()
