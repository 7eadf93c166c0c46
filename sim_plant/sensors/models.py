"""Richer sensor and world models (issue 12): the GP2D12's beam, latency and
per-part timing; the flame's strength, flicker, wall reflections and afterglow.

Both groups live in a noise profile (``[PROFILE.ranger]``,
``[PROFILE.flame_world]`` in ``sim_plant/data/noise_profiles.toml``, in a user
profile file or in a scenario's inline ``[noise]``), beside the noise groups.
The GP2D12's finite beam (2 degrees each side, 5 rays) is on by default; its
latency is off by default (with the beam and the ``datasheet`` noise the
firmware fails 15 of the property test's 80 missions: docs/sensors.md);
everything that draws a random number, and the flame models, are off unless
a profile switches them on (the ``realistic`` profile does), so a profile
that does not name them draws nothing. Values and sources: docs/sensors.md.

Random draws (only when a field asks for one), all from the scenario's one
Generator, once, when the ``SensorSuite`` is built, after the parts' unit
spread: the rangers' periods (5 uniforms), their phases (5 uniforms), the
flame strength (1 uniform), the flicker phases (2 uniforms), in that order.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

GP2D12_PERIOD_SPREAD = 0.0096  # s, the datasheet's 38.3 +- 9.6 ms
# chosen: the beam "a few cm wide at long range" (no published angle): 2 degrees each side
# is a 5.6 cm spot at 80 cm (docs/sensors.md)
BEAM_HALF_ANGLE_DEG = 2.0


@dataclass(frozen=True)
class RangerModel:
    """GP2D12 beam and timing.

    ``beam_half_angle_deg``: half-width of the beam (0 = one ray, the pre-issue-12 model);
    ``beam_rays`` rays spread evenly over it, combined as the part's position
    sensitive detector does: the intensity-weighted mean of 1/d (docs/sensors.md).
    ``latency``: the voltage of a measurement appears only at the end of its
    cycle (one period late) and is held.
    ``period_spread``: each part's period drawn once, uniformly in
    period +- period_spread (s; the datasheet's spread is 0.0096).
    ``random_phase``: each part's first measurement instant drawn uniformly in
    [0, its period) instead of the fixed stagger.
    """

    beam_half_angle_deg: float = BEAM_HALF_ANGLE_DEG
    beam_rays: int = 5
    latency: bool = False
    period_spread: float = 0.0
    random_phase: bool = False

    @property
    def draws(self) -> bool:
        return self.period_spread > 0.0 or self.random_phase


@dataclass(frozen=True)
class FlameWorld:
    """What the flame sensors see besides the paper's point flame.

    ``strength_min``/``strength_max``: the flame's strength, relative to the
    paper's eq. (9) flame, drawn once per mission uniformly in this range
    (equal = no draw). ``flicker_amp``: relative depth of a slow variation
    1 + amp * (0.6 sin(2 pi f t + p1) + 0.4 sin(2 pi 2.7 f t + p2)), f =
    ``flicker_hz``, phases drawn per mission. ``wall_reflectance``: the
    white walls return this fraction of the light, one bounce, image-source
    approximation. ``afterglow_s``: after the flame goes out its light decays
    as exp(-t / afterglow_s) (0 = drops to zero at once; cut off after 10
    time constants).
    """

    strength_min: float = 1.0
    strength_max: float = 1.0
    flicker_amp: float = 0.0
    flicker_hz: float = 1.5
    wall_reflectance: float = 0.0
    afterglow_s: float = 0.0

    @property
    def draws(self) -> bool:
        return self.strength_max > self.strength_min or self.flicker_amp > 0.0


FLICKER_RATIO = 2.7  # second flicker component's frequency / the first (chosen, not a harmonic)


def flicker(t: float, amp: float, f: float, p1: float, p2: float) -> float:
    """The flicker factor at time t (s): the formula of ``FlameWorld``."""
    w = 2.0 * math.pi * f * t
    return 1.0 + amp * (0.6 * math.sin(w + p1) + 0.4 * math.sin(FLICKER_RATIO * w + p2))


def draw_ranger_timing(model: RangerModel, period: float, stagger_phases: list[float],
                       rng: np.random.Generator | None) -> tuple[np.ndarray, np.ndarray]:
    """(periods, phases) of the n rangers; draws only what the model asks for."""
    n = len(stagger_phases)
    periods = np.full(n, period)
    phases = np.array(stagger_phases, dtype=np.float64)
    if model.draws and rng is None:
        raise ValueError("a ranger period spread or random phase is set but no Generator was given")
    if model.period_spread > 0.0:
        assert rng is not None
        periods = period + model.period_spread * (2.0 * rng.random(n) - 1.0)
    if model.random_phase:
        assert rng is not None
        phases = periods * rng.random(n)
    return periods, phases


def draw_flame(world: FlameWorld, rng: np.random.Generator | None) -> tuple[float, float, float]:
    """(strength, flicker phase 1, flicker phase 2) of this mission's flame."""
    if world.draws and rng is None:
        raise ValueError("a flame strength range or flicker is set but no Generator was given")
    strength = world.strength_min
    if world.strength_max > world.strength_min:
        assert rng is not None
        strength = world.strength_min + (world.strength_max - world.strength_min) * float(rng.random())
    p1 = p2 = 0.0
    if world.flicker_amp > 0.0:
        assert rng is not None
        p1, p2 = (2.0 * math.pi * rng.random(2)).tolist()
    return strength, p1, p2
