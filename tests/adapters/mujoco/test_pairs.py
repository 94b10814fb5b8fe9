"""The cam contact pairs read as lists (adapters.mujoco.pairs) against the loop they replaced, for
equality: MuJoCo's MjContact and geom views one by one, frozensets of geoms, each pair's group by its
follower geom's name, the closest contact per cam by a strict '<' in contact order."""

from __future__ import annotations

import mujoco
import numpy as np
import pytest

import scenarios
from adapters.mujoco import MujocoAdapter
from adapters.mujoco.pairs import FOLLOWER, PairTable, closest_contacts
from adapters.mujoco.scale import scale_of

ADAPTER = MujocoAdapter()


def old_groups(m: mujoco.MjModel) -> dict[int, int]:
    """Each pair's group, by the geom names of MuJoCo's geom views."""
    geoms = []
    for k in range(m.npair):
        first = int(m.pair_geom1[k])
        geoms.append(first if m.geom(first).name.endswith(FOLLOWER) else int(m.pair_geom2[k]))
    followers = list(dict.fromkeys(geoms))
    return {k: followers.index(g) for k, g in enumerate(geoms)}


def old_closest(m: mujoco.MjModel, d: mujoco.MjData) -> dict[int, int]:
    """closest_contacts as a loop over d.contact's MjContact views, with frozensets of geoms."""
    groups = old_groups(m)
    pairs = {frozenset((int(m.pair_geom1[k]), int(m.pair_geom2[k]))): k for k in range(m.npair)}
    best: dict[int, tuple[float, int]] = {}
    for i in range(d.ncon):
        contact = d.contact[i]
        pair = pairs.get(frozenset((int(contact.geom1), int(contact.geom2))))
        if pair is None or contact.efc_address < 0:
            continue
        group, dist = groups[pair], float(contact.dist)
        if group not in best or dist < best[group][0]:
            best[group] = (dist, i)
    return {group: i for group, (_, i) in best.items()}


@pytest.mark.parametrize(
    "name", ("cam_roller/spline", "cam_knife_edge/spline", "cam_flat_face", "cam_knife_edge")
)
def test_closest_contacts_are_the_per_contact_loop(name: str) -> None:
    # At the assembly's margin a faceted cam has rows on hundreds of facets; a disc's capsule two
    # equally close ones under a box (the first is the cam's).
    scenario = scenarios.build(name)
    contact = ADAPTER.default_setting(scenario).replace(
        cam_model="contact", preload=100.0, contact_impedance=0.99
    )
    built = ADAPTER.build(scenario, contact)
    m, d = built.model, mujoco.MjData(built.model)
    d.qpos[:] = built.qpos0
    m.pair_margin[:] = scale_of(scenario).length
    mujoco.mj_forward(m, d)
    assert d.ncon >= 2
    table = PairTable.of(m)
    assert dict(enumerate(table.groups)) == old_groups(m)
    assert closest_contacts(m, d) == closest_contacts(m, d, table) == old_closest(m, d)
    pairs = {frozenset((int(m.pair_geom1[k]), int(m.pair_geom2[k]))): k for k in range(m.npair)}
    views = [d.contact[i] for i in range(d.ncon)]
    expected = [
        (i, pairs.get(frozenset((int(c.geom1), int(c.geom2)))), int(c.efc_address), float(c.dist))
        for i, c in enumerate(views)
    ]
    assert list(table.contacts(d)) == [e for e in expected if e[1] is not None]
    rounded = np.round(d.contact.dist, 3)  # ties everywhere: of equally close contacts, the first
    d.contact.dist[:] = rounded
    assert closest_contacts(m, d) == old_closest(m, d)
    d.contact.dist[0] = np.nan  # a NaN met first stays, as no distance is below it
    assert closest_contacts(m, d) == old_closest(m, d)
    d.contact.efc_address[0] = -1  # a contact without a row is not the cam's
    assert closest_contacts(m, d) == old_closest(m, d)
