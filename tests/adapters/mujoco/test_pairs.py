"""The cam contacts read as lists (adapters.mujoco.pairs) against the loop they replaced, for
equality: MuJoCo's MjContact and geom views one by one, frozensets of geoms, each pair's cam by the
geoms' names ('<cam>_follower' and '<cam>_cam<k>', in the scenario's order of cams, for explicit
pairs and for a flat face colliding by bits alike), the closest contact per cam by a strict '<' in
contact order."""

from __future__ import annotations

import mujoco
import numpy as np
import pytest

import scenarios
from adapters.mujoco import MujocoAdapter
from adapters.mujoco.pairs import MANY, PairTable, closest_contacts, margins
from adapters.mujoco.scale import scale_of
from scenarios.scenario import Scenario

ADAPTER = MujocoAdapter()


def old_groups(m: mujoco.MjModel, scenario: Scenario) -> dict[frozenset[int], int]:
    """Each pair of a cam geom and its follower -> the cam's index, by MuJoCo's geom views' names."""
    names = [m.geom(g).name for g in range(m.ngeom)]
    found = {}
    for k, cam in enumerate(scenario.cams):
        follower = names.index(f"{cam.name}_follower")
        for g, name in enumerate(names):
            piece = name.removeprefix(f"{cam.name}_cam")
            if piece != name and (piece == "" or piece.isdigit()):
                found[frozenset((g, follower))] = k
    return found


def old_closest(m: mujoco.MjModel, d: mujoco.MjData, scenario: Scenario) -> dict[int, int]:
    """closest_contacts as a loop over d.contact's MjContact views, with frozensets of geoms."""
    groups = old_groups(m, scenario)
    best: dict[int, tuple[float, int]] = {}
    for i in range(d.ncon):
        contact = d.contact[i]
        group = groups.get(frozenset((int(contact.geom1), int(contact.geom2))))
        if group is None or contact.efc_address < 0:
            continue
        dist = float(contact.dist)
        if group not in best or dist < best[group][0]:
            best[group] = (dist, i)
    return {group: i for group, (_, i) in best.items()}


@pytest.mark.parametrize(
    "name",
    ("cam_roller/spline", "cam_knife_edge/spline", "cam_flat_face/spline", "cam_flat_face", "cam_knife_edge"),
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
    table = PairTable.of(m)
    with margins(m, table, scale_of(scenario).length):
        mujoco.mj_forward(m, d)
    assert d.ncon >= 2
    groups = old_groups(m, scenario)
    assert {frozenset(geoms): k for geoms, k in table.by_geoms.items()} == groups
    assert [m.geom(g).name for g in table.followers] == [f"{cam.name}_follower" for cam in scenario.cams]
    assert closest_contacts(m, d) == closest_contacts(m, d, table) == old_closest(m, d, scenario)
    views = [d.contact[i] for i in range(d.ncon)]
    expected = [
        (i, groups.get(frozenset((int(c.geom1), int(c.geom2)))), int(c.efc_address), float(c.dist))
        for i, c in enumerate(views)
    ]
    assert list(table.contacts(d)) == [e for e in expected if e[1] is not None]
    rounded = np.round(d.contact.dist, 3)  # ties everywhere: of equally close contacts, the first
    d.contact.dist[:] = rounded
    assert closest_contacts(m, d) == old_closest(m, d, scenario)
    d.contact.dist[0] = np.nan  # a NaN met first stays, as no distance is below it
    assert closest_contacts(m, d) == old_closest(m, d, scenario)
    d.contact.efc_address[0] = -1  # a contact without a row is not the cam's
    assert closest_contacts(m, d) == old_closest(m, d, scenario)
    d.contact.dist[d.ncon // 2] = np.nan  # a NaN met later is below none
    assert closest_contacts(m, d) == old_closest(m, d, scenario)
    d.contact.dist[:] = rounded  # the least distance on the last contact
    d.contact.dist[d.ncon - 1] = -1.0
    assert closest_contacts(m, d) == old_closest(m, d, scenario) == {0: d.ncon - 1}
    assert (d.ncon > MANY) == (name.endswith("/spline"))  # both ways of finding it are compared
