"""Robot footprint against the arena walls.

The footprint is the body rectangle (``RobotParams.footprint()``) posed at
(x, y, theta). The response to a wall is kinematic, not a force model: a move
that would make the footprint overlap a wall is cut back to the farthest
collision-free point along that move (bisection on the move fraction to
``CONTACT_TOL``), so the pose never enters a wall. The wheels keep the speed
their own dynamics give them (the tracks slip on the floor), so the encoders
keep counting while the robot pushes.

A contact episode starts when a move is blocked and ends when the footprint,
grown by ``CONTACT_RELEASE`` on every side, is clear of all walls. The
hysteresis keeps one sustained push, or a robot that rests against a wall
and pushes again, to one counted contact.
"""

from __future__ import annotations

import math

import numba as nb
import numpy as np

from sim_plant.drivetrain import P_FRONT, P_LEFT, P_REAR, P_RIGHT, P_RMAX, arc_step
from sim_plant.geometry import convex_overlap

CONTACT_TOL = 1e-6      # m, how close a blocked move gets to the wall
CONTACT_RELEASE = 1e-3  # m, gap that ends a contact episode
_MAX_BISECT = 40


@nb.njit(cache=True)
def footprint_into(poly: np.ndarray, x: float, y: float, th: float, P: np.ndarray,
                   grow: float) -> None:
    """Write the footprint corners (counter-clockwise, world frame) into poly (4, 2)."""
    c = math.cos(th)
    s = math.sin(th)
    f = P[P_FRONT] + grow
    r = P[P_REAR] - grow
    lf = P[P_LEFT] + grow
    rt = P[P_RIGHT] - grow
    # Body-frame corners: front-right, front-left, rear-left, rear-right.
    poly[0, 0] = x + c * f - s * rt
    poly[0, 1] = y + s * f + c * rt
    poly[1, 0] = x + c * f - s * lf
    poly[1, 1] = y + s * f + c * lf
    poly[2, 0] = x + c * r - s * lf
    poly[2, 1] = y + s * r + c * lf
    poly[3, 0] = x + c * r - s * rt
    poly[3, 1] = y + s * r + c * rt


@nb.njit(cache=True)
def first_wall_hit(poly: np.ndarray, wall_polys: np.ndarray, wall_bbox: np.ndarray) -> int:
    """Index of the first wall the polygon overlaps (touching counts), or -1."""
    xmin = min(min(poly[0, 0], poly[1, 0]), min(poly[2, 0], poly[3, 0]))
    xmax = max(max(poly[0, 0], poly[1, 0]), max(poly[2, 0], poly[3, 0]))
    ymin = min(min(poly[0, 1], poly[1, 1]), min(poly[2, 1], poly[3, 1]))
    ymax = max(max(poly[0, 1], poly[1, 1]), max(poly[2, 1], poly[3, 1]))
    for w in range(wall_polys.shape[0]):
        if (wall_bbox[w, 0] > xmax or wall_bbox[w, 2] < xmin
                or wall_bbox[w, 1] > ymax or wall_bbox[w, 3] < ymin):
            continue
        if convex_overlap(poly, wall_polys[w]):
            return w
    return -1


@nb.njit(cache=True)
def limit_move(poly: np.ndarray, x: float, y: float, th: float, ds: float, dth: float,
               P: np.ndarray, wall_polys: np.ndarray,
               wall_bbox: np.ndarray) -> tuple[float, float, float, float]:
    """Farthest pose along the arc (ds, dth) from a collision-free (x, y, th).

    Returns (x, y, th, fraction of the move made); fraction < 1 means the move
    was blocked by a wall. ``poly`` is scratch and is left undefined.
    """
    nx, ny, nth = arc_step(x, y, th, ds, dth)
    footprint_into(poly, nx, ny, nth, P, 0.0)
    if first_wall_hit(poly, wall_polys, wall_bbox) < 0:
        return nx, ny, nth, 1.0
    # Largest corner displacement of the whole move bounds the gap left by the bisection.
    reach = abs(ds) + abs(dth) * P[P_RMAX]
    lo = 0.0
    hi = 1.0
    # A robot already pressed against the wall cannot make even a CONTACT_TOL
    # move: find that out with one test instead of a full bisection.
    first = CONTACT_TOL / reach
    if first < 1.0:
        mx, my, mth = arc_step(x, y, th, ds * first, dth * first)
        footprint_into(poly, mx, my, mth, P, 0.0)
        if first_wall_hit(poly, wall_polys, wall_bbox) >= 0:
            return x, y, th, 0.0
        lo = first
    for _ in range(_MAX_BISECT):
        if (hi - lo) * reach <= CONTACT_TOL:
            break
        mid = 0.5 * (lo + hi)
        mx, my, mth = arc_step(x, y, th, ds * mid, dth * mid)
        footprint_into(poly, mx, my, mth, P, 0.0)
        if first_wall_hit(poly, wall_polys, wall_bbox) < 0:
            lo = mid
        else:
            hi = mid
    if lo == 0.0:
        return x, y, th, 0.0
    mx, my, mth = arc_step(x, y, th, ds * lo, dth * lo)
    return mx, my, mth, lo


@nb.njit(cache=True)
def released(poly: np.ndarray, x: float, y: float, th: float, P: np.ndarray,
             wall_polys: np.ndarray, wall_bbox: np.ndarray) -> bool:
    """True when the footprint grown by CONTACT_RELEASE touches no wall (episode over)."""
    footprint_into(poly, x, y, th, P, CONTACT_RELEASE)
    return first_wall_hit(poly, wall_polys, wall_bbox) < 0


def footprint_polygon(x: float, y: float, th: float, P: np.ndarray) -> np.ndarray:
    """The footprint at a pose as a new (4, 2) array (world frame, counter-clockwise)."""
    poly = np.empty((4, 2))
    footprint_into(poly, x, y, th, P, 0.0)
    return poly
