"""Small systems for Newton's tests, whose roots and Jacobians are known by hand."""

from __future__ import annotations

import numpy as np


class OneUnknown:
    """A one-row, one-unknown system C(q) = row_scale * f(q) (scaled residual f), enough to pin
    Newton's arithmetic: the iterates below are worked by hand from f and f'."""

    def __init__(self, f, df, row_scale: float = 1.0) -> None:  # type: ignore[no-untyped-def]
        self.f, self.df = f, df
        self.row_scales = np.array([row_scale])
        self.column_scales = np.array([1.0])

    def evaluate(self, q: np.ndarray, t: float):  # type: ignore[no-untyped-def]
        return self.residual(q, t), self.row_scales[:, None] * np.array([[self.df(q[0])]]), None

    def residual(self, q: np.ndarray, t: float) -> np.ndarray:
        return self.row_scales * np.array([self.f(q[0])])

    def scaled_jacobian(self, jac: np.ndarray) -> np.ndarray:
        return jac * self.column_scales[None, :] / self.row_scales[:, None]
