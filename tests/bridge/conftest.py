"""Shared helpers of the bridge tests."""

from __future__ import annotations

import os
from collections.abc import Iterator

import pytest

from harness.scenario import Scenario, make_scenario

# The watchdog tests ask 1 s (tests/bridge and tests/pil): a host stalled by a busy machine must not
# trip it during a mission (with 100 ms the CAN test failed once with one busy loop per core; a stall
# of 0.5 s is seen at a load of 8 on 2 cores, hil_bridge/options.py); the report is then waited for.
TEST_WATCHDOG_MS = 1000


def short_scenario(room: int = 1, seconds: float = 3.0) -> Scenario:
    """The start of a mission: enough ticks to drive, turn and talk, few enough to be quick."""
    scn = make_scenario(room=room)
    scn.timing.find_limit_s = seconds
    scn.timing.return_limit_s = 1.0
    return scn


def children_of(pid: int) -> list[int]:
    out: list[int] = []
    for task in os.listdir(f"/proc/{pid}/task"):
        try:
            with open(f"/proc/{pid}/task/{task}/children") as fh:
                out += [int(c) for c in fh.read().split()]
        except FileNotFoundError:
            pass
    return out


def alive(pid: int) -> bool:
    """Running (a zombie or a vanished process is not)."""
    try:
        with open(f"/proc/{pid}/stat") as fh:
            return fh.read().rsplit(")", 1)[1].split()[0] != "Z"
    except FileNotFoundError:
        return False


@pytest.fixture
def no_stray_boards() -> Iterator[None]:
    """Fails the test if it leaves a child process of ours behind."""
    before = set(children_of(os.getpid()))
    yield
    left = [p for p in children_of(os.getpid()) if p not in before and alive(p)]
    assert not left, f"stray child processes: {left}"
