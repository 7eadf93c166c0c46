"""Arena jitter: every wall line and door edge of an arena moved within a tolerance.

The contest's rules call their drawings "general aids": real arenas differ
from the plan by a few centimetres. ``jitter_arena`` draws one such arena from
a ``numpy.random.Generator`` (docs/arena.md, "Arena jitter"):

- Each *wall line* (the centre line shared by the walls at one x, or at one
  y) moves along its normal by its own uniform draw in [-tol, +tol]; the wall
  moves rigidly with it (its thickness and faces come along), and so do the
  room and hallway edges on its faces.
- Each *free wall end* (a wall end not resting on a crossing wall: a door's
  edge) moves along its wall by its own draw in [-tol, +tol], so doors move
  and change width.
- The outer left and bottom walls stay put (the origin is the arena's
  bottom-left outer corner); the outer right and top walls move, so the outer
  square's size varies by up to ±tol.
- Lines closer together than ``MERGE_GAP`` (12 cm; the 2004 map's bottom
  walls of two rooms 2 cm apart in y, or two door edges) move as one.
- Everything between two such lines (home circle, candle spots, hallway
  corners) moves by the linear blend of their shifts: a separable, monotone,
  piecewise-linear warp x -> X(x), y -> Y(y). Rectangles stay rectangles,
  walls that met still meet, no point moves more than ``tol``.

Only arenas whose walls are all axis-parallel (both shipped arenas) can be
jittered. The result is checked with ``validate_arena`` like a loaded file.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from sim_plant.arena import Arena, Hallway, Room, Wall, _ccw, validate_arena
from sim_plant.errors import FfrInputError

MAX_JITTER = 0.05  # m: the stress level; beyond it interior lines could cross
MERGE_GAP = 0.12   # m: lines closer than this (> 2 * MAX_JITTER) move as one, so no two can cross
_EPS = 1e-9


@dataclass(frozen=True)
class Knot:
    """A line of the arena at ``c`` whose band ``c ± h`` moves rigidly by ``shift``."""

    c: float
    h: float
    shift: float


class AxisWarp:
    """x -> x + shift(x): rigid in each knot's band, linear between bands, constant beyond."""

    def __init__(self, knots: list[Knot]) -> None:
        self.knots = sorted(knots, key=lambda k: k.c)

    def shift(self, x: float) -> float:
        ks = self.knots
        if not ks:
            return 0.0
        for k in ks:
            if abs(x - k.c) <= k.h + _EPS:
                return k.shift
        if x <= ks[0].c:
            return ks[0].shift
        for a, b in zip(ks, ks[1:], strict=False):
            lo, hi = a.c + a.h, b.c - b.h
            if lo < x < hi:
                f = (x - lo) / (hi - lo)
                return a.shift + (b.shift - a.shift) * f
        return ks[-1].shift

    def __call__(self, x: float) -> float:
        return x + self.shift(x)


@dataclass(frozen=True)
class Warp:
    """The separable warp of a jittered arena; ``point`` maps a nominal point into it."""

    x: AxisWarp
    y: AxisWarp

    def point(self, p: tuple[float, float]) -> tuple[float, float]:
        return self.x(float(p[0])), self.y(float(p[1]))


def _axis_knots(arena: Arena, axis: int) -> list[tuple[float, float, bool]]:
    """(centre, half band, fixed) of every wall line across ``axis`` and every free wall end along it."""
    lines: list[tuple[float, float, bool]] = []
    for w in arena.walls:
        if abs(w.a[axis] - w.b[axis]) <= _EPS:  # the wall runs across this axis: a wall line
            c = w.a[axis]
            fixed = c - w.t / 2.0 <= _EPS  # the outer left / bottom wall: the origin stays put
            for i, (c0, h0, f0) in enumerate(lines):
                if abs(c0 - c) <= _EPS:
                    lines[i] = (c0, max(h0, w.t / 2.0), f0 or fixed)
                    break
            else:
                lines.append((c, w.t / 2.0, fixed))
    ends: list[tuple[float, float, bool]] = []
    for w in arena.walls:
        if abs(w.a[axis] - w.b[axis]) <= _EPS:
            continue
        for e in (w.a[axis], w.b[axis]):
            if any(abs(e - c) <= h + _EPS for c, h, _ in lines) or any(abs(e - c) <= _EPS for c, _, _ in ends):
                continue
            if e <= _EPS or e >= arena.size[axis] - _EPS:
                continue
            ends.append((e, 0.0, False))
    merged: list[tuple[float, float, bool]] = []  # (lo, hi, fixed) bands
    for c, h, fixed in sorted(lines + ends):
        lo, hi = c - h, c + h
        if merged and lo - merged[-1][1] < MERGE_GAP:
            plo, phi, pf = merged[-1]
            merged[-1] = (plo, max(phi, hi), pf or fixed)
        else:
            merged.append((lo, hi, fixed))
    return [((lo + hi) / 2.0, (hi - lo) / 2.0, fixed) for lo, hi, fixed in merged]


def _check_axis_parallel(arena: Arena) -> None:
    for k, w in enumerate(arena.walls):
        if abs(w.a[0] - w.b[0]) > _EPS and abs(w.a[1] - w.b[1]) > _EPS:
            raise FfrInputError(arena.source, f"walls[{k}]", w.name,
                                "arena jitter needs axis-parallel walls (this one is slanted)")


def check_jitter(arena: Arena, tol: float, source: str = "arena_jitter", field: str = "arena_jitter") -> None:
    """Raise FfrInputError unless ``tol`` can jitter this arena (0 .. MAX_JITTER, lines far enough apart)."""
    if isinstance(tol, bool) or not isinstance(tol, int | float) or not math.isfinite(tol) \
            or not 0.0 <= tol <= MAX_JITTER:
        raise FfrInputError(source, field, tol, f"must be a number of metres in 0 .. {MAX_JITTER}")
    if tol > 0.0:
        _check_axis_parallel(arena)


def draw_warp(arena: Arena, tol: float, rng: np.random.Generator) -> Warp:
    """One draw of every line's and free end's shift (x lines, then y lines, in increasing order)."""
    axes = []
    for axis in (0, 1):
        knots = []
        for c, h, fixed in _axis_knots(arena, axis):
            s = float(rng.uniform(-tol, tol))  # drawn for every knot, fixed or not: the stream's use is fixed
            knots.append(Knot(c, h, 0.0 if fixed else s))
        axes.append(AxisWarp(knots))
    return Warp(axes[0], axes[1])


def apply_warp(arena: Arena, warp: Warp, tol: float) -> Arena:
    """The arena with every coordinate mapped through ``warp`` (wall thicknesses and radii kept)."""
    def pt(p: tuple[float, float]) -> tuple[float, float]:
        return warp.point(p)

    def poly(a: np.ndarray) -> np.ndarray:
        return _ccw(np.array([pt((float(x), float(y))) for x, y in a], dtype=np.float64))

    walls = [Wall(w.name, pt(w.a), pt(w.b), w.t) for w in arena.walls]
    rooms = [Room(r.id, r.name, poly(r.polygon), (pt(r.door[0]), pt(r.door[1])), pt(r.default_candle))
             for r in arena.rooms]
    halls = [Hallway(h.name, poly(h.polygon)) for h in arena.hallways]
    size = (warp.x(arena.size[0]), warp.y(arena.size[1]))
    out = Arena(
        name=arena.name, source=arena.source, size=size, wall_height=arena.wall_height,
        line_width=arena.line_width, candle_circle_radius=arena.candle_circle_radius,
        candle_min_depth=arena.candle_min_depth, candle_radius=arena.candle_radius,
        flame_height=arena.flame_height, home_center=pt(arena.home_center), home_radius=arena.home_radius,
        walls=walls, rooms=rooms, hallways=halls, placement=arena.placement, jitter=tol,
        home_heading=arena.home_heading, candle_base_radius=arena.candle_base_radius,
    )
    return out


def jitter_arena(arena: Arena, tol: float, rng: np.random.Generator,
                 candle: tuple[float, float] | None = None, tries: int = 200) -> tuple[Arena, Warp]:
    """A jittered copy of ``arena`` (and its warp), drawn from ``rng``; ``tol`` 0 returns the arena itself.

    A draw is kept when the jittered arena validates and, if ``candle`` (a
    nominal position) is given, the candle carried by the warp is legal in it;
    otherwise the next draw of the same stream is tried (deterministic). No
    legal draw in ``tries``: FfrInputError.
    """
    check_jitter(arena, tol)
    if tol == 0.0:
        ident = Warp(AxisWarp([]), AxisWarp([]))
        return arena, ident
    last: FfrInputError | None = None
    for _ in range(tries):
        warp = draw_warp(arena, tol, rng)
        out = apply_warp(arena, warp, tol)
        try:
            validate_arena(out)
            if candle is not None:
                out.check_candle(*warp.point(candle), source=f"{arena.source} jittered by ±{tol:g} m")
        except FfrInputError as exc:
            last = exc
            continue
        return out, warp
    raise FfrInputError(arena.source, "arena_jitter", tol,
                        f"no legal jittered arena in {tries} draws (last: {last.why if last else '?'})")
