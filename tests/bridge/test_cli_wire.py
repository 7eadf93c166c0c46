"""``ffr run --link ...`` over the wire, as a user runs it: the same result
as in-process, and a board killed mid-mission ends the run within a second
with exit status 2, one line naming the board, the tick and the counters,
and no process left behind."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from tests.bridge.conftest import alive, children_of

REPO = Path(__file__).resolve().parents[2]
FFR = [sys.executable, "-m", "harness"]


def _run(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run([*FFR, *args], cwd=REPO, capture_output=True, text=True, timeout=120)


@pytest.mark.parametrize("url", ["host-board:serial", "host-board:can"])
def test_ffr_run_over_the_wire_gives_the_in_process_result(url: str) -> None:
    wire, local = _run("run", "--room", "2", "--link", url, "--json", "-"), _run("run", "--room", "2", "--json", "-")
    assert wire.returncode == 0 == local.returncode, wire.stderr
    a, b = json.loads(wire.stdout), json.loads(local.stdout)
    assert a["outcome"] == "home" and a.pop("link", url) == url
    b.pop("link", None)
    # every message answered once, nothing lost or repeated; the wire adds HELLO and RESET
    ca, cb = a.pop("link_counters"), b.pop("link_counters")
    assert ca == cb | {"sent": cb["sent"] + 2, "received": cb["received"] + 2}
    assert ca["crc_errors"] == ca["retries"] == ca["stale"] == ca["board_errors"] == 0
    assert a == b


# A dead board is known at once, not after an answer's timeout: the wait looks every 0.1 s
# (wire_link.GONE_POLL_S). With the timeout set to 10 s, ending within half of it can only be that
# look, and leaves seconds for a busy machine's stalls (seen: 1 s on 2 cores at a load of 8). (The
# board's end can cost one retry: its line closes a moment before its process is reaped.)
GONE_URL = "host-board:serial#step_delay_us=300&timeout_s=10"


def test_board_killed_mid_mission_exits_2_at_once_and_leaves_nothing() -> None:
    # a slowed board (0.3 ms a tick) so that the mission is surely under way when it is killed
    p = subprocess.Popen([*FFR, "run", "--room", "4", "--link", GONE_URL], cwd=REPO,
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        deadline = time.monotonic() + 30
        boards: list[int] = []
        while not boards and time.monotonic() < deadline and p.poll() is None:
            boards = children_of(p.pid)
            time.sleep(0.01)
        assert len(boards) == 1, "the board process did not start"
        time.sleep(1.0)  # handshake done, a few hundred ticks run
        assert p.poll() is None
        os.kill(boards[0], signal.SIGKILL)
        killed = time.monotonic()
        out, err = p.communicate(timeout=10)
        took = time.monotonic() - killed
    finally:
        if p.poll() is None:
            p.kill()
            p.wait()
    assert p.returncode == 2
    assert took < 5.0, f"took {took:.2f} s: the 10 s answer timeout, not the look for a dead board"
    assert err.count("\n") == 1
    assert err.startswith(f"ffr: error: {GONE_URL}: board gone at tick ")
    assert f"board process {boards[0]} killed by SIGKILL" in err and "sent " in err and "retries " in err
    assert "Traceback" not in err and out == ""
    assert not alive(boards[0])


def _is_board(pid: int) -> bool:
    try:
        with open(f"/proc/{pid}/cmdline", "rb") as fh:
            return b"ffr-host-board" in fh.read()
    except OSError:
        return False


def test_a_normal_run_leaves_no_board_behind() -> None:
    p = subprocess.Popen([*FFR, "run", "--room", "1", "--link", "host-board:serial"], cwd=REPO,
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    seen: set[int] = set()
    while p.poll() is None:
        # only the board: other short-lived children (and their recycled PIDs) are not ours to judge
        seen.update(c for c in children_of(p.pid) if _is_board(c))
        time.sleep(0.005)
    p.communicate()
    assert p.returncode == 0 and seen
    assert not any(alive(pid) for pid in seen)


def test_bad_wire_url_is_one_line_exit_2(tmp_path) -> None:
    res = _run("run", "--link", "host-board:serial#faults=lots", "--json", str(tmp_path / "x.json"))
    assert res.returncode == 2 and res.stderr.count("\n") == 1 and "unknown option 'faults'" in res.stderr
    assert not (tmp_path / "x.json").exists()


def test_pytest_link_option_runs_the_suite_over_that_link() -> None:
    test = "tests/harness/test_determinism.py::test_same_seed_bit_identical_without_noise"
    ok = subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", test, "--link",
                         "host-board:can"], cwd=REPO, capture_output=True, text=True, timeout=120)
    assert ok.returncode == 0 and "1 passed" in ok.stdout
    # proof that the option is obeyed: over a line that only echoes, the same test fails
    bad = subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", test, "--link",
                          "serial:loop://#handshake_timeout_s=0.2"], cwd=REPO, capture_output=True, text=True,
                         timeout=120)
    assert bad.returncode == 1 and "board silent during the handshake" in bad.stdout
