"""The plan of a save over parts (reports.store.parts), simulated without files: what each
part holds is followed as a dict, and the table the parts give (newest entry wins, removed keys
hidden) must be the table the store holds, after every save of a long random history."""

from __future__ import annotations

import math
import random

from reports.store.parts import Key, Part, plan_save


class Simulated:
    """Parts as dicts of key -> version, planned by plan_save exactly as the store plans them."""

    def __init__(self, cap: int) -> None:
        self.cap = cap
        self.parts: tuple[Part, ...] | None = None
        self.content: dict[str, dict[Key, int]] = {}
        self.members: dict[str, set[Key]] = {}
        self.written: list[int] = []

    def save(self, table: dict[Key, int], changed: set[Key], removed: set[Key]) -> None:
        plan = plan_save(self.parts, self.members, table, changed, removed, self.cap)
        for file, keys in plan.writes.items():
            assert file not in self.content  # a part is written once, never rewritten in place
            self.content[file] = {k: table[k] for k in keys}
        self.written.append(sum(len(k) for k in plan.writes.values()))
        moved = changed | removed
        self.members = {
            p.file: set(plan.writes[p.file]) if p.file in plan.writes else self.members[p.file] - moved
            for p in plan.parts
        }
        self.parts = plan.parts

    def read(self) -> dict[Key, int]:
        """The table the parts give, resolved as a load resolves them."""
        assert self.parts is not None
        table: dict[Key, int] = {}
        for part in self.parts:
            for key in part.removed:
                table.pop(key, None)
            table.update(self.content[part.file])
        return table


def key(n: int) -> Key:
    return (f"s{n // 10}", "e", f"set {n % 10}")


def test_appends_write_the_batch_and_keep_the_parts_few() -> None:
    simulated, table = Simulated(cap=2000), {}
    batch = 100
    for save in range(200):  # 20,000 rows in 200 saves of 100
        new = {key(save * batch + i): save for i in range(batch)}
        table.update(new)
        simulated.save(table, set(new) if save else set(table), set())
        assert simulated.read() == table
        assert simulated.parts is not None
        # parts: the sealed ones (cap entries or more) plus about log2 of the rest
        assert len(simulated.parts) <= len(table) / simulated.cap + math.log2(len(table) / batch) + 2
    assert max(simulated.written[1:]) <= 2 * simulated.cap + batch  # no save rewrites the store
    rewritten = sum(simulated.written) / len(table)
    assert rewritten <= math.log2(simulated.cap / batch) + 2  # each row written a few times, not n


def test_replacements_and_deletions_resolve_to_the_table_held() -> None:
    generator = random.Random(3)
    simulated, table = Simulated(cap=300), {}
    for save in range(300):
        changed, removed = set(), set()
        for _ in range(generator.randrange(1, 40)):
            k = key(generator.randrange(1500))
            if generator.random() < 0.2 and k in table:
                del table[k]
                removed.add(k)
                changed.discard(k)
            else:
                table[k] = save
                changed.add(k)
                removed.discard(k)
        simulated.save(table, changed if simulated.parts is not None else set(table), removed)
        assert simulated.read() == table, save


def test_a_part_mostly_replaced_is_rewritten_with_its_live_entries() -> None:
    simulated = Simulated(cap=100)
    table = {key(n): 0 for n in range(400)}
    simulated.save(table, set(table), set())
    first = simulated.parts[0].file  # type: ignore[index]
    replaced = {key(n) for n in range(300)}
    table.update(dict.fromkeys(replaced, 1))
    simulated.save(table, replaced, set())
    assert first not in {p.file for p in simulated.parts}  # type: ignore[union-attr]
    assert simulated.read() == table


def test_a_save_without_a_change_lists_the_same_parts() -> None:
    simulated = Simulated(cap=100)
    table = {key(n): 0 for n in range(50)}
    simulated.save(table, set(table), set())
    before = simulated.parts
    simulated.save(table, set(), set())
    assert simulated.parts == before and simulated.written[-1] == 0


def test_a_part_round_trips_through_its_sidecar_form() -> None:
    part = Part("part-000012.parquet", 7, (("a", "b", "c"),))
    assert Part.from_json(part.to_json()) == part


def test_a_plan_that_would_lose_a_key_writes_every_key_instead() -> None:
    """A change the store did not record (a key added behind its back) is not lost: the parts
    would not account for it, so the save writes the whole table."""
    simulated = Simulated(cap=100)
    table = {key(n): 0 for n in range(50)}
    simulated.save(table, set(table), set())
    table[key(99)] = 1  # not in `changed`
    simulated.save(table, set(), set())
    assert simulated.read() == table and simulated.written[-1] == len(table)
