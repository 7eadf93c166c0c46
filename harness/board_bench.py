"""``make bench``, the boards part: each emulated board's ``ffr_step`` profile
and what it means on the real chip. Measured, never asserted.

For every board in ``hil_bridge.qemu_board.MACHINES`` it runs rooms 1 and 4
over ``qemu:<machine>``, compares with the host build (identical?), and
prints the instructions per ``ffr_step`` (mean and worst, counted by QEMU's
``-icount shift=0``), the wall time per tick over the emulated link, and the
CPU load of that step at the chip's real clock for the 10 ms tick, assuming
``Machine.cycles_per_insn`` cycles per instruction (1.25 on a Cortex-M4 with
zero-wait-state flash or ART accelerator, 1.5 on a Cortex-M0 at 16 MHz with
its flash wait states: estimates, not measured on silicon).
"""

from __future__ import annotations

import shutil
import time

from ffr_link import open_link
from harness.b2b import compare_traces
from harness.loop import run_mission
from harness.scenario import make_scenario
from hil_bridge.qemu_board import MACHINES
from sim_plant.broken_pipe import exit_with

TICK_MS = 10.0
# the tick each board runs (docs/boards.md): the Cortex-M0 cannot keep 10 ms, so it runs 20 ms
BOARD_TICK_MS = {"microbit": 20.0}


def load_line(name: str, mean_insn: float, max_insn: int, tick_ms: float = TICK_MS) -> str:
    m = MACHINES[name]
    ms_per_insn = m.cycles_per_insn / m.cpu_hz * 1e3
    mean_ms, max_ms = mean_insn * ms_per_insn, max_insn * ms_per_insn
    verdict = "keeps the tick" if max_ms <= tick_ms else f"worst step {max_ms / tick_ms:.2f}x the tick"
    return (f"at {m.cpu_hz / 1e6:.0f} MHz x {m.cycles_per_insn} cycles/instruction: mean {mean_ms:.3f} ms "
            f"({100 * mean_ms / tick_ms:.1f} % of a {tick_ms:.0f} ms tick), worst {max_ms:.3f} ms "
            f"({100 * max_ms / tick_ms:.1f} %): {verdict}")


def bench_boards(rooms: tuple[int, ...] = (1, 4)) -> None:
    for name in MACHINES:
        for room in rooms:
            scn = make_scenario(room=room)
            _, ref = run_mission(scn)
            link = open_link(f"qemu:{name}")
            try:
                t0 = time.perf_counter()
                res, tgt = run_mission(scn, link)
                wall = time.perf_counter() - t0
            finally:
                link.close()
            ok = compare_traces(ref, tgt)[0]
            prof = link.profile  # type: ignore[attr-defined]
            print(f"  {name:14s} room {room}: {'identical' if ok else 'DIFFERENT'}, {res.outcome}, "
                  f"{len(tgt.i)} ticks, {wall / len(tgt.i) * 1e3:.2f} ms/tick over the link")
            if prof is not None:
                print(f"    ffr_step: mean {prof.mean_insn:.0f}, worst {prof.max_insn} instructions "
                      f"({prof.steps} steps, {prof.rx_overruns} rx overruns)")
                print(f"    {load_line(name, prof.mean_insn, prof.max_insn)}")
                if name in BOARD_TICK_MS:
                    print(f"    {load_line(name, prof.mean_insn, prof.max_insn, BOARD_TICK_MS[name])} "
                          "(its tick: docs/boards.md)")


def main() -> None:
    if shutil.which("qemu-system-arm") is None:
        print("boards: skipped, needs qemu-system-arm")
    else:
        print("boards on QEMU (-icount shift=0: instructions counted exactly; load at the real clock estimated):")
        bench_boards()


if __name__ == "__main__":
    exit_with(main)
