"""The recorded mutation runs, and docs/mutation-results.md generated from them.

`mbxval bench mutation --module PATH --record` (with `--sample N` for a random sample of the module's
mutants) writes benchmarks/mutation_results/<module>.json: every planted mutant's verdict, the
module's mutant count, the sample's size and seed, and what the first pass did not catch. A later
run of named mutants (`--names`, after a test was added to kill them) updates their verdicts and
keeps the first pass's list, so the page can say which mutants new tests killed; `--rest` resumes a
stopped pass with the mutants it had not reached. Nothing here runs
mutmut: the page is a function of the records and of benchmarks/mutation_explained/.

    python -m benchmarks.mutation_results > docs/mutation-results.md
"""

from __future__ import annotations

import json
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from pathlib import Path

RESULTS_DIR = Path(__file__).with_name("mutation_results")
CAUGHT = frozenset({"killed", "timeout"})
VERDICTS = frozenset({"killed", "survived", "timeout", "no tests"})


@dataclass(frozen=True)
class Record:
    """One module's recorded mutants: `mutants` in the module, the `verdicts` of those planted (all of
    them, or a sample of `sample` drawn with `seed`), and those the first pass did not catch."""

    module: str
    mutants: int
    verdicts: Mapping[str, str]
    first_uncaught: tuple[str, ...]
    sample: int | None = None
    seed: int | None = None
    stopped: bool = False
    """The pass was stopped before every mutant was reached: `verdicts` are those it reached."""

    @property
    def planted(self) -> int:
        """Mutants given to the tests ('no tests' ones included: no selected test runs them)."""
        return len(self.verdicts)

    def caught(self) -> int:
        return sum(verdict in CAUGHT for verdict in self.verdicts.values())

    def first_caught(self) -> int:
        return self.planted - len(self.first_uncaught)

    def untested(self) -> int:
        return sum(verdict == "no tests" for verdict in self.verdicts.values())

    def survivors(self) -> tuple[str, ...]:
        return tuple(sorted(name for name, verdict in self.verdicts.items() if verdict == "survived"))

    def killed_by_new_tests(self) -> tuple[str, ...]:
        return tuple(name for name in self.first_uncaught if self.verdicts.get(name) in CAUGHT)


def path_of(module: str) -> Path:
    """The record's file: reports/scoring/metrics.py -> reports.scoring.metrics.json."""
    return RESULTS_DIR / f"{module.removesuffix('.py').replace('/', '.')}.json"


def load(module: str) -> Record | None:
    path = path_of(module)
    if not path.exists():
        return None
    data = json.loads(path.read_text())
    return Record(
        data["module"],
        data["mutants"],
        data["verdicts"],
        tuple(data["first_uncaught"]),
        data.get("sample"),
        data.get("seed"),
        data.get("stopped", False),
    )


def save(record: Record) -> Path:
    unknown = set(record.verdicts.values()) - VERDICTS
    if unknown:
        raise ValueError(f"unknown verdicts {sorted(unknown)}: one of {sorted(VERDICTS)}")
    data = {
        "module": record.module,
        "mutants": record.mutants,
        "sample": record.sample,
        "seed": record.seed,
        "stopped": record.stopped,
        "first_uncaught": list(record.first_uncaught),
        "verdicts": dict(sorted(record.verdicts.items())),
    }
    RESULTS_DIR.mkdir(exist_ok=True)
    path = path_of(record.module)
    path.write_text(json.dumps(data, indent=1) + "\n")
    return path


def record_pass(
    module: str,
    mutants: int,
    verdicts: Mapping[str, str],
    sample: int | None,
    seed: int | None,
    stopped: bool = False,
) -> Record:
    """A first pass over `module`: what it did not catch (survivors, and mutants no selected test
    ran) is kept as the first pass's uncaught."""
    uncaught = tuple(sorted(name for name, verdict in verdicts.items() if verdict not in CAUGHT))
    return Record(module, mutants, dict(verdicts), uncaught, sample, seed, stopped)


def record_again(module: str, verdicts: Mapping[str, str]) -> Record:
    """Named mutants run again: their verdicts replace the recorded ones (each must be recorded)."""
    record = load(module)
    if record is None:
        raise ValueError(f"no recorded pass of {module}: record a pass before re-running mutants by name")
    missing = sorted(set(verdicts) - set(record.verdicts))
    if missing:
        raise ValueError(f"{module}: mutants never planted in its recorded pass: {', '.join(missing)}")
    merged = {**record.verdicts, **verdicts}
    return Record(
        module, record.mutants, merged, record.first_uncaught, record.sample, record.seed, record.stopped
    )


def record_rest(module: str, verdicts: Mapping[str, str]) -> Record:
    """A stopped pass resumed: the verdicts of mutants it had not reached join its own, as first-pass
    verdicts (their uncaught join its uncaught); it is no longer stopped once every mutant is planted."""
    record = load(module)
    if record is None or not record.stopped:
        raise ValueError(f"no stopped pass of {module} recorded: only a stopped pass can be resumed")
    again = sorted(set(verdicts) & set(record.verdicts))
    if again:
        raise ValueError(f"{module}: mutants already planted in its recorded pass: {', '.join(again)}")
    merged = {**record.verdicts, **verdicts}
    uncaught = record_pass(module, record.mutants, verdicts, None, None).first_uncaught
    first = tuple(sorted((*record.first_uncaught, *uncaught)))
    return Record(module, record.mutants, merged, first, stopped=len(merged) < record.mutants)


def records() -> list[Record]:
    """Every recorded module, in path order."""
    found = [load(path.stem.replace(".", "/") + ".py") for path in sorted(RESULTS_DIR.glob("*.json"))]
    return [record for record in found if record is not None]


def package_of(module: str) -> str:
    """The folder holding the module: adapters/mujoco, scenarios/families, scenarios."""
    return module.rpartition("/")[0] or module


def _row(name: str, rows: Iterable[Record], explained: Mapping[str, str]) -> str:
    rows = list(rows)
    mutants = sum(r.mutants for r in rows)
    planted = sum(r.planted for r in rows)
    first = sum(r.first_caught() for r in rows)
    caught = sum(r.caught() for r in rows)
    survivors = [s for r in rows for s in r.survivors()]
    known = sum(s in explained for s in survivors)
    new = sum(len(r.killed_by_new_tests()) for r in rows)
    untested = sum(r.untested() for r in rows)
    if planted == mutants:
        sampled = "all"
    elif len(rows) > 1:
        sampled = f"{planted} of {mutants}"
    elif rows[0].stopped:
        sampled = f"first {planted} reached (stopped)"
    else:
        sampled = f"sample of {planted}"
    return (
        f"| {name} | {mutants} | {sampled} | {first} / {planted} | {new} | {caught} / {planted} | "
        f"{known} | {len(survivors) - known} | {untested} |"
    )


def page(found: list[Record], explained: Mapping[str, str]) -> str:
    """docs/mutation-results.md: per package, then per module."""
    head = (
        "| {} | mutants | planted | caught / planted, first pass | killed by new tests | "
        "caught / planted, now | survivors explained | survivors not explained | no tests |\n"
        "|---|---|---|---|---|---|---|---|---|"
    )
    packages: dict[str, list[Record]] = {}
    for record in found:
        packages.setdefault(package_of(record.module), []).append(record)
    lines = [
        "# Mutation results",
        "",
        "Generated by `python -m benchmarks.mutation_results > docs/mutation-results.md` from the records",
        "in `benchmarks/mutation_results/` (written by `mbxval bench mutation --module PATH --record`); do",
        "not edit by hand. How the runs are made and what each column means: [mutation.md](mutation.md).",
        '"Caught" is killed or timed out; a survivor is explained in `benchmarks/mutation_explained/`',
        '(why it is equivalent) or not; "sample of N": N mutants drawn at random (seeded) from the',
        'module\'s, not all of them; "first N reached (stopped)": a pass stopped by hand after N mutants',
        "(mutmut runs them in the order of their tests' estimated time).",
        "",
        "## By package",
        "",
        head.format("package"),
        *(_row(name, rows, explained) for name, rows in packages.items()),
        "",
        "## By module",
        "",
        head.format("module"),
        *(_row(f"`{r.module}`", [r], explained) for r in found),
    ]
    unexplained = [(r.module, s) for r in found for s in r.survivors() if s not in explained]
    if unexplained:
        lines += ["", "## Survivors not explained", ""]
        lines += [f"- `{name}` ({module})" for module, name in unexplained]
    return "\n".join(lines) + "\n"


EXPLAINED_DIR = Path(__file__).with_name("mutation_explained")
"""One JSON file per mutated module (`reference_solver.compiled.band.json`): each survivor that cannot or
need not be killed, by mutmut's name, with the reason (data, so that passes over different modules
never edit the same file)."""


def explained() -> dict[str, str]:
    """Every explained survivor of every module, by mutant name."""
    reasons: dict[str, str] = {}
    for path in sorted(EXPLAINED_DIR.glob("*.json")):
        reasons.update(json.loads(path.read_text()))
    return reasons


def main() -> None:
    print(page(records(), explained()), end="")


if __name__ == "__main__":
    main()
