"""MuJoCo's stepping as the adapter drives it: the time a divergence is reported at is the start of
the first bad step, found again here by stepping one step at a time; a divergence before t = 0 is
said to be in the run-in, one at t = 0 is not; and softening sets every equality's and contact
pair's solref and the step from the built model."""

from __future__ import annotations

from collections.abc import Iterator

import mujoco
import numpy as np
import pytest

import scenarios
from adapters.base import Setting
from adapters.failures import Diverged
from adapters.mujoco import adapter as mujoco_adapter
from adapters.mujoco.adapter import MujocoAdapter
from adapters.mujoco.simulation import advance, soften

DT = 0.01
SPRING = """<mujoco><option timestep="0.01" integrator="Euler"/><worldbody><body>
<joint name="x" type="slide" axis="1 0 0" stiffness="1e6"/><geom type="sphere" size="0.1" mass="1"/>
</body></worldbody></mujoco>"""
"""A unit mass on a spring of omega = 1000 rad/s stepped at 0.01 s (omega dt = 10, far past the
explicit step's limit of 2): its excursion grows about 100-fold a step until MuJoCo finds the
acceleration bad."""


@pytest.fixture(autouse=True)
def _quiet_mujoco() -> Iterator[None]:
    """MuJoCo's bad-acceleration warnings dropped here (else MuJoCo writes them to MUJOCO_LOG.TXT in
    the working directory); the adapter's handler back afterwards."""
    mujoco.set_mju_user_warning(lambda message: None)
    yield
    mujoco.set_mju_user_warning(mujoco_adapter._warn)


def _bad(d: mujoco.MjData) -> bool:
    return d.warning[mujoco.mjtWarning.mjWARN_BADQACC].number > 0 or not np.isfinite(d.qpos).all()


def _first_bad_step_start(m: mujoco.MjModel, start: float, x0: float) -> float:
    """The time at the start of the first step after which MuJoCo's state is bad, stepped singly."""
    d = mujoco.MjData(m)
    d.time, d.qpos[0] = start, x0
    for _ in range(1000):
        t = d.time
        mujoco.mj_step(m, d)
        if _bad(d):
            return float(t)
    raise AssertionError("never diverged")


def _diverged_at(start: float, x0: float) -> Diverged:
    m = mujoco.MjModel.from_xml_string(SPRING)
    d = mujoco.MjData(m)
    d.time, d.qpos[0] = start, x0
    with pytest.raises(Diverged) as caught:
        advance(m, d, 200)
    return caught.value


def test_a_divergence_is_reported_at_the_start_of_its_first_bad_step() -> None:
    """Started 1e-20 off its rest, the spring steps many times before its acceleration is bad: the
    time is that step's, not the start of the advance (0)."""
    m = mujoco.MjModel.from_xml_string(SPRING)
    expected = _first_bad_step_start(m, 0.0, 1e-20)
    assert expected > 5 * DT
    error = _diverged_at(0.0, 1e-20)
    assert error.time == pytest.approx(expected, abs=1e-12)
    assert str(error) == f"MuJoCo became unstable (bad acceleration) at t = {expected:.6g} s"


def test_a_divergence_before_the_start_is_in_the_run_in_and_one_at_zero_is_not() -> None:
    m = mujoco.MjModel.from_xml_string(SPRING)
    early = _first_bad_step_start(m, -1.0, 1e-20)
    assert early < 0.0
    assert str(_diverged_at(-1.0, 1e-20)) == (
        f"MuJoCo became unstable (bad acceleration) at t = {early:.6g} s (in the run-in before the start)"
    )
    at_once = _diverged_at(0.0, 1e5)  # an acceleration of 1e11 on the first step
    assert at_once.time == 0.0
    assert str(at_once) == "MuJoCo became unstable (bad acceleration) at t = 0 s"


def test_softening_sets_the_built_model_s_step_and_solrefs_on_every_pair_and_equality() -> None:
    """A roller cam as a contact, stepped by RK4 (not the kinematic mode), collides through explicit
    pairs."""
    adapter = MujocoAdapter()
    scenario = scenarios.build("cam_roller")
    setting = Setting("RK4", adapter.default_setting(scenario).options).replace(cam_model="contact")
    model = adapter.build(scenario, setting)
    m = model.model
    assert m.npair > 0 and m.neq > 0
    m.opt.timestep, m.pair_solref[:], m.eq_solref[:] = 1.0, 0.5, 0.5
    soften(m, model)
    assert m.opt.timestep == model.dt
    assert (m.pair_solref == np.asarray(model.contact_solref)).all()
    assert (m.eq_solref == np.asarray(model.solref)).all()
