"""Flame sensors: the paper's intensity model (eqs. 8, 9, Fig. 8) and the ADC output.

I = 0.0125 * K(dθ) / R^2 foot-candles (eq. 9), where

* R (eq. 8) is the distance from the sensor (not the robot's centre) to the
  flame. We use the 3-D distance, including the small height difference
  between sensor and flame, and clamp it to ``r_min`` so a sensor touching
  the candle does not divide by ~0 (the ADC saturates long before).
* K(dθ) is the angular coefficient of the paper's Fig. 8: 1 on the sensor's
  axis, falling smoothly to 0 at ±``k_half_width_deg`` (60°). We use a raised
  cosine, K = (1 + cos(π dθ / 60°)) / 2: it has zero slope on the axis and at
  the edge (no kinks for the firmware's peak search to lock on), K = 0.5 at
  ±30°, which matches the ±30° viewing half-angle of common IR
  phototransistor flame modules, and K = 0 beyond 60°.
  dθ is the horizontal angle between the sensor's aim and the direction from
  the sensor to the flame.

Walls are 33 cm tall and the flame about 17.5 cm high, so any wall edge
between sensor and flame blocks the light completely.

ADC output: counts = clip(round(gain * I) + dark, 0, 2^adc_bits - 1). With
gain 12000 counts/fc and dark 40 counts, a flame on axis at 20 cm
(I = 0.3125 fc) reads 3790 of 4095 (93% of full scale, so the firmware can
still see it grow a little); at 1 m it reads 190, at 2 m 78.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numba as nb
import numpy as np

from sim_plant.geometry import segment_blocked, segment_blocked_soa

INTENSITY_COEFF = 0.0125  # foot-candles * m^2, the paper's eq. (9)


@dataclass(frozen=True)
class FlameModel:
    gain: float = 12000.0  # ADC counts per foot-candle
    dark: int = 40  # counts with no flame in view (offset of the amplifier)
    k_half_width_deg: float = 60.0  # K falls to 0 at this angle off axis
    r_min: float = 0.02  # m, R is clamped to this


@nb.njit(cache=True)
def flame_k(dtheta: float, half_width: float) -> float:
    """Angular coefficient K(dθ) (dθ, half_width in rad): raised cosine, 0 beyond half_width."""
    a = abs(dtheta)
    if a >= half_width:
        return 0.0
    return 0.5 * (1.0 + math.cos(math.pi * a / half_width))


@nb.njit(cache=True)
def flame_intensity(r: float, dtheta: float, half_width: float, r_min: float) -> float:
    """Eq. (9): foot-candles at distance r (m), dθ (rad) off the sensor's axis."""
    r = max(r, r_min)
    return INTENSITY_COEFF * flame_k(dtheta, half_width) / (r * r)


@nb.njit(cache=True)
def flame_sensor_fc(x: float, y: float, c: float, s: float, bx: float, by: float, bz: float,
                    aim: float, theta: float, fx: float, fy: float, fz: float,
                    walls: np.ndarray, half_width: float, r_min: float) -> float:
    """Light (fc) on a sensor at body (bx, by, bz) aimed at ``aim`` rad, robot at (x, y, θ).

    ``c``, ``s`` are cos θ, sin θ; (fx, fy, fz) is the flame. 0 when a wall is in between.
    ``walls``: the wall edges as ``geometry.edges_soa`` lays them out.
    """
    px = x + c * bx - s * by
    py = y + s * bx + c * by
    dx = fx - px
    dy = fy - py
    dz = fz - bz
    dth = math.atan2(dy, dx) - (theta + aim)
    dth = (dth + math.pi) % (2.0 * math.pi) - math.pi
    k = flame_k(dth, half_width)
    if k == 0.0:
        return 0.0
    if segment_blocked_soa(px, py, fx, fy, walls):
        return 0.0
    r = math.sqrt(dx * dx + dy * dy + dz * dz)
    r = max(r, r_min)
    return INTENSITY_COEFF * k / (r * r)


@nb.njit(cache=True)
def point_fc(px: float, py: float, pz: float, aim: float, sx: float, sy: float, sz: float,
             walls: np.ndarray, half_width: float, r_min: float) -> float:
    """Eq. (9) light (fc) of a unit point source at (sx, sy, sz) on a sensor at (px, py, pz)
    aimed at ``aim`` (rad, world frame); 0 when a wall is in between (``walls``: edges_soa)."""
    dx = sx - px
    dy = sy - py
    dz = sz - pz
    dth = math.atan2(dy, dx) - aim
    dth = (dth + math.pi) % (2.0 * math.pi) - math.pi
    k = flame_k(dth, half_width)
    if k == 0.0:
        return 0.0
    if segment_blocked_soa(px, py, sx, sy, walls):
        return 0.0
    r = max(math.sqrt(dx * dx + dy * dy + dz * dz), r_min)
    return INTENSITY_COEFF * k / (r * r)


_NUDGE = 1e-7  # m, a reflection point moved this far off its wall face for the visibility tests


@nb.njit(cache=True)
def reflected_fc(px: float, py: float, pz: float, aim: float, sx: float, sy: float, sz: float,
                 edges: np.ndarray, half_width: float, r_min: float) -> float:
    """Light (fc) of a unit point source reaching the sensor by one bounce off any wall face,
    before the walls' reflectance: the image-source construction.

    Each wall face (a polygon edge, outward normal n; the polygons are
    counter-clockwise) with both sensor and source in front of it mirrors the
    source to an image behind it. The image shines on the sensor as a source
    would (eq. 9 with the sensor-to-image distance and direction) when the
    sensor-to-image line crosses the face itself and neither leg (source to
    the reflection point, the point to the sensor) is blocked by another wall.
    Walls are taller than flame and sensors, so the bounce is always on the wall.
    """
    total = 0.0
    for i in range(edges.shape[0]):
        ax = edges[i, 0]
        ay = edges[i, 1]
        ex = edges[i, 2] - ax
        ey = edges[i, 3] - ay
        ln = math.sqrt(ex * ex + ey * ey)
        if ln <= 0.0:
            continue
        nx = ey / ln
        ny = -ex / ln
        ds = (px - ax) * nx + (py - ay) * ny
        df = (sx - ax) * nx + (sy - ay) * ny
        if ds <= 0.0 or df <= 0.0:
            continue
        ix = sx - 2.0 * df * nx
        iy = sy - 2.0 * df * ny
        u = ds / (ds + df)
        rx = px + u * (ix - px)
        ry = py + u * (iy - py)
        s = ((rx - ax) * ex + (ry - ay) * ey) / (ln * ln)
        if s < 0.0 or s > 1.0:
            continue
        dx = ix - px
        dy = iy - py
        dth = math.atan2(dy, dx) - aim
        dth = (dth + math.pi) % (2.0 * math.pi) - math.pi
        k = flame_k(dth, half_width)
        if k == 0.0:
            continue
        qx = rx + _NUDGE * nx
        qy = ry + _NUDGE * ny
        if segment_blocked(px, py, qx, qy, edges) or segment_blocked(sx, sy, qx, qy, edges):
            continue
        dz = sz - pz
        r = max(math.sqrt(dx * dx + dy * dy + dz * dz), r_min)
        total += INTENSITY_COEFF * k / (r * r)
    return total


def edge_normals(edges: np.ndarray) -> np.ndarray:
    """Per wall edge: its length, unit outward normal and squared length (ln, nx, ny, ln * ln),
    made once per sensor suite for ``reflected_fc_tab``: the operations ``reflected_fc`` does per
    edge per call, in the same order on the same doubles (sqrt and division are correctly rounded
    in Python as in compiled code), so the same numbers (tested bit for bit)."""
    out = np.zeros((edges.shape[0], 4))
    for i in range(edges.shape[0]):
        ex = float(edges[i, 2]) - float(edges[i, 0])
        ey = float(edges[i, 3]) - float(edges[i, 1])
        ln = math.sqrt(ex * ex + ey * ey)
        out[i, 0] = ln
        if ln > 0.0:
            out[i, 1] = ey / ln
            out[i, 2] = -ex / ln
            out[i, 3] = ln * ln
    return out


@nb.njit(cache=True)
def reflected_fc_tab(px: float, py: float, pz: float, aim: float, sx: float, sy: float, sz: float,
                     walls: np.ndarray, en: np.ndarray, half_width: float, r_min: float) -> float:
    """``reflected_fc`` with the edges as ``geometry.edges_soa`` lays them out (``walls``) and
    each edge's length and normal from ``edge_normals`` (what the sensor suite calls every tick):
    no square root and no division per edge before the face tests, and the line-of-sight tests
    on ``segment_blocked_soa``. The same numbers as ``reflected_fc`` (tested bit for bit)."""
    total = 0.0
    for i in range(walls.shape[1]):
        ln = en[i, 0]
        if ln <= 0.0:
            continue
        ax = walls[0, i]
        ay = walls[1, i]
        nx = en[i, 1]
        ny = en[i, 2]
        ds = (px - ax) * nx + (py - ay) * ny
        df = (sx - ax) * nx + (sy - ay) * ny
        if ds <= 0.0 or df <= 0.0:
            continue
        ex = walls[2, i]
        ey = walls[3, i]
        ix = sx - 2.0 * df * nx
        iy = sy - 2.0 * df * ny
        u = ds / (ds + df)
        rx = px + u * (ix - px)
        ry = py + u * (iy - py)
        s = ((rx - ax) * ex + (ry - ay) * ey) / en[i, 3]
        if s < 0.0 or s > 1.0:
            continue
        dx = ix - px
        dy = iy - py
        dth = math.atan2(dy, dx) - aim
        dth = (dth + math.pi) % (2.0 * math.pi) - math.pi
        k = flame_k(dth, half_width)
        if k == 0.0:
            continue
        qx = rx + _NUDGE * nx
        qy = ry + _NUDGE * ny
        if (segment_blocked_soa(px, py, qx, qy, walls)
                or segment_blocked_soa(sx, sy, qx, qy, walls)):
            continue
        dz = sz - pz
        r = max(math.sqrt(dx * dx + dy * dy + dz * dz), r_min)
        total += INTENSITY_COEFF * k / (r * r)
    return total
