"""Benchmarks (``make bench``): measured, never asserted.

Prints the real-time factor of full missions with the in-process link
(simulated seconds per wall-clock second, one core), the cost of each
part of one tick: sensors, firmware step, plant, and the sweep throughput:
``FFR_BENCH_MISSIONS`` (default 1000) missions on all local cores through
``ffr sweep``'s engine, in missions per second.
"""

from __future__ import annotations

import time

import numpy as np

from harness.loop import run_mission
from harness.scenario import make_scenario


def _best(fn, repeat: int = 3) -> float:
    best = float("inf")
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t0)
    return best


def bench_missions() -> None:
    print("full missions, ctypes: link, no noise, trace recorded (best of 3):")
    total_sim = total_wall = 0.0
    for room in (1, 2, 3, 4):
        scn = make_scenario(room=room)
        res, _ = run_mission(scn)  # warm-up (numba cache, library load)
        wall = _best(lambda scn=scn: run_mission(scn))
        total_sim += res.sim_time_s
        total_wall += wall
        ticks = res.sim_time_s / (scn.timing.firmware_period_ms / 1000.0)
        print(f"  room {room}: {res.sim_time_s:6.1f} s simulated in {wall * 1000:6.1f} ms wall "
              f"= {res.sim_time_s / wall:7.0f}x real time, {wall / ticks * 1e6:5.1f} us/tick")
    print(f"  all four: real-time factor {total_sim / total_wall:.0f}x")


def bench_parts(n: int = 20000) -> None:
    from harness.firmware_config import build_config
    from harness.links.base import new_inputs, new_outputs
    from harness.links.ctypes_link import CtypesLink
    from sim_plant.candle import Candle
    from sim_plant.plant import Plant
    from sim_plant.sensors import SensorSuite, new_output

    scn = make_scenario(room=1)
    plant = Plant(scn.arena, scn.robot, *scn.start)
    candle = Candle(*scn.candle, scn.robot, scn.arena)
    sensors = SensorSuite(scn.arena, scn.robot, candle, scn.noise, np.random.default_rng(0))
    hw = new_output()
    link = CtypesLink()
    link.reset(build_config(scn.robot))
    inp, out = new_inputs(), new_outputs()
    link.bind(inp, out)

    def s() -> None:
        for k in range(n):
            sensors.sample(k * 0.01, plant.x, plant.y, plant.theta, plant.phi_l, plant.phi_r, hw)

    def f() -> None:
        for _ in range(n):
            link.step_bound()

    def p() -> None:
        for _ in range(n):
            plant.apply(300, 320)
            plant.integrate(0.01)
            if plant.in_contact:
                plant.apply(0, 0)

    print(f"per tick, {n} ticks (best of 3):")
    for name, fn in (("sensors.sample", s), ("firmware step (ctypes)", f), ("plant apply+integrate 10x1ms", p)):
        print(f"  {name:30s} {_best(fn) / n * 1e6:6.2f} us")


def bench_sweep(n: int) -> None:
    import os

    from harness import sweep as sw

    per_room = max(1, n // 4)
    spec = sw.SweepSpec(candles="random", n_candles=per_room, seeds=(0,), noise="typical")
    jobs = sw.build_jobs(spec)[:n]
    sim = 0.0
    t0 = time.perf_counter()
    rows = sw.execute(jobs)
    wall = time.perf_counter() - t0
    sim = sum(r["sim_time_s"] or 0.0 for r in rows)
    ok = sum(1 for r in rows if r["success"])
    print(f"sweep: {len(rows)} missions (random legal candles, typical noise) on {os.cpu_count()} cores "
          f"in {wall:.1f} s wall, cluster start included = {len(rows) / wall:.1f} missions/s "
          f"({sim / wall:.0f}x real time; {ok} succeeded)")


def main() -> None:
    import os

    from hil_bridge.bench import bench_links

    bench_missions()
    bench_parts()
    bench_sweep(int(os.environ.get("FFR_BENCH_MISSIONS", "1000")))
    bench_links()


if __name__ == "__main__":
    main()
