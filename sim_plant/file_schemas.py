"""Schemas of the plant-side input files: arena, robot (with ``[calibration]``) and noise profiles.

Declared once here, checked by ``sim_plant.schema.check`` in every loader (docs/inputs.md: how to add
a field). Types, ranges and cross-field rules live here; the loaders build the model's dataclasses
from the checked data. A struct's field defaults are the model's defaults.
"""

from __future__ import annotations

from typing import Annotated, Literal

from msgspec import Meta, Struct

from sim_plant.schema import rule

# -- shared field types ---------------------------------------------------------------------------

Point = Annotated[tuple[float, float], Meta(description="a point [x, y]")]
Segment = Annotated[tuple[Point, Point], Meta(description="a segment [[x, y], [x, y]]")]
Polygon = Annotated[list[Point], Meta(min_length=3, description="a polygon [[x, y], ...] (3+ points)")]
Positive = Annotated[float, Meta(gt=0)]
NonNeg = Annotated[float, Meta(ge=0)]
PositiveInt = Annotated[int, Meta(gt=0)]
Prob = Annotated[float, Meta(ge=0, le=1)]
Angle = Annotated[float, Meta(ge=-360, le=360)]

# Candle placement rules by rules edition (``[arena] placement`` in an arena file, docs/arena.md):
# - "entry-depth": later editions' text: the candle's circle does not touch the doorway line, and
#   the robot's front can move ``candle_min_depth`` (33 cm) into the room before reaching it;
# - "door-line": the 2001 contest plan: the circle only must not touch the doorway line (a candle
#   may stand just beside a door, as two of that plan's four candle targets do).
PLACEMENT_RULES = ("entry-depth", "door-line")
MAX_FOOTPRINT = 0.31  # m, the contest's limit on the robot's length and width


class Table(Struct, forbid_unknown_fields=True, kw_only=True):
    """Every table refuses unknown keys; fields are given by name."""


# -- arena files (sim_plant/data/arena_*.toml, docs/arena.md) -----------------------------------

class ArenaTable(Table, kw_only=True):
    name: str | None = None  # default: the file's stem
    size: Point
    wall_height: Positive
    line_width: Positive
    candle_circle_radius: Positive
    candle_min_depth: NonNeg = 0.33
    candle_base_radius: Annotated[float, Meta(ge=0, le=0.15)] = 0.0
    candle_radius: Positive = 0.0125
    flame_height: Positive = 0.175
    placement: Literal[PLACEMENT_RULES] = "entry-depth"

    def __post_init__(self) -> None:
        if self.size[0] <= 0 or self.size[1] <= 0:
            raise rule("size", "must be positive")


class HomeTable(Table, kw_only=True):
    center: Point
    radius: Positive
    heading_deg: float = 90.0


class WallTable(Table, kw_only=True):
    name: str = "wall"
    a: Point
    b: Point
    t: Positive

    def __post_init__(self) -> None:
        if self.a == self.b:
            raise rule("b", "wall has zero length")


class RoomTable(Table, kw_only=True):
    id: Annotated[int, Meta(ge=1)]
    name: str | None = None  # default: room<id>
    polygon: Polygon
    door: Segment
    default_candle: Point


class HallwayTable(Table, kw_only=True):
    name: str = "hallway"
    polygon: Polygon


class ArenaFile(Table, kw_only=True):
    arena: ArenaTable
    home: HomeTable
    walls: Annotated[list[WallTable], Meta(min_length=1)]
    rooms: Annotated[list[RoomTable], Meta(min_length=1)]
    hallways: Annotated[list[HallwayTable], Meta(min_length=1)]

    def __post_init__(self) -> None:
        seen: set[int] = set()
        for i, r in enumerate(self.rooms):
            if r.id in seen:
                raise rule(f"rooms[{i}].id", "must be a unique integer >= 1")
            seen.add(r.id)


# -- robot files (sim_plant/data/robot_default.toml, docs/drivetrain.md) ------------------------

class BodyTable(Table, kw_only=True):
    length_front: Positive
    length_rear: Positive
    width: Positive
    height: Positive
    mass: Positive


class TrackTable(Table, kw_only=True):
    wheel_radius: Positive
    track_width: Positive
    L_r: Positive
    k: Positive
    L_2: Positive
    mu: NonNeg
    wheel_inertia: Positive
    body_inertia: bool


class MotorTable(Table, kw_only=True):
    R: Positive
    L: Positive
    Kt: Positive
    Kb: Positive
    J: Positive
    B: NonNeg
    gear_ratio: Positive
    battery: Positive
    pwm_max: PositiveInt


class EncoderTable(Table, kw_only=True):
    ticks_per_rev: PositiveInt


class IrPoseTable(Table, kw_only=True):
    x: float
    y: float
    angle_deg: Angle


class IrTable(Table, kw_only=True):
    """The five GP2D12 rangers (sim_plant.robot.IR_NAMES), each one's pose."""

    CF: IrPoseTable
    LF: IrPoseTable
    RF: IrPoseTable
    LR: IrPoseTable
    RR: IrPoseTable


class LineSensorTable(Table, kw_only=True):
    x: float
    y: float
    spot_radius: NonNeg
    white_fraction: Annotated[float, Meta(gt=0, le=1)]


class FlameTable(Table, kw_only=True):
    x: float
    y_offset: float
    height: float
    aim_deg: float
    adc_bits: PositiveInt


class FansTable(Table, kw_only=True):
    x: float
    reach: float
    half_angle_deg: float
    time_to_extinguish: float


class SlipTable(Table, kw_only=True):
    track_factor: Annotated[float, Meta(ge=1, le=3)] = 1.0
    turn_radius: Positive = 0.10
    creep: Annotated[float, Meta(ge=0, lt=1)] = 0.0
    floor_mu: Positive = 0.6
    scrub_mu: NonNeg = 0.0
    contact_length: Positive = 0.12
    wall_mu: float = -1.0


class SidesTable(Table, kw_only=True):
    left_motor: Positive = 1.0
    right_motor: Positive = 1.0
    left_friction: Positive = 1.0
    right_friction: Positive = 1.0
    left_wheel_radius: Positive = 1.0
    right_wheel_radius: Positive = 1.0


class BatteryTable(Table, kw_only=True):
    internal_resistance: NonNeg = 0.0
    fan_current: NonNeg = 0.0


class CalibrationIrTable(Table, kw_only=True):
    CF: IrPoseTable | None = None
    LF: IrPoseTable | None = None
    RF: IrPoseTable | None = None
    LR: IrPoseTable | None = None
    RR: IrPoseTable | None = None


class CalibrationTable(Table, kw_only=True):
    wheel_radius: Positive | None = None
    track_width: Positive | None = None
    ticks_per_rev: PositiveInt | None = None
    ir: CalibrationIrTable | None = None


class RobotFile(Table, kw_only=True):
    body: BodyTable
    track: TrackTable
    motor: MotorTable
    encoder: EncoderTable
    ir: IrTable
    line_sensor: LineSensorTable
    flame: FlameTable
    fans: FansTable
    slip: SlipTable | None = None
    sides: SidesTable | None = None
    battery: BatteryTable | None = None
    calibration: CalibrationTable | None = None

    def __post_init__(self) -> None:
        b = self.body
        if b.length_front + b.length_rear > MAX_FOOTPRINT:
            raise rule("body.length_front", f"robot longer than the contest's {MAX_FOOTPRINT} m")
        if b.width > MAX_FOOTPRINT:
            raise rule("body.width", f"robot wider than the contest's {MAX_FOOTPRINT} m")
        if self.track.track_width > b.width:
            raise rule("track.track_width", "wider than the body")


# -- noise profiles (sim_plant/data/noise_profiles.toml, docs/sensors.md) -----------------------

class AnalogNoiseTable(Table, kw_only=True):
    sigma: NonNeg = 0.0
    bias: float = 0.0
    quant_step: NonNeg = 0.0
    dropout_prob: Prob = 0.0
    dropout_mode: Literal["zero", "hold"] = "zero"
    spike_prob: Prob = 0.0
    spike_amp: NonNeg = 0.0
    unit_gain_spread: Annotated[float, Meta(ge=0, lt=1)] = 0.0
    unit_offset_spread: NonNeg = 0.0
    unit_pivot: float = 0.0

    def __post_init__(self) -> None:
        if self.dropout_prob + self.spike_prob > 1.0:
            raise rule("spike_prob", "dropout_prob + spike_prob must be <= 1")


class LineNoiseTable(Table, kw_only=True):
    flip_prob: Prob = 0.0


class EncoderNoiseTable(Table, kw_only=True):
    slip_prob: Prob = 0.0
    slip_fraction: Prob = 0.0


class RangerTable(Table, kw_only=True):
    beam_half_angle_deg: Annotated[float, Meta(ge=0, le=30)] = 2.0  # BEAM_HALF_ANGLE_DEG
    beam_rays: Annotated[int, Meta(ge=1, le=64)] = 5
    latency: bool = False
    period_spread: Annotated[float, Meta(ge=0, le=0.03)] = 0.0
    random_phase: bool = False


class FlameWorldTable(Table, kw_only=True):
    strength_min: Annotated[float, Meta(ge=0, le=100)] = 1.0
    strength_max: Annotated[float, Meta(ge=0, le=100)] = 1.0
    flicker_amp: Prob = 0.0
    flicker_hz: Annotated[float, Meta(ge=0, le=50)] = 1.5
    wall_reflectance: Prob = 0.0
    afterglow_s: Annotated[float, Meta(ge=0, le=10)] = 0.0

    def __post_init__(self) -> None:
        if self.strength_max < self.strength_min:
            raise rule("strength_max", f"must be >= strength_min ({self.strength_min})")


def _range(lo: float, hi: float) -> object:
    """A [lo, hi] range whose ends lie within [lo, hi] (the reality group's ranges)."""
    end = Annotated[float, Meta(ge=lo, le=hi)]
    return Annotated[tuple[end, end], Meta(description=f"a range [lo, hi] within [{lo:g}, {hi:g}]")]


Spread = Annotated[float, Meta(ge=0, lt=1)]
MountSpread = Annotated[float, Meta(ge=0, lt=90)]


class RealityTable(Table, kw_only=True):
    """sim_plant/reality.py: ranges of the plant's truth and the team's calibration error."""

    track_factor: _range(1.0, 3.0) = (1.0, 1.0)  # type: ignore[valid-type]
    turn_radius: _range(1e-3, 10.0) = (0.10, 0.10)  # type: ignore[valid-type]
    creep: _range(0.0, 0.9) = (0.0, 0.0)  # type: ignore[valid-type]
    floor_mu: _range(0.05, 2.0) = (0.6, 0.6)  # type: ignore[valid-type]
    scrub_mu: _range(0.0, 2.0) = (0.0, 0.0)  # type: ignore[valid-type]
    wall_mu: _range(0.0, 2.0) = (-1.0, -1.0)  # type: ignore[valid-type]
    internal_resistance: _range(0.0, 10.0) = (0.0, 0.0)  # type: ignore[valid-type]
    fan_current: _range(0.0, 10.0) = (0.0, 0.0)  # type: ignore[valid-type]
    motor_spread: Spread = 0.0
    side_motor: Spread = 0.0
    side_friction: Spread = 0.0
    side_wheel_radius: Spread = 0.0
    ir_mount_mm: MountSpread = 0.0
    ir_mount_deg: MountSpread = 0.0
    cal_wheel_radius: Spread = 0.0
    cal_track_width: Spread = 0.0

    def __post_init__(self) -> None:
        for name in ("track_factor", "turn_radius", "creep", "floor_mu", "scrub_mu", "wall_mu",
                     "internal_resistance", "fan_current"):
            r = getattr(self, name)
            if r[0] > r[1]:
                raise rule(name, "must satisfy lo <= hi")


class ProfileTable(Table, kw_only=True):
    """One noise profile: a top-level table of a profiles file, or a scenario's inline ``[noise]``."""

    description: str = ""
    ir: AnalogNoiseTable | None = None
    flame: AnalogNoiseTable | None = None
    line: LineNoiseTable | None = None
    encoder: EncoderNoiseTable | None = None
    ranger: RangerTable | None = None
    flame_world: FlameWorldTable | None = None
    reality: RealityTable | None = None


NoiseFile = dict[str, ProfileTable]  # profile name -> profile
