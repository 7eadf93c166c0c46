"""Per-tick cost of Plant.apply + Plant.integrate(0.010) (a script, not a test).

Run: .venv/bin/python tests/sim_plant/bench_plant.py
Drives a mission-like PWM pattern (straight runs, stops, reversals, spins,
with a small deterministic per-tick wobble) in the hallway at home, without
touching a wall, then times a sustained push against a wall separately.
"""

from __future__ import annotations

import math
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2]))

from sim_plant.arena import load_arena  # noqa: E402
from sim_plant.plant import Plant  # noqa: E402
from sim_plant.robot import load_robot  # noqa: E402

TICK = 0.010


def pattern(k: int) -> tuple[int, int]:
    """PWM for tick k: forward, stop, back, spin left, spin right; 1 s each, with wobble.

    The wobble is common to both wheels on the straight runs and the two spins
    mirror each other, so the robot stays in its hallway and never touches a wall.
    """
    phase = (k // 100) % 5
    wobble = (k * 37) % 21 - 10
    if phase == 0:
        return 450 + wobble, 450 + wobble
    if phase == 1:
        return wobble, wobble
    if phase == 2:
        return -450 + wobble, -450 + wobble
    if phase == 3:
        return -400 - wobble, 400 + wobble
    return 400 + wobble, -400 - wobble


def run(plant_dt: float, ticks: int) -> tuple[float, Plant]:
    arena, robot = load_arena(), load_robot()
    plant = Plant(arena, robot, 2.19, 1.60, math.pi / 2, plant_dt=plant_dt)
    plant.apply(0, 0)
    plant.integrate(TICK)  # compile / load the cache outside the timing
    cmds = [pattern(k) for k in range(ticks)]
    apply, integrate = plant.apply, plant.integrate
    t0 = time.perf_counter()
    for pl, pr in cmds:
        apply(pl, pr)
        integrate(TICK)
    return (time.perf_counter() - t0) / ticks * 1e6, plant


def push(plant_dt: float, ticks: int) -> float:
    arena, robot = load_arena(), load_robot()
    plant = Plant(arena, robot, 2.19, 2.20, math.pi / 2, plant_dt=plant_dt)
    plant.apply(600, 600)
    for _ in range(100):
        plant.integrate(TICK)
    assert plant.in_contact
    t0 = time.perf_counter()
    for _ in range(ticks):
        plant.apply(600, 600)
        plant.integrate(TICK)
    return (time.perf_counter() - t0) / ticks * 1e6


def main() -> None:
    ticks = 20000
    for dt in (0.001, TICK):
        best = min(run(dt, ticks)[0] for _ in range(3))
        _, plant = run(dt, ticks)
        print(f"plant_dt={dt * 1e3:4.1f} ms ({round(TICK / dt):2d} substeps): {best:5.2f} us/tick "
              f"(free driving, contacts={plant.contacts}, min clearance "
              f"{plant.min_clearance * 1e3:.1f} mm, path {plant.path_length:.1f} m)")
        print(f"{'':31s}{push(dt, 2000):5.2f} us/tick (sustained push against a wall)")


if __name__ == "__main__":
    main()
