"""``make bench``, the wire part: per-tick round-trip cost of each link and the
real-time factor of a whole mission over it. Measured, never asserted."""

from __future__ import annotations

import contextlib
import shutil
import time
from pathlib import Path

import numpy as np

from ffr_link import open_link
from ffr_link.base import LinkError, new_inputs, new_outputs
from harness.firmware_config import build_config
from harness.loop import run_mission
from harness.scenario import make_scenario
from hil_bridge import codec
from hil_bridge.codec import MsgType
from hil_bridge.datagram_link import DatagramLink
from sim_plant.broken_pipe import exit_with

LINKS = ("ctypes:", "host-board:serial", "host-board:serial#transport=tcp", "host-board:can", "host-board:can#fd=1")
EMULATED = "qemu:mps2-an386"  # the Cortex-M4 build, when QEMU is installed: over its Ethernet (the default)
EMULATED_UART = "qemu:mps2-an386#transport=uart"  # ... and over its UART, for comparison
QEMU_GOAL_X = 20  # the emulated board's real-time factor goal (docs/pil.md)


def round_trip_us(url: str, n: int = 3000) -> float:
    """Mean µs of one link.step (inputs out, outputs back), the firmware driving along."""
    scn = make_scenario(room=1)
    with open_link(url) as link:
        link.reset(build_config(scn.robot))
        inp, out = new_inputs(), new_outputs()
        inp["start"], inp["ir_mv"] = 1, (400, 400, 400, 400, 400)
        for k in range(50):  # warm-up
            inp["seq"], inp["t_ms"] = k, 10 * k
            link.step(inp, out)
        t0 = time.perf_counter()
        for k in range(50, 50 + n):
            inp["seq"], inp["t_ms"] = k, 10 * k
            link.step(inp, out)
        return (time.perf_counter() - t0) / n * 1e6


def _context_switches(pid: int) -> int:
    """Voluntary and forced context switches of all of a process's threads so far (Linux /proc):
    each is a thread going to sleep and being woken, or pre-empted."""
    total = 0
    for status in Path(f"/proc/{pid}/task").glob("*/status"):
        with contextlib.suppress(OSError):
            for line in status.read_text().splitlines():
                if "ctxt_switches:" in line:
                    total += int(line.split()[1])
    return total


def tick_anatomy(url: str, n: int = 2000) -> str:
    """Where a tick's round trip goes over a serial or datagram link: from sending INPUTS to the
    first byte of the answer (the board receiving the frame, stepping, starting to answer), then to
    the whole OUTPUTS frame (the answer arriving), medians over n ticks. Over datagrams the first
    byte comes with the whole answer, in one piece."""
    scn = make_scenario(room=1)
    with open_link(url) as link:
        link.reset(build_config(scn.robot))
        inp, out = new_inputs(), new_outputs()
        inp["start"], inp["ir_mv"] = 1, (400, 400, 400, 400, 400)
        first, rest, reads = [], [], []
        board = getattr(link, "board", None)  # an emulated board: count QEMU's thread wake-ups
        pid = board.proc.pid if url.startswith("qemu:") and board is not None else 0
        c0, t0 = _context_switches(pid) if pid else 0, time.perf_counter()
        for k in range(n):
            inp["seq"], inp["t_ms"] = k, 10 * k
            r0 = link.reads  # type: ignore[attr-defined]
            link.step(inp, out)
            done = time.perf_counter()
            first.append(link.first_byte_at - link.sent_at)  # type: ignore[attr-defined]
            rest.append(done - link.first_byte_at)  # type: ignore[attr-defined]
            reads.append(link.reads - r0)  # type: ignore[attr-defined]
        datagrams = isinstance(link, DatagramLink)
        qemu = ""
        if pid:
            busy_s, busy = time.perf_counter() - t0, _context_switches(pid) - c0
            c1 = _context_switches(pid)
            time.sleep(0.5)  # the same board idle: its millisecond clock alone
            idle = (_context_switches(pid) - c1) / 0.5
            qemu = (f"; QEMU's threads switch {busy / n:.1f} times a tick ({idle * busy_s / n:.1f} of them the "
                    f"idle millisecond clock: {idle:.0f} a second idle)")
    n_in = len(codec.frame_encode(codec.encode_msg(MsgType.INPUTS, inp)))
    n_out = len(codec.frame_encode(codec.encode_msg(MsgType.OUTPUTS, out)))
    f, r = float(np.median(first[200:])) * 1e6, float(np.median(rest[200:])) * 1e6
    if datagrams:
        return (f"INPUTS {n_in} bytes in one datagram -> the whole OUTPUTS ({n_out} bytes, one datagram) "
                f"{f:.0f} us; -> decoded and checked {r:.0f} us more{qemu}")
    return (f"INPUTS {n_in} bytes sent -> first answer byte {f:.0f} us ({f / n_in:.1f} us a byte in); "
            f"-> whole OUTPUTS ({n_out} bytes, read in {np.mean(reads[200:]):.1f} pieces) {r:.0f} us more{qemu}")


def bench_links() -> None:
    print("links: round trip per tick (3000 ticks) and a whole mission (room 4) over each:")
    scn = make_scenario(room=4)
    run_mission(scn)  # warm-up (numba cache, library)
    links = LINKS + ((EMULATED, EMULATED_UART) if shutil.which("qemu-system-arm") else ())
    for url in links:
        try:
            rt = round_trip_us(url)
        except LinkError as exc:  # e.g. QEMU installed but the board image not built
            print(f"  {url:32s} skipped: {exc}")
            continue
        with open_link(url) as link:
            t0 = time.perf_counter()
            res, trace = run_mission(scn, link, record=False)
            wall = time.perf_counter() - t0
        ticks = res.sim_time_s / (scn.timing.firmware_period_ms / 1000.0)
        print(f"  {url:32s} round trip {rt:7.1f} us/tick; mission {res.sim_time_s:5.1f} s simulated in "
              f"{wall:6.2f} s = {res.sim_time_s / wall:6.0f}x real time ({wall / ticks * 1e6:6.1f} us/tick), "
              f"{res.outcome}")
        errors = {k: v for k, v in res.link_counters.items() if k not in ("sent", "received") and v}
        print(f"  {'':32s} link counters: sent {res.link_counters['sent']}, received "
              f"{res.link_counters['received']}, errors {errors or 'none'}")
        if (url.startswith(("qemu:", "host-board:serial")) and "#" not in url) or url == EMULATED_UART:
            print(f"  {'':32s} tick anatomy: {tick_anatomy(url)}")
        if url == EMULATED:
            factor = res.sim_time_s / wall
            print(f"  {'':32s} goal: room 4 over {EMULATED} at >= {QEMU_GOAL_X}x real time: "
                  f"{'met' if factor >= QEMU_GOAL_X else 'NOT met'} ({factor:.1f}x) over its Ethernet; "
                  "what limits it: docs/pil.md")


if __name__ == "__main__":
    exit_with(bench_links)
