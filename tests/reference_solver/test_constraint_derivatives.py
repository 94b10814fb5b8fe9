"""C_q, C_t and Q_d of every constraint kind against finite differences of C alone.

Q_d is checked through the second difference of C along the straight path (q + s q_dot, t + s), on
which q_ddot = 0: d^2 C/ds^2 = (C_q q_dot)_q q_dot + 2 C_qt q_dot + C_tt = -Q_d.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from reference_solver.system import ConstraintSystem
from scenarios import (
    GROUND,
    AbsoluteDriver,
    Body,
    ConstantSpeed,
    EccentricDisc,
    FlatFaceCam,
    GearPair,
    Ground,
    Harmonic,
    KnifeEdgeCam,
    Point,
    PointPathDriver,
    Prismatic,
    RackPinion,
    RelativeDisplacementDriver,
    RelativeRotationDriver,
    Revolute,
    RevoluteRevolute,
    RollerCam,
    Scenario,
    SplineProfile,
)

EXAMPLES = 200
real = st.floats(-1.0, 1.0, allow_nan=False)
vec = st.tuples(real, real)
angle = st.floats(-math.pi, math.pi)
positive = st.floats(0.05, 1.0)
other_body = st.sampled_from(["b", GROUND])
motion = st.one_of(
    st.builds(ConstantSpeed, real, st.floats(-5, 5)),
    st.builds(Harmonic, real, real, st.floats(0.1, 5), angle),
)
SPLINE = SplineProfile(
    tuple(0.5 + 0.1 * math.sin(3 * k * 2 * math.pi / 12) + 0.05 * (k % 2) for k in range(12))
)
profile = st.one_of(st.builds(EccentricDisc, st.floats(0.3, 1.0), st.floats(0.0, 0.25)), st.just(SPLINE))


def _between(kind: Any, name: str, *rest: st.SearchStrategy[Any]) -> st.SearchStrategy[Any]:
    """Constraints of `kind` named `name` between a point of body a and a point of b or the ground,
    the rest of their fields drawn from `rest`."""
    return st.builds(
        kind, st.just(name), st.builds(Point, st.just("a"), vec), st.builds(Point, other_body, vec), *rest
    )


CONSTRAINTS = {
    "ground": st.builds(Ground, st.just("g"), st.just("a"), st.tuples(real, real, angle)),
    "revolute": _between(Revolute, "r"),
    "prismatic": _between(Prismatic, "p", vec.filter(lambda v: math.hypot(*v) > 0.1), angle),
    "revolute_revolute": _between(RevoluteRevolute, "rr", positive),
    "absolute_driver": st.builds(
        AbsoluteDriver, st.just("d"), st.just("a"), st.sampled_from(["x", "y", "theta"]), motion
    ),
    "relative_rotation": st.builds(RelativeRotationDriver, st.just("d"), st.just("a"), other_body, motion),
    "point_path": st.builds(
        PointPathDriver, st.just("d"), st.builds(Point, st.just("a"), vec), motion, motion
    ),
    "relative_displacement": _between(RelativeDisplacementDriver, "d", motion, motion),
    "gear_pair": st.builds(
        GearPair,
        st.just("m"),
        st.just("a"),
        positive,
        st.just("b"),
        positive,
        st.sampled_from([GROUND, "c"]),
        st.booleans(),
        angle,
        angle,
        angle,
    ),
    "gear_pair_fixed_sun": st.builds(
        GearPair, st.just("m"), st.just(GROUND), positive, st.just("a"), positive, st.just("c")
    ),
    "rack_pinion": st.builds(
        RackPinion,
        st.just("rp"),
        st.builds(Point, st.just("a"), vec),
        positive,
        st.builds(Point, other_body, vec),
        vec.filter(lambda v: math.hypot(*v) > 0.1),
        real,
    ),
    "knife_edge_cam": st.builds(
        KnifeEdgeCam, st.just("k"), st.just("a"), profile, st.builds(Point, st.just("b"), vec), angle
    ),
    "roller_cam": st.builds(
        RollerCam, st.just("k"), st.just("a"), profile, st.builds(Point, st.just("b"), vec), positive, angle
    ),
    "flat_face_cam": st.builds(
        FlatFaceCam,
        st.just("k"),
        st.just("a"),
        profile,
        st.builds(Point, st.just("b"), vec),
        vec.filter(lambda v: math.hypot(*v) > 0.1),
        angle,
    ),
    "cam_on_ground": st.builds(
        KnifeEdgeCam, st.just("k"), st.just(GROUND), profile, st.builds(Point, st.just("b"), vec), angle
    ),
}


def system_of(constraint) -> ConstraintSystem:  # type: ignore[no-untyped-def]
    bodies = tuple(Body(name, (0.0, 0.0, 0.0)) for name in ("a", "b", "c"))
    is_driver = isinstance(
        constraint, AbsoluteDriver | RelativeRotationDriver | PointPathDriver | RelativeDisplacementDriver
    )
    scenario = Scenario(
        family="test",
        variant="default",
        bodies=bodies,
        joints=() if is_driver else (constraint,),
        drivers=(constraint,) if is_driver else (),
        t_end=1.0,
        steps=1,
        characteristic_length=1.0,
    )
    return ConstraintSystem(scenario)


def check_derivatives(constraint, seed: int) -> None:  # type: ignore[no-untyped-def]
    system = system_of(constraint)
    rng = np.random.default_rng(seed)
    n = system.unknowns
    q = rng.uniform(-1, 1, n)
    qd = rng.uniform(-1, 1, n)
    t = float(rng.uniform(0, 2))
    c, jac, q_d = system.evaluate(q, t, qd)

    eps = 1e-6
    fd_jac = np.column_stack(
        [(system.residual(q + eps * e, t) - system.residual(q - eps * e, t)) / (2 * eps) for e in np.eye(n)]
    )
    np.testing.assert_allclose(jac, fd_jac, atol=1e-7 * (1 + np.abs(fd_jac).max()), rtol=0)

    fd_ct = (system.residual(q, t + eps) - system.residual(q, t - eps)) / (2 * eps)
    np.testing.assert_allclose(system.c_t(t), fd_ct, atol=1e-7 * (1 + np.abs(fd_ct).max()), rtol=0)

    # The second derivative along (qd, 1) by central differences at h and h/2, Richardson-extrapolated:
    # truncation O(h^4) ~ 1e-11 and round-off ~ eps / (h/2)^2 ~ 1e-10: every drawn case passes at 1e-8
    # (and several fail at 1e-9), so 1e-7 keeps a factor of ten over what the differences can resolve.
    def second(h: float) -> np.ndarray:
        return (system.residual(q + h * qd, t + h) - 2 * c + system.residual(q - h * qd, t - h)) / h**2

    h = 2e-3
    extrapolated = (4 * second(h / 2) - second(h)) / 3
    np.testing.assert_allclose(q_d, -extrapolated, atol=1e-7 * (1 + np.abs(extrapolated).max()), rtol=0)


def make_test(kind: str):  # type: ignore[no-untyped-def]
    @settings(max_examples=EXAMPLES, deadline=None, derandomize=True)
    @given(constraint=CONSTRAINTS[kind], seed=st.integers(0, 2**32 - 1))
    def test(constraint, seed):  # type: ignore[no-untyped-def]
        check_derivatives(constraint, seed)

    test.__name__ = f"test_derivatives_{kind}"
    return test


for _kind in CONSTRAINTS:
    globals()[f"test_derivatives_{_kind}"] = make_test(_kind)


@settings(max_examples=EXAMPLES, deadline=None, derandomize=True)
@given(profile=profile, phi=st.floats(-10, 10))
def test_profile_derivatives(profile, phi):  # type: ignore[no-untyped-def]
    """d(phi) and its three derivatives against central differences of the one below."""
    h = 1e-5
    here = np.array(profile.radii(phi))
    plus, minus = np.array(profile.radii(phi + h)), np.array(profile.radii(phi - h))
    fd = (plus[:3] - minus[:3]) / (2 * h)
    if isinstance(profile, EccentricDisc):
        np.testing.assert_allclose(here[1:4], fd, atol=1e-5)
    else:  # the spline's third derivative jumps at knots: d'' differenced across one is off by O(h)
        np.testing.assert_allclose(here[1], fd[0], atol=1e-8)
        np.testing.assert_allclose(here[2], fd[1], atol=1e-4)


def test_finite_differences_catch_a_wrong_jacobian(monkeypatch):  # type: ignore[no-untyped-def]
    """The check is not vacuous: a sign slip in the revolute's Jacobian makes it fail."""
    import pytest

    from reference_solver import kinematic_vectors

    original = kinematic_vectors.perp
    monkeypatch.setattr(kinematic_vectors, "perp", lambda v: -original(v))
    joint = Revolute("r", Point("a", (0.3, 0.2)), Point("b", (-0.1, 0.4)))
    with pytest.raises(AssertionError):
        check_derivatives(joint, 1)
