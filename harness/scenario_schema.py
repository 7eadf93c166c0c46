"""Schemas of the harness's input files: scenarios (every table), their events, and scoring.

Declared once here and checked by ``sim_plant.schema.check`` (docs/inputs.md). The arena, robot
and noise tables a scenario names or inlines are declared in ``sim_plant/file_schemas.py``.
Checks that need the loaded arena (a candle's room, a start pose in the home circle, an infrared
source inside the arena, furniture clear of the walls) stay with the scenario's builder; the
``[firmware]`` table's keys are checked against the loaded firmware's config layout
(``harness/firmware_config.py``): here it is only a table of numbers, strings and arrays.
"""

from __future__ import annotations

from typing import Annotated, Literal

from msgspec import Meta, Struct

from harness.event_channels import CHANNELS, FAULTS, LIMITS, WHEELS
from harness.start_pose import START_AREAS
from sim_plant.file_schemas import NonNeg, Point, Positive, ProfileTable
from sim_plant.schema import rule

Scalar = bool | int | float | str
Value = Annotated[Scalar | list[Scalar], Meta(description="a number, string, boolean or an array of them")]


class Table(Struct, forbid_unknown_fields=True, kw_only=True):
    """Every table refuses unknown keys; fields are given by name."""


class CandleTable(Table, kw_only=True):
    room: int | None = None
    position: Point | None = None

    def __post_init__(self) -> None:
        if self.room is not None and self.position is not None:
            raise rule("position", "give either candle.room or candle.position")


class StartTable(Table, kw_only=True):
    x: float | None = None
    y: float | None = None
    heading_deg: float | None = None  # default: the arena's home heading
    random: bool = False
    area: Literal[START_AREAS] = "home"  # type: ignore[valid-type]

    def __post_init__(self) -> None:
        pose = {"heading_deg": self.heading_deg, "x": self.x, "y": self.y}
        if self.random:
            given = [k for k, v in pose.items() if v is not None]
            if given:
                raise rule(given[0], "give either start.random = true or a pose (x, y, heading_deg)")
        else:
            for k in ("x", "y"):
                if pose[k] is None:
                    raise rule(k, "missing")


class TimingTable(Table, kw_only=True):
    firmware_period_ms: Annotated[int, Meta(ge=1, le=1000)] = 10
    plant_dt_ms: Positive = 1.0
    find_limit_s: Positive = 300.0
    return_limit_s: Positive = 120.0
    start_delay_ms: Annotated[int, Meta(ge=0)] = 0

    def __post_init__(self) -> None:
        steps = self.firmware_period_ms / self.plant_dt_ms
        if abs(steps - round(steps)) > 1e-9:
            raise rule("plant_dt_ms", "must divide the firmware period into whole plant steps")


class EventTable(Table, kw_only=True):
    """One ``[[events]]`` fault (harness/events.py)."""

    at_s: NonNeg
    sensor: str
    fault: Literal[FAULTS]  # type: ignore[valid-type]
    duration_s: Positive | None = None  # default: to the end
    value: float | None = None  # dead: the reading (within the channel's range)
    sigma: Positive | None = None  # noisy: required
    fraction: Annotated[float, Meta(gt=0, le=0.95)] | None = None  # slip: required

    def __post_init__(self) -> None:
        known = WHEELS if self.fault == "slip" else CHANNELS
        if self.sensor not in known:
            what = "wheel" if self.fault == "slip" else "sensor"
            raise rule("sensor", f"unknown {what} for '{self.fault}' (known: {', '.join(known)})")
        for k, needed in (("value", "dead"), ("sigma", "noisy"), ("fraction", "slip")):
            if getattr(self, k) is not None and self.fault != needed:
                raise rule(k, f"only for fault '{needed}'")
        if self.fault == "dead" and self.value is not None:
            lo, hi = LIMITS.get(CHANNELS[self.sensor], (-2.0**31, 2.0**31 - 1))
            if not lo <= self.value <= hi:
                raise rule("value", f"must be a number in [{lo:g}, {hi:g}]")
        if self.fault == "noisy" and self.sigma is None:
            raise rule("sigma", "missing (noisy needs sigma)")
        if self.fault == "slip" and self.fraction is None:
            raise rule("fraction", "missing (slip needs fraction)")


Events = Annotated[list[EventTable], Meta(description="an array of tables ([[events]])")]


class FurnitureTable(Table, kw_only=True):
    x: float
    y: float
    width: Positive
    depth: Positive
    heading_deg: float = 0.0


class IrSourceTable(Table, kw_only=True):
    name: str = "ir_source"
    position: Point  # inside the arena (checked with the arena)
    height: Annotated[float, Meta(ge=0, le=5)] | None = None  # default: the arena's flame height
    strength: Annotated[float, Meta(ge=0, le=1000)]


class ScenarioFile(Table, kw_only=True):
    """A scenario file (docs/scenarios.md)."""

    name: str | None = None  # default: the file's stem
    seed: Annotated[int, Meta(ge=0)] = 0
    noise: Annotated[str | ProfileTable, Meta(description="a profile name or file, or a table")] = "none"
    arena: Annotated[str, Meta(description="a file path")] | None = None
    robot: Annotated[str, Meta(description="a file path")] | None = None
    arena_jitter: NonNeg = 0.0
    candle: CandleTable | None = None
    start: StartTable | None = None
    timing: TimingTable | None = None
    firmware: dict[str, Value] | None = None  # keys: harness/firmware_config.py
    robot_overrides: dict[str, Value] | None = None  # keys: dotted robot paths (sim_plant/robot.py)
    events: Events = []
    stop_on_contact: bool = False
    furniture: Annotated[int | list[FurnitureTable],
                         Meta(description="a count or [[furniture]] tables")] | None = None
    ir_source: list[IrSourceTable] | None = None


# -- scoring (harness/data/scoring.toml) --------------------------------------------------------

Factor = Annotated[float, Meta(ge=0)]


class ModeFactorTable(Table, kw_only=True):
    return_trip: Factor
    arbitrary_start: Factor = 1.0
    furniture: Factor = 1.0


class PenaltyTable(Table, kw_only=True):
    wall_contact: Factor
    candle_knocked: Factor = 0.0


class ScoringFile(Table, kw_only=True):
    incomplete_score: Factor
    room_factor: dict[str, Factor]
    mode_factor: ModeFactorTable
    penalty: PenaltyTable

    def __post_init__(self) -> None:
        for k in self.room_factor:
            if not k.isdigit() or int(k) < 1:
                raise rule(f"room_factor.{k}", "room numbers are integers >= 1")
        if not self.room_factor:
            raise rule("room_factor", "must name at least one room")
