"""Wheel encoders: cumulative integer counts from the wheel angle.

counts = floor(phi * ticks_per_rev / 2π), so counts step at every whole tick
and go negative (floor, not truncation) when the wheel turns backwards past
its start. Slip (counts lost, from the noise profile) is applied by the
suite as an offset on phi before this conversion.
"""

from __future__ import annotations

import math

import numba as nb

TWO_PI = 2.0 * math.pi


@nb.njit(cache=True)
def encoder_counts(phi: float, ticks_per_rev: float) -> int:
    """Cumulative encoder count for a wheel angle phi (rad)."""
    return math.floor(phi * ticks_per_rev / TWO_PI)
