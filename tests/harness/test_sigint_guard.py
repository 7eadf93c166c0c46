"""Ctrl-C while numba takes the mission's Generator in (harness/sigint_guard.py).

numba unboxes a ``numpy.random.Generator`` through ``ctypes.cast`` and does not check that the
call succeeded: a Ctrl-C landing there killed the process with SIGSEGV (a served sweep's exit
status -11 in CI). The first test puts the Ctrl-C exactly there; without the guard in
harness/loop.py it dies of SIGSEGV."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
from pathlib import Path

import pytest

from harness.sigint_guard import sigint_deferred

REPO = Path(__file__).resolve().parents[2]

# Sends SIGINT to itself from inside numba's unboxing of the Generator: the cast of a bit
# generator's C function to c_void_p, during the mission kernel's call.
_SCRIPT = r"""
import ctypes, os, signal, sys
import harness.loop as loop
from harness.cli import main

real_cast, real_kernel = ctypes.cast, loop.mission_kernel
state = {"armed": False, "fired": 0}

def cast(obj, typ):
    if state["armed"] and typ is ctypes.c_void_p and isinstance(obj, ctypes._CFuncPtr):
        state["armed"] = False
        state["fired"] += 1
        os.kill(os.getpid(), signal.SIGINT)
    return real_cast(obj, typ)

def kernel(*args):
    state["armed"] = True
    try:
        return real_kernel(*args)
    finally:
        print("mission kernel returned", flush=True)

ctypes.cast = cast
loop.mission_kernel = kernel
code = main(["run", "--room", "1"])
print("ctrl-c sent inside the unboxing:", state["fired"], flush=True)
sys.exit(code)
"""


def test_ctrl_c_while_numba_takes_the_generator_in_stops_the_command_cleanly(tmp_path: Path) -> None:
    script = tmp_path / "ctrl_c.py"
    script.write_text(_SCRIPT)
    env = {**os.environ, "FFR_NO_SERVER": "1"}
    r = subprocess.run([sys.executable, str(script)], cwd=REPO, env=env, capture_output=True, text=True,
                       timeout=300)
    assert r.returncode == 130, (r.returncode, r.stdout, r.stderr)  # was -11 (SIGSEGV)
    assert "ctrl-c sent inside the unboxing: 1" in r.stdout  # the test reached the window it is about
    assert "mission kernel returned" in r.stdout  # the mission ended first: Ctrl-C acted on after it
    assert r.stderr.strip().splitlines()[-1] == "ffr: interrupted"


@pytest.fixture
def default_sigint() -> object:
    before = signal.signal(signal.SIGINT, signal.default_int_handler)
    yield
    signal.signal(signal.SIGINT, before)


@pytest.mark.usefixtures("default_sigint")
def test_a_ctrl_c_inside_the_block_is_raised_at_its_end_not_before() -> None:
    reached = []
    with pytest.raises(KeyboardInterrupt), sigint_deferred():
        os.kill(os.getpid(), signal.SIGINT)
        reached.append("after the signal")
    assert reached == ["after the signal"]
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler


@pytest.mark.usefixtures("default_sigint")
def test_without_a_ctrl_c_the_block_is_silent_and_leaves_the_handler_as_it_was() -> None:
    with sigint_deferred():
        assert signal.getsignal(signal.SIGINT) is not signal.default_int_handler
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler


def test_a_handler_of_the_callers_gets_the_ctrl_c_once_after_the_block() -> None:
    calls = []
    before = signal.signal(signal.SIGINT, lambda signum, _frame: calls.append(signum))
    try:
        with sigint_deferred():
            os.kill(os.getpid(), signal.SIGINT)
            os.kill(os.getpid(), signal.SIGINT)
            assert calls == []
        assert calls == [signal.SIGINT]
    finally:
        signal.signal(signal.SIGINT, before)


def test_an_ignored_ctrl_c_stays_ignored() -> None:
    before = signal.signal(signal.SIGINT, signal.SIG_IGN)  # a forked sweep worker's
    try:
        with sigint_deferred():
            assert signal.getsignal(signal.SIGINT) is signal.SIG_IGN
            os.kill(os.getpid(), signal.SIGINT)
        assert signal.getsignal(signal.SIGINT) is signal.SIG_IGN
    finally:
        signal.signal(signal.SIGINT, before)


@pytest.mark.usefixtures("default_sigint")
def test_the_block_is_told_of_a_ctrl_c_as_it_is_noted() -> None:
    with pytest.raises(KeyboardInterrupt), sigint_deferred() as noted:
        assert not noted.is_set()
        os.kill(os.getpid(), signal.SIGINT)
        assert noted.is_set()  # a loop inside can stop on its own terms before the end raises


def test_the_ctrl_c_tests_hold_when_the_suite_is_started_with_ctrl_c_ignored() -> None:
    """A CI runner may start the suite with SIGINT ignored (tests/conftest.py puts Python's
    handler back): the Ctrl-C test above, run so, still sees its command stopped by it."""
    name = test_ctrl_c_while_numba_takes_the_generator_in_stops_the_command_cleanly.__name__
    test = f"{Path(__file__).relative_to(REPO)}::{name}"
    r = subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", test], cwd=REPO,
                       preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_IGN),
                       capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stdout[-3000:]
