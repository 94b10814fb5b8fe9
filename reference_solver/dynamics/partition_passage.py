"""A singular passage as the partitioned method meets it: C_q itself losing rank (A02's links lining
up), not merely the chosen dependent block degrading.

The partitioned method repartitions when its dependent block's reciprocal condition number falls
REPARTITION times below its value at the choice (forward.py). Away from a passage a fresh partition
restores it. Next to one no partition can: every square block of C_q is singular where C_q loses rank
(interlacing), so the fresh block is as degraded as the old, and each repartition restarts the
integrator a tenth nearer the singular instant with a small first step. On A02's two loops over
10 s the events come at 4e-2, 4e-3, ..., 4e-6 of C_q's smallest singular value, the last 7e-3 s
after the passage at t = 5.1132, where Newton on the dependent coordinates cannot converge (the
dependent block singular to round-off): a bare "did not converge" said nothing of the passage.

So a repartition that regains less than GAIN of what the old block lost marks a passage, and a
failure there (Newton on the dependent coordinates, or the integrator) is `singular_passage`: the
time, how far C_q had lost rank at the last repartition, and the method that crosses (ALI3-P, the
native default on scenes that declare their passages). The numerics are the partitioned method's
own: going on without repartitioning next to a passage, or solving a partition's first state from
the integrator's last accepted step, changed which runs crossed (A02's two loops over 10 s on the
compiled path passed, its four seconds at rtol 1e-12 on the plain path, the dynamics suite's
truth, crawled or failed), so neither is done: crossing a passage with independent coordinates is
luck either way.
"""

from __future__ import annotations

import numpy as np

from reference_solver.errors import SingularConfigurationError
from reference_solver.system import ConstraintSystem

GAIN = 0.3
"""A fresh partition below GAIN times the old one's conditioning at its choice (the old one lost a
factor REPARTITION = 0.1 when the event fired) regained less than a third of it: C_q is losing rank."""


def is_passage(fresh: float, before: float) -> bool:
    """Whether a fresh partition's conditioning `fresh` shows a passage, the old partition's having
    been `before` at its choice."""
    return fresh < GAIN * before


def rank_margin(system: ConstraintSystem, jac: np.ndarray) -> tuple[float, int]:
    """C_q's smallest structural singular value over its largest (scaled C_q), and how many of its
    singular values lie within 10 times that smallest: how far, and by how many ranks, it is from
    losing rank."""
    s = np.linalg.svd(system.scaled_jacobian(jac), compute_uv=False)
    s = s[: min(system.size, system.unknowns)]
    if s.size == 0 or s[0] == 0.0:
        return 0.0, 0
    return float(s[-1] / s[0]), int(np.count_nonzero(s <= 10.0 * s[-1]))


def singular_passage(
    system: ConstraintSystem, t: float, passage: tuple[float, np.ndarray]
) -> SingularConfigurationError:
    """The error of a partitioned run that failed at `t` next to the singular passage its last
    repartition showed (`passage`: that repartition's time, and C_q there)."""
    start, jac = passage
    margin, ranks = rank_margin(system, jac)
    return SingularConfigurationError(
        f"{system.scenario.name}: singular passage at t={t:.6g}: C_q is losing rank (at t={start:.6g} "
        f"its smallest singular value was {margin:.2g} of its largest, {ranks} within 10 times that), "
        "so no choice of independent coordinates stays regular and the partitioned method cannot "
        "cross it: use --mode ali3p",
        time=t,
        rank_deficiency=ranks,
    )
