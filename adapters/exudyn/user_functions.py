"""The Python and symbolic user functions the Exudyn model hands to Exudyn: time-dependent offsets
of coordinate constraints, and constraint and Jacobian functions of coordinate-vector connectors.

Offsets of the motions Exudyn can record (constant speed, harmonic, constant) are symbolic user
functions, evaluated inside Exudyn at almost no cost; any other motion is a Python function of its
own f(t) and f'(t). The constraint functions wrap an adapters.exudyn.constraints constraint for
Exudyn's marker coordinates and keep the last evaluation, since Exudyn asks for the residual and
the Jacobian at the same state.
"""

from __future__ import annotations

from typing import Any

import exudyn as exu
from exudyn.advancedUtilities import CreateSymbolicUserFunction

from adapters.exudyn.constraints import UserConstraint
from scenarios.bodies import GROUND
from scenarios.motions import Constant, ConstantSpeed, Harmonic, Motion


def offset_functions(mbs: Any, motion: Motion, scale: float, base: float) -> tuple[dict[str, Any], list[Any]]:
    """Exudyn's offset user functions for offset(t) = base + scale f(t), and what must be kept
    alive with the model (the symbolic functions hold their expression trees)."""
    symbolic = _symbolic_offsets(mbs, motion, scale, base)
    if symbolic is not None:
        return {"offsetUserFunction": symbolic[0], "offsetUserFunction_t": symbolic[1]}, list(symbolic)

    def offset(mbs: Any, t: float, itemNumber: int, lOffset: float) -> float:
        return base + scale * motion.f(t)

    def offset_t(mbs: Any, t: float, itemNumber: int, lOffset: float) -> float:
        return scale * motion.df(t)

    return {"offsetUserFunction": offset, "offsetUserFunction_t": offset_t}, []


def constraint_functions(constraint: UserConstraint, width: int) -> tuple[Any, Any]:
    """Exudyn's constraint and Jacobian user functions of `constraint` over the marker coordinates:
    the moving bodies' (x, y, theta) in the constraint's order, the extra unknowns, then (when one node is
    covered twice) a repeat that the constraint ignores."""
    moving = [k for k, b in enumerate(constraint.bodies) if b != GROUND]
    size = 3 * len(moving) + constraint.extra
    padding = [0.0] * (width - size)
    zero = [0.0, 0.0, 0.0]
    last: list[Any] = [None, None]  # Exudyn asks for residual and Jacobian at the same state

    def evaluate(q: list[float], t: float) -> tuple[list[float], list[list[float]], list[float]]:
        key = (t, *q[:size])
        if last[0] == key:
            return last[1]  # type: ignore[no-any-return]
        slot = iter(range(0, 3 * len(moving), 3))
        poses = [zero if b == GROUND else q[(s := next(slot)) : s + 3] for b in constraint.bodies]
        residual, blocks, extra_block, c_t = constraint.evaluate(poses, q[size - constraint.extra : size], t)
        jac = [
            [value for k in moving for value in blocks[k][row]] + extra_block[row] + padding
            for row in range(constraint.size)
        ]
        last[0], last[1] = key, (residual, jac, c_t)
        return residual, jac, c_t

    def constraint_function(
        mbs: Any, t: float, itemNumber: int, q: Any, q_t: Any, velocityLevel: bool
    ) -> Any:
        residual, jac, c_t = evaluate(_floats(q), t)
        if not velocityLevel:
            return residual
        v = _floats(q_t)
        return [
            sum(a * b for a, b in zip(row, v, strict=True)) + ct for row, ct in zip(jac, c_t, strict=True)
        ]

    def jacobian_function(mbs: Any, t: float, itemNumber: int, q: Any, q_t: Any, velocityLevel: bool) -> Any:
        return evaluate(_floats(q), t)[1]

    return constraint_function, jacobian_function


def _symbolic_offsets(mbs: Any, motion: Motion, scale: float, base: float) -> tuple[Any, Any] | None:
    """Symbolic offset(t) = base + scale f(t) and its rate, for the motions Exudyn can record."""
    sym: Any = exu.symbolic  # type: ignore[attr-defined]
    if isinstance(motion, ConstantSpeed):
        a, b = base + scale * motion.start, scale * motion.rate

        def offset(mbs: Any, t: Any, itemNumber: Any, lOffset: Any) -> Any:
            return a + b * t

        def offset_t(mbs: Any, t: Any, itemNumber: Any, lOffset: Any) -> Any:
            return b + 0.0 * t

    elif isinstance(motion, Harmonic):
        h = motion

        def offset(mbs: Any, t: Any, itemNumber: Any, lOffset: Any) -> Any:
            return base + scale * (h.mean + h.amplitude * sym.cos(h.omega * t + h.phase))

        def offset_t(mbs: Any, t: Any, itemNumber: Any, lOffset: Any) -> Any:
            return -scale * h.amplitude * h.omega * sym.sin(h.omega * t + h.phase)

    elif isinstance(motion, Constant):
        value = base + scale * motion.value

        def offset(mbs: Any, t: Any, itemNumber: Any, lOffset: Any) -> Any:
            return value + 0.0 * t

        def offset_t(mbs: Any, t: Any, itemNumber: Any, lOffset: Any) -> Any:
            return 0.0 * t

    else:
        return None
    kind = "ObjectConnectorCoordinate"
    return (
        CreateSymbolicUserFunction(mbs, offset, "offsetUserFunction", itemTypeName=kind),
        CreateSymbolicUserFunction(mbs, offset_t, "offsetUserFunction_t", itemTypeName=kind),
    )


def _floats(values: Any) -> list[float]:
    return values.tolist() if hasattr(values, "tolist") else list(values)  # type: ignore[no-any-return]
