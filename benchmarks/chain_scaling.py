"""The native solver's cost per time point against the size of the mechanism: the chain of N
four-bar loops (scenario four_bar_chain, n = 6 N + 3 unknowns), N from 1 to 1000, and the slope of
log(cost) against log(N) fitted by least squares.

    python -m benchmarks.chain_scaling [--repeats N] [--loops 1,2,5,...]

A linear cost has slope 1 (the sparse band LU keeps it so); the dense LU of the plain path would
tend to 3. The slope over N >= 10 is printed too: there the fixed cost per point no longer counts.
"""

from __future__ import annotations

import argparse

import numpy as np

import scenarios
from benchmarks.timing import native_per_point
from reference_solver.compiled import path

LOOPS = (1, 2, 5, 10, 20, 50, 100, 200, 500, 1000)
POINTS = 201


def slope(loops: np.ndarray, cost: np.ndarray) -> float:
    return float(np.polyfit(np.log(loops), np.log(cost), 1)[0])


def main(argv: list[str] | None = None) -> float:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--loops", default=",".join(map(str, LOOPS)))
    args = parser.parse_args(argv)
    loops = np.array([int(k) for k in args.loops.split(",")])
    print(f"{'N':>6}{'n':>7}{'band kl+ku':>11}{'us/point':>12}{'ns/unknown':>12}")
    costs = []
    for count in loops:
        scenario = scenarios.build("four_bar_chain", overrides={"loops": int(count)})
        program = path.compiled(scenario).program
        assert program is not None
        cost = native_per_point(scenario, True, POINTS, args.repeats).value
        assert cost is not None
        costs.append(cost)
        bandwidth = int(program.sizes[2] + program.sizes[3])
        print(f"{count:>6}{program.n:>7}{bandwidth:>11}{cost:>12.2f}{1e3 * cost / program.n:>12.1f}")
    cost_array = np.array(costs)
    large = loops >= 10
    print(
        f"log-log slope over N >= 10: {slope(loops[large], cost_array[large]):.3f}" if large.sum() > 1 else ""
    )
    fitted = slope(loops, cost_array)
    print(f"log-log slope of the cost per point against N (all N): {fitted:.3f}")
    return fitted


if __name__ == "__main__":
    main()
