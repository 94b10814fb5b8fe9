"""How a command ends when the user stops it: Ctrl-C, a closed pipe, or bad input."""

from __future__ import annotations

import os
import sys

INTERRUPTED = 130  # 128 + SIGINT, as shells report a Ctrl-C
CLOSED_PIPE = 141  # 128 + SIGPIPE
USAGE = 2


def interrupted(what: str) -> int:
    """One line on stderr and exit status 130 (every temporary file is removed where it is made)."""
    print(f"mbxval: {what}", file=sys.stderr)
    return INTERRUPTED


def closed_pipe() -> int:
    """The reader of stdout went away (`| head`): end quietly, and keep Python's final flush of
    stdout from reporting the broken pipe at exit."""
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
    except (OSError, ValueError):  # stdout without a file descriptor (captured in a test)
        pass
    return CLOSED_PIPE


def usage_error(message: str) -> int:
    print(f"mbxval: error: {message}", file=sys.stderr)
    return USAGE
