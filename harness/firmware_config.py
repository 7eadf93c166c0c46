"""Build the firmware's configuration for a simulated robot, for any firmware that meets the
contract (docs/contract.md).

The configuration's layout is the firmware's own: read from the library's layout table
(``LibraryLayout.config_dtype``), never compared with ours. Start from the bytes the firmware's
``ffr_config_default`` writes, write the robot's geometry into it as the team calibrated it (the
robot's ``[calibration]``: what was measured, by default exactly the robot's values; under the
``realistic`` profile drawn apart from the plant's truth, see ``sim_plant/reality.py``) into the
config fields with the contract's well-known names that the firmware HAS (``CALIBRATION_NAMES``),
then apply the scenario's tuning overrides by field name (``--set firmware.X=V``, a scenario's
``[firmware]``, a sweep's ``--param firmware.X=...``), each checked against the field's type.
"""

from __future__ import annotations

import difflib
from collections.abc import Mapping
from typing import Any

import numpy as np

from ffr_link.abi import IR_COUNT, LibraryLayout, type_code
from ffr_link.ctypes_link import default_config, firmware_info
from sim_plant.errors import FfrInputError
from sim_plant.robot import IR_NAMES, RobotParams

# The contract's calibration names (docs/contract.md): field -> (unit, values). The harness writes
# the robot's calibration into those the firmware's config has; a firmware without one simply does
# not get it. The GP2D12 fit's names (ir_k_mv_mm, ir_offset_mv, ir_d0_mm) are reserved with the
# same meaning but not written: the firmware's own defaults stand (as they always have for ours).
CALIBRATION_NAMES = ("wheel_radius_mm", "track_width_mm", "encoder_ticks_per_rev", "body_front_mm",
                     "body_half_width_mm", "ir_x_mm", "ir_y_mm", "ir_angle_deg", "line_sensor_x_mm")
RESERVED_CALIBRATION_NAMES = ("ir_k_mv_mm", "ir_offset_mv", "ir_d0_mm")
# The contract's mode name (docs/contract.md): where the team places the robot, which a team knows on
# the day (never the start pose). Written when the firmware's config has it: 0 at home, 1 anywhere in a
# hallway (the arbitrary start mode, ``--start hallway``).
START_AREA_FIELD = "start_area"
START_AREA_CODES = {"home": 0, "hallway": 1}
# Our firmware's structure, not tuning: filled by its own ffr_config_default, never by --set.
REFERENCE_PRIVATE = frozenset({"route_len", "return_start"})


def calibration_values(robot: RobotParams) -> dict[str, float | list[float]]:
    """The robot's geometry as the team calibrated it (``RobotParams.calibrated``: the robot file's
    ``[calibration]``, by default exactly the robot's values), never the plant's truth; in the
    contract's units (mm, degrees, counts per wheel revolution)."""
    wheel_radius, track_width, ticks, ir = robot.calibrated()
    assert len(IR_NAMES) == IR_COUNT
    return {
        "wheel_radius_mm": wheel_radius * 1000.0,
        "track_width_mm": track_width * 1000.0,
        "encoder_ticks_per_rev": float(ticks),
        "body_front_mm": robot.body.length_front * 1000.0,
        "body_half_width_mm": robot.body.width * 500.0,
        "ir_x_mm": [ir[n].x * 1000.0 for n in IR_NAMES],
        "ir_y_mm": [ir[n].y * 1000.0 for n in IR_NAMES],
        "ir_angle_deg": [ir[n].angle_deg for n in IR_NAMES],
        "line_sensor_x_mm": robot.line_sensor.x * 1000.0,
    }


def geometry_from_robot(cfg: np.ndarray, robot: RobotParams) -> None:
    """Write the calibration into the fields of ``cfg`` (any firmware's config) with the contract's
    names; an integer field gets the value rounded to the nearest integer."""
    fields = cfg.dtype.fields or {}
    for name, value in calibration_values(robot).items():
        if name not in fields:
            continue
        dt = fields[name][0]
        shape = dt.shape
        want = shape[0] if shape else 1
        vals = value if isinstance(value, list) else [value]
        if len(vals) != want:
            raise FfrInputError("firmware", f"firmware.{name}", f"{want} value(s)",
                                f"the contract's calibration field holds {len(vals)} (docs/contract.md)")
        base = dt.base if shape else dt
        if base.kind in "ui":
            vals = [int(round(v)) for v in vals]
        cfg[name] = vals if shape else vals[0]


def _private(name: str, dt: np.dtype, firmware: LibraryLayout | None) -> bool:
    """Not settable by name: reserved padding, arrays of sub-structs, our route's structure."""
    base = dt.base if dt.shape else dt
    return (name.startswith("reserved") or base.names is not None
            or (firmware is not None and firmware.is_reference and name in REFERENCE_PRIVATE))


def tunable_fields(firmware: LibraryLayout | None = None) -> list[str]:
    fw = firmware or firmware_info()
    dt = fw.config_dtype
    return [n for n in dt.names or () if not _private(n, dt.fields[n][0], fw)]  # type: ignore[index]


def describe_fields(firmware: LibraryLayout | None = None, cfg: np.ndarray | None = None) -> list[str]:
    """One line per settable config field: name, type[count], default (ffr run --list-firmware-config)."""
    fw = firmware or firmware_info()
    if cfg is None:
        cfg = default_config_of(fw)
    lines = []
    for name in tunable_fields(fw):
        dt = cfg.dtype.fields[name][0]  # type: ignore[index]
        base = dt.base if dt.shape else dt
        kind = {"f": "float", "u": "unsigned", "i": "integer"}[base.kind]
        code = type_code({np.dtype("u1"): 1, np.dtype("<i2"): 2, np.dtype("<u2"): 3, np.dtype("<i4"): 4,
                          np.dtype("<u4"): 5, np.dtype("<f4"): 6}.get(base.newbyteorder("<"), 6))
        v = cfg[name]
        val = "[" + ", ".join(_fmt(x) for x in np.ravel(v)) + "]" if dt.shape else _fmt(v)
        lines.append(f"{name:<28} {code}{'[' + str(dt.shape[0]) + ']' if dt.shape else '':<4} {kind:<9} {val}")
    return lines


def _fmt(v: Any) -> str:
    return f"{float(v):.9g}" if np.asarray(v).dtype.kind == "f" else str(int(v))


def default_config_of(firmware: LibraryLayout | None) -> np.ndarray:
    """``ffr_config_default``'s bytes of that firmware (None: $FFR_FIRMWARE_LIB, else ours)."""
    return default_config(firmware.path if firmware is not None and firmware.path else None)


def apply_overrides(cfg: np.ndarray, overrides: Mapping[str, Any], source: str,
                    firmware: LibraryLayout | None = None) -> None:
    """Set fields of ``cfg`` (a record of the firmware's config dtype) by name, each checked:
    an unknown or private name is refused with a "did you mean", a value against the field's
    type and range; FfrInputError (one line, exit 2) otherwise."""
    fields = cfg.dtype.fields
    assert fields is not None
    fw = firmware or firmware_info()
    for key, value in overrides.items():
        name = f"firmware.{key}"
        if key not in fields or _private(key, fields[key][0], fw):
            close = difflib.get_close_matches(key, tunable_fields(fw), n=1, cutoff=0.6)
            hint = f"; did you mean '{close[0]}'?" if close else ""
            raise FfrInputError(source, name, value,
                                f"no such setting in the firmware '{fw.firmware_name}'{hint} "
                                f"(ffr run --list-firmware-config)")
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
            else:
                fmax = float(np.finfo(base).max)
                if not -fmax <= v <= fmax:
                    raise FfrInputError(source, name, value, f"must be a finite number in [{-fmax:g}, {fmax:g}]")
        cfg[key] = vals if shape else vals[0]


def build_config(robot: RobotParams, overrides: Mapping[str, Any] | None = None,
                 source: str = "firmware", library: str | None = None,
                 firmware: LibraryLayout | None = None, start_area: str = "home") -> np.ndarray:
    """The configuration for one mission: the firmware's defaults, the calibration, the start area
    (the contest's mode, ``START_AREA_FIELD`` if the firmware has it; at home it stays the firmware's
    default), the overrides. ``firmware``: the loaded library's description (``link.firmware``); else
    ``library``'s."""
    if firmware is not None:
        cfg = default_config_of(firmware)
    else:
        cfg = default_config(library)
        firmware = firmware_info(library)
    geometry_from_robot(cfg, robot)
    if start_area != "home" and START_AREA_FIELD in (cfg.dtype.fields or {}):
        cfg[START_AREA_FIELD] = START_AREA_CODES[start_area]
    if overrides:
        apply_overrides(cfg, overrides, source, firmware)
    return cfg
