"""A stored table as Parquet parts: which parts a generation lists, and which a save writes.

A table (results.parquet, trajectories.parquet) is a folder of parts, part-NNNNNN.parquet, listed in
order in the generation's sidecar. Each part holds entries keyed by (scenario, engine, setting) and
the keys deleted just before it (`removed`); an entry in a later part wins over one in an earlier
part, and a removed key hides the entries of the parts before. A save writes the entries changed
since the last one as one new part and lists the older parts again without reading or rewriting
them; so a save costs its batch, not the store.

So that the parts stay few, a save also merges (compaction, written from the entries the store holds
in memory, which are the stored ones): the newest parts, from the oldest one that holds no more live
entries than RATIO times all the parts after it, become one part (each entry is rewritten about
log2(n) times over a store's life, and a store of n entries has about log2(n) parts), but a part of
`cap` entries or more is sealed and merged no further (so no save rewrites more than about 2 * cap
entries); a part of which less than half is live (replaced or deleted since) is rewritten with its live
entries alone.
"""

from __future__ import annotations

import re
from collections.abc import Collection, Iterable, Mapping
from dataclasses import dataclass
from typing import Any

Key = tuple[str, str, str]
PART = re.compile(r"part-(\d{6,})\.parquet")
RATIO = 1.0
MIN_GARBAGE = 64  # a part smaller than this is never rewritten for its dead entries alone


@dataclass(frozen=True)
class Part:
    """One part file of a table: its name, the entries written in it, and the keys deleted just
    before it (which hide the entries of the older parts)."""

    file: str
    entries: int
    removed: tuple[Key, ...] = ()

    def to_json(self) -> dict[str, Any]:
        return {"file": self.file, "entries": self.entries, "removed": [list(k) for k in self.removed]}

    @staticmethod
    def from_json(value: Any) -> Part:
        """A part as the sidecar lists it; ValueError when it is not one."""
        if not isinstance(value, dict) or not PART.fullmatch(str(value.get("file", ""))):
            raise ValueError(f"not a part: {str(value)[:80]}")
        removed = value.get("removed", [])
        if not isinstance(removed, list) or not all(isinstance(k, list) and len(k) == 3 for k in removed):
            raise ValueError(f"part {value['file']} has a malformed list of removed keys")
        return Part(str(value["file"]), int(value.get("entries", 0)), tuple(_key(k) for k in removed))


def _key(values: Iterable[Any]) -> Key:
    a, b, c = (str(v) for v in values)
    return (a, b, c)


def number(file: str) -> int:
    found = PART.fullmatch(file)
    return int(found.group(1)) if found else 0


@dataclass(frozen=True)
class Plan:
    """What one save of a table does: the parts the new generation lists (oldest first) and, for
    each part it writes, the keys of the entries that part holds (in key order)."""

    parts: tuple[Part, ...]
    writes: dict[str, list[Key]]


def plan_save(
    parts: tuple[Part, ...] | None,
    members: Mapping[str, set[Key]],
    live: Collection[Key],
    changed: Iterable[Key],
    removed: Iterable[Key],
    cap: int,
    clean: bool = False,
) -> Plan:
    """The parts after a save, from the live keys each stored part holds (`members`), the keys the
    store holds now (`live`) and what changed. `parts` None (a new store, one read from the single
    file of an older mbxval, or a table replaced whole) writes every live key as one part;
    otherwise the `changed` keys become a new part with the stored keys of `removed`, and the parts
    are compacted. Its cost is that of the batch and of the parts it merges, not of the store. A
    plan whose parts would not hold every live key exactly once (what changed was not all recorded)
    falls back to writing every key, so that no row is ever lost to a merge. `clean` (a run's last
    save) writes every key as one part if any stored part still holds a replaced or deleted entry,
    so that a direct read of the folder sees each key once."""
    if parts is None:
        return _whole(live, 1)
    batch = {k for k in changed if k in live}
    stored = {k: f for k in {*batch, *removed} for f in _holders(members, k)}
    gone = tuple(sorted(k for k in set(removed) if k in stored and k not in live))
    counts = {p.file: len(members.get(p.file, ())) for p in parts}
    for file in stored.values():
        counts[file] -= 1
    counter = max((number(p.file) for p in parts), default=0)
    new: list[Part] = list(parts)
    sources: dict[str, set[str]] = {}  # each part written -> the parts whose entries it holds
    fresh = ""
    if batch or gone:
        counter += 1
        fresh = f"part-{counter:06d}.parquet"
        new.append(Part(fresh, len(batch), gone))
        sources[fresh], counts[fresh] = {fresh}, len(batch)
    for index, part in enumerate(new):  # parts mostly replaced or deleted since: their live entries
        alive = counts[part.file]
        if part.file != fresh and part.entries >= MIN_GARBAGE and 2 * alive < part.entries:
            counter += 1
            rewritten = Part(f"part-{counter:06d}.parquet", alive, part.removed if index else ())
            new[index], sources[rewritten.file], counts[rewritten.file] = rewritten, {part.file}, alive
    start = _merge_start([counts[p.file] for p in new], cap)
    if start is not None:
        merged = new[start:]
        counter += 1
        removed_keys = tuple(sorted({k for p in merged for k in p.removed})) if start else ()
        total = sum(counts[p.file] for p in merged)
        part = Part(f"part-{counter:06d}.parquet", total, removed_keys)
        sources[part.file] = {s for p in merged for s in sources.pop(p.file, {p.file})}
        new = [*new[:start], part]
    writes: dict[str, list[Key]] = {}
    for file, olds in sources.items():
        keys = {k for old in olds for k in members.get(old, ()) if k not in stored}
        if fresh in olds:
            keys |= batch
        writes[file] = sorted(keys)
    accounted = sum(map(len, writes.values())) + sum(counts[p.file] for p in new if p.file not in writes)
    if accounted != len(live):  # the parts would not hold every live key once: write them all
        return _whole(live, counter + 1)
    if clean and sum(p.entries for p in new) != len(live):
        return _whole(live, counter + 1)
    return Plan(tuple(new), writes)


def _whole(live: Collection[Key], counter: int) -> Plan:
    """Every live key written as one part."""
    file = f"part-{counter:06d}.parquet"
    everything = sorted(live)
    return Plan((Part(file, len(everything)),), {file: everything})


def _holders(members: Mapping[str, set[Key]], key: Key) -> list[str]:
    return [f for f, keys in members.items() if key in keys][:1]


def _merge_start(sizes: list[int], cap: int) -> int | None:
    """The oldest part, after the last sealed one (of `cap` live entries or more), holding no more
    live entries than RATIO times the parts after it: it and every newer part are merged."""
    sealed = max((i for i, size in enumerate(sizes) if size >= cap), default=-1)
    after, start = 0, None
    for index in range(len(sizes) - 1, sealed, -1):
        if index < len(sizes) - 1 and sizes[index] <= RATIO * after:
            start = index
        after += sizes[index]
    return start
