"""How a command ends when the user stops it: Ctrl-C, SIGTERM, a closed pipe, or bad input.

SIGTERM (a CI job cancelled, `kill`, `timeout`) is turned into Terminated, a KeyboardInterrupt, so
that it unwinds through the same cleanup as a Ctrl-C: every temporary file is removed where it is
made, the runs stored so far stay stored; the command then ends with one line and exit 143."""

from __future__ import annotations

import atexit
import contextlib
import os
import signal
import sys
from types import FrameType

from scenarios.names import printable

INTERRUPTED = 130  # 128 + SIGINT, as shells report a Ctrl-C
TERMINATED = 143  # 128 + SIGTERM
CLOSED_PIPE = 141  # 128 + SIGPIPE
USAGE = 2


class Terminated(KeyboardInterrupt):
    """SIGTERM, raised where the program is, to unwind like a Ctrl-C."""


class _Sigterm:
    """Who installed the handler, and whether SIGTERM came (an exception raised from a signal
    handler can be swallowed, as inside os.fork's callbacks: `raise_if_terminated` raises it again
    at the next safe point)."""

    owner: int | None = None
    received = False
    forking = False  # inside os.fork's callbacks, where an exception is printed and dropped


def _terminate(signum: int, frame: FrameType | None) -> None:
    signal.signal(signal.SIGTERM, signal.SIG_DFL)  # a second SIGTERM ends the process at once
    if os.getpid() != _Sigterm.owner:  # a forked child (a figure worker, an engine run): die as asked
        os.kill(os.getpid(), signal.SIGTERM)
        return
    _Sigterm.received = True
    if not _Sigterm.forking:  # else raise_if_terminated raises it at the next safe point
        raise Terminated


def _forking() -> None:
    _Sigterm.forking = True


def _forked_parent() -> None:
    _Sigterm.forking = False


def _default_in_child() -> None:
    """A forked child takes SIGTERM's default action back at once: a Python handler runs only when
    the child's main thread runs bytecode, so a child blocked in a lock (an idle pool worker that
    Pool.terminate stops with SIGTERM) would never end, and its parent would wait for it forever."""
    _Sigterm.forking = False
    with contextlib.suppress(ValueError):  # not the main thread: the handler ends a child as SIGTERM does
        signal.signal(signal.SIGTERM, signal.SIG_DFL)


def catch_sigterm() -> None:
    """Make SIGTERM raise Terminated in this process; forked children end as SIGTERM ends them."""
    if _Sigterm.owner is None:
        os.register_at_fork(before=_forking, after_in_parent=_forked_parent, after_in_child=_default_in_child)
    _Sigterm.owner, _Sigterm.received = os.getpid(), False
    signal.signal(signal.SIGTERM, _terminate)


def raise_if_terminated() -> None:
    """Raise Terminated if SIGTERM came and its exception was swallowed on the way."""
    if _Sigterm.received and os.getpid() == _Sigterm.owner:
        raise Terminated


def interrupted(what: str, error: BaseException | None = None) -> int:
    """One line on stderr and exit status 130, or 143 for SIGTERM (every temporary file is removed
    where it is made)."""
    if isinstance(error, Terminated):
        _Sigterm.received = False  # said once
        print(f"mbxval: {what.replace('interrupted', 'terminated by SIGTERM', 1)}", file=sys.stderr)
        return TERMINATED
    print(f"mbxval: {what}", file=sys.stderr)
    return INTERRUPTED


def end(status: int) -> int:
    """`status`, or after a Ctrl-C or SIGTERM the process ended at once with it. The command has
    unwound by then (its temporary files removed, the rows stored so far kept); the exit handlers
    run (worker pools, a Dask cluster, temporary directories) and the output is flushed, but the
    interpreter's teardown of every module loaded (numba, scipy, the engines: tenths of a CPU
    second, seconds on a loaded machine) is skipped."""
    if status not in (INTERRUPTED, TERMINATED):
        return status
    atexit._run_exitfuncs()
    for stream in (sys.stdout, sys.stderr):
        with contextlib.suppress(OSError, ValueError):
            stream.flush()
    os._exit(status)


def closed_pipe() -> int:
    """The reader of stdout went away (`| head`): end quietly, and keep Python's final flush of
    stdout from reporting the broken pipe at exit."""
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
    except (OSError, ValueError):  # stdout without a file descriptor (captured in a test)
        pass
    return CLOSED_PIPE


MAX_MESSAGE = 2000
"""An error is one line of at most this many characters: a value quoted from a file or an argument
can be any size."""


def usage_error(message: str) -> int:
    """The one line of bad input, and exit status 2: a message of several lines joined, a control
    character written as its escape (a value quoted from an argument cannot act on the terminal)."""
    line = printable(" | ".join(part.strip() for part in message.splitlines() if part.strip()))
    if len(line) > MAX_MESSAGE:
        line = line[: MAX_MESSAGE - 30] + f"... ({len(line)} characters)"
    print(f"mbxval: error: {line}", file=sys.stderr)
    return USAGE
