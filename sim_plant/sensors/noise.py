"""Sensor noise and fault injection: named profiles, and the per-reading kernels.

Everything is off unless a profile switches it on. Profiles live in
``sim_plant/data/noise_profiles.toml`` (``none``, ``typical``, ``harsh``) or in
a user file of the same layout; ``load_noise_profile`` reads either.

Per channel group:

* ``ir`` (mV) and ``flame`` (ADC counts), applied to each reading in order:
  + ``bias`` + ``sigma`` * N(0, 1); a spike of ±``spike_amp`` with
  probability ``spike_prob`` (sign equally likely); quantisation to
  ``quant_step`` (0 = only the output's own integer unit); with probability
  ``dropout_prob`` the reading is lost: ``dropout_mode = "zero"`` reads 0,
  ``"hold"`` keeps the previous output. IR noise is drawn once per GP2D12
  measurement (the part's output is held between measurements), flame noise
  every tick.
  Unit-to-unit spread (``unit_gain_spread``, ``unit_offset_spread``,
  ``unit_pivot``): each part's own calibration, drawn once per mission and
  per sensor, uniformly: reading = pivot + g*(clean - pivot) + o with
  g in 1 ± unit_gain_spread and o in ± unit_offset_spread. For the GP2D12
  with the pivot at its 80 cm output this is the datasheet's statement
  directly: output at 80 cm 0.25-0.55 V (offset), swing 80->10 cm
  1.75-2.25 V (gain). The draws come from the same Generator, after the
  first noise block, and only when a spread is set.
* ``line``: ``flip_prob``, probability per tick that the bit reads inverted.
* ``encoder``: ``slip_prob``, probability per tick and wheel that the
  encoder misses ``slip_fraction`` of that tick's rotation (counts lost for good).

Random numbers: only from the one ``numpy.random.Generator`` handed in, drawn
in blocks of ``BLOCK`` normals and uniforms, refilled when fewer than
``MARGIN`` remain (before a tick that could need more). The consumption
pattern depends only on the profile and the trajectory, so the same seed
gives a bit-identical trace. With noise off nothing is ever drawn.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numba as nb
import numpy as np

from sim_plant.errors import FfrInputError
from sim_plant.file_schemas import NoiseFile, ProfileTable
from sim_plant.reality import Reality, reality_to_table
from sim_plant.schema import check, read_toml
from sim_plant.sensors.models import FlameWorld, RangerModel

DEFAULT_PROFILES = Path(__file__).resolve().parent.parent / "data" / "noise_profiles.toml"

BLOCK = 4096
MARGIN = 32  # > the most draws one tick can take (7 normals, 10 uniforms)

# Packed parameter layout for the kernels.
SIGMA, BIAS, QUANT, DROP_P, DROP_HOLD, SPIKE_P, SPIKE_AMP = range(7)
IR_BASE = 0
FLAME_BASE = 7
LINE_FLIP = 14
ENC_SLIP_P = 15
ENC_SLIP_F = 16
ENABLED = 17
N_PARAMS = 18

@dataclass(frozen=True)
class AnalogNoise:
    sigma: float = 0.0  # gaussian σ per reading (IR: mV, flame: counts)
    bias: float = 0.0  # constant offset, same unit
    quant_step: float = 0.0  # ADC step, same unit; 0 = none
    dropout_prob: float = 0.0  # probability a reading is lost
    dropout_mode: str = "zero"  # "zero": lost reading reads 0; "hold": previous output kept
    spike_prob: float = 0.0  # probability of a spike
    spike_amp: float = 0.0  # spike size, same unit, sign random
    unit_gain_spread: float = 0.0  # per-part gain drawn once in 1 ± this (uniform)
    unit_offset_spread: float = 0.0  # per-part offset drawn once in ± this (uniform), same unit
    unit_pivot: float = 0.0  # the reading the gain scales about, same unit

    @property
    def enabled(self) -> bool:
        return any((self.sigma, self.bias, self.quant_step, self.dropout_prob,
                    self.spike_prob and self.spike_amp)) or self.unit_spread

    @property
    def unit_spread(self) -> bool:
        return self.unit_gain_spread > 0.0 or self.unit_offset_spread > 0.0

    def draw_units(self, n: int, rng: np.random.Generator | None) -> np.ndarray:
        """(n, 2) per-part (gain, offset); identity (1, 0) without a spread, and then no draw."""
        out = np.zeros((n, 2))
        out[:, 0] = 1.0
        if not self.unit_spread:
            return out
        if rng is None:
            raise ValueError("a unit spread is set but no numpy.random.Generator was given")
        u = rng.random((n, 2))
        out[:, 0] = 1.0 + self.unit_gain_spread * (2.0 * u[:, 0] - 1.0)
        out[:, 1] = self.unit_offset_spread * (2.0 * u[:, 1] - 1.0)
        return out


@dataclass(frozen=True)
class LineNoise:
    flip_prob: float = 0.0  # probability per tick that the bit is inverted

    @property
    def enabled(self) -> bool:
        return self.flip_prob > 0.0


@dataclass(frozen=True)
class EncoderNoise:
    slip_prob: float = 0.0  # probability per tick and wheel of a slip
    slip_fraction: float = 0.0  # fraction of that tick's rotation the encoder misses

    @property
    def enabled(self) -> bool:
        return self.slip_prob > 0.0 and self.slip_fraction > 0.0


@dataclass(frozen=True)
class NoiseProfile:
    name: str = "none"
    ir: AnalogNoise = field(default_factory=AnalogNoise)
    flame: AnalogNoise = field(default_factory=AnalogNoise)
    line: LineNoise = field(default_factory=LineNoise)
    encoder: EncoderNoise = field(default_factory=EncoderNoise)
    # plant truth and the team's calibration drawn apart (sim_plant/reality.py); not a sensor
    # noise: ``enabled`` below does not count it
    reality: Reality = field(default_factory=Reality)
    ranger: RangerModel = field(default_factory=RangerModel)  # GP2D12 beam and timing (models.py)
    flame_world: FlameWorld = field(default_factory=FlameWorld)  # flame strength, flicker, ...
    description: str = field(default="", compare=False)
    source: str = field(default="built-in", compare=False)

    @property
    def enabled(self) -> bool:
        return self.ir.enabled or self.flame.enabled or self.line.enabled or self.encoder.enabled

    def packed(self) -> np.ndarray:
        """The parameters as the flat float64 array the kernels read."""
        p = np.zeros(N_PARAMS)
        for base, g in ((IR_BASE, self.ir), (FLAME_BASE, self.flame)):
            p[base + SIGMA] = g.sigma
            p[base + BIAS] = g.bias
            p[base + QUANT] = g.quant_step
            p[base + DROP_P] = g.dropout_prob
            p[base + DROP_HOLD] = 1.0 if g.dropout_mode == "hold" else 0.0
            p[base + SPIKE_P] = g.spike_prob
            p[base + SPIKE_AMP] = g.spike_amp
        p[LINE_FLIP] = self.line.flip_prob
        p[ENC_SLIP_P] = self.encoder.slip_prob
        p[ENC_SLIP_F] = self.encoder.slip_fraction
        p[ENABLED] = 1.0 if self.enabled else 0.0
        return p


# -- loading ---------------------------------------------------------------

_GROUPS: dict[str, type] = {"ir": AnalogNoise, "flame": AnalogNoise, "line": LineNoise,
                            "encoder": EncoderNoise, "ranger": RangerModel,
                            "flame_world": FlameWorld}


def _build(cls: type, table: Any) -> Any:
    if table is None:
        return cls()
    return cls(**{f.name: getattr(table, f.name) for f in dataclasses.fields(cls)})


def _profile(src: str, name: str, table: Any) -> NoiseProfile:
    """One profile from its table (checked against ``sim_plant/file_schemas.ProfileTable``)."""
    t = check(table, ProfileTable, src, name)
    groups = {g: _build(cls, getattr(t, g)) for g, cls in _GROUPS.items()}
    return NoiseProfile(name=name, source=src, description=t.description, reality=_build(Reality, t.reality),
                        **groups)


def profiles_from_dict(data: dict[str, Any], source: str) -> dict[str, NoiseProfile]:
    """Every profile of a profiles file's tables (checked against ``file_schemas.NoiseFile``)."""
    check(data, NoiseFile, source)
    return {name: _profile(source, name, t) for name, t in data.items()}


def profile_from_table(table: Any, source: str, name: str = "inline") -> NoiseProfile:
    """A profile from one TOML table (e.g. a scenario's inline ``[noise]``)."""
    return _profile(source, name, table)


def profile_to_table(prof: NoiseProfile) -> dict[str, Any]:
    """The profile as a TOML-ready table, only the fields that differ from 'off'."""
    out: dict[str, Any] = {}
    for gname in _GROUPS:
        g = getattr(prof, gname)
        d = {f.name: getattr(g, f.name) for f in dataclasses.fields(g)
             if getattr(g, f.name) != f.default}
        if d:
            out[gname] = d
    r = reality_to_table(prof.reality)
    if r:
        out["reality"] = r
    return out


def load_noise_profile(name_or_path: str | Path = "none") -> NoiseProfile:
    """A profile by name from the bundled file, or from a TOML file.

    A file holds one or more profiles as top-level tables (``[myprofile.ir]``
    ...); ``FILE.toml`` picks its only profile, ``FILE.toml#name`` one of several.
    Unknown names, unknown fields and bad values raise ``FfrInputError``.
    """
    spec = str(name_or_path)
    is_path = isinstance(name_or_path, Path) or "/" in spec or "\\" in spec or ".toml" in spec
    if not is_path:
        src = str(DEFAULT_PROFILES)
        data = read_toml(DEFAULT_PROFILES)
        if spec not in data:
            raise FfrInputError(src, "profile", spec,
                                f"unknown noise profile (known: {', '.join(data)})")
        return _profile(src, spec, data[spec])
    path, _, want = spec.partition("#")
    data = read_toml(path)
    check(data, NoiseFile, path)  # every profile of the file, not only the one picked
    if want:
        if want not in data:
            raise FfrInputError(path, "profile", want,
                                f"no such profile in this file (has: {', '.join(data) or 'none'})")
        return _profile(path, want, data[want])
    if len(data) != 1:
        raise FfrInputError(path, "profile", sorted(data),
                            "the file must hold exactly one profile, or name one as FILE.toml#name")
    name = next(iter(data))
    return _profile(path, name, data[name])


# -- random numbers ----------------------------------------------------------

class NoiseStream:
    """Block buffers of N(0,1) and U[0,1) draws from the one Generator, and the read positions."""

    def __init__(self, rng: np.random.Generator | None, enabled: bool) -> None:
        self.rng = rng
        n = BLOCK if enabled else 0
        self.normals = np.zeros(n)
        self.uniforms = np.zeros(n)
        self.pos = np.zeros(2, dtype=np.int64)  # next normal, next uniform
        if enabled:
            if rng is None:
                raise ValueError("a noise profile is on but no numpy.random.Generator was given")
            self.refill()

    def refill(self) -> None:
        assert self.rng is not None
        self.rng.standard_normal(out=self.normals)
        self.rng.random(out=self.uniforms)
        self.pos[:] = 0


@nb.njit(cache=True)
def needs_refill(pos: np.ndarray, n: int) -> bool:
    return pos[0] > n - MARGIN or pos[1] > n - MARGIN


@nb.njit(cache=True)
def next_uniform(uniforms: np.ndarray, pos: np.ndarray) -> float:
    u = uniforms[pos[1]]
    pos[1] += 1
    return u


@nb.njit(cache=True)
def apply_analog(v: float, p: np.ndarray, base: int, normals: np.ndarray, uniforms: np.ndarray,
                 pos: np.ndarray, prev: float) -> float:
    """One analog reading through bias, gaussian noise, spikes, quantisation and dropout."""
    v += p[base + BIAS]
    if p[base + SIGMA] > 0.0:
        v += p[base + SIGMA] * normals[pos[0]]
        pos[0] += 1
    p_drop = p[base + DROP_P]
    p_spike = p[base + SPIKE_P]
    dropped = False
    if p_drop + p_spike > 0.0:
        # One uniform decides dropout, a positive spike or a negative spike.
        u = next_uniform(uniforms, pos)
        if u < p_drop:
            dropped = True
        elif u < p_drop + 0.5 * p_spike:
            v += p[base + SPIKE_AMP]
        elif u < p_drop + p_spike:
            v -= p[base + SPIKE_AMP]
    q = p[base + QUANT]
    if q > 0.0:
        v = math.floor(v / q + 0.5) * q
    if dropped:
        return prev if p[base + DROP_HOLD] != 0.0 else 0.0
    return v


@nb.njit(cache=True)
def flip_bit(bit: int, p: np.ndarray, uniforms: np.ndarray, pos: np.ndarray) -> int:
    if p[LINE_FLIP] > 0.0 and next_uniform(uniforms, pos) < p[LINE_FLIP]:
        return 1 - bit
    return bit


@nb.njit(cache=True)
def slip(dphi: float, p: np.ndarray, uniforms: np.ndarray, pos: np.ndarray) -> float:
    """Rotation the encoder misses this tick (0 unless a slip is drawn)."""
    if p[ENC_SLIP_P] > 0.0 and p[ENC_SLIP_F] > 0.0 and next_uniform(uniforms, pos) < p[ENC_SLIP_P]:
        return p[ENC_SLIP_F] * dphi
    return 0.0
