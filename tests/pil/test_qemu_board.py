"""Processor-in-the-loop: the Cortex-M4 build on QEMU's mps2-an386, in the same missions.

The four rooms' missions run on the emulated board and are compared back to
back with the host build: the actuator traces must be bit-identical. QEMU is
started and stopped cleanly whatever happens: success, a killed board, Ctrl-C.
"""

from __future__ import annotations

import os
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from harness.b2b import back_to_back
from harness.links import LinkError, open_link
from harness.scenario import make_scenario

REPO = Path(__file__).resolve().parents[2]
BUDGET_INSN = 20_000  # stated in the Makefile's bench target and docs/pil.md
WORST_INSN = 5_000  # the firmware's own bound on its worst tick (docs/pil.md)

# under CI the tools are installed by .ci/run: a missing one fails there instead of skipping
pytestmark = pytest.mark.skipif(
    (shutil.which("qemu-system-arm") is None or shutil.which("arm-none-eabi-gcc") is None)
    and not os.environ.get("CI"),
    reason="needs qemu-system-arm and arm-none-eabi-gcc (CI installs both)")


@pytest.fixture(scope="module", autouse=True)
def board_image() -> None:
    res = subprocess.run(["make", "-s", "firmware-boards"], cwd=REPO, capture_output=True, text=True, timeout=600)
    assert res.returncode == 0, res.stderr


def _qemu_pids() -> set[int]:
    # this checkout's boards only: another checkout's QEMU on the same machine is not ours to count
    out = subprocess.run(["pgrep", "-f", f"qemu-system-arm -M .* -kernel {REPO}/build/"], capture_output=True,
                         text=True)
    return {int(p) for p in out.stdout.split()}


@pytest.mark.parametrize("room", [1, 2, 3, 4])
def test_mission_on_the_emulated_board_equals_the_host_build(room: int) -> None:
    before = _qemu_pids()
    target = open_link("qemu:mps2-an386")
    try:
        rep = back_to_back(make_scenario(room=room), target)
    finally:
        target.close()
    assert rep.identical, rep.detail
    assert rep.results[1].outcome == "home"
    assert rep.ticks_target == rep.ticks_reference > 3000
    # a clean link is silent: every message answered once, nothing garbled, repeated or late
    c = rep.results[1].link_counters
    assert c["sent"] == c["received"] > rep.ticks_target
    assert c["crc_errors"] == c["retries"] == c["stale"] == c["board_errors"] == c["watchdog"] == 0, c
    prof = target.profile  # type: ignore[attr-defined]
    assert prof is not None and prof.steps >= 3000
    assert prof.rx_overruns == 0
    assert 200 < prof.mean_insn <= prof.max_insn <= WORST_INSN < BUDGET_INSN
    assert _qemu_pids() == before  # QEMU is gone


def test_unknown_machine_is_a_clear_error() -> None:
    with pytest.raises(LinkError, match="unknown emulated board 'vax'"):
        open_link("qemu:vax")


def _start_cli(*args: str) -> subprocess.Popen[str]:
    return subprocess.Popen([sys.executable, "-m", "harness", "run", "--room", "4", *args],
                            cwd=REPO, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)


def _wait_for_qemu(before: set[int], timeout_s: float = 20.0) -> int:
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        new = _qemu_pids() - before
        if new:
            return new.pop()
        time.sleep(0.05)
    raise AssertionError("QEMU did not start")


def test_board_killed_mid_mission_clear_error_no_stray_process() -> None:
    before = _qemu_pids()
    cli = _start_cli("--link", "qemu:mps2-an386")
    pid = _wait_for_qemu(before)
    time.sleep(1.5)  # the mission is under way
    os.kill(pid, signal.SIGKILL)
    t0 = time.monotonic()
    out, err = cli.communicate(timeout=30)
    assert time.monotonic() - t0 < 3.0
    assert cli.returncode == 2, err
    assert err.count("\n") == 1 and err.startswith("ffr: error: qemu:mps2-an386:") and "killed by SIGKILL" in err
    assert "Traceback" not in err
    assert _qemu_pids() == before


def test_ctrl_c_shuts_qemu_down() -> None:
    before = _qemu_pids()
    cli = _start_cli("--link", "qemu:mps2-an386")
    _wait_for_qemu(before)
    time.sleep(1.5)
    cli.send_signal(signal.SIGINT)
    _, err = cli.communicate(timeout=30)
    assert cli.returncode == 130 and "interrupted" in err
    assert _qemu_pids() == before
