"""Run a function in a child process with a time limit, so that a crash or a hang costs one run.

The child is forked (cheap with every engine imported, where a spawned interpreter would have to
import them again), runs the function, and sends its result back through a
pipe. A `Worker` keeps its child for many calls (a group of runs: one fork, not one per run) and
forks a new one only after a call that crashed it or ran out of time. The child's stdout and stderr
go to a temporary file, emptied before each call: engine chatter stays out of the progress bar, and
the last lines explain a hard crash.

JIT-compiled code (numba) compiled in a child is lost with it: code that compiles on first use and
should be compiled once, like the reference solver, runs first in this process (`run_here`), and
every forked child inherits the compiled code.
"""

from __future__ import annotations

import contextlib
import ctypes
import faulthandler
import multiprocessing
import os
import signal
import sys
import tempfile
import traceback
from collections.abc import Callable
from dataclasses import dataclass
from multiprocessing.connection import Connection
from typing import Any, Generic, Literal, TypeVar

from adapters.threads import one_blas_thread

T = TypeVar("T")
A = TypeVar("A")

PR_SET_PDEATHSIG = 1
CALL, STOP = "call", "stop"
Kind = Literal["ok", "error", "crash", "timeout"]


@dataclass(frozen=True)
class Outcome(Generic[T]):
    """What became of an isolated call: `value` when kind is 'ok', otherwise a one-line `message`."""

    kind: Kind
    value: T | None = None
    message: str = ""


def run_isolated(function: Callable[[], T], timeout: float) -> Outcome[T]:
    """Call `function()` in a forked child; give up and kill it after `timeout` seconds."""
    worker: Worker[None, T] = Worker(lambda _: function())
    with worker:
        return worker.call(None, timeout)


class Worker(Generic[A, T]):
    """A forked child that calls `function(argument)` for each argument sent to it, one call at a
    time, each with its own time limit: forked once for many calls (a fork of a process with every engine
    loaded is cheap), forked again after a call that crashed it or ran out of time,
    so that a crash or a hang still costs only its own call. `function` is the parent's, as it was
    when the child was forked; only the arguments and the results cross the pipe. Use it as a
    context manager: leaving it ends the child."""

    def __init__(self, function: Callable[[A], T]) -> None:
        self.function = function
        self.output = tempfile.TemporaryFile()  # noqa: SIM115 (closed by close): the child's output
        self.child: Any = None
        self.tasks: Connection | None = None
        self.results: Connection | None = None
        self.forks = 0
        """How many children this worker has forked (one, unless calls crashed or timed out)."""

    @property
    def ready(self) -> bool:
        """Whether a child is forked and waiting (the next call forks one otherwise)."""
        return self.child is not None

    def call(self, argument: A, timeout: float) -> Outcome[T]:
        """`function(argument)` in the child, or what became of it."""
        if self.child is None:
            self._start()
        assert self.tasks is not None and self.results is not None
        self.output.seek(0)  # the file offset is shared with the child: its output starts afresh
        self.output.truncate()
        try:
            self.tasks.send((CALL, argument))
            if not self.results.poll(timeout):
                self._stop("kill")
                return Outcome("timeout", message=f"no result within the time limit of {timeout:g} s")
            kind, payload = self.results.recv()
        except (EOFError, BrokenPipeError):
            exitcode = self._stop("reap")
            return Outcome("crash", message=_crash_message(exitcode, self.output))
        if kind == "ok":
            return Outcome("ok", value=payload)
        return Outcome("error", message=str(payload))

    def close(self) -> None:
        """Release the child (it leaves its loop and exits on its own) and drop the output file."""
        self._stop("release")
        self.output.close()

    def __enter__(self) -> Worker[A, T]:
        return self

    def __exit__(self, kind: object, *exc: object) -> None:
        if kind is not None:  # interrupted (Ctrl-C, a stop signal), perhaps mid-call: no waiting
            self._stop("kill")
        self.close()

    def _start(self) -> None:
        context = multiprocessing.get_context("fork")
        task_reader, self.tasks = context.Pipe(duplex=False)
        self.results, result_writer = context.Pipe(duplex=False)
        ends = (task_reader, result_writer, self.tasks, self.results)
        arguments = (self.function, ends, self.output.fileno())
        self.child = context.Process(target=_serve, args=arguments, daemon=True)
        self.child.start()
        self.forks += 1
        task_reader.close()
        result_writer.close()

    def _stop(self, how: Literal["kill", "reap", "release"]) -> int | None:
        """End the child and close the pipes: killed (a timeout, an interrupt), reaped (it died:
        its exit code), or released (told to leave its loop and not waited for: it exits while
        this process goes on; multiprocessing reaps it at the next fork or at exit)."""
        child, tasks, results = self.child, self.tasks, self.results
        if child is None or tasks is None or results is None:
            return None
        self.child = self.tasks = self.results = None
        if how == "release":  # told, not left to see EOF: a sibling's fork may hold the pipe open
            with contextlib.suppress(OSError):
                tasks.send((STOP, None))
        if how == "kill":
            child.kill()
        tasks.close()
        results.close()
        if how == "release":
            return None
        child.join(5.0)
        if child.exitcode is None:  # the pipe closed but the process lives on
            child.kill()
            child.join()
        exitcode: int | None = child.exitcode
        return exitcode


def run_here(function: Callable[[], T], timeout: float) -> Outcome[T]:
    """Call `function()` in this process, with its exceptions caught and a time limit that
    interrupts Python code (SIGALRM; compiled code is interrupted when it returns to Python).
    For our own code whose state the forked runs should inherit, such as JIT-compiled kernels."""

    def expire(signum: int, frame: Any) -> None:
        raise _Expired

    previous = signal.signal(signal.SIGALRM, expire)
    signal.setitimer(signal.ITIMER_REAL, timeout)
    try:
        return Outcome("ok", value=function())
    except _Expired:
        return Outcome("timeout", message=f"no result within the time limit of {timeout:g} s")
    except Exception as error:
        where = traceback.extract_tb(error.__traceback__)[-1]
        return Outcome("error", message=f"{type(error).__name__}: {error} (at {where.name}:{where.lineno})")
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)


class _Expired(BaseException):
    """Raised by the alarm; a BaseException so that the function's own handlers let it through."""


def _serve(function: Callable[[Any], Any], ends: tuple[Connection, ...], output_fd: int) -> None:
    """The child's loop: call `function` on each argument received, send back what came of it,
    until the parent says stop or closes the pipe."""
    tasks, results, *parents = ends
    for end in parents:
        end.close()
    _die_with_parent()
    os.dup2(output_fd, 1)
    os.dup2(output_fd, 2)
    faulthandler.enable(file=2)  # a hard crash leaves its Python stack in the output file
    one_blas_thread()  # inherited from a parent that set it; set here for one that did not
    while True:
        try:
            what, argument = tasks.recv()
        except EOFError:
            break
        if what == STOP:
            break
        try:
            result: tuple[str, Any] = ("ok", function(argument))
        except BaseException as error:
            where = traceback.extract_tb(error.__traceback__)[-1]
            result = ("error", f"{type(error).__name__}: {error} (at {where.name}:{where.lineno})")
        for stream in (sys.stdout, sys.stderr):
            with contextlib.suppress(Exception):
                stream.flush()  # before the parent empties the output for the next call
        results.send(result)
    results.close()


def _die_with_parent() -> None:
    """Linux: the child gets SIGKILL when the runner dies, so no orphan runs on."""
    with contextlib.suppress(OSError, AttributeError):
        ctypes.CDLL(None, use_errno=True).prctl(PR_SET_PDEATHSIG, signal.SIGKILL)


def _crash_message(exitcode: int | None, output: Any) -> str:
    if exitcode is not None and exitcode < 0:
        how = f"killed by {signal.Signals(-exitcode).name}"
    else:
        how = f"exited with status {exitcode}"
    output.seek(0)
    lines = [line.strip() for line in output.read().decode(errors="replace").splitlines() if line.strip()]
    return f"the engine process died ({how}) without a result{_explain(lines)}"


def _explain(lines: list[str]) -> str:
    """The fatal error and innermost Python frame of a faulthandler dump, or the last output line."""
    fatal = [line for line in lines if line.startswith("Fatal Python error")]
    if not fatal:
        return f": {lines[-1][:300]}" if lines else ""
    start = lines.index(fatal[0])
    frames = [line for line in lines[start:] if line.startswith("File ")]
    where = f", innermost {frames[0]}" if frames else ""
    return f": {fatal[0]}{where}"[:400]
