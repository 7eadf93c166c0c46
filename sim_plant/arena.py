"""The contest arena: walls, rooms, hallways, white lines, home and candle rules.

Loaded from a TOML file (``sim_plant/data/arena_2004.toml`` is the default).
All lengths in metres, coordinates as in the design notes: origin at the
bottom-left outer corner, x right, y up.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from sim_plant.errors import CandlePlacementError, FfrInputError
from sim_plant.file_schemas import ArenaFile
from sim_plant.geometry import (
    first_open_point,
    point_in_convex,
    point_segment_distance,
    polygon_edges,
    thick_segment_polygon,
)
from sim_plant.schema import check, read_toml

DEFAULT_ARENA = Path(__file__).parent / "data" / "arena_2004.toml"



@dataclass(frozen=True)
class Wall:
    name: str
    a: tuple[float, float]
    b: tuple[float, float]
    t: float


@dataclass(frozen=True)
class Room:
    id: int
    name: str
    polygon: np.ndarray  # (k, 2) counter-clockwise, convex
    door: tuple[tuple[float, float], tuple[float, float]]  # doorway line centre line
    default_candle: tuple[float, float]

    def contains(self, x: float, y: float) -> bool:
        return bool(point_in_convex(x, y, self.polygon))

    @property
    def inward(self) -> tuple[float, float]:
        """Unit normal of the doorway line pointing into the room."""
        (ax, ay), (bx, by) = self.door
        length = math.hypot(bx - ax, by - ay)
        nx, ny = -(by - ay) / length, (bx - ax) / length
        cx, cy = self.polygon.mean(axis=0)
        if (cx - ax) * nx + (cy - ay) * ny < 0:
            nx, ny = -nx, -ny
        return nx, ny

    def entry_zone(self, depth: float) -> np.ndarray:
        """The door's rectangle extruded ``depth`` into the room, (4, 2) CCW."""
        (ax, ay), (bx, by) = self.door
        nx, ny = self.inward
        pts = np.array(
            [[ax, ay], [bx, by], [bx + nx * depth, by + ny * depth], [ax + nx * depth, ay + ny * depth]]
        )
        return _ccw(pts)


@dataclass(frozen=True)
class Hallway:
    name: str
    polygon: np.ndarray


@dataclass
class Arena:
    name: str
    source: str
    size: tuple[float, float]
    wall_height: float
    line_width: float
    candle_circle_radius: float
    candle_min_depth: float
    candle_radius: float
    flame_height: float
    home_center: tuple[float, float]
    home_radius: float
    walls: list[Wall]
    rooms: list[Room]
    hallways: list[Hallway]
    # Which edition's candle placement rule ``check_candle`` follows (PLACEMENT_RULES, file_schemas.py).
    placement: str = "entry-depth"
    # The default start heading in the home circle (rad from +x; ``[home] heading_deg``, default 90).
    home_heading: float = math.pi / 2
    # Tolerance the walls were jittered by (0: the file's arena as drawn; sim_plant/arena_jitter.py).
    jitter: float = 0.0
    # the candle's base as an obstacle (issue 12): a disc the rangers see and the robot
    # knocks over; 0 = not an obstacle (docs/sensors.md)
    candle_base_radius: float = 0.0
    # Derived arrays for the compiled kernels.
    wall_polys: np.ndarray = field(init=False, repr=False)
    wall_edges: np.ndarray = field(init=False, repr=False)
    wall_bbox: np.ndarray = field(init=False, repr=False)
    door_polys: np.ndarray = field(init=False, repr=False)

    def __post_init__(self) -> None:
        self.wall_polys = np.stack([thick_segment_polygon(w.a, w.b, w.t) for w in self.walls])
        self.wall_edges = polygon_edges(self.wall_polys)
        self.wall_bbox = np.stack(
            [np.concatenate([p.min(axis=0), p.max(axis=0)]) for p in self.wall_polys]
        )
        self.door_polys = np.stack(
            [thick_segment_polygon(r.door[0], r.door[1], self.line_width) for r in self.rooms]
        )

    # -- queries ---------------------------------------------------------
    def room(self, room_id: int) -> Room:
        for r in self.rooms:
            if r.id == room_id:
                return r
        ids = [r.id for r in self.rooms]
        raise FfrInputError(self.source, "room", room_id, f"no such room (rooms: {ids})")

    def room_at(self, x: float, y: float) -> Room | None:
        for r in self.rooms:
            if r.contains(x, y):
                return r
        return None

    def in_hallway(self, x: float, y: float) -> bool:
        return any(point_in_convex(x, y, h.polygon) for h in self.hallways)

    def wall_distance(self, x: float, y: float) -> float:
        """Distance from a point to the nearest wall surface (0 inside a wall)."""
        best = math.inf
        for p in self.wall_polys:
            if point_in_convex(x, y, p):
                return 0.0
            for j in range(4):
                a, b = p[j], p[(j + 1) % 4]
                best = min(best, point_segment_distance(x, y, a[0], a[1], b[0], b[1]))
        return best

    # -- candle placement rules -----------------------------------------
    def check_candle(self, x: float, y: float, source: str = "candle") -> Room:
        """Return the candle's room, or raise CandlePlacementError naming the rule."""
        val = [round(x, 4), round(y, 4)]
        room = self.room_at(x, y)
        if room is None:
            if self.in_hallway(x, y):
                raise CandlePlacementError(source, "candle", val, "in-hallway",
                                           "the candle is never placed in a hallway")
            raise CandlePlacementError(source, "candle", val, "outside-rooms",
                                       "the candle must stand inside a room")
        if self.wall_distance(x, y) < self.candle_radius:
            raise CandlePlacementError(source, "candle", val, "in-wall",
                                       "the candle overlaps a wall")
        ring_outer = self.candle_circle_radius + self.line_width / 2.0
        (ax, ay), (bx, by) = room.door
        if point_segment_distance(x, y, ax, ay, bx, by) < ring_outer + self.line_width / 2.0:
            raise CandlePlacementError(source, "candle", val, "circle-touches-doorway",
                                       f"its circle touches the doorway line of room {room.id}")
        if self.placement == "door-line":
            return room
        zone = room.entry_zone(self.candle_min_depth)
        if _circle_meets_convex(x, y, ring_outer, zone):
            raise CandlePlacementError(
                source, "candle", val, "entry-depth",
                f"the robot must move {self.candle_min_depth * 100:.0f} cm into room "
                f"{room.id} before reaching the candle circle")
        return room

    def random_candle(self, room_id: int, rng: np.random.Generator) -> tuple[float, float]:
        """A uniformly random legal candle position in a room (rejection sampling)."""
        room = self.room(room_id)
        lo = room.polygon.min(axis=0)
        hi = room.polygon.max(axis=0)
        for _ in range(10000):
            x, y = rng.uniform(lo, hi)
            try:
                self.check_candle(float(x), float(y))
            except CandlePlacementError:
                continue
            return float(x), float(y)
        raise RuntimeError(f"room {room_id}: no legal candle position found")  # pragma: no cover


def _ccw(pts: np.ndarray) -> np.ndarray:
    x, y = pts[:, 0], pts[:, 1]
    area = 0.5 * float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y))
    return pts if area > 0 else pts[::-1].copy()


def _circle_meets_convex(cx: float, cy: float, r: float, poly: np.ndarray) -> bool:
    if point_in_convex(cx, cy, poly):
        return True
    n = poly.shape[0]
    return any(
        point_segment_distance(cx, cy, *poly[i], *poly[(i + 1) % n]) < r for i in range(n)
    )


# -- loading ---------------------------------------------------------------

def _polygon(src: str, name: str, v: Any) -> np.ndarray:
    """A convex polygon, counter-clockwise (the schema checked its shape: 3+ points [x, y])."""
    arr = _ccw(np.asarray(v, dtype=np.float64))
    n = arr.shape[0]
    for i in range(n):
        a, b, c = arr[i], arr[(i + 1) % n], arr[(i + 2) % n]
        if (b[0] - a[0]) * (c[1] - b[1]) - (b[1] - a[1]) * (c[0] - b[0]) < -1e-12:
            raise FfrInputError(src, name, [list(q) for q in v], "must be convex")
    return arr


def load_arena(path: str | Path | None = None) -> Arena:
    p = Path(path) if path is not None else DEFAULT_ARENA
    return arena_from_dict(read_toml(p), str(p), p.stem)


def arena_from_dict(data: dict[str, Any], source: str, default_name: str = "arena") -> Arena:
    """An arena from an arena file's tables; ``default_name`` when ``[arena]`` names none."""
    src = source
    # keys, types, ranges and the cross-field rules: sim_plant/file_schemas.py
    f: ArenaFile = check(data, ArenaFile, src)
    a, home = f.arena, f.home
    walls = [Wall(w.name, w.a, w.b, w.t) for w in f.walls]
    rooms = [Room(r.id, r.name if r.name is not None else f"room{r.id}",
                  _polygon(src, f"rooms[{i}].polygon", r.polygon), r.door, r.default_candle)
             for i, r in enumerate(f.rooms)]
    hallways = [Hallway(h.name, _polygon(src, f"hallways[{i}].polygon", h.polygon))
                for i, h in enumerate(f.hallways)]
    arena = Arena(
        name=a.name if a.name is not None else default_name, source=src, size=a.size,
        wall_height=a.wall_height, line_width=a.line_width, candle_circle_radius=a.candle_circle_radius,
        candle_min_depth=a.candle_min_depth, candle_radius=a.candle_radius, flame_height=a.flame_height,
        candle_base_radius=a.candle_base_radius, home_center=home.center, home_radius=home.radius,
        walls=walls, rooms=sorted(rooms, key=lambda rm: rm.id), hallways=hallways,
        placement=a.placement, home_heading=math.radians(home.heading_deg),
    )
    validate_arena(arena, [next(i for i, r in enumerate(f.rooms) if r.id == rm.id) for rm in arena.rooms])
    return arena


def validate_arena(arena: Arena, room_index: list[int] | None = None) -> None:
    """Raise FfrInputError unless the arena is one a mission can run in.

    Every room closed by walls except across its doorway (points just outside
    each side of its polygon lie in a wall or on the doorway's line), each
    doorway an opening wider than its line, the home circle's centre in a
    hallway and clear of the walls, every wall inside the outer square, and
    every room's default candle legal under the arena's placement rule.
    ``room_index[k]``: the file's index of ``arena.rooms[k]`` (for messages).
    """
    src = arena.source
    w, h = arena.size
    for k, poly in enumerate(arena.wall_polys):
        if poly[:, 0].min() < -1e-9 or poly[:, 1].min() < -1e-9 or poly[:, 0].max() > w + 1e-9 \
                or poly[:, 1].max() > h + 1e-9:
            raise FfrInputError(src, f"walls[{k}]", arena.walls[k].name, "wall outside the arena's outer square")
    reach = max(wl.t for wl in arena.walls) + arena.line_width
    for k, rm in enumerate(arena.rooms):
        idx = room_index[k] if room_index else k
        (ax, ay), (bx, by) = rm.door
        if math.hypot(bx - ax, by - ay) <= arena.line_width:
            raise FfrInputError(src, f"rooms[{idx}].door", [list(rm.door[0]), list(rm.door[1])],
                                "doorway not wider than its line")
        mx, my = (ax + bx) / 2.0, (ay + by) / 2.0
        if any(point_in_convex(mx, my, p) for p in _shrunk(arena.wall_polys)):
            raise FfrInputError(src, f"rooms[{idx}].door", [list(rm.door[0]), list(rm.door[1])],
                                "doorway blocked by a wall")
        gap = _room_gap(arena, rm, reach)
        if gap is not None:
            raise FfrInputError(src, f"rooms[{idx}].polygon", [round(gap[0], 4), round(gap[1], 4)],
                                f"room {rm.id} is not closed: no wall and no doorway there")
    hx, hy = arena.home_center
    if not arena.in_hallway(hx, hy) or arena.wall_distance(hx, hy) <= 0.0:
        raise FfrInputError(src, "home.center", [hx, hy], "the home circle's centre must lie in a hallway")
    for k, rm in enumerate(arena.rooms):
        idx = room_index[k] if room_index else k
        arena.check_candle(*rm.default_candle, source=f"{src}: rooms[{idx}].default_candle")


def _shrunk(polys: np.ndarray, by: float = 1e-6) -> list[np.ndarray]:
    """Wall polygons shrunk a hair towards their centres (a door edge touching a wall is not inside it)."""
    out = []
    for p in polys:
        c = p.mean(axis=0)
        d = p - c
        n = np.linalg.norm(d, axis=1, keepdims=True)
        out.append(c + d * np.maximum(0.0, 1.0 - by / np.maximum(n, 1e-12)))
    return out


def _room_gap(arena: Arena, rm: Room, reach: float, step: float = 0.01,
              off: float = 0.003) -> tuple[float, float] | None:
    """A point just outside the room's polygon in no wall and off the doorway, or None (closed)."""
    poly = rm.polygon
    n = poly.shape[0]
    (ax, ay), (bx, by) = rm.door
    for i in range(n):
        p, q = poly[i], poly[(i + 1) % n]
        ex, ey = q[0] - p[0], q[1] - p[1]
        length = math.hypot(ex, ey)
        ox, oy = ey / length, -ex / length  # outward normal of a CCW polygon
        m = max(2, int(length / step))
        f = np.arange(1, m) / m  # as j / m, j = 1 .. m - 1: the same points, in the same order
        xs, ys = p[0] + ex * f + ox * off, p[1] + ey * f + oy * off
        k = first_open_point(xs, ys, arena.wall_polys, ax, ay, bx, by, reach)
        if k >= 0:
            return float(xs[k]), float(ys[k])
    return None
