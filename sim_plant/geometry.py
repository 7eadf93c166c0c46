"""Planar geometry kernels shared by the sensors, collisions and arena checks.

These run inside the lockstep loop hundreds of thousands of times per mission,
so they are numba-compiled loops over flat float64 arrays instead of numpy
expressions: a numpy call costs microseconds of overhead on arrays this small,
a compiled loop over ~60 wall edges costs well under one.

Walls are stored as ``edges``: an (M, 4) array of segments x1, y1, x2, y2 (the
four sides of every wall rectangle), and ``polys``: an (N, 4, 2) array of the
wall rectangles' corners, counter-clockwise.
"""

from __future__ import annotations

import math

import numba as nb
import numpy as np

_EPS = 1e-12


@nb.njit(cache=True, fastmath=False)
def ray_cast(ox: float, oy: float, dx: float, dy: float, edges: np.ndarray, max_range: float) -> float:
    """Distance along the unit ray (ox,oy)+t(dx,dy) to the first edge, or max_range."""
    return ray_cast_first(ox, oy, dx, dy, edges, edges.shape[0], max_range)


@nb.njit(cache=True, fastmath=False, inline="always")
def ray_cast_first(ox: float, oy: float, dx: float, dy: float, edges: np.ndarray, n: int,
                   max_range: float) -> float:
    """``ray_cast`` against the first ``n`` edges only: the GP2D12 beam casts five rays per
    measurement against the edges its wedge kept at the front of a scratch buffer, inlined
    and without a view of the buffer (a call and a view cost about as much as the casts)."""
    best = max_range
    for i in range(n):
        x1 = edges[i, 0]
        y1 = edges[i, 1]
        ex = edges[i, 2] - x1
        ey = edges[i, 3] - y1
        den = dx * ey - dy * ex
        if abs(den) < _EPS:
            continue
        wx = x1 - ox
        wy = y1 - oy
        t = (wx * ey - wy * ex) / den
        if t < 0.0 or t >= best:
            continue
        s = (wx * dy - wy * dx) / den
        if 0.0 <= s <= 1.0:
            best = t
    return best


@nb.njit(cache=True, fastmath=False)
def segment_blocked(ax: float, ay: float, bx: float, by: float, edges: np.ndarray) -> bool:
    """True when the segment a-b crosses any wall edge (line of sight is blocked)."""
    dx = bx - ax
    dy = by - ay
    for i in range(edges.shape[0]):
        x1 = edges[i, 0]
        y1 = edges[i, 1]
        ex = edges[i, 2] - x1
        ey = edges[i, 3] - y1
        den = dx * ey - dy * ex
        if abs(den) < _EPS:
            continue
        wx = x1 - ax
        wy = y1 - ay
        t = (wx * ey - wy * ex) / den
        s = (wx * dy - wy * dx) / den
        if 0.0 <= t <= 1.0 and 0.0 <= s <= 1.0:
            return True
    return False


def edges_soa(edges: np.ndarray) -> np.ndarray:
    """(M, 4) edges -> (4, M) rows x1, y1, ex = x2 - x1, ey = y2 - y1 (the same subtractions
    ``segment_blocked`` makes), contiguous per row: the layout ``segment_blocked_soa`` runs on."""
    e = np.asarray(edges, dtype=np.float64).reshape(-1, 4)
    return np.ascontiguousarray(np.stack([e[:, 0], e[:, 1], e[:, 2] - e[:, 0], e[:, 3] - e[:, 1]]))


@nb.njit(cache=True, fastmath=False, error_model="numpy")
def segment_blocked_soa(ax: float, ay: float, bx: float, by: float, soa: np.ndarray) -> bool:
    """``segment_blocked`` on ``edges_soa``'s layout, the same answer (tested): every edge's
    test is the same arithmetic, evaluated without branches (a division by a zero ``den`` gives
    inf or nan under error_model="numpy", and the ``abs(den) >= eps`` term masks it), so the
    compiler runs four edges at a time; the result is an OR, which no order changes. The flame
    sensors' line of sight and wall reflections call this every tick (~3x faster than the
    branchy loop on 56 edges)."""
    dx = bx - ax
    dy = by - ay
    x1s = soa[0]
    y1s = soa[1]
    exs = soa[2]
    eys = soa[3]
    hit = False
    for i in range(x1s.shape[0]):
        ex = exs[i]
        ey = eys[i]
        den = dx * ey - dy * ex
        wx = x1s[i] - ax
        wy = y1s[i] - ay
        t = (wx * ey - wy * ex) / den
        s = (wx * dy - wy * dx) / den
        hit |= (abs(den) >= _EPS) & (t >= 0.0) & (t <= 1.0) & (s >= 0.0) & (s <= 1.0)
    return hit


@nb.njit(cache=True, fastmath=False)
def point_segment_distance(px: float, py: float, x1: float, y1: float, x2: float, y2: float) -> float:
    ex = x2 - x1
    ey = y2 - y1
    l2 = ex * ex + ey * ey
    t = 0.0
    if l2 > _EPS:
        t = ((px - x1) * ex + (py - y1) * ey) / l2
        t = min(1.0, max(0.0, t))
    qx = x1 + t * ex - px
    qy = y1 + t * ey - py
    return math.sqrt(qx * qx + qy * qy)


@nb.njit(cache=True, fastmath=False)
def point_in_convex(px: float, py: float, poly: np.ndarray) -> bool:
    """Point inside (or on) a counter-clockwise convex polygon."""
    n = poly.shape[0]
    for i in range(n):
        x1 = poly[i, 0]
        y1 = poly[i, 1]
        j = i + 1 if i + 1 < n else 0  # (i + 1) % n without the integer division (hot path)
        x2 = poly[j, 0]
        y2 = poly[j, 1]
        if (x2 - x1) * (py - y1) - (y2 - y1) * (px - x1) < 0.0:
            return False
    return True


@nb.njit(cache=True, fastmath=False)
def first_open_point(xs: np.ndarray, ys: np.ndarray, polys: np.ndarray, ax: float, ay: float, bx: float,
                     by: float, reach: float) -> int:
    """The index of the first point (xs[k], ys[k]) inside none of the convex polygons ``polys`` and
    farther than ``reach`` from the segment a-b, or -1: an arena's check that a room is closed
    (sim_plant/arena.py, ``_room_gap``) asks this of a few hundred points per room side, for every
    jittered arena a sweep draws (its cost: ``python -m harness.bench arena``)."""
    for k in range(xs.shape[0]):
        inside = False
        for w in range(polys.shape[0]):
            if point_in_convex(xs[k], ys[k], polys[w]):
                inside = True
                break
        if not inside and point_segment_distance(xs[k], ys[k], ax, ay, bx, by) > reach:
            return k
    return -1


@nb.njit(cache=True, fastmath=False)
def _segments_distance(a: np.ndarray, i: int, b: np.ndarray, j: int) -> float:
    """Distance between edge i of polygon a and edge j of polygon b (non-crossing)."""
    na = a.shape[0]
    nb_ = b.shape[0]
    ax1 = a[i, 0]
    ay1 = a[i, 1]
    ax2 = a[(i + 1) % na, 0]
    ay2 = a[(i + 1) % na, 1]
    bx1 = b[j, 0]
    by1 = b[j, 1]
    bx2 = b[(j + 1) % nb_, 0]
    by2 = b[(j + 1) % nb_, 1]
    d = point_segment_distance(ax1, ay1, bx1, by1, bx2, by2)
    d = min(d, point_segment_distance(ax2, ay2, bx1, by1, bx2, by2))
    d = min(d, point_segment_distance(bx1, by1, ax1, ay1, ax2, ay2))
    d = min(d, point_segment_distance(bx2, by2, ax1, ay1, ax2, ay2))
    return d


@nb.njit(cache=True, fastmath=False)
def convex_overlap(a: np.ndarray, b: np.ndarray) -> bool:
    """Separating-axis test for two convex polygons (touching counts as overlap)."""
    for poly_idx in range(2):
        p = a if poly_idx == 0 else b
        n = p.shape[0]
        for i in range(n):
            nx = -(p[(i + 1) % n, 1] - p[i, 1])
            ny = p[(i + 1) % n, 0] - p[i, 0]
            amin = 1e300
            amax = -1e300
            for k in range(a.shape[0]):
                v = a[k, 0] * nx + a[k, 1] * ny
                amin = min(amin, v)
                amax = max(amax, v)
            bmin = 1e300
            bmax = -1e300
            for k in range(b.shape[0]):
                v = b[k, 0] * nx + b[k, 1] * ny
                bmin = min(bmin, v)
                bmax = max(bmax, v)
            if amax < bmin or bmax < amin:
                return False
    return True


@nb.njit(cache=True, fastmath=False)
def clearance(poly: np.ndarray, wall_polys: np.ndarray, wall_bbox: np.ndarray, cutoff: float) -> float:
    """Smallest distance from a convex polygon to any wall rectangle; 0 when touching.

    Walls whose bounding box is farther than ``cutoff`` are skipped; the result
    is then at most ``cutoff``.
    """
    xmin = 1e300
    xmax = -1e300
    ymin = 1e300
    ymax = -1e300
    for k in range(poly.shape[0]):
        xmin = min(xmin, poly[k, 0])
        xmax = max(xmax, poly[k, 0])
        ymin = min(ymin, poly[k, 1])
        ymax = max(ymax, poly[k, 1])
    best = cutoff
    for w in range(wall_polys.shape[0]):
        if (wall_bbox[w, 0] - xmax > best or xmin - wall_bbox[w, 2] > best
                or wall_bbox[w, 1] - ymax > best or ymin - wall_bbox[w, 3] > best):
            continue
        wp = wall_polys[w]
        if convex_overlap(poly, wp):
            return 0.0
        for i in range(poly.shape[0]):
            for j in range(wp.shape[0]):
                d = _segments_distance(poly, i, wp, j)
                if d < best:
                    best = d
    return best


def thick_segment_polygon(a: tuple[float, float], b: tuple[float, float], t: float) -> np.ndarray:
    """Rectangle (4, 2), counter-clockwise, with a-b as its centre line and width t."""
    ax, ay = a
    bx, by = b
    length = math.hypot(bx - ax, by - ay)
    ux, uy = (bx - ax) / length, (by - ay) / length
    nx, ny = -uy * t / 2.0, ux * t / 2.0
    return np.array(
        [[ax - nx, ay - ny], [bx - nx, by - ny], [bx + nx, by + ny], [ax + nx, ay + ny]],
        dtype=np.float64,
    )


def polygon_edges(polys: np.ndarray) -> np.ndarray:
    """(N, k, 2) polygons -> (N*k, 4) edge segments."""
    n, k, _ = polys.shape
    edges = np.empty((n * k, 4), dtype=np.float64)
    for i in range(n):
        for j in range(k):
            edges[i * k + j, 0:2] = polys[i, j]
            edges[i * k + j, 2:4] = polys[i, (j + 1) % k]
    return edges
