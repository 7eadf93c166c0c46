"""Fault injection for the wire links: drop, corrupt, duplicate or delay a
seeded fraction of frames, in both directions, on the host's side of the wire.

Frames are whatever the transport moves (serial: one COBS frame; CAN: one CAN
frame); ``corrupt`` flips one bit. One ``numpy.random.Generator`` seeded from
the spec decides, so a faulty run replays exactly.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass, field, fields
from typing import Generic, TypeVar

import numpy as np

T = TypeVar("T")


@dataclass(frozen=True)
class FaultSpec:
    drop: float = 0.0       # fraction of frames lost
    corrupt: float = 0.0    # fraction with one bit flipped
    duplicate: float = 0.0  # fraction sent twice
    delay: float = 0.0      # fraction held back ...
    delay_s: float = 0.02   # ... this long
    seed: int = 0

    def __post_init__(self) -> None:
        for f in ("drop", "corrupt", "duplicate", "delay"):
            v = getattr(self, f)
            if not 0.0 <= v <= 1.0:
                raise ValueError(f"faults: {f} = {v}: expected a fraction in 0..1")
        if self.delay_s < 0:
            raise ValueError(f"faults: delay_s = {self.delay_s}: expected >= 0")

    @property
    def active(self) -> bool:
        return any((self.drop, self.corrupt, self.duplicate, self.delay))

    @classmethod
    def names(cls) -> set[str]:
        return {f.name for f in fields(cls)}


@dataclass
class FaultCounters:
    dropped: int = 0
    corrupted: int = 0
    duplicated: int = 0
    delayed: int = 0


def flip_bit(data: bytes, rng: np.random.Generator) -> bytes:
    if not data:
        return data
    b = bytearray(data)
    i = int(rng.integers(len(b)))
    b[i] ^= 1 << int(rng.integers(8))
    return bytes(b)


@dataclass
class FaultInjector(Generic[T]):
    """``filter(frame)`` -> the frames to deliver now; ``due()`` -> delayed frames whose time has come."""

    spec: FaultSpec
    corrupt_fn: Callable[[T, np.random.Generator], T]
    counters: FaultCounters = field(default_factory=FaultCounters)

    def __post_init__(self) -> None:
        self.rng = np.random.default_rng(self.spec.seed)
        self._held: list[tuple[float, T]] = []

    def filter(self, frame: T) -> list[T]:
        s = self.spec
        if not s.active:
            return [frame]
        u = self.rng.random(4)
        if u[0] < s.drop:
            self.counters.dropped += 1
            return []
        if u[1] < s.corrupt:
            self.counters.corrupted += 1
            frame = self.corrupt_fn(frame, self.rng)
        if u[2] < s.delay:
            self.counters.delayed += 1
            self._held.append((time.monotonic() + s.delay_s, frame))
            return []
        if u[3] < s.duplicate:
            self.counters.duplicated += 1
            return [frame, frame]
        return [frame]

    def due(self) -> list[T]:
        if not self._held:
            return []
        now = time.monotonic()
        out = [f for t, f in self._held if t <= now]
        self._held = [(t, f) for t, f in self._held if t > now]
        return out

    @property
    def holding(self) -> bool:
        return bool(self._held)
