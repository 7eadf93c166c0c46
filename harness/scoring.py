"""Mission outcome and contest score.

Outcomes (the JSON contract): "home" = flame out and the robot stopped inside
the home circle; "extinguished" = flame out, robot not (yet) home;
"timeout" = flame still burning at the find limit; "collision" = the run was
ended by a wall contact (scenario ``stop_on_contact``) or the robot stayed
pushed against a wall, or by knocking the candle over (then ``detail`` is
"knocked the candle over" and ``candle_knocked`` is true; docs/sensors.md);
"error" = the firmware gave up or the link failed.
"""

from __future__ import annotations

import functools
import math
import os
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from sim_plant.schema import check, read_toml

TIME_DECIMALS = 3  # a mission's times in its JSON (s)


def seconds_text(v: float | None) -> str:
    """A mission time as tables and pictures print it: to 0.1 s from the value its JSON keeps, so
    every output (and the acceptance, which reads the JSON) prints one figure. 73.85 s computed
    (7,385 ticks of 10 ms) lies a hair above 73.85; its JSON value, the float nearest 73.85, a
    hair below: 73.8 everywhere, not 73.9 in some."""
    return "-" if v is None else f"{round(float(v), TIME_DECIMALS):.1f}"


SCORING_FILE = Path(__file__).parent / "data" / "scoring.toml"


@dataclass(frozen=True)
class ScoringRules:
    incomplete_score: float
    room_factor: dict[int, float]
    return_trip_factor: float
    wall_contact_penalty: float
    # the optional modes' factors besides the return trip (arbitrary_start, furniture)
    mode_factors: dict[str, float] = field(default_factory=dict)
    candle_knocked_penalty: float = 0.0

    @classmethod
    def load(cls, path: Path = SCORING_FILE) -> ScoringRules:
        # Every mission loads the rules (~0.45 ms); kept per file version, never across an edit.
        try:
            st = os.stat(path)
        except OSError:
            return cls.from_dict(read_toml(path), str(path))  # its one-line error
        return _load_version(str(path), st.st_mtime_ns, st.st_size)

    @classmethod
    def from_dict(cls, data: dict[str, Any], source: str) -> ScoringRules:
        from harness.scenario_schema import ScoringFile

        check(data, ScoringFile, source)  # harness/scenario_schema.py
        return cls(
            incomplete_score=float(data["incomplete_score"]),
            room_factor={int(k): float(v) for k, v in data["room_factor"].items()},
            return_trip_factor=float(data["mode_factor"]["return_trip"]),
            wall_contact_penalty=float(data["penalty"]["wall_contact"]),
            mode_factors={k: float(v) for k, v in data["mode_factor"].items() if k != "return_trip"},
            candle_knocked_penalty=float(data["penalty"].get("candle_knocked", 0.0)),
        )


@functools.lru_cache(maxsize=8)
def _load_version(path: str, _mtime_ns: int, _size: int) -> ScoringRules:
    return ScoringRules.from_dict(read_toml(path), path)


@dataclass
class MissionResult:
    outcome: str
    room: int | None
    candle: tuple[float, float]
    time_to_extinguish_s: float | None
    total_time_s: float | None
    wall_contacts: int
    min_wall_clearance_m: float
    path_length_m: float
    seed: int
    rooms_searched: int = 0
    score: float = 0.0
    detail: str = ""
    scenario: str = ""
    link: str = "ctypes:"
    sim_time_s: float = 0.0
    final_pose: tuple[float, float, float] = (0.0, 0.0, 0.0)
    # what crossed the link during this mission (LinkCounters.as_dict(); docs/protocol.md)
    link_counters: dict[str, int] = field(default_factory=dict)
    start_pose: tuple[float, float, float] = (0.0, 0.0, 0.0)  # x, y (m), heading (rad) the mission started at
    arena_jitter: float = 0.0  # m, the arena's walls moved by up to this (drawn from the seed)
    modes: list[str] = field(default_factory=list)  # optional modes run in (arbitrary_start, furniture)
    furniture: list[list[float]] = field(default_factory=list)  # each piece: x, y, width, depth (m), heading (deg)
    candle_knocked: bool = False  # the run ended because the robot knocked the candle over
    extra: dict[str, Any] = field(default_factory=dict)

    def to_json(self) -> dict[str, Any]:
        def r(v: float | None, nd: int = TIME_DECIMALS) -> float | None:
            return None if v is None else round(float(v), nd)

        out: dict[str, Any] = {
            "outcome": self.outcome,
            "room": self.room,
            "candle": [round(self.candle[0], 4), round(self.candle[1], 4)],
            "time_to_extinguish_s": r(self.time_to_extinguish_s),
            "total_time_s": r(self.total_time_s),
            "wall_contacts": int(self.wall_contacts),
            "min_wall_clearance_m": r(self.min_wall_clearance_m, 4),
            "path_length_m": r(self.path_length_m, 3),
            "seed": int(self.seed),
            "rooms_searched": int(self.rooms_searched),
            "score": r(self.score, 2),
            "detail": self.detail,
            "scenario": self.scenario,
            "link": self.link,
            "link_counters": dict(self.link_counters),
            "candle_knocked": bool(self.candle_knocked),
            "sim_time_s": r(self.sim_time_s),
            "final_pose": [round(self.final_pose[0], 4), round(self.final_pose[1], 4),
                           round(math.degrees(self.final_pose[2]), 2)],
            "start_pose": [round(self.start_pose[0], 4), round(self.start_pose[1], 4),
                           round(math.degrees(self.start_pose[2]), 2)],
            "arena_jitter": self.arena_jitter,
            "modes": list(self.modes),
            "furniture": [list(p) for p in self.furniture],
        }
        out.update(self.extra)
        return out


def contest_score(rules: ScoringRules, outcome: str, time_to_extinguish_s: float | None,
                  rooms_searched: int, wall_contacts: int, modes: Sequence[str] = (),
                  candle_knocked: bool = False) -> float:
    """Lower is better; knocking the candle over adds its penalty to whatever the run scored."""
    extra = rules.candle_knocked_penalty if candle_knocked else 0.0
    if outcome not in ("home", "extinguished") or time_to_extinguish_s is None:
        return rules.incomplete_score + extra
    rf = rules.room_factor.get(max(1, rooms_searched), min(rules.room_factor.values()))
    mode = rules.return_trip_factor if outcome == "home" else 1.0
    for m in modes:
        mode *= rules.mode_factors[m]
    return time_to_extinguish_s * rf * mode + rules.wall_contact_penalty * wall_contacts + extra
