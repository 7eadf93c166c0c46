"""Robot footprint against the arena walls.

The footprint is the body rectangle (``RobotParams.footprint()``) posed at
(x, y, theta). The response to a wall is kinematic, not a force model: a move
that would make the footprint overlap a wall is cut back to the farthest
collision-free point along that move (bisection on the move fraction to
``CONTACT_TOL``), so the pose never enters a wall. The wheels keep the speed
their own dynamics give them (the tracks slip on the floor), so the encoders
keep counting while the robot pushes.

With friction contact on (``slip.wall_mu`` >= 0 in the robot file; off by
default, when a blocked move simply ends at the wall) the rest of a blocked
move slides along the wall (``slide_along``): its translation's component
into the wall is taken by the wall, its tangential component is kept less
wall_mu times the normal one (Coulomb: the friction force is at most mu
times the normal force, so a push at angle beta to the wall slides
d (cos beta - mu sin beta), nothing once tan beta >= 1/mu), and the rest of
its rotation is kept where the walls allow it.

A contact episode starts when a move is blocked and ends when the footprint,
grown by ``CONTACT_RELEASE`` on every side, is clear of all walls. The
hysteresis keeps one sustained push, or a robot that rests against a wall
and pushes again, to one counted contact.
"""

from __future__ import annotations

import math

import numba as nb
import numpy as np

from sim_plant.drivetrain import P_FRONT, P_LEFT, P_REAR, P_RIGHT, P_RMAX, P_WALL_MU, arc_step
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


@nb.njit(cache=True)
def contact_normal(poly: np.ndarray, wall: np.ndarray) -> tuple[float, float]:
    """Unit normal of the contact, pointing from the wall towards the robot: the separating axis
    (edge normal of either convex polygon) with the largest gap between them."""
    best = -1e300
    bx = 0.0
    by = 0.0
    for poly_idx in range(2):
        p = poly if poly_idx == 0 else wall
        o = wall if poly_idx == 0 else poly
        n = p.shape[0]
        cx = 0.0
        cy = 0.0
        for k in range(n):
            cx += p[k, 0] / n
            cy += p[k, 1] / n
        for i in range(n):
            ex = p[(i + 1) % n, 0] - p[i, 0]
            ey = p[(i + 1) % n, 1] - p[i, 1]
            ln = math.hypot(ex, ey)
            if ln == 0.0:
                continue
            nx = ey / ln
            ny = -ex / ln
            if (p[i, 0] - cx) * nx + (p[i, 1] - cy) * ny < 0.0:  # make it point out of p
                nx = -nx
                ny = -ny
            pmax = -1e300
            for k in range(n):
                pmax = max(pmax, p[k, 0] * nx + p[k, 1] * ny)
            omin = 1e300
            for k in range(o.shape[0]):
                omin = min(omin, o[k, 0] * nx + o[k, 1] * ny)
            gap = omin - pmax
            if gap > best:
                best = gap
                # out of the wall: towards the robot; out of the robot: towards the wall
                bx, by = (-nx, -ny) if poly_idx == 0 else (nx, ny)
    return bx, by


@nb.njit(cache=True)
def limit_shift(poly: np.ndarray, x: float, y: float, th: float, dx: float, dy: float,
                dth: float, P: np.ndarray, wall_polys: np.ndarray,
                wall_bbox: np.ndarray) -> tuple[float, float, float, float]:
    """Farthest collision-free pose along the straight shift (dx, dy) with rotation dth (both in
    proportion) from a collision-free pose; returns (x, y, th, fraction made)."""
    footprint_into(poly, x + dx, y + dy, th + dth, P, 0.0)
    if first_wall_hit(poly, wall_polys, wall_bbox) < 0:
        return x + dx, y + dy, th + dth, 1.0
    reach = math.hypot(dx, dy) + abs(dth) * P[P_RMAX]
    lo = 0.0
    hi = 1.0
    for _ in range(_MAX_BISECT):
        if (hi - lo) * reach <= CONTACT_TOL:
            break
        mid = 0.5 * (lo + hi)
        footprint_into(poly, x + dx * mid, y + dy * mid, th + dth * mid, P, 0.0)
        if first_wall_hit(poly, wall_polys, wall_bbox) < 0:
            lo = mid
        else:
            hi = mid
    return x + dx * lo, y + dy * lo, th + dth * lo, lo


@nb.njit(cache=True)
def slide_along(poly: np.ndarray, cx: float, cy: float, cth: float, x0: float, y0: float,
                th0: float, ds: float, dth: float, P: np.ndarray, wall_polys: np.ndarray,
                wall_bbox: np.ndarray) -> tuple[float, float, float, float]:
    """After ``limit_move`` stopped the move (ds, dth) from (x0, y0, th0) at the contact pose
    (cx, cy, cth): the rest of it with friction against the wall it hit. Returns the pose and the
    distance slid."""
    fx, fy, fth = arc_step(x0, y0, th0, ds, dth)
    footprint_into(poly, fx, fy, fth, P, 0.0)
    w = first_wall_hit(poly, wall_polys, wall_bbox)
    if w < 0:
        return cx, cy, cth, 0.0
    footprint_into(poly, cx, cy, cth, P, 0.0)
    nx, ny = contact_normal(poly, wall_polys[w])
    tx = fx - cx
    ty = fy - cy
    dn = tx * nx + ty * ny
    ux = tx - dn * nx
    uy = ty - dn * ny
    ut = math.hypot(ux, uy)
    sx = 0.0
    sy = 0.0
    if ut > 0.0:
        keep = ut - P[P_WALL_MU] * max(0.0, -dn)
        if keep > 0.0:
            sx = ux / ut * keep
            sy = uy / ut * keep
    rot = fth - cth
    if sx == 0.0 and sy == 0.0 and rot == 0.0:
        return cx, cy, cth, 0.0
    mx, my, mth, f = limit_shift(poly, cx, cy, cth, sx, sy, rot, P, wall_polys, wall_bbox)
    if f == 0.0 and rot != 0.0 and (sx != 0.0 or sy != 0.0):
        mx, my, mth, f = limit_shift(poly, cx, cy, cth, sx, sy, 0.0, P, wall_polys, wall_bbox)
    return mx, my, mth, math.hypot(sx, sy) * f
