"""``make bench``, the wire part: per-tick round-trip cost of each link and the
real-time factor of a whole mission over it. Measured, never asserted."""

from __future__ import annotations

import shutil
import time

from harness.firmware_config import build_config
from harness.links import open_link
from harness.links.base import LinkError, new_inputs, new_outputs
from harness.loop import run_mission
from harness.scenario import make_scenario

LINKS = ("ctypes:", "host-board:serial", "host-board:serial#transport=tcp", "host-board:can", "host-board:can#fd=1")
EMULATED = "qemu:mps2-an386"  # the Cortex-M4 build, when QEMU is installed


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


def bench_links() -> None:
    print("links: round trip per tick (3000 ticks) and a whole mission (room 4) over each:")
    scn = make_scenario(room=4)
    run_mission(scn)  # warm-up (numba cache, library)
    links = LINKS + ((EMULATED,) if shutil.which("qemu-system-arm") else ())
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


if __name__ == "__main__":
    bench_links()
