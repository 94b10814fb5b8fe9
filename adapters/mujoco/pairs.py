"""A model's cam contacts read in bulk: which cam each pair of geoms that may touch belongs to, each
cam's closest contact, and the contact margins of some cams set for a while.

A faceted cam is hundreds of geom pairs on one follower geom (a group, adapters.mujoco.cams): explicit
contact pairs, or, for a flat face on facets, pairs MuJoCo finds itself by the cam's contype and
conaffinity bit. The assembly (adapters.mujoco.assembly) and the contact check at every output time
(adapters.mujoco.cam_load) look these up at each call. They are read from MuJoCo's arrays as plain
lists (pair_geom1/2, the name table, geom_contype/conaffinity, d.contact's columns) rather than
through one MjContact or geom view per item, which costs far more per call on hundreds of facets; the
closest contacts of more than MANY contacts (the assembly's margin reaches hundreds of facets) on
arrays, with the same answers.
"""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field

import mujoco
import numpy as np

FOLLOWER = "_follower"
"""The suffix of a follower geom's name (adapters.mujoco.cams)."""
MANY = 32
"""Contacts from which closest_contacts works on arrays (below, numpy's per-call overhead costs more
than the loop: 7 us against 0.1-0.2 ms on a disc cam's two contacts)."""


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
    keys: np.ndarray = field(default_factory=lambda: np.empty(0, dtype=np.int64), compare=False)
    """by_geoms' geom pairs as lower * ngeom + higher, sorted, for lookups on arrays."""
    key_groups: np.ndarray = field(default_factory=lambda: np.empty(0, dtype=np.int64), compare=False)
    """The group of each of `keys`."""
    ngeom: int = 0
    """The model's geom count, the base of `keys`."""

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
        keys = np.array([a * m.ngeom + b for a, b in by_geoms], dtype=np.int64)
        order = np.argsort(keys)
        key_groups = np.array(list(by_geoms.values()), dtype=np.int64)[order]
        own_pairs = tuple(map(tuple, own))
        return cls(
            tuple(followers[k] for k in range(count)), own_pairs, by_geoms, keys[order], key_groups, m.ngeom
        )

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

    def groups_of(self, d: mujoco.MjData) -> np.ndarray:
        """Each contact's group (cam), -1 where its geoms are no cam's or it has no row."""
        n = d.ncon
        c = d.contact
        first, second = c.geom1[:n].astype(np.int64), c.geom2[:n].astype(np.int64)
        keys = np.minimum(first, second) * self.ngeom + np.maximum(first, second)
        at = np.minimum(np.searchsorted(self.keys, keys), len(self.keys) - 1)
        found = (self.keys[at] == keys) & (c.efc_address[:n] >= 0)
        return np.where(found, self.key_groups[at], -1)


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
    if d.ncon > MANY and len(table.keys):
        return _closest_on_arrays(d, table)
    best: dict[int, tuple[float, int]] = {}
    for i, group, address, dist in table.contacts(d):
        if address < 0:
            continue
        if group not in best or dist < best[group][0]:
            best[group] = (dist, i)
    return {group: i for group, (_, i) in best.items()}


def _closest_on_arrays(d: mujoco.MjData, table: PairTable) -> dict[int, int]:
    """closest_contacts on arrays, the loop's answer: per group in the order its first contact with a
    row comes, the first of its least distances, or its first contact where that one's distance is
    NaN (no distance is below a NaN, and a later NaN is below none)."""
    groups = table.groups_of(d)
    dist = d.contact.dist[: d.ncon]
    best = {}
    for group in dict.fromkeys(groups[groups >= 0].tolist()):
        ours = np.flatnonzero(groups == group)
        values = dist[ours]
        if np.isnan(values[0]):
            best[group] = int(ours[0])
            continue
        numbers = ~np.isnan(values)
        best[group] = int(ours[numbers][np.argmin(values[numbers])])
    return best


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
