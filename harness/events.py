"""Scenario events: faults that start at a given time, on one sensor or wheel.

A scenario's ``[[events]]`` say "the right-front ranger dies at 30 s" or "the
left wheel slips by 30 % from 12 s for 4 s". They act on the sensor path:
after ``SensorSuite.sample`` has written the tick's hardware units and before
the firmware sees them, so the plant stays true and only what the firmware
reads changes. Faults:

* ``dead``: the sensor reads ``value`` (default 0: a GP2D12 or flame sensor
  with its output at 0 V, the line sensor dark, an encoder that stops counting).
* ``stuck``: the sensor keeps the reading it had when the fault began.
* ``noisy``: gaussian noise of ``sigma`` (the sensor's unit) is added.
* ``slip`` (``wheel.L`` / ``wheel.R``): the track slips on the floor, so the
  encoder counts ``1 / (1 - fraction)`` times the rotation that moved the
  robot: the firmware's odometry over-estimates that wheel's travel.

Every event lasts ``duration_s`` (default: to the end). Noisy events draw
from the mission's one ``numpy.random.Generator``, in tick order.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numba as nb
import numpy as np

from harness.event_channels import CHANNELS, FAULTS, LIMITS, WHEELS
from sim_plant.sensors.channels import CH_ENC_L, CH_ENC_R

_LIMITS = LIMITS


@dataclass(frozen=True)
class Event:
    at_s: float
    sensor: str
    fault: str
    duration_s: float = math.inf
    value: float = 0.0  # dead: the reading
    sigma: float = 0.0  # noisy: gaussian sigma, sensor units
    fraction: float = 0.0  # slip: share of the wheel's rotation lost on the floor

    @property
    def channel(self) -> int:
        return WHEELS[self.sensor] if self.fault == "slip" else CHANNELS[self.sensor]

    def to_table(self) -> dict[str, Any]:
        d: dict[str, Any] = {"at_s": self.at_s, "sensor": self.sensor, "fault": self.fault}
        if math.isfinite(self.duration_s):
            d["duration_s"] = self.duration_s
        if self.fault == "dead" and self.value:
            d["value"] = self.value
        if self.fault == "noisy":
            d["sigma"] = self.sigma
        if self.fault == "slip":
            d["fraction"] = self.fraction
        return d


def parse_events(raw: Any, source: str) -> list[Event]:
    """Validate a scenario's ``events`` array (``harness/scenario_schema.EventTable``); errors name
    file, field and value on one line."""
    from harness.scenario_schema import Events
    from sim_plant.schema import check

    return [Event(t.at_s, t.sensor, t.fault, math.inf if t.duration_s is None else t.duration_s,
                  t.value or 0.0, t.sigma or 0.0, t.fraction or 0.0)
            for t in check(raw, Events, source, "events")]


class EventRunner:
    """Applies a scenario's events to each tick's hardware units, in place."""

    def __init__(self, events: list[Event], rng: np.random.Generator) -> None:
        self.events = list(events)
        self.rng = rng
        self.held: dict[int, int] = {}  # channel -> reading when a 'stuck' began
        self.enc_prev: dict[int, int] = {}  # raw encoder counts at the last tick
        self.enc_extra: dict[int, float] = {}  # counts added by slip so far
        self.active = [False] * len(self.events)

    def apply(self, t: float, hw: np.ndarray) -> None:
        # Encoders by increments: slip scales this tick's rotation, a dead or
        # stuck encoder drops it; the counts lost or added stay lost or added.
        for ch in (CH_ENC_L, CH_ENC_R):
            raw = int(hw[ch])
            prev = self.enc_prev.get(ch, raw)
            self.enc_prev[ch] = raw
            gain = 1.0
            for ev in self.events:
                if ev.channel == ch and ev.fault != "noisy" and ev.at_s <= t < ev.at_s + ev.duration_s:
                    gain = gain / (1.0 - ev.fraction) if ev.fault == "slip" else 0.0
            if gain != 1.0:
                self.enc_extra[ch] = self.enc_extra.get(ch, 0.0) + (gain - 1.0) * (raw - prev)
            if ch in self.enc_extra:
                hw[ch] = raw + math.floor(self.enc_extra[ch] + 0.5)
        for k, ev in enumerate(self.events):
            ch = ev.channel
            if ch in (CH_ENC_L, CH_ENC_R) and ev.fault != "noisy":
                continue
            on = ev.at_s <= t < ev.at_s + ev.duration_s
            if on and not self.active[k]:
                self.held[ch] = int(hw[ch])
            self.active[k] = on
            if not on:
                continue
            if ev.fault == "stuck":
                hw[ch] = self.held[ch]
            elif ev.fault == "dead":
                hw[ch] = int(ev.value)
            else:  # noisy
                v = float(hw[ch]) + ev.sigma * float(self.rng.standard_normal())
                lo, hi = _LIMITS.get(ch, (-2.0**31, 2.0**31 - 1))
                hw[ch] = int(min(max(math.floor(v + 0.5), lo), hi))


# -- the compiled twin of EventRunner.apply (the lockstep kernel, harness/tick.py) --------

# packed event columns; fault codes
E_AT, E_DUR, E_CH, E_FAULT, E_VALUE, E_SIGMA, E_FRAC, E_LO, E_HI = range(9)
N_E = 9
F_DEAD, F_STUCK, F_NOISY, F_SLIP = range(4)
# state columns per channel: held reading, previous raw encoder count, counts added so far
EV_HELD, EV_PREV, EV_HAS_PREV, EV_EXTRA = range(4)
N_EV_STATE = 4


def pack_events(events: list[Event]) -> np.ndarray:
    """(n, N_E) float64 table of the events for ``apply_events``."""
    ev = np.zeros((len(events), N_E))
    for k, e in enumerate(events):
        lo, hi = _LIMITS.get(e.channel, (-2.0**31, 2.0**31 - 1))
        ev[k] = (e.at_s, e.duration_s, e.channel, FAULTS.index(e.fault), e.value, e.sigma,
                 e.fraction, lo, hi)
    return ev


@nb.njit(cache=True)
def apply_events(t: float, hw: np.ndarray, ev: np.ndarray, state: np.ndarray, active: np.ndarray,
                 rng: np.random.Generator) -> None:
    """``EventRunner.apply`` on packed events: same arithmetic, same draws in the same order.

    ``state`` is (N_CHANNELS, N_EV_STATE) zeros at the start, ``active`` (n,) zeros.
    """
    n = ev.shape[0]
    for ch in (CH_ENC_L, CH_ENC_R):
        raw = np.int64(hw[ch])
        prev = np.int64(state[ch, EV_PREV]) if state[ch, EV_HAS_PREV] != 0.0 else raw
        state[ch, EV_PREV] = raw
        state[ch, EV_HAS_PREV] = 1.0
        gain = 1.0
        for k in range(n):
            f = ev[k, E_FAULT]
            if ev[k, E_CH] == ch and f != F_NOISY and ev[k, E_AT] <= t < ev[k, E_AT] + ev[k, E_DUR]:
                gain = gain / (1.0 - ev[k, E_FRAC]) if f == F_SLIP else 0.0
        if gain != 1.0:
            state[ch, EV_EXTRA] = state[ch, EV_EXTRA] + (gain - 1.0) * (raw - prev)
        # an encoder without extra counts reads raw either way (floor(0.0 + 0.5) == 0)
        hw[ch] = raw + np.int64(math.floor(state[ch, EV_EXTRA] + 0.5))
    for k in range(n):
        ch = int(ev[k, E_CH])
        f = ev[k, E_FAULT]
        if ch in (CH_ENC_L, CH_ENC_R) and f != F_NOISY:
            continue
        on = ev[k, E_AT] <= t < ev[k, E_AT] + ev[k, E_DUR]
        if on and active[k] == 0:
            state[ch, EV_HELD] = hw[ch]
        active[k] = 1 if on else 0
        if not on:
            continue
        if f == F_STUCK:
            hw[ch] = np.int32(state[ch, EV_HELD])
        elif f == F_DEAD:
            hw[ch] = np.int32(int(ev[k, E_VALUE]))
        else:  # noisy
            v = float(hw[ch]) + ev[k, E_SIGMA] * rng.standard_normal()
            hw[ch] = np.int32(min(max(math.floor(v + 0.5), ev[k, E_LO]), ev[k, E_HI]))
