"""A package's face (reports.face): each name it offers is the object its module defines,
loaded on first use; a face imports none of its parts until asked; and no face offers a name that
a module of its package also bears (the import system would set the module in its place)."""

from __future__ import annotations

import importlib
import subprocess
import sys
import types
from pathlib import Path

import pytest

import reports
from reports.face import origins

ROOT = Path(reports.__file__).parent
FACES = sorted(p.parent.name for p in ROOT.glob("*/__init__.py") if "reports.face" in p.read_text())


@pytest.mark.parametrize("package", FACES)
def test_every_name_a_face_offers_is_its_modules_own(package: str) -> None:
    face = importlib.import_module(f"reports.{package}")
    assert origins(face.__name__)
    for name in origins(face.__name__):
        module, attribute = origins(face.__name__)[name]
        value = getattr(face, name)
        if module == face.__name__:
            assert isinstance(value, types.ModuleType) and value.__name__ == f"{module}.{attribute}"
        else:
            assert value is getattr(importlib.import_module(module), attribute)


@pytest.mark.parametrize("package", FACES)
def test_no_face_offers_a_name_one_of_its_modules_bears(package: str) -> None:
    parts = {p.stem for p in (ROOT / package).glob("*.py")} | {p.name for p in (ROOT / package).glob("*/")}
    face = importlib.import_module(f"reports.{package}")
    clashes = {
        name
        for name, (module, _) in origins(face.__name__).items()
        if name in parts and module != face.__name__
    }
    assert clashes == set()


def test_a_face_imports_none_of_its_parts_until_asked() -> None:
    probe = (
        "import sys, reports.store, reports.run, reports.scoring\n"
        "print(sorted(m for m in sys.modules if m.count('.') > 1 and m.startswith('reports.')))\n"
        "from reports.store import WriterLock\n"
        "print('reports.store.lock' in sys.modules, 'reports.store.results_store' in sys.modules)\n"
    )
    done = subprocess.run(
        [sys.executable, "-c", probe], capture_output=True, text=True, check=True, cwd=ROOT.parent
    )
    assert done.stdout.splitlines() == ["[]", "True False"]


def test_a_name_the_face_does_not_offer_is_an_attribute_error() -> None:
    import reports.store

    with pytest.raises(AttributeError, match="no attribute 'tables_of'"):
        reports.store.tables_of  # noqa: B018 (the lookup is the test)
