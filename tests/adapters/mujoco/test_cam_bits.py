"""A flat face on a faceted cam collides by a contype/conaffinity bit (adapters.mujoco.cams) and its
contacts are those of one explicit pair per facet, the construction it replaced: built here apart from
the adapter's writer, from the model's own MJCF (the same geoms, each bit's geoms paired by hand), and
compared contact by contact at many random cam angles and follower positions, with and without a
detection margin, for equality of every field the solver reads; the closest distance and normal
against the face's plane computed from the facets' end points; a run of steps, equal to the bit. The
table of cam contacts numbers a model mixing both kinds in the order of its cams, and `margins` gives
a cam colliding by bits the body margin MuJoCo's compiler gives a geom margin written in the file."""

from __future__ import annotations

import xml.etree.ElementTree as ET

import mujoco
import numpy as np
import pytest

import scenarios
from adapters.base import EngineFailure
from adapters.mujoco import MujocoAdapter
from adapters.mujoco.cam_load import check_contacts
from adapters.mujoco.pairs import PairTable, closest_contacts, margins
from adapters.mujoco.scale import scale_of
from scenarios.cams import follower_body

ADAPTER = MujocoAdapter()
SAMPLES = 200


def explicit_pairs(xml: str) -> str:
    """The model with each bit's cam geoms and follower as explicit pairs, in the geoms' order,
    carrying the geoms' condim, solref and solimp; no geom collides by bits."""
    root = ET.fromstring(xml)
    geoms = list(root.iter("geom"))
    followers = [g for g in geoms if int(g.get("conaffinity", "0"))]
    contact = root.find("contact")
    if contact is None:
        contact = ET.SubElement(root, "contact")
    for follower in followers:
        bit = int(follower.get("conaffinity", "0"))
        for geom in geoms:
            if int(geom.get("contype", "0")) & bit:
                attrs = {key: geom.get(key, "") for key in ("name", "condim", "solref", "solimp")}
                attrs["geom1"], attrs["geom2"] = attrs.pop("name"), follower.get("name", "")
                ET.SubElement(contact, "pair", attrs)
    for geom in geoms:
        geom.set("contype", "0")
        geom.set("conaffinity", "0")
    flag = root.find("option/flag")
    assert flag is not None
    flag.attrib.pop("filterparent", None)
    return ET.tostring(root, encoding="unicode")


@pytest.fixture(scope="module")
def flat_face() -> tuple[scenarios.Scenario, str]:
    scenario = scenarios.build("cam_flat_face/spline")
    return scenario, ADAPTER.build(scenario, ADAPTER.default_setting(scenario)).xml


def _contacts(m: mujoco.MjModel, d: mujoco.MjData) -> np.ndarray:
    """Every field of d.contact the constraint solver reads, one row per contact, in order."""
    n = d.ncon
    c = d.contact
    columns = (
        c.geom[:n],
        c.dist[:n, None],
        c.pos[:n],
        c.frame[:n],
        c.dim[:n, None],
        c.includemargin[:n, None],
    )
    more = (c.solref[:n], c.solimp[:n], c.friction[:n], c.solreffriction[:n], c.mu[:n, None])
    return (
        np.hstack([np.asarray(a, dtype=float).reshape(n, -1) for a in (*columns, *more)])
        if n
        else np.empty((0, 0))
    )


def _face_distance(m: mujoco.MjModel, d: mujoco.MjData, name: str) -> tuple[float, np.ndarray]:
    """The least distance from the cam's facets to the follower's face, and the face's outward normal:
    the face is the box's side at -y (adapters.mujoco.cams: the box lies behind its face), each facet
    a capsule whose outer side is its segment moved by its radius."""
    box = m.geom(f"{name}_follower").id
    normal = -d.geom_xmat[box].reshape(3, 3)[:, 1]
    plane = d.geom_xpos[box] + normal * m.geom_size[box][1]
    least = np.inf
    for g in range(m.ngeom):
        if m.geom(g).name.startswith(f"{name}_cam"):
            axis = d.geom_xmat[g].reshape(3, 3)[:, 2] * m.geom_size[g][1]
            ends = (d.geom_xpos[g] + axis, d.geom_xpos[g] - axis)
            least = min(least, *((end - plane) @ normal - m.geom_size[g][0] for end in ends))
    return float(least), normal


def _place(m: mujoco.MjModel, d: mujoco.MjData, name: str, follower_q: int, target: float) -> None:
    """Slide the follower so that its face is `target` from the cam (the distance is linear in the
    slide: the face is a plane moving along the follower's line)."""
    mujoco.mj_kinematics(m, d)
    before, _ = _face_distance(m, d, name)
    d.qpos[follower_q] += 0.01
    mujoco.mj_kinematics(m, d)
    slope = (_face_distance(m, d, name)[0] - before) / 0.01
    d.qpos[follower_q] += (target - before) / slope - 0.01


@pytest.mark.parametrize("margin", [0.0, 1.0])
def test_the_contacts_are_those_of_one_explicit_pair_per_facet(flat_face, margin: float) -> None:  # type: ignore[no-untyped-def]
    # margin: in characteristic lengths (1: the assembly's, where hundreds of facets have contacts);
    # the face from 0.2 % of the length into the cam (20 times the preload's static penetration,
    # half a facet's radius) to 0.2 % off it, or to half the margin off
    scenario, xml = flat_face
    bits, pairs = mujoco.MjModel.from_xml_string(xml), mujoco.MjModel.from_xml_string(explicit_pairs(xml))
    assert pairs.npair == 512 and not np.any(pairs.geom_contype)
    assert bits.npair == 0 and np.count_nonzero(bits.geom_contype) == 512
    contact = scenario.cams[0]
    cam_q = bits.jnt_qposadr[bits.body(contact.cam).jntadr[0]]
    follower_q = bits.jnt_qposadr[bits.body(follower_body(contact)).jntadr[0]]
    length = scale_of(scenario).length
    rng = np.random.default_rng(20261125)
    d_bits, d_pairs = mujoco.MjData(bits), mujoco.MjData(pairs)
    mujoco.mj_resetDataKeyframe(bits, d_bits, 0)
    start = d_bits.qpos.copy()
    touching = 0
    with margins(bits, PairTable.of(bits), margin * length):
        pairs.pair_margin[:] = margin * length
        for _ in range(SAMPLES):
            d_bits.qpos[:] = start
            d_bits.qpos[cam_q] = rng.uniform(0.0, 2.0 * np.pi)
            target = rng.uniform(-0.002, max(0.002, margin / 2)) * length
            _place(bits, d_bits, contact.name, follower_q, target)
            d_pairs.qpos[:] = d_bits.qpos
            for m, d in ((bits, d_bits), (pairs, d_pairs)):
                mujoco.mj_kinematics(m, d)
                mujoco.mj_collision(m, d)
            np.testing.assert_array_equal(_contacts(bits, d_bits), _contacts(pairs, d_pairs))
            distance, normal = _face_distance(bits, d_bits, contact.name)
            assert distance == pytest.approx(target, abs=1e-12 * length)
            if distance < margin * length:
                touching += 1
                closest = int(np.argmin(d_bits.contact.dist[: d_bits.ncon]))
                assert abs(d_bits.contact.dist[closest] - distance) <= 1e-12 * length
                assert abs(abs(d_bits.contact.frame[closest][:3] @ normal) - 1.0) <= 1e-12
            else:
                assert d_bits.ncon == 0
    assert touching >= (SAMPLES if margin else SAMPLES // 4)


def test_a_run_of_steps_is_the_explicit_pairs_run_to_the_bit(flat_face) -> None:  # type: ignore[no-untyped-def]
    _, xml = flat_face
    runs = []
    for text in (xml, explicit_pairs(xml)):
        m = mujoco.MjModel.from_xml_string(text)
        d = mujoco.MjData(m)
        mujoco.mj_resetDataKeyframe(m, d, 0)
        states = []
        for _ in range(300):
            mujoco.mj_step(m, d)
            states.append(np.concatenate([d.qpos, d.qvel, d.qacc, d.efc_force]))
        runs.append(np.concatenate(states))
        assert d.ncon >= 1
    np.testing.assert_array_equal(runs[0], runs[1])


def test_only_a_flat_face_on_facets_collides_by_bits() -> None:
    for name, bits in (
        ("cam_flat_face/spline", True),
        ("cam_roller/spline", False),
        ("cam_flat_face", False),
    ):
        scenario = scenarios.build(name)
        setting = ADAPTER.default_setting(scenario).replace(cam_model="contact", preload=100.0)
        xml = ADAPTER.build(scenario, setting).xml
        m = mujoco.MjModel.from_xml_string(xml)
        assert bool(np.any(m.geom_contype)) == bits, name
        assert bool(m.opt.disableflags & mujoco.mjtDisableBit.mjDSBL_FILTERPARENT) == bits, name
        assert (m.npair == 0) == bits, name


MIXED = """
<mujoco>
  <option><flag filterparent="disable"/></option>
  <default><geom contype="0" conaffinity="0"/></default>
  <worldbody>
    <body name="c0"><joint type="hinge" axis="0 0 1"/>
      <geom name="a_cam0" type="capsule" fromto="0 0 0 0.1 0 0" size="0.01"/>
      <geom name="a_cam1" type="capsule" fromto="0.1 0 0 0.1 0.1 0" size="0.01"/>
    </body>
    <body name="f0" pos="0.2 0 0"><joint type="slide" axis="1 0 0"/>
      <geom name="a_follower" type="sphere" size="0.02"/>
    </body>
    <body name="c1" pos="0 1 0"><joint type="hinge" axis="0 0 1"/>
      <geom type="sphere" size="0.05" rgba="1 1 1 1"/>
      <geom name="b_cam0" type="capsule" fromto="0 0 0 0.1 0 0" size="0.01" contype="2" conaffinity="0"/>
      <geom name="b_cam1" type="capsule" fromto="0.1 0 0 0.1 0.1 0" size="0.01" contype="2" conaffinity="0"/>
    </body>
    <body name="f1" pos="0.2 1 0"><joint type="slide" axis="1 0 0"/>
      <geom type="sphere" size="0.01"/>
      <geom name="b_follower" type="box" size="0.3 0.02 0.02" contype="0" conaffinity="2" MARGIN/>
    </body>
    <body name="c2" pos="0 2 0"><joint type="hinge" axis="0 0 1"/>
      <geom name="c_cam" type="capsule" fromto="0 0 0 0.1 0 0" size="0.01"/>
    </body>
    <body name="f2" pos="0.2 2 0"><joint type="slide" axis="1 0 0"/>
      <geom name="c_follower" type="sphere" size="0.02"/>
    </body>
  </worldbody>
  <contact>
    <pair geom1="a_follower" geom2="a_cam0"/>
    <pair geom1="a_cam1" geom2="a_follower"/>
    <pair geom1="c_cam" geom2="c_follower"/>
  </contact>
</mujoco>
"""


def test_a_mixed_model_numbers_its_cams_in_their_order() -> None:
    m = mujoco.MjModel.from_xml_string(MIXED.replace("MARGIN", ""))
    table = PairTable.of(m)
    geom = {
        name: m.geom(name).id for name in ("a_cam0", "a_cam1", "a_follower", "b_cam0", "b_cam1", "b_follower")
    }
    geom.update(c_cam=m.geom("c_cam").id, c_follower=m.geom("c_follower").id)
    assert table.followers == (geom["a_follower"], geom["b_follower"], geom["c_follower"])
    assert table.pairs == ((0, 1), (), (2,))
    expected = {
        frozenset((geom["a_cam0"], geom["a_follower"])): 0,
        frozenset((geom["a_cam1"], geom["a_follower"])): 0,
        frozenset((geom["b_cam0"], geom["b_follower"])): 1,
        frozenset((geom["b_cam1"], geom["b_follower"])): 1,
        frozenset((geom["c_cam"], geom["c_follower"])): 2,
    }
    assert {frozenset(pair): k for pair, k in table.by_geoms.items()} == expected
    assert all(a <= b for a, b in table.by_geoms)
    wrong = (
        MIXED.replace("MARGIN", "")
        .replace('contype="2"', 'contype="8"')
        .replace('conaffinity="2"', 'conaffinity="8"')
    )
    with pytest.raises(ValueError, match="do not number 3 cams"):
        PairTable.of(mujoco.MjModel.from_xml_string(wrong))


def test_margins_are_set_as_the_compiler_sets_them_and_restored() -> None:
    m = mujoco.MjModel.from_xml_string(MIXED.replace("MARGIN", ""))
    written = mujoco.MjModel.from_xml_string(MIXED.replace("MARGIN", 'margin="0.3"'))
    table = PairTable.of(m)
    before = (m.pair_margin.copy(), m.geom_margin.copy(), m.body_margin.copy())
    with margins(m, table, 0.3, [1, 2]):
        np.testing.assert_array_equal(m.body_margin, written.body_margin)
        np.testing.assert_array_equal(m.geom_margin, written.geom_margin)
        np.testing.assert_array_equal(m.pair_margin, [0.0, 0.0, 0.3])
    np.testing.assert_array_equal(m.pair_margin, before[0])
    np.testing.assert_array_equal(m.geom_margin, before[1])
    np.testing.assert_array_equal(m.body_margin, before[2])


def test_a_face_lifted_off_fails_past_its_allowance_and_not_before(flat_face) -> None:  # type: ignore[no-untyped-def]
    scenario, xml = flat_face
    m = mujoco.MjModel.from_xml_string(xml)
    d = mujoco.MjData(m)
    mujoco.mj_resetDataKeyframe(m, d, 0)
    mujoco.mj_forward(m, d)
    contact = scenario.cams[0]
    dof = m.jnt_dofadr[m.body(follower_body(contact)).jntadr[0]]
    closest = closest_contacts(m, d)[0]
    slope = d.efc_J.reshape(d.nefc, m.nv)[d.contact[closest].efc_address, dof]
    depth = -float(d.contact[closest].dist)
    gap = 1e-4 * scale_of(scenario).length
    d.qpos[m.jnt_qposadr[m.body(follower_body(contact)).jntadr[0]]] += (depth + gap) / slope
    mujoco.mj_forward(m, d)
    assert closest_contacts(m, d) == {}
    lifted, _ = _face_distance(m, d, contact.name)
    assert lifted == pytest.approx(gap, rel=1e-6)
    check_contacts(m, d, 100.0, {0: 1.01 * gap})
    with pytest.raises(EngineFailure, match=f"contact lost: cam '{contact.name}'"):
        check_contacts(m, d, 100.0, {0: 0.99 * gap})
    assert m.geom_margin.max() == 0.0 and m.body_margin.max() == 0.0
