"""Robot parameters: body, tracked drive train, DC motors and sensor layout.

Loaded from TOML (``sim_plant/data/robot_default.toml`` documents every
default and where it came from). ``override(robot, "ir.LF.angle_deg", 40)``
changes one value by its dotted path, for scenarios and sweeps.
"""

from __future__ import annotations

import copy
import dataclasses
import difflib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from sim_plant.arena import _Reader, read_toml
from sim_plant.errors import FfrInputError

DEFAULT_ROBOT = Path(__file__).parent / "data" / "robot_default.toml"
IR_NAMES = ("CF", "LF", "RF", "LR", "RR")
MAX_FOOTPRINT = 0.31  # m, contest limit on length and width


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
class RobotParams:
    body: Body
    track: Track
    motor: Motor
    encoder: Encoder
    ir: dict[str, IrPose]
    line_sensor: LineSensor
    flame: Flame
    fans: Fans
    source: str = field(default="robot", compare=False)

    def footprint(self) -> tuple[float, float, float, float]:
        """(front, rear, left, right) extents of the body rectangle in the body frame."""
        hw = self.body.width / 2.0
        return self.body.length_front, -self.body.length_rear, hw, -hw


_POSITIVE = {
    "body": ("length_front", "length_rear", "width", "height", "mass"),
    "track": ("wheel_radius", "track_width", "L_r", "k", "L_2", "wheel_inertia"),
    "motor": ("R", "L", "Kt", "Kb", "J", "gear_ratio", "battery", "pwm_max"),
}


def _section(root: _Reader, name: str, cls: type) -> Any:
    sec = root.sub(name)
    kwargs: dict[str, Any] = {}
    for f in dataclasses.fields(cls):
        if f.type in ("bool", bool):
            v = sec.get(f.name)
            if not isinstance(v, bool):
                raise FfrInputError(root.source, f"{name}.{f.name}", v, "must be true or false")
            kwargs[f.name] = v
        elif f.type in ("int", int):
            v = sec.get(f.name)
            if isinstance(v, bool) or not isinstance(v, int) or v <= 0:
                raise FfrInputError(root.source, f"{name}.{f.name}", v, "must be a positive integer")
            kwargs[f.name] = v
        else:
            kwargs[f.name] = sec.number(f.name, positive=f.name in _POSITIVE.get(name, ()),
                                        lo=0.0 if f.name in ("mu", "B", "spot_radius") else None)
    unknown = set(sec.table) - {f.name for f in dataclasses.fields(cls)}
    if unknown:
        k = sorted(unknown)[0]
        raise FfrInputError(root.source, f"{name}.{k}", sec.table[k], "unknown field")
    return cls(**kwargs)


ROBOT_SECTIONS = ("body", "track", "motor", "encoder", "ir", "line_sensor", "flame", "fans")


def robot_from_dict(data: dict[str, Any], source: str) -> RobotParams:
    root = _Reader(source, data)
    unknown = sorted(set(data) - set(ROBOT_SECTIONS))
    if unknown:
        near = difflib.get_close_matches(unknown[0], ROBOT_SECTIONS, n=1)
        hint = f"did you mean {near[0]!r}? " if near else ""
        raise FfrInputError(source, unknown[0], data[unknown[0]],
                            f"unknown section ({hint}known: {', '.join(ROBOT_SECTIONS)})")
    ir_tab = root.sub("ir")
    ir = {}
    for n in IR_NAMES:
        s = ir_tab.sub(n)
        ir[n] = IrPose(s.number("x"), s.number("y"), s.number("angle_deg", lo=-360, hi=360))
    extra = set(ir_tab.table) - set(IR_NAMES)
    if extra:
        raise FfrInputError(source, f"ir.{sorted(extra)[0]}", "...", f"unknown ranger (known: {IR_NAMES})")
    robot = RobotParams(
        body=_section(root, "body", Body),
        track=_section(root, "track", Track),
        motor=_section(root, "motor", Motor),
        encoder=_section(root, "encoder", Encoder),
        ir=ir,
        line_sensor=_section(root, "line_sensor", LineSensor),
        flame=_section(root, "flame", Flame),
        fans=_section(root, "fans", Fans),
        source=source,
    )
    b = robot.body
    if b.length_front + b.length_rear > MAX_FOOTPRINT:
        raise FfrInputError(source, "body.length_front", b.length_front,
                            f"robot longer than the contest's {MAX_FOOTPRINT} m")
    if b.width > MAX_FOOTPRINT:
        raise FfrInputError(source, "body.width", b.width, f"robot wider than the contest's {MAX_FOOTPRINT} m")
    if robot.track.track_width > b.width:
        raise FfrInputError(source, "track.track_width", robot.track.track_width, "wider than the body")
    if not 0.0 < robot.line_sensor.white_fraction <= 1.0:
        raise FfrInputError(source, "line_sensor.white_fraction", robot.line_sensor.white_fraction,
                            "must be in (0, 1]")
    return robot


def load_robot(path: str | Path | None = None) -> RobotParams:
    p = Path(path) if path is not None else DEFAULT_ROBOT
    return robot_from_dict(read_toml(p), str(p))


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
    data = dataclasses.asdict(new) | {"ir": {k: dataclasses.asdict(v) for k, v in new.ir.items()}}
    data.pop("source", None)
    try:
        return robot_from_dict(data, source)
    except FfrInputError as exc:
        raise FfrInputError(source, f"robot.{dotted}", value, exc.why) from None
