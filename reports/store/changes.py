"""What changed in a results store since it was read or last saved, so that a save writes only that.

The store's rows and trajectories are dictionaries keyed by (scenario, engine, setting) that record
every key set, replaced or deleted (`changed`, `removed`), and a row is itself a dictionary that
tells its owner when it is edited in place (`row["stale"] = True`), so that no change is missed and
no stored row is silently stale. A dictionary assigned whole (`store.rows = {...}`) or cleared
stands for a new table (`replaced`): the next save writes it whole.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from typing import Any, TypeVar

K = TypeVar("K")
V = TypeVar("V")


class Changes(dict[K, V]):
    """A dict that records the keys set (`changed`) and deleted (`removed`) since `settle()`, and
    whether it was cleared (`replaced`)."""

    def __init__(self, items: Mapping[K, V] | None = None, replaced: bool = False) -> None:
        super().__init__()
        self.changed: set[K] = set()
        self.removed: set[K] = set()
        self.replaced = replaced
        for key, value in (items or {}).items():
            super().__setitem__(key, self._held(key, value))

    def _held(self, key: K, value: V) -> V:
        return value

    def touch(self, key: K) -> None:
        self.changed.add(key)
        self.removed.discard(key)

    def settle(self) -> None:
        """Everything is stored now."""
        self.changed, self.removed, self.replaced = set(), set(), False

    def __setitem__(self, key: K, value: V) -> None:
        super().__setitem__(key, self._held(key, value))
        self.touch(key)

    def __delitem__(self, key: K) -> None:
        super().__delitem__(key)
        self.changed.discard(key)
        self.removed.add(key)

    def pop(self, key: K, *default: Any) -> Any:
        if key in self:
            value = self[key]
            del self[key]
            return value
        return super().pop(key, *default)

    def popitem(self) -> tuple[K, V]:
        key, value = super().popitem()
        self.changed.discard(key)
        self.removed.add(key)
        return key, value

    def clear(self) -> None:
        super().clear()
        self.settle()
        self.replaced = True

    def setdefault(self, key: K, default: Any = None) -> Any:
        if key not in self:
            self[key] = default
        return self[key]

    def update(self, *others: Any, **more: Any) -> None:
        for key, value in dict(*others, **more).items():
            self[key] = value

    def __ior__(self, other: Any) -> Changes[K, V]:  # type: ignore[override,misc]
        self.update(other)
        return self


class Row(dict[str, Any]):
    """A stored row: a plain dict that tells its owner (a ChangedRows) when it is edited in place.
    It pickles and copies as a plain dict."""

    def __init__(self, values: Mapping[str, Any], owner: ChangedRows[Any] | None, key: Any) -> None:
        super().__init__(values)
        self._owner, self._key = owner, key

    def _edited(self) -> None:
        if self._owner is not None and self._owner.get(self._key) is self:
            self._owner.touch(self._key)

    def __setitem__(self, name: str, value: Any) -> None:
        super().__setitem__(name, value)
        self._edited()

    def __delitem__(self, name: str) -> None:
        super().__delitem__(name)
        self._edited()

    def update(self, *others: Any, **more: Any) -> None:
        super().update(*others, **more)
        self._edited()

    def pop(self, name: str, *default: Any) -> Any:
        value = super().pop(name, *default)
        self._edited()
        return value

    def popitem(self) -> tuple[str, Any]:
        item = super().popitem()
        self._edited()
        return item

    def clear(self) -> None:
        super().clear()
        self._edited()

    def setdefault(self, name: str, default: Any = None) -> Any:
        value = super().setdefault(name, default)
        self._edited()
        return value

    def __ior__(self, other: Any) -> Row:  # type: ignore[override,misc]
        self.update(other)
        return self

    def __reduce__(self) -> tuple[type[dict[str, Any]], tuple[dict[str, Any]]]:
        return dict, (dict(self),)


class ChangedRows(Changes[K, dict[str, Any]]):
    """The store's rows: each value held as a Row (a copy of the dict given), so that an edit in
    place is recorded too."""

    def _held(self, key: K, value: dict[str, Any]) -> dict[str, Any]:
        return Row(value, self, key)


def tracked_rows(rows: Mapping[K, dict[str, Any]] | Iterable[tuple[K, dict[str, Any]]]) -> ChangedRows[K]:
    """Rows read from a store: nothing changed yet."""
    return ChangedRows(dict(rows))
