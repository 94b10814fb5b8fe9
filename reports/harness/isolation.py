"""Run a function in a child process with a time limit, so that a crash or a hang costs one run.

The child is forked (cheap: about 5 ms here with every engine imported, against about 1 s for a
spawned interpreter that has to import them again), runs the function, and sends its result back
through a pipe. The child's stdout and stderr go to a temporary file: engine chatter stays out of
the progress bar, and the last lines explain a hard crash.

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
import tempfile
import traceback
from collections.abc import Callable
from dataclasses import dataclass
from multiprocessing.connection import Connection
from typing import Any, Generic, Literal, TypeVar

T = TypeVar("T")

PR_SET_PDEATHSIG = 1
Kind = Literal["ok", "error", "crash", "timeout"]


@dataclass(frozen=True)
class Outcome(Generic[T]):
    """What became of an isolated call: `value` when kind is 'ok', otherwise a one-line `message`."""

    kind: Kind
    value: T | None = None
    message: str = ""


def run_isolated(function: Callable[[], T], timeout: float) -> Outcome[T]:
    """Call `function()` in a forked child; give up and kill it after `timeout` seconds."""
    context = multiprocessing.get_context("fork")
    receiver, sender = context.Pipe(duplex=False)
    with tempfile.TemporaryFile() as output:
        child = context.Process(target=_child, args=(function, sender, output.fileno()), daemon=True)
        child.start()
        sender.close()
        try:
            if not receiver.poll(timeout):
                _kill(child)
                return Outcome("timeout", message=f"no result within the time limit of {timeout:g} s")
            kind, payload = receiver.recv()
        except EOFError:
            child.join()
            return Outcome("crash", message=_crash_message(child.exitcode, output))
        finally:
            receiver.close()
        child.join()
    if kind == "ok":
        return Outcome("ok", value=payload)
    return Outcome("error", message=str(payload))


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


def _child(function: Callable[[], Any], sender: Connection, output_fd: int) -> None:
    _die_with_parent()
    os.dup2(output_fd, 1)
    os.dup2(output_fd, 2)
    faulthandler.enable(file=2)  # a hard crash leaves its Python stack in the output file
    try:
        result: tuple[str, Any] = ("ok", function())
    except BaseException as error:
        where = traceback.extract_tb(error.__traceback__)[-1]
        result = ("error", f"{type(error).__name__}: {error} (at {where.name}:{where.lineno})")
    sender.send(result)
    sender.close()


def _die_with_parent() -> None:
    """Linux: the child gets SIGKILL when the runner dies, so no orphan runs on."""
    with contextlib.suppress(OSError, AttributeError):
        ctypes.CDLL(None, use_errno=True).prctl(PR_SET_PDEATHSIG, signal.SIGKILL)


def _kill(child: Any) -> None:
    child.kill()
    child.join(5.0)


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
