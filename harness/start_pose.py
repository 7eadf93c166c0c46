"""Start poses in the home circle, and the mission's derived random streams.

A mission has one seed. Its sensor noise and events draw from
``numpy.random.default_rng(seed)`` exactly as before; the random start pose
and the arena jitter each draw from their own stream derived from the same
seed (``SeedSequence(seed, spawn_key=(k,))``), so switching them on or off
never changes the noise a mission sees (docs/scenarios.md).
"""

from __future__ import annotations

import math

import numpy as np

from sim_plant.arena import Arena
from sim_plant.errors import FfrInputError
from sim_plant.geometry import convex_overlap
from sim_plant.robot import RobotParams

START_STREAM = 1   # spawn key of the random start pose's stream
JITTER_STREAM = 2  # spawn key of the arena jitter's stream
_MAX_TRIES = 10000


def stream(seed: int, key: int) -> np.random.Generator:
    """The mission's derived stream ``key`` (never the noise stream ``default_rng(seed)`` itself)."""
    return np.random.default_rng(np.random.SeedSequence(seed, spawn_key=(key,)))


def footprint(robot: RobotParams, x: float, y: float, th: float) -> np.ndarray:
    """The body rectangle at (x, y, th), (4, 2) counter-clockwise."""
    f, r, lf, rt = robot.footprint()
    c, s = math.cos(th), math.sin(th)
    body = ((f, rt), (f, lf), (r, lf), (r, rt))
    return np.array([[x + c * bx - s * by, y + s * bx + c * by] for bx, by in body], dtype=np.float64)


def start_problem(arena: Arena, robot: RobotParams, pose: tuple[float, float, float]) -> str | None:
    """Why a start pose is not allowed (None: it is): the robot's centre outside the home circle,
    or its footprint touching a wall."""
    x, y, th = pose
    hx, hy = arena.home_center
    d = math.hypot(x - hx, y - hy)
    if not d <= arena.home_radius:
        return (f"the robot's centre is {d * 100:.1f} cm from the home circle's centre "
                f"(radius {arena.home_radius * 100:.1f} cm)")
    poly = footprint(robot, x, y, th)
    for w, wp in zip(arena.walls, arena.wall_polys, strict=True):
        if convex_overlap(poly, wp):
            return f"the robot's footprint touches wall {w.name!r}"
    return None


def check_start(arena: Arena, robot: RobotParams, pose: tuple[float, float, float], source: str,
                field: str = "start") -> None:
    why = start_problem(arena, robot, pose)
    if why:
        val = [round(pose[0], 4), round(pose[1], 4), round(math.degrees(pose[2]), 2)]
        raise FfrInputError(source, field, val, why)


def draw_start(arena: Arena, robot: RobotParams, rng: np.random.Generator) -> tuple[float, float, float]:
    """A start pose drawn uniformly over the allowed ones: the centre uniform over the home disc's
    area, the heading uniform in [0, 360°), a pair whose footprint touches a wall drawn again."""
    hx, hy = arena.home_center
    for _ in range(_MAX_TRIES):
        r = arena.home_radius * math.sqrt(float(rng.uniform()))
        a = float(rng.uniform(0.0, 2.0 * math.pi))
        th = float(rng.uniform(0.0, 2.0 * math.pi))
        pose = (hx + r * math.cos(a), hy + r * math.sin(a), th)
        if start_problem(arena, robot, pose) is None:
            return pose
    raise FfrInputError(arena.source, "home", [hx, hy],
                        "the robot's footprint fits nowhere in the home circle")  # pragma: no cover
