"""Furniture: the contest's optional mode with objects standing in the rooms.

A piece is a box (a rectangle on the floor, as tall as the walls), placed in a
room; it becomes one more wall of the arena (``furnish``), so the rangers see
it, the plant collides with it and a touch counts as a wall contact, with no
new code on the hot path.

Where a piece may stand (``furniture_problem``; docs/arena.md, Furniture). No
published sizes or placement rules were found: these are chosen.

- inside one room;
- never blocking the door: clear of the door's entry zone, the doorway line
  extruded ``DOOR_CLEAR`` (45 cm: the robot's length and a turn) into the room;
- clear of the candle: every point of the piece at least ``CANDLE_CLEAR``
  (10 cm) outside the candle circle;
- against a wall (its back within ``AGAINST`` = 3 cm of one of the room's
  walls) or free-standing with ``PASS_CLEAR`` (25 cm: the body's 20 cm width
  and some) to every wall, so that it never makes a gap the robot fits in
  only just.

Random furniture (``draw_furniture``) takes sizes uniform in
``SIZE_RANGE`` (10-20 cm a side, chosen), one piece per room in turn (a room
with no place left passes it to the next), its sides square to the room's
walls, and is drawn again until the rules hold.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from sim_plant.arena import Arena, Room, Wall
from sim_plant.errors import FfrInputError
from sim_plant.geometry import convex_overlap, point_in_convex, point_segment_distance

DOOR_CLEAR = 0.45    # m, the door's entry zone kept free (chosen)
CANDLE_CLEAR = 0.10  # m, beyond the candle circle (chosen)
AGAINST = 0.03       # m, "against a wall": its back this close (chosen)
PASS_CLEAR = 0.25    # m, a free-standing piece's gap to every wall (chosen)
SIZE_RANGE = (0.10, 0.20)  # m, a side of a random piece (chosen)
MAX_PIECES = 8
_TRIES = 2000


@dataclass(frozen=True)
class Piece:
    """A box on the floor: centre (m), width across and depth along its heading (m), heading (rad)."""

    x: float
    y: float
    width: float
    depth: float
    heading: float = 0.0

    def polygon(self) -> np.ndarray:
        c, s = math.cos(self.heading), math.sin(self.heading)
        hd, hw = self.depth / 2.0, self.width / 2.0
        return np.array([[self.x + c * dx - s * dy, self.y + s * dx + c * dy]
                         for dx, dy in ((hd, -hw), (hd, hw), (-hd, hw), (-hd, -hw))], dtype=np.float64)

    def as_wall(self, k: int) -> Wall:
        """The same rectangle as a thick segment: its centre line along the depth, the width its thickness."""
        c, s = math.cos(self.heading), math.sin(self.heading)
        hd = self.depth / 2.0
        return Wall(f"furniture_{k}", (self.x - c * hd, self.y - s * hd), (self.x + c * hd, self.y + s * hd),
                    self.width)

    def as_list(self) -> list[float]:
        return [round(self.x, 4), round(self.y, 4), round(self.width, 4), round(self.depth, 4),
                round(math.degrees(self.heading), 2)]


def _gap_to_room_walls(poly: np.ndarray, room: Room) -> float:
    """The least distance from the piece's corners to the room's boundary (the walls' faces)."""
    rp = room.polygon
    n = rp.shape[0]
    return min(point_segment_distance(float(px), float(py), float(rp[i, 0]), float(rp[i, 1]),
                                      float(rp[(i + 1) % n, 0]), float(rp[(i + 1) % n, 1]))
               for px, py in poly for i in range(n))


def furniture_problem(arena: Arena, piece: Piece, candle: tuple[float, float],
                      others: list[Piece] | None = None) -> str | None:
    """Why the piece may not stand there (None: it may)."""
    if not (piece.width > 0.0 and piece.depth > 0.0):
        return "width and depth must be > 0"
    poly = piece.polygon()
    room = arena.room_at(piece.x, piece.y)
    if room is None or not all(room.contains(float(px), float(py)) for px, py in poly):
        return "not inside one room"
    if convex_overlap(poly, room.entry_zone(DOOR_CLEAR)):
        return f"blocks the door of room {room.id} (its first {DOOR_CLEAR * 100:.0f} cm must stay free)"
    reach = arena.candle_circle_radius + CANDLE_CLEAR
    cx, cy = candle
    n = poly.shape[0]
    if point_in_convex(cx, cy, poly) or min(
            point_segment_distance(cx, cy, float(poly[i, 0]), float(poly[i, 1]),
                                   float(poly[(i + 1) % n, 0]), float(poly[(i + 1) % n, 1]))
            for i in range(n)) < reach:
        return f"within {reach * 100:.0f} cm of the candle"
    gap = _gap_to_room_walls(poly, room)
    if AGAINST < gap < PASS_CLEAR:
        return (f"{gap * 100:.1f} cm from a wall: stand against it (<= {AGAINST * 100:.0f} cm) "
                f"or leave {PASS_CLEAR * 100:.0f} cm to pass")
    for o in others or []:
        if convex_overlap(poly, o.polygon()):
            return "overlaps another piece"
    return None


def check_furniture(arena: Arena, pieces: list[Piece], candle: tuple[float, float], source: str) -> None:
    if len(pieces) > MAX_PIECES:
        raise FfrInputError(source, "furniture", len(pieces), f"at most {MAX_PIECES} pieces")
    for k, p in enumerate(pieces):
        why = furniture_problem(arena, p, candle, pieces[:k])
        if why:
            raise FfrInputError(source, f"furniture[{k}]", p.as_list(), why)


def draw_furniture(arena: Arena, n: int, candle: tuple[float, float], rng: np.random.Generator,
                   source: str = "furniture") -> list[Piece]:
    """``n`` random pieces, one per room in turn (rooms in file order), each drawn until it may stand."""
    if not 0 <= n <= MAX_PIECES:
        raise FfrInputError(source, "furniture", n, f"expected 0..{MAX_PIECES} pieces")
    pieces: list[Piece] = []
    for k in range(n):
        # its room in turn; a room with no place left (a small room holding the candle) passes the
        # piece on to the next
        for step in range(len(arena.rooms)):
            room = arena.rooms[(k + step) % len(arena.rooms)]
            piece = _place(arena, room, candle, pieces, rng)
            if piece is not None:
                pieces.append(piece)
                break
        else:
            raise FfrInputError(source, "furniture", n, f"no place for piece {k} in any room")
    return pieces


def _place(arena: Arena, room: Room, candle: tuple[float, float], pieces: list[Piece],
           rng: np.random.Generator) -> Piece | None:
    """A random piece where it may stand in ``room`` (None after ``_TRIES`` draws)."""
    lo, hi = room.polygon.min(axis=0), room.polygon.max(axis=0)
    for _ in range(_TRIES):
        w, d = (float(v) for v in rng.uniform(*SIZE_RANGE, size=2))
        heading = 0.5 * math.pi * int(rng.integers(0, 2))
        if rng.uniform() < 0.5:  # against one of the room's walls (a bounding-box side: rooms are rectangles)
            side = int(rng.integers(0, 4))
            ex = (d if heading == 0.0 else w) / 2.0
            ey = (w if heading == 0.0 else d) / 2.0
            x, y = (float(v) for v in rng.uniform(lo + [ex, ey], hi - [ex, ey]))
            gap = 0.01
            x = [lo[0] + ex + gap, hi[0] - ex - gap, x, x][side]
            y = [y, y, lo[1] + ey + gap, hi[1] - ey - gap][side]
        else:
            x, y = (float(v) for v in rng.uniform(lo, hi))
        piece = Piece(float(x), float(y), w, d, heading)
        if furniture_problem(arena, piece, candle, pieces) is None:
            return piece
    return None


def furnish(arena: Arena, pieces: list[Piece]) -> Arena:
    """The arena with each piece as one more wall (rangers, collisions and contacts see it)."""
    if not pieces:
        return arena
    return dataclasses.replace(arena, walls=[*arena.walls, *(p.as_wall(k) for k, p in enumerate(pieces))])
