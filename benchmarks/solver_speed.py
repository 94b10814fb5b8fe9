"""The native solver's cost per time point on each scenario family, side by side in one process with
MuJoCo's mj_step (RK4 and implicitfast) and Exudyn's cost per step on the same mechanism.

    python -m benchmarks.solver_speed [--repeats N] [--families a,b,...]

Native: a full position, velocity and acceleration analysis per time point at tolerance 1e-12, the
compiled path over a long grid, the plain path over a short one. MuJoCo: mj_step from a
Python loop (what a user calling it per step pays) and, for reference, mj_step's own loop (nstep).
Exudyn: its default setting's simulation time per step. Every time is the best of the repeats.
The last line prints the slider-crank ratio alone (native compiled / MuJoCo RK4 step).
"""

from __future__ import annotations

import argparse
import time

import scenarios
from benchmarks.timing import Cost, exudyn_per_step, mujoco_per_step, native_per_point
from reference_solver.compiled import path

FAST_POINTS = 2001
PLAIN_POINTS = 51
MUJOCO_STEPS = 2000
HEADER = (
    f"{'family':<16}{'n':>5}{'compiled':>10}{'plain':>10}{'mj RK4':>10}{'mj impl':>10}"
    f"{'RK4 nstep':>10}{'impl nstep':>11}{'exudyn':>10}{'RK4 ratio':>10}{'impl ratio':>10}"
)


def _ratio(a: Cost, b: Cost) -> str:
    return f"{a.value / b.value:10.2f}" if a.value is not None and b.value else f"{'-':>10}"


def first_call_seconds() -> float:
    """CPU seconds of the first compiled-path analysis in this process: numba's compilation, or loading
    its cache."""
    scenario = scenarios.build("slider_crank", overrides={"steps": 2})
    start = time.process_time()
    path.run(scenario, scenario.times())  # type: ignore[arg-type]
    return time.process_time() - start


def main(argv: list[str] | None = None) -> float | None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=5)
    kinematic = [n for n, f in scenarios.all_families().items() if not f.dynamic]
    parser.add_argument("--families", default=",".join(kinematic))
    args = parser.parse_args(argv)
    print(f"numba first call (compile or cache load): {first_call_seconds():.2f} s")
    print("microseconds per time point (native) or per step (engines); best of", args.repeats, "repeats")
    print(HEADER)
    ratios: dict[str, Cost] = {}
    notes: list[str] = []
    for family in args.families.split(","):
        scenario = scenarios.build(family)
        compiled = native_per_point(scenario, True, FAST_POINTS, args.repeats)
        plain = native_per_point(scenario, False, PLAIN_POINTS, max(1, args.repeats // 2))
        rk4, rk4_n = mujoco_per_step(scenario, "RK4", MUJOCO_STEPS, args.repeats)
        impl, impl_n = mujoco_per_step(scenario, "implicitfast", MUJOCO_STEPS, args.repeats)
        exudyn = exudyn_per_step(scenario, max(1, args.repeats // 2))
        n = path.compiled(scenario).program
        size = n.n if n is not None else 0
        print(
            f"{family:<16}{size:>5}{compiled.cell()}{plain.cell()}{rk4.cell()}{impl.cell()}"
            f"{rk4_n.cell()}{impl_n.cell(11)}{exudyn.cell()}{_ratio(compiled, rk4)}{_ratio(compiled, impl)}"
        )
        notes += [f"  {family}: {c.note}" for c in (rk4, exudyn) if c.value is None]
        ratios[family] = Cost(compiled.value / rk4.value if compiled.value and rk4.value else None)
    if notes:
        print("not measured:")
        print("\n".join(notes))
    slider = ratios.get("slider_crank", Cost(None)).value
    print(f"slider_crank native/MuJoCo-RK4 ratio: {slider:.3f}" if slider else "slider_crank ratio: -")
    return slider


if __name__ == "__main__":
    main()
