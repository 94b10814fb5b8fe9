"""A model's cam contact pairs read in bulk: which cam each pair belongs to, which pair each contact
is of, and each cam's closest contact.

A faceted cam is hundreds of pairs on one follower geom (a group, adapters.mujoco.cams), and the
assembly (adapters.mujoco.assembly) and the contact check at every output time
(adapters.mujoco.cam_load) look these up at each call. They are read from MuJoCo's arrays as plain
lists (pair_geom1/2, the name table, d.contact's columns) rather than through one MjContact or
geom view per item, which cost about 2 ms per call on 512 facets; the lookups themselves are the
same, so the answers are.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass

import mujoco

FOLLOWER = "_follower"
"""The suffix of a follower geom's name (adapters.mujoco.cams)."""


def follower_geom(m: mujoco.MjModel, pair: int) -> int:
    """The pair's follower geom (named '<cam>_follower'; MuJoCo may store it as either geom)."""
    first = int(m.pair_geom1[pair])
    return first if m.geom(first).name.endswith(FOLLOWER) else int(m.pair_geom2[pair])


@dataclass(frozen=True)
class PairTable:
    """Each pair's cam contact (`groups`: the index of its follower geom among the pairs' follower
    geoms, in the order of the pairs, which is the order of the scenario's cams), and each pair by
    its two geoms (`by_geoms`, lower id first; of two pairs over the same geoms, the later)."""

    groups: tuple[int, ...]
    by_geoms: dict[tuple[int, int], int]

    @classmethod
    def of(cls, m: mujoco.MjModel) -> PairTable:
        names, suffix = m.names, FOLLOWER.encode()
        starts = m.name_geomadr.tolist()
        pairs = list(zip(m.pair_geom1.tolist(), m.pair_geom2.tolist(), strict=True))
        firsts = set(m.pair_geom1.tolist())  # on a faceted cam, one follower or all the facets
        named = {g: names[starts[g] : names.index(b"\0", starts[g])].endswith(suffix) for g in firsts}
        followers = [first if named[first] else second for first, second in pairs]
        index = {geom: k for k, geom in enumerate(dict.fromkeys(followers))}
        by_geoms = {((a, b) if a <= b else (b, a)): k for k, (a, b) in enumerate(pairs)}
        return cls(tuple(index[geom] for geom in followers), by_geoms)

    def contacts(self, d: mujoco.MjData) -> Iterator[tuple[int, int, int, float]]:
        """Each contact over a pair's geoms, in d.contact's order: its index, its pair, its
        efc_address (negative: no row) and its distance."""
        n = d.ncon
        if not n or not self.groups:
            return
        c = d.contact
        columns = (
            c.geom1[:n].tolist(),
            c.geom2[:n].tolist(),
            c.efc_address[:n].tolist(),
            c.dist[:n].tolist(),
        )
        for i, (a, b, address, dist) in enumerate(zip(*columns, strict=True)):
            pair = self.by_geoms.get((a, b) if a <= b else (b, a))
            if pair is not None:
                yield i, pair, address, dist


def closest_contacts(m: mujoco.MjModel, d: mujoco.MjData, table: PairTable | None = None) -> dict[int, int]:
    """Per cam contact (pair group), the index in d.contact of its closest contact with a row.
    `table`: PairTable.of(m), where the caller has it already."""
    table = PairTable.of(m) if table is None else table
    best: dict[int, tuple[float, int]] = {}
    for i, pair, address, dist in table.contacts(d):
        if address < 0:
            continue
        group = table.groups[pair]
        if group not in best or dist < best[group][0]:
            best[group] = (dist, i)
    return {group: i for group, (_, i) in best.items()}
