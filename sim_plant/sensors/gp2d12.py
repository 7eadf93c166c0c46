"""Sharp GP2D12 infrared ranger: distance -> output voltage, and the ray-cast measurement.

The curve (``distance_to_mv``), in four pieces:

* 10-80 cm: the datasheet's typical table, interpolated by a monotone
  piecewise-cubic Hermite (PCHIP, Fritsch-Carlson slopes) in ``u = 1/(d + 4 cm)``.
  The sensor is close to linear in that variable (the common fit is
  V = 33.2/(d_cm + 4) + 0.015), so the cubic pieces are nearly straight and
  never overshoot; the curve passes exactly through every table point.
* 8-10 cm: the top of the fold-back. A cubic Hermite from the peak
  (8 cm, 2.60 V, slope 0) to the table's 10 cm point with the table curve's
  own slope there, so the curve is smooth at 10 cm. The 2.60 V / 8 cm peak is
  read off the datasheet's graph; the cubic stays monotone for any peak above
  2.57 V (Fritsch-Carlson bound, given the 10 cm slope of -18 V/m).
* 0-8 cm: fold-back. V = V_peak * q * (2 - q), q = d / 8 cm: a parabola from
  0 V at contact up to the peak with zero slope there. Below 10 cm the output
  is thus ambiguous with a farther wall (5 cm reads like ~11.5 cm), as on the
  real part.
* beyond 80 cm: V = V_floor + (V_80 - V_floor) * exp(-(d - 80 cm) / L), with
  the floor at 0.30 V (the "no object" reading, inside the datasheet's
  0.25-0.55 V band at 80 cm) and L chosen so the slope is continuous at 80 cm
  (L ~ 0.21 m, so 1.0 m reads ~0.345 V and 1.5 m ~0.304 V).

The measurement: one ray from the sensor's pose to the nearest wall surface,
made once per measurement period (38.3 ms) and held in between.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numba as nb
import numpy as np

from sim_plant.geometry import point_in_convex, ray_cast, ray_cast_first

# Datasheet typical curve (distance m, output V).
DATASHEET_TABLE: tuple[tuple[float, float], ...] = (
    (0.10, 2.45), (0.12, 2.125), (0.14, 1.86), (0.16, 1.66), (0.18, 1.52),
    (0.20, 1.38), (0.25, 1.14), (0.30, 0.975), (0.35, 0.85), (0.40, 0.76),
    (0.45, 0.68), (0.50, 0.62), (0.60, 0.54), (0.70, 0.48), (0.80, 0.42),
)
D_NEAR = 0.10  # m, start of the datasheet's range
D_FAR = 0.80  # m, end of the datasheet's range
D_PEAK = 0.08  # m, where the fold-back peaks
V_PEAK = 2.60  # V
V_FLOOR = 0.30  # V, reading with no object in range
U_OFFSET = 0.04  # m, the k in u = 1/(d + k)
MEASUREMENT_PERIOD = 0.0383  # s, datasheet typical
IR_MV_MAX = 5000  # output clipped to the 5 V supply


def _pchip_slopes(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """Shape-preserving node slopes (Fritsch-Carlson, weighted harmonic mean)."""
    h = np.diff(x)
    delta = np.diff(y) / h
    n = x.size
    m = np.zeros(n)
    for k in range(1, n - 1):
        if delta[k - 1] * delta[k] > 0.0:
            w1 = 2.0 * h[k] + h[k - 1]
            w2 = h[k] + 2.0 * h[k - 1]
            m[k] = (w1 + w2) / (w1 / delta[k - 1] + w2 / delta[k])

    def end(h0: float, h1: float, d0: float, d1: float) -> float:
        s = ((2.0 * h0 + h1) * d0 - h0 * d1) / (h0 + h1)
        if s * d0 <= 0.0:
            return 0.0
        if d0 * d1 <= 0.0 and abs(s) > 3.0 * abs(d0):
            return 3.0 * d0
        return s

    m[0] = end(h[0], h[1], delta[0], delta[1])
    m[-1] = end(h[-1], h[-2], delta[-1], delta[-2])
    return m


# Knots in u, ascending (so from 80 cm down to 10 cm).
_D = np.array([p[0] for p in DATASHEET_TABLE])[::-1].copy()
_U = 1.0 / (_D + U_OFFSET)
_V = np.array([p[1] for p in DATASHEET_TABLE])[::-1].copy()
_M = _pchip_slopes(_U, _V)  # dV/du at each knot
# dV/dd at the ends of the table (du/dd = -u^2).
_SLOPE_NEAR = float(_M[-1] * -(_U[-1] ** 2))
_SLOPE_FAR = float(_M[0] * -(_U[0] ** 2))
_V_NEAR = float(_V[-1])
_V_FAR = float(_V[0])
TAIL_LENGTH = (_V_FAR - V_FLOOR) / -_SLOPE_FAR  # m


@nb.njit(cache=True)
def mv_of_distance(d: float) -> float:
    """Scalar GP2D12 output in mV for a wall at distance d (m); see the module docstring."""
    if d <= 0.0:
        return 0.0
    if d < D_PEAK:
        q = d / D_PEAK
        return 1000.0 * V_PEAK * q * (2.0 - q)
    if d < D_NEAR:
        h = D_NEAR - D_PEAK
        s = (d - D_PEAK) / h
        s2 = s * s
        s3 = s2 * s
        v = ((2.0 * s3 - 3.0 * s2 + 1.0) * V_PEAK + (-2.0 * s3 + 3.0 * s2) * _V_NEAR
             + (s3 - s2) * h * _SLOPE_NEAR)
        return 1000.0 * v
    if d > D_FAR:
        return 1000.0 * (V_FLOOR + (_V_FAR - V_FLOOR) * math.exp(-(d - D_FAR) / TAIL_LENGTH))
    u = 1.0 / (d + U_OFFSET)
    k = 0
    n = _U.shape[0]
    while k < n - 2 and u > _U[k + 1]:
        k += 1
    h = _U[k + 1] - _U[k]
    s = (u - _U[k]) / h
    s2 = s * s
    s3 = s2 * s
    v = ((2.0 * s3 - 3.0 * s2 + 1.0) * _V[k] + (s3 - 2.0 * s2 + s) * h * _M[k]
         + (-2.0 * s3 + 3.0 * s2) * _V[k + 1] + (s3 - s2) * h * _M[k + 1])
    return 1000.0 * v


@nb.njit(cache=True)
def _mv_array(d: np.ndarray) -> np.ndarray:
    out = np.empty(d.shape[0])
    for i in range(d.shape[0]):
        out[i] = mv_of_distance(d[i])
    return out


def distance_to_mv(d_m: float | np.ndarray) -> float | np.ndarray:
    """GP2D12 typical output (mV, float) for wall distance(s) in metres; any array shape."""
    arr = np.asarray(d_m, dtype=np.float64)
    out = _mv_array(np.ascontiguousarray(arr).ravel()).reshape(arr.shape)
    return float(out) if arr.ndim == 0 else out


@dataclass(frozen=True)
class Gp2d12Model:
    """Timing and range of the rangers.

    ``period``: one measurement every ``period`` s, output held in between.
    ``stagger``: the five rangers free-run unsynchronised, so ranger i's
    measurement instants are t0 + i*period/5 + k*period (t0 = the first
    ``sample`` call, when every ranger reports its power-up measurement);
    with ``stagger=False`` all measure together at t0 + k*period.
    ``max_range``: ray length; beyond the arena's diagonal means "no wall".
    """

    period: float = MEASUREMENT_PERIOD
    stagger: bool = True
    max_range: float = 4.0

    def phases(self, n: int) -> list[float]:
        return [i * self.period / n if self.stagger else 0.0 for i in range(n)]


@nb.njit(cache=True)
def ir_ray_distance(px: float, py: float, dx: float, dy: float, edges: np.ndarray,
                    wall_polys: np.ndarray, max_range: float) -> float:
    """Distance from a ranger at (px, py) looking along unit (dx, dy) to the nearest wall.

    A ranger pushed into a wall (a collision) sees the wall at 0 m.
    """
    for w in range(wall_polys.shape[0]):
        if point_in_convex(px, py, wall_polys[w]):
            return 0.0
    return ray_cast(px, py, dx, dy, edges, max_range)


@nb.njit(cache=True)
def ray_circle(px: float, py: float, dx: float, dy: float, cx: float, cy: float, r: float,
               max_range: float) -> float:
    """Distance along the unit ray (px, py) + t (dx, dy) to a circle of radius r at (cx, cy),
    or max_range when it misses (a ranger inside the circle sees it at 0 m)."""
    wx = cx - px
    wy = cy - py
    c2 = wx * wx + wy * wy - r * r
    if c2 <= 0.0:
        return 0.0
    b = wx * dx + wy * dy
    if b <= 0.0:
        return max_range
    disc = b * b - c2
    if disc < 0.0:
        return max_range
    t = b - math.sqrt(disc)
    return t if t < max_range else max_range


_WEDGE_MARGIN = 1e-9  # m^2 (a cross product): an edge this close to the beam's edge is kept


def beam_table_py(half: float, n_rays: int) -> np.ndarray:
    """The beam's rotations, computed once per suite instead of once per measurement: row 0
    cos, sin of ``half``; row 1 + j cos, sin of ray j's offset from the aim. The same
    expressions ``beam_distance`` evaluated per ray, so the same numbers (bit for bit).
    ``half`` <= 0 or ``n_rays`` <= 1: one ray, the table has only row 0.

    Plain Python for the sensor suite (no compiled kernel to load at start-up: each costs
    ~10 ms, docs/architecture.md); ``beam_table`` is the same function compiled, for kernels."""
    n = 1 if half <= 0.0 or n_rays <= 1 else n_rays
    tab = np.empty((n + 1, 2))
    tab[0, 0] = math.cos(half)
    tab[0, 1] = math.sin(half)
    tab[1, 0] = 1.0  # one ray: no rotation (row 1 is not read)
    tab[1, 1] = 0.0
    if n > 1:
        for j in range(n):
            o = -half + 2.0 * half * j / (n - 1)
            tab[1 + j, 0] = math.cos(o)
            tab[1 + j, 1] = math.sin(o)
    return tab


beam_table = nb.njit(cache=True)(beam_table_py)


def wedge_soa(edges: np.ndarray) -> np.ndarray:
    """(M, 4) edges -> (4, M) rows x1, y1, x2, y2, contiguous per row: the layout ``_wedge_into``
    reads (the very doubles of ``edges``, so its tests are the same arithmetic)."""
    return np.ascontiguousarray(np.asarray(edges, dtype=np.float64).reshape(-1, 4).T)


@nb.njit(cache=True)
def _wedge_into(px: float, py: float, dx0: float, dy0: float, ch: float, sh: float,
                edges: np.ndarray, wsoa: np.ndarray, keep: np.ndarray, out: np.ndarray) -> int:
    """The wall edges a ray within +-half (< 90 degrees; ``ch``, ``sh`` its cos and sin) of
    the unit aim (dx0, dy0) from (px, py) can hit, copied in order into ``out[:n]``; returns n.
    An edge is left out only when both its ends are behind the ranger, or both beyond the
    same side of the beam (the beam is convex, so the edge cannot cross it). Casting the
    beam's rays against these only gives the same distances, for less work.

    ``wsoa``: the same edges as ``wedge_soa`` lays them out; ``keep``: scratch of one byte per
    edge. The tests run without branches over the rows (the compiler takes four edges at a
    time: ~1.7x faster than testing edge by edge, make bench), then the kept edges are copied."""
    lx = dx0 * ch - dy0 * sh  # the beam's left (counter-clockwise) boundary
    ly = dx0 * sh + dy0 * ch
    rx = dx0 * ch + dy0 * sh  # and its right one
    ry = -dx0 * sh + dy0 * ch
    m = wsoa.shape[1]
    for i in range(m):  # wsoa[r, i], not row views: a view costs a reference count per call
        ax = wsoa[0, i] - px
        ay = wsoa[1, i] - py
        bx = wsoa[2, i] - px
        by = wsoa[3, i] - py
        behind = (ax * dx0 + ay * dy0 < -_WEDGE_MARGIN) & (bx * dx0 + by * dy0 < -_WEDGE_MARGIN)
        left = (lx * ay - ly * ax > _WEDGE_MARGIN) & (lx * by - ly * bx > _WEDGE_MARGIN)
        right = (rx * ay - ry * ax < -_WEDGE_MARGIN) & (rx * by - ry * bx < -_WEDGE_MARGIN)
        keep[i] = not (behind | left | right)
    n = 0
    for i in range(m):
        if keep[i]:
            out[n, 0] = edges[i, 0]
            out[n, 1] = edges[i, 1]
            out[n, 2] = edges[i, 2]
            out[n, 3] = edges[i, 3]
            n += 1
    return n


@nb.njit(cache=True)
def _edges_in_wedge(px: float, py: float, dx0: float, dy0: float, half: float,
                    edges: np.ndarray) -> np.ndarray:
    """``_wedge_into`` as a new array (tests and reports; the sensors reuse a scratch buffer)."""
    out = np.empty((edges.shape[0], 4))
    wsoa = np.ascontiguousarray(edges.T)
    keep = np.empty(edges.shape[0], dtype=np.uint8)
    n = _wedge_into(px, py, dx0, dy0, math.cos(half), math.sin(half), edges, wsoa, keep, out)
    return out[:n].copy()


@nb.njit(cache=True)
def beam_distance_tab(px: float, py: float, dx0: float, dy0: float, tab: np.ndarray,
                      edges: np.ndarray, wall_polys: np.ndarray, scratch: np.ndarray,
                      wsoa: np.ndarray, keep: np.ndarray,
                      max_range: float, cx: float, cy: float, obs_r: float) -> float:
    """``beam_distance`` with the beam's rotations from ``beam_table`` (tab.shape[0] - 1 rays)
    and the edges inside the wedge collected into ``scratch`` (at least edges' shape; ``wsoa``
    and ``keep`` as ``_wedge_into`` takes them): what the sensors call per measurement, with no
    trigonometry of the beam and no allocation."""
    for w in range(wall_polys.shape[0]):
        if point_in_convex(px, py, wall_polys[w]):
            return 0.0
    n_rays = tab.shape[0] - 1
    hits = edges  # the edges the rays are cast against: the first m rows
    m = edges.shape[0]
    if n_rays > 1:
        m = _wedge_into(px, py, dx0, dy0, tab[0, 0], tab[0, 1], edges, wsoa, keep, scratch)
        hits = scratch
    num = 0.0
    den = 0.0
    for j in range(n_rays):
        dx = dx0
        dy = dy0
        if n_rays > 1:
            co = tab[1 + j, 0]
            so = tab[1 + j, 1]
            dx = dx0 * co - dy0 * so
            dy = dx0 * so + dy0 * co
        d = ray_cast_first(px, py, dx, dy, hits, m, max_range)
        if obs_r > 0.0:
            d = min(d, ray_circle(px, py, dx, dy, cx, cy, obs_r, max_range))
        if d <= 0.0:
            return 0.0
        if n_rays == 1:
            return d
        if d >= max_range:
            continue
        w2 = 1.0 / (d * d)
        den += w2
        num += w2 / d
    if den == 0.0:
        return max_range
    return den / num


@nb.njit(cache=True)
def beam_distance(px: float, py: float, dx0: float, dy0: float, half: float, n_rays: int,
                  edges: np.ndarray,
                  wall_polys: np.ndarray, max_range: float, cx: float, cy: float,
                  obs_r: float) -> float:
    """The distance a ranger at (px, py) aimed along unit (dx0, dy0) reports.

    ``half`` = 0 or ``n_rays`` = 1: one ray (``ir_ray_distance``). Otherwise
    ``n_rays`` rays evenly over +-``half`` (rad) about the aim, each of equal power;
    a ray hitting at d_j returns light ~ 1/d_j^2 (a diffuse wall, a small
    receiving lens) whose image falls on the detector at a place ~ 1/d_j
    (triangulation), and the detector reports the intensity-weighted centroid:
    1/d = sum(d_j^-3) / sum(d_j^-2). A ray that hits nothing within
    ``max_range`` returns no light (all miss: ``max_range``). With ``obs_r`` > 0
    a disc (the candle's base) of that radius at (cx, cy) is a target too.
    (The sensor suite calls ``beam_distance_tab`` with the table and scratch made once.)
    """
    return beam_distance_tab(px, py, dx0, dy0, beam_table(half, n_rays), edges, wall_polys,
                             np.empty((edges.shape[0], 4)), np.ascontiguousarray(edges.T),
                             np.empty(edges.shape[0], dtype=np.uint8), max_range, cx, cy, obs_r)
