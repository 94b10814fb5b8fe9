"""Andrews' squeezing mechanism in the Test Set for IVP Solvers' own formulation (seven joint
angles, its mass matrix, forces and constraint Jacobian transcribed from andrews.f), integrated
here in index-1 form: an independent derivation to hold the absolute-coordinate model against."""

from __future__ import annotations

import numpy as np
from scipy.integrate import solve_ivp

from scenarios.families.andrews_squeezer import (
    C0,
    DA,
    EA,
    FA,
    INERTIA,
    INITIAL,
    L0,
    MOM,
    RA,
    RR,
    SA,
    SB,
    SC,
    SD,
    SS,
    TA,
    TB,
    UA,
    UB,
    XB,
    XC,
    YB,
    YC,
    ZF,
    ZT,
    D,
    E,
    M,
    U,
)


def constraint_jacobian(y: np.ndarray) -> np.ndarray:
    """g_q (6 x 7); complex y allowed (complex-step derivatives)."""
    be, th, ga, ph, de, om, ep = y
    sin, cos = np.sin, np.cos
    g = np.zeros((6, 7), dtype=y.dtype)
    for row in (0, 2, 4):
        g[row, 0], g[row, 1] = -RR * sin(be) + D * sin(be + th), D * sin(be + th)
        g[row + 1, 0], g[row + 1, 1] = RR * cos(be) - D * cos(be + th), -D * cos(be + th)
    g[0, 2], g[1, 2] = -SS * cos(ga), -SS * sin(ga)
    g[2, 3], g[2, 4] = -E * cos(ph + de), -E * cos(ph + de) + ZT * sin(de)
    g[3, 3], g[3, 4] = -E * sin(ph + de), -E * sin(ph + de) - ZT * cos(de)
    g[4, 5], g[4, 6] = ZF * sin(om + ep), ZF * sin(om + ep) - U * cos(ep)
    g[5, 5], g[5, 6] = -ZF * cos(om + ep), -ZF * cos(om + ep) - U * sin(ep)
    return g


def rates(t: float, z: np.ndarray) -> np.ndarray:
    y, v = z[:7], z[7:]
    _, th, ga, ph, _, om, _ = y
    bep, thp, _, php, dep, omp, epp = v
    sin, cos = np.sin, np.cos
    m1, m2, m3, m4, m5, m6, m7 = M
    i1, i2, i3, i4, i5, i6, i7 = INERTIA
    mm = np.zeros((7, 7))
    mm[0, 0] = m1 * RA**2 + m2 * (RR**2 - 2 * DA * RR * cos(th) + DA**2) + i1 + i2
    mm[1, 0] = m2 * (DA**2 - DA * RR * cos(th)) + i2
    mm[1, 1] = m2 * DA**2 + i2
    mm[2, 2] = m3 * (SA**2 + SB**2) + i3
    mm[3, 3] = m4 * (E - EA) ** 2 + i4
    mm[4, 3] = m4 * ((E - EA) ** 2 + ZT * (E - EA) * sin(ph)) + i4
    mm[4, 4] = m4 * (ZT**2 + 2 * ZT * (E - EA) * sin(ph) + (E - EA) ** 2) + m5 * (TA**2 + TB**2) + i4 + i5
    mm[5, 5] = m6 * (ZF - FA) ** 2 + i6
    mm[6, 5] = m6 * ((ZF - FA) ** 2 - U * (ZF - FA) * sin(om)) + i6
    mm[6, 6] = m6 * ((ZF - FA) ** 2 - 2 * U * (ZF - FA) * sin(om) + U**2) + m7 * (UA**2 + UB**2) + i6 + i7
    mm = np.tril(mm) + np.tril(mm, -1).T
    xd, yd = SD * cos(ga) + SC * sin(ga) + XB, SD * sin(ga) - SC * cos(ga) + YB
    length = np.hypot(xd - XC, yd - YC)
    force = -C0 * (length - L0) / length
    fx, fy = force * (xd - XC), force * (yd - YC)
    ff = np.array(
        [
            MOM - m2 * DA * RR * thp * (thp + 2 * bep) * sin(th),
            m2 * DA * RR * bep**2 * sin(th),
            fx * (SC * cos(ga) - SD * sin(ga)) + fy * (SD * cos(ga) + SC * sin(ga)),
            m4 * ZT * (E - EA) * dep**2 * cos(ph),
            -m4 * ZT * (E - EA) * php * (php + 2 * dep) * cos(ph),
            -m6 * U * (ZF - FA) * epp**2 * cos(om),
            m6 * U * (ZF - FA) * omp * (omp + 2 * epp) * cos(om),
        ]
    )
    g = constraint_jacobian(y)
    h = 1e-30
    g_dot_v = (constraint_jacobian(y + 1j * h * v) @ v).imag / h
    kkt = np.block([[mm, g.T], [g, np.zeros((6, 6))]])
    solution = np.linalg.solve(kkt, np.concatenate([ff, -g_dot_v]))
    return np.concatenate([v, solution[:7]])


def angles_at(t_end: float, rtol: float = 1e-13) -> np.ndarray:
    """The seven angles at t_end from the test set's initial state."""
    start = np.concatenate([np.array(INITIAL), np.zeros(7)])
    sol = solve_ivp(rates, (0.0, t_end), start, method="DOP853", rtol=rtol, atol=rtol * 1e-2)
    return sol.y[:7, -1]  # type: ignore[no-any-return]
