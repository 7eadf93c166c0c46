"""Downward line sensor (photo-reflector): 1 over a white line, else 0.

White on the black floor: the 2.5 cm line across each doorway, the home
circle's ring and the candle circle's ring (each ring a 2.5 cm line centred
on its radius).

Spot model: the sensor sees a disc of radius ``spot_radius`` and reads 1 when
at least ``white_fraction`` of it is white. The white fraction is analytic:
across a straight band of half-width w centred at offset s from the disc
centre, the covered fraction is C((w - s)/ρ) - C((-w - s)/ρ), with C(z) the
fraction of a unit disc left of the chord at z. The rings (15 cm radius)
are treated as straight bands locally (error ~ρ²/R, negligible for a 5 mm
spot); a doorway line's ends multiply in the same 1-D fraction along the
line (exact away from the ends, a close approximation at them). The white
shapes never overlap, so their fractions add.
"""

from __future__ import annotations

import math

import numba as nb
import numpy as np

from sim_plant.arena import Arena


def door_segments(arena: Arena) -> np.ndarray:
    """(n_rooms, 4) doorway-line centre lines x1, y1, x2, y2."""
    return np.array([[*r.door[0], *r.door[1]] for r in arena.rooms], dtype=np.float64)


@nb.njit(cache=True)
def _chord_fraction(z: float) -> float:
    """Fraction of the unit disc with coordinate <= z."""
    if z <= -1.0:
        return 0.0
    if z >= 1.0:
        return 1.0
    return 0.5 + (z * math.sqrt(1.0 - z * z) + math.asin(z)) / math.pi


@nb.njit(cache=True)
def band_fraction(s: float, half_w: float, rho: float) -> float:
    """Fraction of a disc (radius rho, centre at offset s) inside the band |n| <= half_w."""
    if rho <= 0.0:
        return 1.0 if abs(s) <= half_w else 0.0
    return _chord_fraction((half_w - s) / rho) - _chord_fraction((-half_w - s) / rho)


@nb.njit(cache=True)
def white_fraction(px: float, py: float, doors: np.ndarray, half_w: float, rho: float,
                   hx: float, hy: float, hr: float, cx: float, cy: float, cr: float) -> float:
    """White fraction of the spot at (px, py): doorways, home ring (hx, hy, hr), candle ring."""
    reach = half_w + rho
    total = 0.0
    for i in range(doors.shape[0]):
        x1 = doors[i, 0]
        y1 = doors[i, 1]
        ex = doors[i, 2] - x1
        ey = doors[i, 3] - y1
        length = math.sqrt(ex * ex + ey * ey)
        ux = ex / length
        uy = ey / length
        wx = px - x1
        wy = py - y1
        across = -uy * wx + ux * wy
        if abs(across) >= reach:
            continue
        along = ux * wx + uy * wy
        if along <= -rho or along >= length + rho:
            continue
        f = band_fraction(across, half_w, rho)
        if rho > 0.0:
            f *= _chord_fraction((length - along) / rho) - _chord_fraction(-along / rho)
        total += f
    for k in range(2):
        ox = hx if k == 0 else cx
        oy = hy if k == 0 else cy
        r = hr if k == 0 else cr
        s = math.sqrt((px - ox) ** 2 + (py - oy) ** 2) - r
        if abs(s) < reach:
            total += band_fraction(s, half_w, rho)
    return min(total, 1.0)
