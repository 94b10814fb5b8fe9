"""A model's cam contacts read in bulk: which cam each pair of geoms that may touch belongs to, each
cam's closest contact, and the contact margins of some cams set for a while.

A faceted cam is hundreds of geom pairs on one follower geom (a group, adapters.mujoco.cams): explicit
contact pairs, or, for a flat face on facets, pairs MuJoCo finds itself by the cam's contype and
conaffinity bit. The assembly (adapters.mujoco.assembly) and the contact check at every output time
(adapters.mujoco.cam_load) look these up at each call. They are read from MuJoCo's arrays as plain
lists (pair_geom1/2, the name table, geom_contype/conaffinity, d.contact's columns) rather than
through one MjContact or geom view per item, which cost about 2 ms per call on 512 facets.
"""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass

import mujoco
import numpy as np

FOLLOWER = "_follower"
"""The suffix of a follower geom's name (adapters.mujoco.cams)."""


@dataclass(frozen=True)
class PairTable:
    """Per cam contact (a group, numbered in the order of the scenario's cams): its follower geom
    (`followers`) and its explicit pairs (`pairs`, none for a cam colliding by bits); and each pair of
    geoms that may touch by its two geoms, lower id first, to its group (`by_geoms`).

    The groups' order is read from the model: a cam colliding by bits has bit k of its follower's
    conaffinity where k is its index among the cams (CamPair.mask), and the explicit pairs, written in
    the cams' order, fill the other indices in the order their followers first appear."""

    followers: tuple[int, ...]
    pairs: tuple[tuple[int, ...], ...]
    by_geoms: dict[tuple[int, int], int]

    @classmethod
    def of(cls, m: mujoco.MjModel) -> PairTable:
        names, suffix = m.names, FOLLOWER.encode()
        starts = m.name_geomadr.tolist()
        pairs = list(zip(m.pair_geom1.tolist(), m.pair_geom2.tolist(), strict=True))
        firsts = set(m.pair_geom1.tolist())  # on a faceted cam, one follower or all the facets
        named = {g: names[starts[g] : names.index(b"\0", starts[g])].endswith(suffix) for g in firsts}
        paired = [first if named[first] else second for first, second in pairs]
        bits = _nonzero(m.geom_conaffinity)
        by_bits = {int(mask).bit_length() - 1: geom for geom, mask in bits}
        count = len(by_bits) + len(dict.fromkeys(paired))
        if len(by_bits) < len(bits) or any(k >= count for k in by_bits):
            raise ValueError(f"the followers' conaffinity bits {sorted(by_bits)} do not number {count} cams")
        free = iter(k for k in range(count) if k not in by_bits)
        group = {geom: next(free) for geom in dict.fromkeys(paired)}
        followers = {**by_bits, **{k: geom for geom, k in group.items()}}
        own: list[list[int]] = [[] for _ in range(count)]
        by_geoms = {}
        for k, ((a, b), follower) in enumerate(zip(pairs, paired, strict=True)):
            own[group[follower]].append(k)
            by_geoms[(a, b) if a <= b else (b, a)] = group[follower]
        for geom, mask in _nonzero(m.geom_contype):
            for k, follower in by_bits.items():
                if mask & (1 << k):
                    by_geoms[(geom, follower) if geom <= follower else (follower, geom)] = k
        return cls(tuple(followers[k] for k in range(count)), tuple(map(tuple, own)), by_geoms)

    def contacts(self, d: mujoco.MjData) -> Iterator[tuple[int, int, int, float]]:
        """Each contact over a cam's geoms, in d.contact's order: its index, its group (cam), its
        efc_address (negative: no row) and its distance."""
        n = d.ncon
        if not n or not self.followers:
            return
        c = d.contact
        columns = (
            c.geom1[:n].tolist(),
            c.geom2[:n].tolist(),
            c.efc_address[:n].tolist(),
            c.dist[:n].tolist(),
        )
        for i, (a, b, address, dist) in enumerate(zip(*columns, strict=True)):
            group = self.by_geoms.get((a, b) if a <= b else (b, a))
            if group is not None:
                yield i, group, address, dist


def collides(m: mujoco.MjModel) -> bool:
    """Whether the model has cam contacts: explicit pairs, or geoms colliding by bits."""
    return bool(m.npair) or bool(np.any(m.geom_conaffinity))


def _nonzero(column: np.ndarray) -> list[tuple[int, int]]:
    """(geom, value) of each geom whose value in this contype or conaffinity column is not zero."""
    found = np.flatnonzero(column)
    return list(zip(found.tolist(), column[found].tolist(), strict=True))


def closest_contacts(m: mujoco.MjModel, d: mujoco.MjData, table: PairTable | None = None) -> dict[int, int]:
    """Per cam contact (pair group), the index in d.contact of its closest contact with a row.
    `table`: PairTable.of(m), where the caller has it already."""
    table = PairTable.of(m) if table is None else table
    best: dict[int, tuple[float, int]] = {}
    for i, group, address, dist in table.contacts(d):
        if address < 0:
            continue
        if group not in best or dist < best[group][0]:
            best[group] = (dist, i)
    return {group: i for group, (_, i) in best.items()}


@contextmanager
def margins(
    m: mujoco.MjModel, table: PairTable, margin: float, groups: list[int] | None = None
) -> Iterator[None]:
    """Meanwhile, these cams' contacts (all by default) are detected within `margin`: their explicit
    pairs' margin, or, colliding by bits, their follower geom's (the cam geoms' are 0, and MuJoCo adds
    the two) and its body's, which MuJoCo's mid-phase tests the bodies' bounding-volume trees with
    (the compiler's largest geom margin plus gap of the body, kept so here)."""
    chosen = range(len(table.followers)) if groups is None else groups
    pairs = [p for k in chosen for p in table.pairs[k]]
    geoms = [table.followers[k] for k in chosen if not table.pairs[k]]
    bodies = sorted({int(m.geom_bodyid[g]) for g in geoms})
    saved = (m.pair_margin[pairs].copy(), m.geom_margin[geoms].copy(), m.body_margin[bodies].copy())
    m.pair_margin[pairs] = margin
    m.geom_margin[geoms] = margin
    for body in bodies:
        own = slice(m.body_geomadr[body], m.body_geomadr[body] + m.body_geomnum[body])
        m.body_margin[body] = float(np.max(m.geom_margin[own] + m.geom_gap[own]))
    try:
        yield
    finally:
        m.pair_margin[pairs], m.geom_margin[geoms], m.body_margin[bodies] = saved
