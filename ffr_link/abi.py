"""The firmware's I/O and configuration structs, as numpy dtypes.

These are the Python half of the contract in ``firmware/include/ffr.h``. The
dtypes are declared here field by field (numpy's ``align=True`` lays them out
as a C compiler does) and, when a firmware library is loaded, compared with
the layout table the library exports (``ffr_layout``): a library built from
other headers is refused with a message naming the first field that differs.
"""

from __future__ import annotations

import ctypes
from dataclasses import dataclass

import numpy as np

IR_COUNT = 5
ROUTE_MAX = 48
ROOMS_MAX = 4

# ffr_struct_id_t and ffr_type_t from ffr.h
S_INPUTS, S_OUTPUTS, S_CONFIG, S_STEP = 0, 1, 2, 3
STRUCT_NAMES = {S_INPUTS: "inputs", S_OUTPUTS: "outputs", S_CONFIG: "config", S_STEP: "step"}
TYPE_CODES = {1: "u1", 2: "i2", 3: "u2", 4: "i4", 5: "u4", 6: "f4", 0: "step"}

STATE_NAMES = (
    "IDLE", "FOLLOW", "TURN", "FORWARD", "ENTER", "SCAN", "APPROACH", "EXTINGUISH",
    "VERIFY", "TO_DOOR", "EXIT", "HOMING", "DONE", "FAILED", "ORIENT",
)
ST_DONE = STATE_NAMES.index("DONE")
ST_FAILED = STATE_NAMES.index("FAILED")
FLAG_FLAME_SEEN, FLAG_EXTINGUISHED, FLAG_IN_ROOM, FLAG_DONE, FLAG_FAILED = 1, 2, 4, 8, 16
FAIL_NAMES = {0: "", 1: "no flame found", 2: "fans did not put the flame out",
              3: "doorway line not found", 4: "invalid route program", 5: "flame lost"}

# Route program opcodes, sides and events (ffr_op_t, ffr_side_t, ffr_event_t).
OPS = {"END": 0, "FOLLOW": 1, "TURN": 2, "FORWARD": 3, "ROOM": 4, "HOME": 5}
SIDES = {"LEFT": 0, "RIGHT": 1, "NONE": 2}
EVENTS = {"FRONT": 0, "OPEN_L": 1, "OPEN_R": 2, "LINE": 3}

_F = list[tuple[str, str, int]]

INPUT_FIELDS: _F = [
    ("t_ms", "u4", 1), ("seq", "u4", 1), ("enc", "i4", 2), ("ir_mv", "u2", IR_COUNT),
    ("flame", "u2", 2), ("line", "u1", 1), ("start", "u1", 1),
]
OUTPUT_FIELDS: _F = [
    ("seq", "u4", 1), ("pwm", "i2", 2), ("fan", "u1", 1), ("state", "u1", 1), ("room", "u1", 1),
    ("rooms_searched", "u1", 1), ("line_count", "u1", 1), ("flags", "u1", 1), ("step", "u1", 1),
    ("fail_code", "u1", 1), ("odo_x_mm", "i2", 1), ("odo_y_mm", "i2", 1),
    ("odo_heading_cdeg", "i2", 1), ("reserved", "i2", 1),
]
STEP_FIELDS: _F = [
    ("op", "u1", 1), ("side", "u1", 1), ("event", "u1", 1), ("arg", "u1", 1),
    ("param", "i2", 1), ("reserved", "i2", 1),
]
_CFG_FLOATS_A = [
    "wheel_radius_mm", "track_width_mm", "encoder_ticks_per_rev", "body_front_mm", "body_half_width_mm",
]
_CFG_FLOATS_B = [
    "line_sensor_x_mm", "ir_k_mv_mm", "ir_offset_mv", "ir_d0_mm", "ir_min_mm", "ir_max_mm", "ir_min_mv",
    "ff_gain_permille_per_mm_s", "ff_offset_permille", "speed_kp", "speed_ki", "accel_mm_s2",
]
_CFG_FLOATS_C = [
    "cruise_speed_mm_s", "room_speed_mm_s", "approach_speed_mm_s", "turn_rate_deg_s", "scan_rate_deg_s",
    "wall_target_mm", "wall_kp_deg_per_mm", "wall_max_deg", "heading_kp", "wall_align_gain",
    "front_stop_mm", "front_slow_mm", "open_mm", "open_confirm_mm", "wall_seen_mm", "hallway_half_mm",
    "turn_tol_deg", "line_holdoff_mm", "room_line_max_mm", "room_entry_mm", "room_exit_mm",
    "home_advance_mm", "flame_detect", "flame_out", "flame_steer_deg", "approach_stop_mm",
    "guard_side_mm", "guard_stop_mm",
]
CONFIG_FIELDS: _F = (
    [(n, "f4", 1) for n in _CFG_FLOATS_A]
    + [("ir_x_mm", "f4", IR_COUNT), ("ir_y_mm", "f4", IR_COUNT), ("ir_angle_deg", "f4", IR_COUNT)]
    + [(n, "f4", 1) for n in _CFG_FLOATS_B]
    + [("pwm_limit", "i2", 1), ("reserved0", "i2", 1)]
    + [(n, "f4", 1) for n in _CFG_FLOATS_C]
    + [("fan_timeout_ms", "u4", 1), ("flame_out_confirm_ms", "u4", 1), ("verify_ms", "u4", 1),
       ("fan_attempts", "u1", 1), ("scan_dir", "u1", 1), ("route_len", "u1", 1), ("home_wall_side", "u1", 1),
       ("route", "step", ROUTE_MAX), ("return_start", "u1", ROOMS_MAX)]
)
# Config fields a scenario may not set directly (structure, not tuning).
CONFIG_PRIVATE = {"reserved0", "route", "route_len", "return_start"}


def _dtype(fields: _F) -> np.dtype:
    spec = []
    for name, code, count in fields:
        base = STEP_DTYPE if code == "step" else np.dtype("<" + code)
        spec.append((name, base, (count,)) if count > 1 else (name, base))
    return np.dtype(spec, align=True)


STEP_DTYPE = _dtype(STEP_FIELDS)
INPUTS_DTYPE = _dtype(INPUT_FIELDS)
OUTPUTS_DTYPE = _dtype(OUTPUT_FIELDS)
CONFIG_DTYPE = _dtype(CONFIG_FIELDS)
EXPECTED = {S_INPUTS: (INPUT_FIELDS, INPUTS_DTYPE), S_OUTPUTS: (OUTPUT_FIELDS, OUTPUTS_DTYPE),
            S_CONFIG: (CONFIG_FIELDS, CONFIG_DTYPE), S_STEP: (STEP_FIELDS, STEP_DTYPE)}


class FirmwareLayoutError(RuntimeError):
    """The firmware build does not match the harness's view of its structs."""


class _Field(ctypes.Structure):
    _fields_ = [("name", ctypes.c_char_p), ("struct_id", ctypes.c_uint16), ("type", ctypes.c_uint16),
                ("offset", ctypes.c_uint16), ("count", ctypes.c_uint16)]


@dataclass(frozen=True)
class LibraryLayout:
    """What a firmware build says about itself."""

    version: int
    sizes: dict[int, int]
    fields: list[tuple[int, str, str, int, int]]  # (struct id, name, type code, offset, count)
    layout_hash: int


def read_layout(lib: ctypes.CDLL) -> LibraryLayout:
    lib.ffr_layout.restype = ctypes.POINTER(_Field)
    lib.ffr_layout.argtypes = [ctypes.POINTER(ctypes.c_uint32)]
    lib.ffr_sizeof.restype = ctypes.c_uint32
    lib.ffr_sizeof.argtypes = [ctypes.c_uint32]
    lib.ffr_version.restype = ctypes.c_uint32
    lib.ffr_layout_hash.restype = ctypes.c_uint32
    n = ctypes.c_uint32()
    ptr = lib.ffr_layout(ctypes.byref(n))
    fields = []
    for i in range(n.value):
        f = ptr[i]
        fields.append((f.struct_id, f.name.decode(), TYPE_CODES.get(f.type, f"?{f.type}"), f.offset, f.count))
    sizes = {sid: lib.ffr_sizeof(sid) for sid in (S_INPUTS, S_OUTPUTS, S_CONFIG, S_STEP, 99)}
    return LibraryLayout(lib.ffr_version(), sizes, fields, lib.ffr_layout_hash())


def check_layout(layout: LibraryLayout, source: str) -> None:
    """Raise FirmwareLayoutError naming the first field where ``layout`` differs."""
    for sid, (fields, dtype) in EXPECTED.items():
        sname = STRUCT_NAMES[sid]
        have = [(name, code, off, cnt) for s, name, code, off, cnt in layout.fields if s == sid]
        for i, (name, code, count) in enumerate(fields):
            want_off = dtype.fields[name][1]
            if i >= len(have):
                raise FirmwareLayoutError(f"{source}: {sname}.{name}: missing from the library's layout")
            hname, hcode, hoff, hcnt = have[i]
            if hname != name:
                raise FirmwareLayoutError(
                    f"{source}: {sname}.{name}: the library has field '{hname}' in its place")
            if hcode != code or hcnt != count:
                raise FirmwareLayoutError(
                    f"{source}: {sname}.{name}: type {hcode}[{hcnt}] in the library, {code}[{count}] expected")
            if hoff != want_off:
                raise FirmwareLayoutError(
                    f"{source}: {sname}.{name}: offset {hoff} in the library, {want_off} expected")
        if len(have) > len(fields):
            raise FirmwareLayoutError(f"{source}: {sname}.{have[len(fields)][0]}: unknown to the harness")
        if layout.sizes[sid] != dtype.itemsize:
            raise FirmwareLayoutError(
                f"{source}: {sname}: size {layout.sizes[sid]} in the library, {dtype.itemsize} expected")
