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
FURNITURE_STREAM = 3  # spawn key of the random furniture's stream
START_AREAS = ("home", "hallway")  # hallway: the contest's arbitrary start mode
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


def start_problem(arena: Arena, robot: RobotParams, pose: tuple[float, float, float],
                  area: str = "home") -> str | None:
    """Why a start pose is not allowed (None: it is): the robot's centre outside the home circle
    (area "home") or outside every hallway (area "hallway": the arbitrary start mode), or its
    footprint touching a wall (furniture included)."""
    x, y, th = pose
    hx, hy = arena.home_center
    d = math.hypot(x - hx, y - hy)
    if area == "hallway":
        if not arena.in_hallway(x, y):
            return "the robot's centre is in no hallway"
    elif not d <= arena.home_radius:
        return (f"the robot's centre is {d * 100:.1f} cm from the home circle's centre "
                f"(radius {arena.home_radius * 100:.1f} cm)")
    poly = footprint(robot, x, y, th)
    for w, wp in zip(arena.walls, arena.wall_polys, strict=True):
        if convex_overlap(poly, wp):
            return f"the robot's footprint touches wall {w.name!r}"
    return None


def check_start(arena: Arena, robot: RobotParams, pose: tuple[float, float, float], source: str,
                field: str = "start", area: str = "home") -> None:
    why = start_problem(arena, robot, pose, area)
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


def draw_hallway_start(arena: Arena, robot: RobotParams,
                       rng: np.random.Generator) -> tuple[float, float, float]:
    """The arbitrary start mode: the centre uniform over the hallways' floor (a hallway picked by
    its area), the heading uniform in [0, 360°), a pose whose footprint touches a wall drawn again."""
    areas = np.array([_area(h.polygon) for h in arena.hallways])
    cum = np.cumsum(areas) / areas.sum()
    for _ in range(_MAX_TRIES):
        h = arena.hallways[min(int(np.searchsorted(cum, rng.uniform())), len(arena.hallways) - 1)]
        lo, hi = h.polygon.min(axis=0), h.polygon.max(axis=0)
        x, y = (float(v) for v in rng.uniform(lo, hi))
        th = float(rng.uniform(0.0, 2.0 * math.pi))
        if not arena.in_hallway(x, y):
            continue
        pose = (x, y, th)
        if start_problem(arena, robot, pose, "hallway") is None:
            return pose
    raise FfrInputError(arena.source, "hallways", len(arena.hallways),
                        "the robot's footprint fits in no hallway")  # pragma: no cover


def _area(poly: np.ndarray) -> float:
    x, y = poly[:, 0], poly[:, 1]
    return 0.5 * abs(float(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1))))
