"""Build the firmware's configuration for a simulated robot.

Start from the firmware's own defaults (``ffr_config_default``), write the
robot's geometry into it as the team calibrated it (the robot's
``[calibration]``: what was measured, by default exactly the robot's values;
under the ``realistic`` profile drawn apart from the plant's truth, see
``sim_plant/reality.py``): wheel radius, track width, encoder resolution,
ranger poses; then
apply the scenario's tuning overrides by field name.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from ffr_link.abi import CONFIG_DTYPE, CONFIG_PRIVATE, IR_COUNT
from ffr_link.ctypes_link import default_config
from sim_plant.errors import FfrInputError
from sim_plant.robot import IR_NAMES, RobotParams


def geometry_from_robot(cfg: np.ndarray, robot: RobotParams) -> None:
    """The robot's geometry as the team calibrated it (``RobotParams.calibrated``: the robot
    file's ``[calibration]``, by default exactly the robot's values), never the plant's truth."""
    wheel_radius, track_width, ticks, ir = robot.calibrated()
    cfg["wheel_radius_mm"] = wheel_radius * 1000.0
    cfg["track_width_mm"] = track_width * 1000.0
    cfg["encoder_ticks_per_rev"] = float(ticks)
    cfg["body_front_mm"] = robot.body.length_front * 1000.0
    cfg["body_half_width_mm"] = robot.body.width * 500.0
    cfg["ir_x_mm"] = [ir[n].x * 1000.0 for n in IR_NAMES]
    cfg["ir_y_mm"] = [ir[n].y * 1000.0 for n in IR_NAMES]
    cfg["ir_angle_deg"] = [ir[n].angle_deg for n in IR_NAMES]
    cfg["line_sensor_x_mm"] = robot.line_sensor.x * 1000.0


def tunable_fields() -> list[str]:
    assert CONFIG_DTYPE.names is not None
    return [n for n in CONFIG_DTYPE.names if n not in CONFIG_PRIVATE]


def apply_overrides(cfg: np.ndarray, overrides: Mapping[str, Any], source: str) -> None:
    fields = CONFIG_DTYPE.fields
    assert fields is not None
    for key, value in overrides.items():
        name = f"firmware.{key}"
        if key not in fields or key in CONFIG_PRIVATE:
            raise FfrInputError(source, name, value, "no such firmware setting (see firmware/include/ffr.h)")
        dt = fields[key][0]
        shape = dt.shape
        base = dt.base if shape else dt
        vals = value if isinstance(value, list) else [value]
        expect = shape[0] if shape else 1
        if len(vals) != expect:
            raise FfrInputError(source, name, value, f"needs {expect} value(s)")
        for v in vals:
            if isinstance(v, bool) or not isinstance(v, int | float) or v != v:
                raise FfrInputError(source, name, value, "must be a number")
            if base.kind in "ui":
                info = np.iinfo(base)
                if int(v) != v or not info.min <= v <= info.max:
                    raise FfrInputError(source, name, value, f"must be an integer in [{info.min}, {info.max}]")
        cfg[key] = vals if shape else vals[0]


def build_config(robot: RobotParams, overrides: Mapping[str, Any] | None = None,
                 source: str = "firmware", library: str | None = None) -> np.ndarray:
    cfg = default_config(library)
    geometry_from_robot(cfg, robot)
    if overrides:
        apply_overrides(cfg, overrides, source)
    assert len(IR_NAMES) == IR_COUNT
    return cfg
