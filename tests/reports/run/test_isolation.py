"""The isolated calls: a Worker keeps one forked child for many calls, and a call that crashes the
child, hangs or raises costs that call only; the next call gets a new child where one is needed."""

from __future__ import annotations

import ctypes
import os
import time

from reports.run.isolation import Worker, run_isolated


def behave(how: str) -> int:
    """The child's pid, after doing `how`."""
    if how == "crash":
        print("about to crash", flush=True)
        ctypes.string_at(0)  # a real segmentation fault
    if how == "hang":
        time.sleep(3600)
    if how == "raise":
        raise RuntimeError("engine internal error")
    if how == "chatter":
        print("engine chatter")
    return os.getpid()


def test_calls_share_one_child_until_one_crashes_or_hangs() -> None:
    with Worker(behave) as worker:
        first, second = worker.call("ok", 10.0), worker.call("chatter", 10.0)
        assert first.kind == second.kind == "ok"
        assert first.value == second.value != os.getpid()  # one child, not this process
        raised = worker.call("raise", 10.0)
        assert raised.kind == "error"
        assert "RuntimeError: engine internal error" in raised.message
        assert worker.call("ok", 10.0).value == first.value  # an exception keeps the child
        crashed = worker.call("crash", 10.0)
        assert crashed.kind == "crash"
        assert "SIGSEGV" in crashed.message
        after_crash = worker.call("ok", 10.0)
        assert after_crash.kind == "ok"
        assert after_crash.value != first.value
        started = time.monotonic()
        hung = worker.call("hang", 0.5)
        assert hung.kind == "timeout"
        assert "time limit of 0.5 s" in hung.message
        assert time.monotonic() - started < 5.0
        after_hang = worker.call("ok", 10.0)
        assert after_hang.kind == "ok"
        assert after_hang.value not in (first.value, after_crash.value)
        assert worker.forks == 3


def test_a_crash_message_holds_only_its_own_call_s_output() -> None:
    with Worker(behave) as worker:
        worker.call("chatter", 10.0)
        crashed = worker.call("crash", 10.0)
    assert crashed.kind == "crash"
    assert "SIGSEGV" in crashed.message
    assert "chatter" not in crashed.message


def test_leaving_the_worker_ends_its_child() -> None:
    with Worker(behave) as worker:
        pid = worker.call("ok", 10.0).value
        child = worker.child
    assert pid is not None
    assert worker.child is None
    assert child is not None
    child.join(10.0)  # not waited for by the worker: it exits on its own
    assert child.exitcode == 0  # it left its loop when told


def test_run_isolated_is_one_call_in_its_own_child() -> None:
    outcome = run_isolated(lambda: behave("ok"), 10.0)
    assert outcome.kind == "ok"
    assert outcome.value != os.getpid()
    assert run_isolated(lambda: behave("crash"), 10.0).kind == "crash"
