"""SIGTERM in the command's own process unwinds (stop.Terminated); a forked child takes SIGTERM's
default action back at fork, so that a child blocked where no Python handler can run (an idle
figure worker that Pool.terminate stops) still ends, and its parent never waits for it forever."""

from __future__ import annotations

import os
import signal
import time

import pytest

from reports.run import stop


@pytest.fixture
def sigterm_caught():  # type: ignore[no-untyped-def]
    previous = signal.getsignal(signal.SIGTERM)
    stop.catch_sigterm()
    yield
    signal.signal(signal.SIGTERM, previous)


def test_the_command_s_process_turns_sigterm_into_terminated(sigterm_caught) -> None:
    with pytest.raises(stop.Terminated):
        os.kill(os.getpid(), signal.SIGTERM)
        signal.sigtimedwait([], 0.1)  # a point where the handler runs


def test_a_forked_child_has_sigterm_s_default_action(sigterm_caught) -> None:
    pid = os.fork()
    if pid == 0:  # the child: exit 0 when SIGTERM is back to its default, 1 otherwise
        os._exit(0 if signal.getsignal(signal.SIGTERM) == signal.SIG_DFL else 1)
    _, status = os.waitpid(pid, 0)
    assert os.WIFEXITED(status) and os.WEXITSTATUS(status) == 0
    assert signal.getsignal(signal.SIGTERM) is not signal.SIG_DFL  # the parent keeps its handler


def test_a_forked_child_blocked_in_a_signal_free_wait_ends_on_sigterm(sigterm_caught) -> None:
    """sigwait blocks without running Python handlers: only the default action ends the child."""
    ready, told = os.pipe()
    pid = os.fork()
    if pid == 0:
        signal.pthread_sigmask(signal.SIG_BLOCK, [signal.SIGUSR1])
        os.write(told, b"!")  # past fork's own steps: SIGTERM now meets the child as it will be
        signal.sigwait([signal.SIGUSR1])
        os._exit(3)
    os.read(ready, 1)
    os.kill(pid, signal.SIGTERM)
    for _ in range(100):  # a child that does not end within 10 s fails the test, never hangs it
        done, status = os.waitpid(pid, os.WNOHANG)
        if done:
            break
        time.sleep(0.1)
    else:
        os.kill(pid, signal.SIGKILL)
        os.waitpid(pid, 0)
        pytest.fail("the forked child ignored SIGTERM")
    assert os.WIFSIGNALED(status) and os.WTERMSIG(status) == signal.SIGTERM
