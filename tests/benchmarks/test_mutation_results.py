"""docs/mutation-results.md is what the recorded mutation runs give, and the records' arithmetic: a
first pass's survivors later caught count as killed by new tests, a re-run names only planted
mutants, and every record belongs to a module the bench knows."""

from __future__ import annotations

from pathlib import Path

import pytest

from benchmarks import mutation_results
from benchmarks.mutation import EXPLAINED, MODULES, _dotted
from benchmarks.mutation_results import Record, page, record_again, record_pass, records

PAGE = Path(__file__).resolve().parents[2] / "docs" / "mutation-results.md"


def test_the_page_is_what_the_records_give() -> None:
    assert PAGE.read_text() == page(records(), EXPLAINED), (
        "docs/mutation-results.md is stale: python -m benchmarks.mutation_results > docs/mutation-results.md"
    )


def test_every_record_is_of_a_module_the_bench_mutates_and_names_its_own_mutants() -> None:
    found = records()
    assert found
    for record in found:
        assert record.module in MODULES, record.module
        assert all(name.startswith(_dotted(record.module) + ".") for name in record.verdicts)
        assert set(record.first_uncaught) <= set(record.verdicts)
        assert record.planted <= record.mutants
        if record.sample is None and not record.stopped:
            assert record.planted == record.mutants, record.module


def test_a_survivor_caught_on_a_re_run_is_killed_by_a_new_test(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr(mutation_results, "RESULTS_DIR", tmp_path)
    module = "reports/scoring/agreement.py"
    names = [f"reports.scoring.agreement.x_f__mutmut_{k}" for k in range(1, 6)]
    verdicts = dict(zip(names, ["killed", "survived", "survived", "timeout", "no tests"], strict=True))
    mutation_results.save(record_pass(module, 9, verdicts, sample=5, seed=1))
    first = mutation_results.load(module)
    assert first is not None and first.first_uncaught == (names[1], names[2], names[4])
    assert (first.planted, first.caught(), first.first_caught(), first.untested()) == (5, 2, 2, 1)
    again = record_again(module, {names[1]: "killed", names[4]: "killed"})
    assert again.killed_by_new_tests() == (names[1], names[4]) and again.survivors() == (names[2],)
    assert (again.caught(), again.first_caught(), again.sample, again.seed) == (4, 2, 5, 1)
    with pytest.raises(ValueError, match=r"never planted in its recorded pass: .*mutmut_7"):
        record_again(module, {"reports.scoring.agreement.x_f__mutmut_7": "killed"})
    with pytest.raises(ValueError, match=r"no recorded pass of reports/scoring/metrics\.py"):
        record_again("reports/scoring/metrics.py", {})
    with pytest.raises(ValueError, match=r"unknown verdicts \['lost'\]"):
        mutation_results.save(Record(module, 1, {names[0]: "lost"}, ()))


def test_the_page_sums_modules_into_their_package_and_lists_the_unexplained() -> None:
    one = Record(
        "adapters/mujoco/tree.py",
        10,
        {"a.x__mutmut_1": "killed", "a.x__mutmut_2": "survived"},
        ("a.x__mutmut_2",),
    )
    two = Record(
        "adapters/mujoco/simulation.py",
        2,
        {"b.x__mutmut_1": "killed", "b.x__mutmut_2": "killed"},
        ("b.x__mutmut_2",),
    )
    text = page([one, two], {})
    assert "| adapters/mujoco | 12 | 4 of 12 | 2 / 4 | 1 | 3 / 4 | 0 | 1 | 0 |" in text
    assert "| `adapters/mujoco/tree.py` | 10 | sample of 2 | 1 / 2 | 0 | 1 / 2 | 0 | 1 | 0 |" in text
    assert "| `adapters/mujoco/simulation.py` | 2 | all | 1 / 2 | 1 | 2 / 2 | 0 | 0 | 0 |" in text
    assert text.endswith("- `a.x__mutmut_2` (adapters/mujoco/tree.py)\n")


def test_a_stopped_pass_says_how_many_mutants_it_reached() -> None:
    stopped = Record("reports/scoring/energy_drift.py", 9, {"c.x__mutmut_1": "killed"}, (), stopped=True)
    row = "| `reports/scoring/energy_drift.py` | 9 | first 1 reached (stopped) | 1 / 1 | 0 | 1 / 1 | 0 | 0"
    assert row in page([stopped], {})


def test_a_stopped_pass_resumed_adds_the_rest_as_first_pass_verdicts(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr(mutation_results, "RESULTS_DIR", tmp_path)
    module = "reports/scoring/energy_drift.py"
    names = [f"reports.scoring.energy_drift.x_f__mutmut_{k}" for k in range(1, 6)]
    first = dict(zip(names[:2], ["killed", "survived"], strict=True))
    mutation_results.save(record_pass(module, 5, first, None, None, stopped=True))
    part = mutation_results.record_rest(module, {names[2]: "survived"})
    assert part.stopped and part.planted == 3 and part.first_uncaught == (names[1], names[2])
    mutation_results.save(part)
    whole = mutation_results.record_rest(module, {names[3]: "killed", names[4]: "timeout"})
    assert not whole.stopped and (whole.planted, whole.caught(), whole.first_caught()) == (5, 3, 3)
    assert "| `reports/scoring/energy_drift.py` | 5 | all | 3 / 5 | 0 | 3 / 5 |" in page([whole], {})
    with pytest.raises(ValueError, match=r"already planted in its recorded pass: .*mutmut_1"):
        mutation_results.record_rest(module, {names[0]: "killed"})
    mutation_results.save(whole)
    with pytest.raises(ValueError, match=r"no stopped pass of reports/scoring/energy_drift\.py"):
        mutation_results.record_rest(module, {})
