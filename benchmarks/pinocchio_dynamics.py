"""Pinocchio's free dynamics: cost per step of each mode's default, and how much of it is
Pinocchio's own kernels rather than the adapter's Python (the marching loop, the loads' terms).

    python -m benchmarks.pinocchio_dynamics [--repeats N] [SCENARIO ...]

The kernels are timed alone, in a tight loop at the start state: the constrained dynamics
(constraintDynamics, or aba on a tree, or forwardDynamics on the rows), the kinematics the loads
need (computeJointJacobians, updateFramePlacements, a getFrameJacobian per load point) and
pin.integrate; their sum per step (RK4: four accelerations and four integrates; Euler: one and one)
divided by the run's time per step is the share of the run that measures Pinocchio.
"""

from __future__ import annotations

import argparse

import numpy as np
import pinocchio as pin

import scenarios
from adapters.pinocchio import PinocchioAdapter
from adapters.pinocchio.adapter import Built
from adapters.pinocchio.row_dynamics import RowDynamicSolver
from adapters.pinocchio.simulation import RK4
from adapters.timing import fastest
from scenarios.forces import AppliedForce, SpringDamper

SCENARIOS = ("four_bar_gravity", "andrews_squeezer", "slider_crank_spring", "compound_pendulum")
CALLS = 2000


def per_call(action: object) -> float:
    return fastest(action, repeats=3, warmup=1, number=CALLS)[0]  # type: ignore[arg-type]


def kernels(built: Built) -> tuple[float, float]:
    """(seconds per acceleration, seconds per pin.integrate) of Pinocchio's own calls."""
    solver, pm = built.dynamics, built.pm
    assert solver is not None and built.start is not None
    model, data = pm.model, pm.model.createData()
    _, q, v = built.start
    tau = solver.tau(0.0, q, v)
    if isinstance(solver, RowDynamicSolver):
        jac = np.zeros((0, model.nv))
        rows = solver.all_constraint_rows.evaluate(built.kinematics.snapshot(q, v))
        jac, gamma = rows.jac, rows.drift
        dynamics = per_call(lambda: pin.forwardDynamics(model, data, q, v, tau, jac, gamma, 0.0))
    elif solver.cmodels:
        cm, cd, prox = solver.cmodels, solver.cdatas, solver.prox
        pin.initConstraintDynamics(model, data, cm, cd)
        dynamics = per_call(lambda: pin.constraintDynamics(model, data, q, v, tau, cm, cd, prox))
    else:
        dynamics = per_call(lambda: pin.aba(model, data, q, v, tau))
    forces = built.scenario.forces
    frames = [pm.frame_id[p] for f in forces if isinstance(f, SpringDamper) for p in (f.p_i, f.p_j)]
    frames += [pm.frame_id[f.point] for f in forces if isinstance(f, AppliedForce)]
    loads = 0.0
    if frames:

        def load_kinematics() -> None:
            pin.computeJointJacobians(model, data, q)
            pin.updateFramePlacements(model, data)
            for fid in frames:
                pin.getFrameJacobian(model, data, fid, pin.ReferenceFrame.LOCAL_WORLD_ALIGNED)

        loads = per_call(load_kinematics)
    dq = 1e-3 * v
    return dynamics + loads, per_call(lambda: pin.integrate(model, q, dq))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scenarios", nargs="*", default=list(SCENARIOS))
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()
    adapter = PinocchioAdapter()
    header = f"{'scenario':22s} {'mode':10s} {'steps':>6s} {'us/step':>9s} {'Pinocchio us/step':>18s}"
    print(f"{header} {'share':>6s}")
    for name in args.scenarios:
        scenario = scenarios.load(name)
        for mode in ("dynamic", "baumgarte", "euler"):
            setting = adapter.free_setting(scenario, mode)
            result = adapter.run(scenario, setting, repeats=args.repeats, warmup=1)
            if result.status != "ok":
                print(f"{name:22s} {mode:10s} {result.status}: {result.message}")
                continue
            per_step = result.run_time / result.steps
            acceleration, integrate = kernels(adapter.build(scenario, setting))
            evaluations = 4 if mode != "euler" else 1
            assert (mode != "euler") == (adapter.build(scenario, setting).dynamics.method == RK4)  # type: ignore[union-attr]
            pinocchio = evaluations * (acceleration + integrate)
            print(
                f"{name:22s} {mode:10s} {result.steps:6d} {1e6 * per_step:9.1f} {1e6 * pinocchio:18.1f} "
                f"{100 * pinocchio / per_step:5.0f}%"
            )


if __name__ == "__main__":
    main()
