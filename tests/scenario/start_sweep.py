"""Seeded sweeps of the firmware's robustness: start pose and calibration error.

Run from the repository root (docs/firmware.md quotes what these print):

    .venv/bin/python -m tests.scenario.start_sweep poses [--n 24] [--seed 0] [--noise none] [--anywhere]
    .venv/bin/python -m tests.scenario.start_sweep calibration [--noise none] [--seed 0]

``poses``: for each room, ``n`` headings evenly over 0-360 degrees (each
jittered within its slot) at positions drawn uniformly in the home circle
where the robot has room to turn in place. ``calibration``: a grid of the
plant's true wheel radius x {0.97 .. 1.03} and track width x {0.95 .. 1.05}
with the firmware told the nominal values, every room. Each prints one line
per failure (an ``ffr run`` command) and the pass rate.
"""

from __future__ import annotations

import argparse
import math
import sys

import numpy as np

from harness.loop import run_mission
from harness.scenario import Scenario, make_scenario
from harness.start_pose import start_problem
from sim_plant.arena import Arena, load_arena
from sim_plant.robot import load_robot

# clearance kept beyond the body's farthest corner so the robot can turn in place at the start
TURN_MARGIN_M = 0.01

WHEEL_SCALES = (0.97, 0.985, 1.0, 1.015, 1.03)
TRACK_SCALES = (0.95, 0.975, 1.0, 1.025, 1.05)


def turn_radius_m() -> float:
    """The body's farthest corner from the axle midpoint (it sweeps this circle turning in place)."""
    return load_robot().turn_radius()


def start_poses(n: int, seed: int, arena: Arena | None = None,
                centre: bool = False, anywhere: bool = False) -> list[tuple[float, float, float]]:
    """n start poses: heading k*360/n plus a uniform jitter within its slot, position uniform in the
    home circle where the robot can turn in place (drawn from one seeded generator); with
    ``anywhere``, uniform over the whole circle wherever the body's footprint at that heading
    touches no wall (as ``harness.start_pose.draw_start``); with ``centre``, at the circle's
    centre."""
    arena = arena or load_arena()
    robot = load_robot()
    rng = np.random.default_rng(seed)
    hx, hy = arena.home_center
    need = turn_radius_m() + TURN_MARGIN_M
    poses = []
    for k in range(n):
        heading = (k + rng.uniform(0.0, 1.0)) * 2.0 * math.pi / n
        while not centre:
            r = arena.home_radius * math.sqrt(rng.uniform(0.0, 1.0))
            a = rng.uniform(0.0, 2.0 * math.pi)
            x, y = hx + r * math.cos(a), hy + r * math.sin(a)
            if anywhere and start_problem(arena, robot, (x, y, heading)) is None:
                break
            if not anywhere and arena.wall_distance(x, y) >= need:
                break
        else:
            x, y = hx, hy
        poses.append((x, y, heading))
    return poses


def calibration_overrides(wheel: float, track: float) -> tuple[dict[str, float], dict[str, float]]:
    """(plant truth overrides, firmware belief) for a wheel radius and track width scale."""
    t = load_robot().track
    truth = {"track.wheel_radius": t.wheel_radius * wheel, "track.track_width": t.track_width * track}
    belief = {"wheel_radius_mm": t.wheel_radius * 1000.0, "track_width_mm": t.track_width * 1000.0}
    return truth, belief


def replay(scn: Scenario) -> str:
    """The failing mission as a command line; the start pose goes in a scenario file's [start]."""
    x, y, h = scn.start
    cmd = f"ffr run --room {scn.room} --seed {scn.seed}"
    if scn.noise.name != "none":
        cmd += f" --noise {scn.noise.name}"
    for k, v in scn.robot_overrides.items():
        cmd += f" --set robot.{k}={v:.5f}"
    for k, v in scn.firmware.items():
        cmd += f" --set firmware.{k}={v:.3f}"
    return cmd + f"  # [start] x = {x:.4f}, y = {y:.4f}, heading_deg = {math.degrees(h):.2f}"


def ok(res) -> bool:
    return res.outcome == "home" and res.wall_contacts == 0


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="start_sweep")
    ap.add_argument("what", choices=("poses", "calibration"))
    ap.add_argument("--n", type=int, default=24)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--noise", default="none")
    ap.add_argument("--rooms", default="1,2,3,4")
    ap.add_argument("--centre", action="store_true", help="poses: every start at the home circle's centre")
    ap.add_argument("--anywhere", action="store_true",
                    help="poses: anywhere in the circle where the footprint fits (not only with room to turn)")
    a = ap.parse_args(argv)
    rooms = [int(r) for r in a.rooms.split(",")]
    scns: list[Scenario] = []
    if a.what == "poses":
        for room in rooms:
            for pose in start_poses(a.n, a.seed + room, centre=a.centre, anywhere=a.anywhere):
                scns.append(make_scenario(room=room, start=pose, noise=a.noise, seed=a.seed))
    else:
        for room in rooms:
            for w in WHEEL_SCALES:
                for t in TRACK_SCALES:
                    truth, belief = calibration_overrides(w, t)
                    scns.append(make_scenario(room=room, noise=a.noise, seed=a.seed,
                                              robot_overrides=truth, firmware=belief))
    good = 0
    for scn in scns:
        res, _ = run_mission(scn, record=False)
        if ok(res):
            good += 1
        else:
            print(f"FAIL {res.outcome} contacts={res.wall_contacts} {res.detail!r}: {replay(scn)}", flush=True)
    print(f"{a.what}: {good}/{len(scns)} home with no wall contact ({100.0 * good / len(scns):.1f} %)")
    return 0 if good == len(scns) else 1


if __name__ == "__main__":
    sys.exit(main())
