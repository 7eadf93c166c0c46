"""The contest arena: walls, rooms, hallways, white lines, home and candle rules.

Loaded from a TOML file (``sim_plant/data/arena_2004.toml`` is the default).
All lengths in metres, coordinates as in the design notes: origin at the
bottom-left outer corner, x right, y up.
"""

from __future__ import annotations

import copy
import math
import tomllib
from dataclasses import dataclass, field
from functools import lru_cache
from pathlib import Path
from typing import Any

import numpy as np

from sim_plant.errors import CandlePlacementError, FfrInputError
from sim_plant.geometry import (
    point_in_convex,
    point_segment_distance,
    polygon_edges,
    thick_segment_polygon,
)

DEFAULT_ARENA = Path(__file__).parent / "data" / "arena_2004.toml"

# Candle placement rules by rules edition (``[arena] placement`` in an arena file, docs/arena.md):
# - "entry-depth": later editions' text: the candle's circle does not touch the doorway line, and
#   the robot's front can move ``candle_min_depth`` (33 cm) into the room before reaching it;
# - "door-line": the 2001 contest plan: the circle only must not touch the doorway line (a candle
#   may stand just beside a door, as two of that plan's four candle targets do).
PLACEMENT_RULES = ("entry-depth", "door-line")


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
    # Which edition's candle placement rule ``check_candle`` follows (PLACEMENT_RULES).
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

class _Reader:
    """Typed field access into a TOML table with one-line errors."""

    def __init__(self, source: str, table: dict[str, Any], prefix: str = "") -> None:
        self.source = source
        self.table = table
        self.prefix = prefix

    def _name(self, key: str) -> str:
        return f"{self.prefix}{key}"

    def get(self, key: str, default: Any = ...) -> Any:
        if key not in self.table:
            if default is ...:
                raise FfrInputError(self.source, self._name(key), None, "missing")
            return default
        return self.table[key]

    def number(self, key: str, default: Any = ..., lo: float | None = None,
               hi: float | None = None, positive: bool = False) -> float:
        v = self.get(key, default)
        if isinstance(v, bool) or not isinstance(v, int | float) or not math.isfinite(v):
            raise FfrInputError(self.source, self._name(key), v, "must be a finite number")
        if positive and v <= 0:
            raise FfrInputError(self.source, self._name(key), v, "must be > 0")
        if lo is not None and v < lo:
            raise FfrInputError(self.source, self._name(key), v, f"must be >= {lo}")
        if hi is not None and v > hi:
            raise FfrInputError(self.source, self._name(key), v, f"must be <= {hi}")
        return float(v)

    def point(self, key: str, default: Any = ...) -> tuple[float, float]:
        v = self.get(key, default)
        if (not isinstance(v, list) or len(v) != 2
                or not all(isinstance(c, int | float) and not isinstance(c, bool) for c in v)):
            raise FfrInputError(self.source, self._name(key), v, "must be a point [x, y]")
        return float(v[0]), float(v[1])

    def string(self, key: str, default: Any = ...) -> str:
        v = self.get(key, default)
        if not isinstance(v, str):
            raise FfrInputError(self.source, self._name(key), v, "must be a string")
        return v

    def tables(self, key: str) -> list[_Reader]:
        v = self.get(key)
        if not isinstance(v, list) or not v or not all(isinstance(t, dict) for t in v):
            raise FfrInputError(self.source, self._name(key), "...", "must be a non-empty array of tables")
        return [_Reader(self.source, t, f"{self._name(key)}[{i}].") for i, t in enumerate(v)]

    def sub(self, key: str) -> _Reader:
        v = self.get(key)
        if not isinstance(v, dict):
            raise FfrInputError(self.source, self._name(key), v, "must be a table")
        return _Reader(self.source, v, f"{self._name(key)}.")


def read_toml(path: str | Path) -> dict[str, Any]:
    """Read a TOML file; unreadable or malformed files raise FfrInputError."""
    p = Path(path)
    try:
        text = p.read_text(encoding="utf-8")
    except OSError as exc:
        raise FfrInputError(str(p), "(file)", str(p), exc.strerror or "cannot be read") from None
    except UnicodeDecodeError as exc:
        raise FfrInputError(str(p), "(encoding)", f"byte {exc.start}",
                            "not UTF-8 text (TOML files are UTF-8)") from None
    try:
        return copy.deepcopy(_parse_toml(text))
    except tomllib.TOMLDecodeError as exc:
        raise FfrInputError(str(p), "(syntax)", None, str(exc)) from None


@lru_cache(maxsize=32)
def _parse_toml(text: str) -> dict[str, Any]:
    # Parsed once per content: a sweep reads the same noise profile and scoring
    # files for every mission (~7 ms each time); read_toml hands out copies.
    return tomllib.loads(text)


def _polygon(r: _Reader, key: str) -> np.ndarray:
    v = r.get(key)
    try:
        arr = np.asarray(v, dtype=np.float64)
    except (TypeError, ValueError):
        arr = None
    if arr is None or arr.ndim != 2 or arr.shape[1] != 2 or arr.shape[0] < 3:
        raise FfrInputError(r.source, r._name(key), v, "must be a polygon [[x, y], ...] (3+ points)")
    arr = _ccw(arr)
    n = arr.shape[0]
    for i in range(n):
        a, b, c = arr[i], arr[(i + 1) % n], arr[(i + 2) % n]
        if (b[0] - a[0]) * (c[1] - b[1]) - (b[1] - a[1]) * (c[0] - b[0]) < -1e-12:
            raise FfrInputError(r.source, r._name(key), v, "must be convex")
    return arr


def _only(r: _Reader, known: set[str]) -> None:
    """Unknown keys are errors: a misspelt field must never quietly fall back to its default."""
    unknown = sorted(set(r.table) - known)
    if unknown:
        raise FfrInputError(r.source, r._name(unknown[0]), r.table[unknown[0]],
                            f"unknown field (known: {', '.join(sorted(known))})")


def load_arena(path: str | Path | None = None) -> Arena:
    p = Path(path) if path is not None else DEFAULT_ARENA
    src = str(p)
    root = _Reader(src, read_toml(p))
    _only(root, {"arena", "home", "walls", "rooms", "hallways"})
    a = root.sub("arena")
    _only(a, {"name", "size", "wall_height", "line_width", "candle_circle_radius", "candle_min_depth",
              "candle_base_radius", "candle_radius", "flame_height", "placement"})
    home = root.sub("home")
    _only(home, {"center", "radius", "heading_deg"})
    size = a.point("size")
    if size[0] <= 0 or size[1] <= 0:
        raise FfrInputError(src, "arena.size", list(size), "must be positive")
    walls = []
    for w in root.tables("walls"):
        _only(w, {"name", "a", "b", "t"})
        wa, wb = w.point("a"), w.point("b")
        if wa == wb:
            raise FfrInputError(src, w._name("b"), list(wb), "wall has zero length")
        walls.append(Wall(w.string("name", "wall"), wa, wb, w.number("t", positive=True)))
    rooms = []
    seen: set[int] = set()
    for r in root.tables("rooms"):
        _only(r, {"id", "name", "polygon", "door", "default_candle"})
        rid = r.get("id")
        if isinstance(rid, bool) or not isinstance(rid, int) or rid < 1 or rid in seen:
            raise FfrInputError(src, r._name("id"), rid, "must be a unique integer >= 1")
        seen.add(rid)
        door = r.get("door")
        if (not isinstance(door, list) or len(door) != 2
                or not all(isinstance(q, list) and len(q) == 2 for q in door)):
            raise FfrInputError(src, r._name("door"), door, "must be a segment [[x, y], [x, y]]")
        door_t = ((float(door[0][0]), float(door[0][1])), (float(door[1][0]), float(door[1][1])))
        rooms.append(Room(rid, r.string("name", f"room{rid}"), _polygon(r, "polygon"), door_t,
                          r.point("default_candle")))
    hallways = []
    for h in root.tables("hallways"):
        _only(h, {"name", "polygon"})
        hallways.append(Hallway(h.string("name", "hallway"), _polygon(h, "polygon")))
    placement = a.string("placement", "entry-depth")
    if placement not in PLACEMENT_RULES:
        raise FfrInputError(src, "arena.placement", placement, f"expected one of {', '.join(PLACEMENT_RULES)}")
    arena = Arena(
        name=a.string("name", p.stem), source=src, size=size,
        wall_height=a.number("wall_height", positive=True),
        line_width=a.number("line_width", positive=True),
        candle_circle_radius=a.number("candle_circle_radius", positive=True),
        candle_min_depth=a.number("candle_min_depth", 0.33, lo=0.0),
        candle_radius=a.number("candle_radius", 0.0125, positive=True),
        flame_height=a.number("flame_height", 0.175, positive=True),
        candle_base_radius=a.number("candle_base_radius", 0.0, lo=0.0, hi=0.15),
        home_center=home.point("center"), home_radius=home.number("radius", positive=True),
        walls=walls, rooms=sorted(rooms, key=lambda rm: rm.id), hallways=hallways,
        placement=placement,
        home_heading=math.radians(home.number("heading_deg", 90.0)),
    )
    validate_arena(arena, [next(i for i, r in enumerate(root.table["rooms"]) if r.get("id") == rm.id)
                           for rm in arena.rooms])
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
        for j in range(1, m):
            f = j / m
            x, y = p[0] + ex * f + ox * off, p[1] + ey * f + oy * off
            if any(point_in_convex(x, y, wp) for wp in arena.wall_polys):
                continue
            if point_segment_distance(x, y, ax, ay, bx, by) <= reach:
                continue
            return x, y
    return None
