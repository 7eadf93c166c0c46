"""Robot parameters: body, tracked drive train, DC motors and sensor layout.

Loaded from TOML (``sim_plant/data/robot_default.toml`` documents every
default and where it came from). ``override(robot, "ir.LF.angle_deg", 40)``
changes one value by its dotted path, for scenarios and sweeps.
"""

from __future__ import annotations

import copy
import dataclasses
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from sim_plant.errors import FfrInputError
from sim_plant.file_schemas import RobotFile
from sim_plant.schema import check, read_toml

DEFAULT_ROBOT = Path(__file__).parent / "data" / "robot_default.toml"
IR_NAMES = ("CF", "LF", "RF", "LR", "RR")


@dataclass
class Body:
    length_front: float
    length_rear: float
    width: float
    height: float
    mass: float


@dataclass
class Track:
    wheel_radius: float
    track_width: float
    L_r: float
    k: float
    L_2: float
    mu: float
    wheel_inertia: float
    body_inertia: bool


@dataclass
class Motor:
    R: float
    L: float
    Kt: float
    Kb: float
    J: float
    B: float
    gear_ratio: float
    battery: float
    pwm_max: int


@dataclass
class Encoder:
    ticks_per_rev: int


@dataclass
class IrPose:
    x: float
    y: float
    angle_deg: float


@dataclass
class LineSensor:
    x: float
    y: float
    spot_radius: float
    white_fraction: float


@dataclass
class Flame:
    x: float
    y_offset: float
    height: float
    aim_deg: float
    adc_bits: int


@dataclass
class Fans:
    x: float
    reach: float
    half_angle_deg: float
    time_to_extinguish: float


@dataclass
class Slip:
    """Skid-steer slip, scrub and wall friction (docs/drivetrain.md "Reality"). The defaults are
    the ideal drive train of the paper's equations: no slip, no scrub, a wall stops the robot."""

    track_factor: float = 1.0     # chi_0: effective / geometric track width when spinning in place
    turn_radius: float = 0.10     # m: turn radius at which chi - 1 has fallen to half (chosen)
    creep: float = 0.0            # longitudinal slip fraction at the traction limit (0: none)
    floor_mu: float = 0.6         # floor traction coefficient: traction limit floor_mu * g
    scrub_mu: float = 0.0         # lateral friction coefficient of the scrub torque (0: none)
    contact_length: float = 0.12  # m, track contact length the scrub moment acts over (chosen)
    wall_mu: float = -1.0         # body-to-wall friction; < 0: no sliding (the robot stops dead)


@dataclass
class Sides:
    """Per-side scale factors on the nominal [motor] and [track] values (1 = identical sides)."""

    left_motor: float = 1.0       # scales Kt and Kb (the motor constant)
    right_motor: float = 1.0
    left_friction: float = 1.0    # scales the track's Coulomb friction torque T_f
    right_friction: float = 1.0
    left_wheel_radius: float = 1.0
    right_wheel_radius: float = 1.0


@dataclass
class Battery:
    internal_resistance: float = 0.0  # ohm; 0: an ideal source
    fan_current: float = 0.0          # A drawn while the fan runs (sags the motors' supply with R_int)


@dataclass
class Calibration:
    """What the team measured and configures the firmware with. None: exactly the robot's value."""

    wheel_radius: float | None = None
    track_width: float | None = None
    ticks_per_rev: int | None = None
    ir: dict[str, IrPose] = field(default_factory=dict)


@dataclass
class RobotParams:
    body: Body
    track: Track
    motor: Motor
    encoder: Encoder
    ir: dict[str, IrPose]
    line_sensor: LineSensor
    flame: Flame
    fans: Fans
    slip: Slip = field(default_factory=Slip)
    sides: Sides = field(default_factory=Sides)
    battery: Battery = field(default_factory=Battery)
    calibration: Calibration = field(default_factory=Calibration)
    source: str = field(default="robot", compare=False)

    @property
    def ideal_drive(self) -> bool:
        """True when none of the drive-train reality effects is on (the paper's equations)."""
        return self.slip == Slip() and self.sides == Sides() and self.battery == Battery()

    def calibrated(self) -> tuple[float, float, int, dict[str, IrPose]]:
        """(wheel radius, track width, ticks per rev, ranger poses) the firmware is configured with."""
        c = self.calibration
        return (self.track.wheel_radius if c.wheel_radius is None else c.wheel_radius,
                self.track.track_width if c.track_width is None else c.track_width,
                self.encoder.ticks_per_rev if c.ticks_per_rev is None else c.ticks_per_rev,
                {n: c.ir.get(n, self.ir[n]) for n in IR_NAMES})

    def footprint(self) -> tuple[float, float, float, float]:
        """(front, rear, left, right) extents of the body rectangle in the body frame."""
        hw = self.body.width / 2.0
        return self.body.length_front, -self.body.length_rear, hw, -hw

    def turn_radius(self) -> float:
        """The body's farthest corner from the axle midpoint (m): the circle it sweeps turning in place."""
        return math.hypot(max(self.body.length_front, self.body.length_rear), self.body.width / 2.0)


def _build(cls: type, table: Any) -> Any:
    """A model dataclass from its checked schema table (None: the dataclass's defaults)."""
    if table is None:
        return cls()
    return cls(**{f.name: getattr(table, f.name) for f in dataclasses.fields(cls)})


def robot_from_dict(data: dict[str, Any], source: str) -> RobotParams:
    """A robot from a robot file's tables (checked against ``sim_plant/file_schemas.RobotFile``)."""
    f: RobotFile = check(data, RobotFile, source)
    cal = Calibration()
    if f.calibration is not None:
        c = f.calibration
        cal = Calibration(c.wheel_radius, c.track_width, c.ticks_per_rev,
                          {n: _build(IrPose, getattr(c.ir, n)) for n in IR_NAMES
                           if c.ir is not None and getattr(c.ir, n) is not None})
    return RobotParams(
        body=_build(Body, f.body),
        track=_build(Track, f.track),
        motor=_build(Motor, f.motor),
        encoder=_build(Encoder, f.encoder),
        ir={n: _build(IrPose, getattr(f.ir, n)) for n in IR_NAMES},
        line_sensor=_build(LineSensor, f.line_sensor),
        flame=_build(Flame, f.flame),
        fans=_build(Fans, f.fans),
        slip=_build(Slip, f.slip),
        sides=_build(Sides, f.sides),
        battery=_build(Battery, f.battery),
        calibration=cal,
        source=source,
    )


def load_robot(path: str | Path | None = None) -> RobotParams:
    p = Path(path) if path is not None else DEFAULT_ROBOT
    return robot_from_dict(read_toml(p), str(p))


def robot_to_dict(robot: RobotParams) -> dict[str, Any]:
    """The robot as the dict ``robot_from_dict`` reads (a calibration's unset fields left out)."""
    data = dataclasses.asdict(robot) | {"ir": {k: dataclasses.asdict(v) for k, v in robot.ir.items()}}
    data.pop("source", None)
    cal = {k: v for k, v in data["calibration"].items() if v is not None and v != {}}
    data["calibration"] = cal
    return data


def override(robot: RobotParams, dotted: str, value: Any, source: str = "override") -> RobotParams:
    """A copy of ``robot`` with one field changed, e.g. ``"motor.R"`` or ``"ir.LF.angle_deg"``."""
    new = copy.deepcopy(robot)
    parts = dotted.split(".")
    obj: Any = new
    for p in parts[:-1]:
        obj = obj.get(p) if isinstance(obj, dict) else getattr(obj, p, None)
        if obj is None:
            raise FfrInputError(source, f"robot.{dotted}", value, "no such robot parameter")
    last = parts[-1]
    if not dataclasses.is_dataclass(obj) or last not in {f.name for f in dataclasses.fields(obj)}:
        raise FfrInputError(source, f"robot.{dotted}", value, "no such robot parameter")
    old = getattr(obj, last)
    if old is None:  # an unset calibration value: the field's type says what it takes
        ftype = str(next(f.type for f in dataclasses.fields(obj) if f.name == last))
        old = 0 if ftype.startswith("int") else 0.0
    if isinstance(old, bool):
        if not isinstance(value, bool):
            raise FfrInputError(source, f"robot.{dotted}", value, "must be true or false")
    elif isinstance(old, int):
        if isinstance(value, bool) or not isinstance(value, int | float) or int(value) != value:
            raise FfrInputError(source, f"robot.{dotted}", value, "must be an integer")
        value = int(value)
    else:
        if isinstance(value, bool) or not isinstance(value, int | float):
            raise FfrInputError(source, f"robot.{dotted}", value, "must be a number")
        value = float(value)
    setattr(obj, last, value)
    # Re-validate the whole set so an override can't produce an illegal robot.
    data = robot_to_dict(new)
    try:
        return robot_from_dict(data, source)
    except FfrInputError as exc:
        raise FfrInputError(source, f"robot.{dotted}", value, exc.why) from None
