"""The firmware contract's Python half (``firmware/include/ffr_contract.h``, docs/contract.md).

The I/O structs are fixed by the contract: their dtypes are declared here field by field
(numpy's ``align=True`` lays them out as a C compiler does) and compared with the layout table a
library exports (``ffr_layout``); a library built from other headers is refused with a message
naming the first field that differs. The configuration is the firmware's own: its dtype is READ
from the same table (never compared with ours), and so are the names of its states and failure
codes (``ffr_names``) and its name (``ffr_firmware_name``).
"""

from __future__ import annotations

import ctypes
from dataclasses import dataclass, field

import numpy as np

CONTRACT_MAJOR = 2  # FFR_CONTRACT_MAJOR: the contract this harness speaks
CONFIG_MAX = 1024   # FFR_CONFIG_MAX: the most configuration bytes a board takes
IR_COUNT = 5

# struct ids and element types of ffr_contract.h
S_INPUTS, S_OUTPUTS, S_CONFIG, S_OWN, S_STATE = 0, 1, 2, 16, 99
STRUCT_NAMES = {S_INPUTS: "inputs", S_OUTPUTS: "outputs", S_CONFIG: "config"}
T_STRUCT = 0
TYPE_CODES = {1: "u1", 2: "i2", 3: "u2", 4: "i4", 5: "u4", 6: "f4"}
TYPE_IDS = {v: k for k, v in TYPE_CODES.items()}
NAMES_STATE, NAMES_FAIL, NAMES_OWN = 0, 1, 16
FLAG_FLAME_SEEN, FLAG_EXTINGUISHED, FLAG_IN_ROOM, FLAG_DONE, FLAG_FAILED = 1, 2, 4, 8, 16
REFERENCE_PREFIX = "ffr-reference"  # ffr_firmware_name() of our own firmware (firmware/)

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


def _dtype(fields: _F) -> np.dtype:
    spec = []
    for name, code, count in fields:
        base = np.dtype("<" + code)
        spec.append((name, base, (count,)) if count > 1 else (name, base))
    return np.dtype(spec, align=True)


INPUTS_DTYPE = _dtype(INPUT_FIELDS)
OUTPUTS_DTYPE = _dtype(OUTPUT_FIELDS)
EXPECTED = {S_INPUTS: (INPUT_FIELDS, INPUTS_DTYPE), S_OUTPUTS: (OUTPUT_FIELDS, OUTPUTS_DTYPE)}


class FirmwareLayoutError(RuntimeError):
    """The firmware build does not meet the contract (or not the harness's view of its I/O)."""


class _Field(ctypes.Structure):
    _fields_ = [("name", ctypes.c_char_p), ("struct_id", ctypes.c_uint16), ("type", ctypes.c_uint16),
                ("offset", ctypes.c_uint16), ("count", ctypes.c_uint16)]


Row = tuple[int, str, int, int, int]  # (struct id, name, type id as in the table, offset, count)


@dataclass(frozen=True)
class LibraryLayout:
    """What a firmware build says about itself (read from the library, or from a board)."""

    version: int
    sizes: dict[int, int]               # struct id -> ffr_sizeof (inputs, outputs, config, own, 99 = state)
    rows: list[Row]                     # the layout table, in order
    layout_hash: int
    names: dict[int, tuple[str, ...]] = field(default_factory=dict)  # kind -> names
    firmware_name: str = ""
    path: str = ""                      # the library it was read from ("" for a board's)
    dtypes: dict[int, np.dtype] = field(default_factory=dict, compare=False, repr=False)

    @property
    def fields(self) -> list[tuple[int, str, str, int, int]]:
        """(struct id, name, type code, offset, count); type code 'u1'...'f4', 'sNN' = sub-struct NN."""
        return [(s, n, type_code(t), o, c) for s, n, t, o, c in self.rows]

    @property
    def config_dtype(self) -> np.dtype:
        return self.dtypes[S_CONFIG]

    @property
    def state_names(self) -> tuple[str, ...]:
        return self.names.get(NAMES_STATE, ())

    @property
    def fail_names(self) -> tuple[str, ...]:
        return self.names.get(NAMES_FAIL, ())

    @property
    def is_reference(self) -> bool:
        """Our own firmware (firmware/): its private fields (the route program) are ours to fill."""
        return self.firmware_name.startswith(REFERENCE_PREFIX)

    def state_name(self, code: int) -> str:
        s = self.state_names
        return s[code] if 0 <= code < len(s) else f"state {code}"

    def fail_name(self, code: int) -> str:
        f = self.fail_names
        return f[code] if 0 <= code < len(f) and f[code] else f"code {code}"


def type_code(t: int) -> str:
    if t & 0xFF == T_STRUCT:
        return f"s{t >> 8}"
    return TYPE_CODES.get(t, f"?{t}")


def read_layout(lib: ctypes.CDLL, path: str = "") -> LibraryLayout:
    """Everything the library describes about itself (AttributeError: a function is missing)."""
    lib.ffr_layout.restype = ctypes.POINTER(_Field)
    lib.ffr_layout.argtypes = [ctypes.POINTER(ctypes.c_uint32)]
    lib.ffr_sizeof.restype = ctypes.c_uint32
    lib.ffr_sizeof.argtypes = [ctypes.c_uint32]
    lib.ffr_version.restype = ctypes.c_uint32
    lib.ffr_version.argtypes = []
    lib.ffr_layout_hash.restype = ctypes.c_uint32
    lib.ffr_layout_hash.argtypes = []
    lib.ffr_names.restype = ctypes.POINTER(ctypes.c_char_p)
    lib.ffr_names.argtypes = [ctypes.c_uint32, ctypes.POINTER(ctypes.c_uint32)]
    lib.ffr_firmware_name.restype = ctypes.c_char_p
    lib.ffr_firmware_name.argtypes = []
    n = ctypes.c_uint32()
    ptr = lib.ffr_layout(ctypes.byref(n))
    rows: list[Row] = []
    for i in range(n.value):
        f = ptr[i]
        rows.append((f.struct_id, (f.name or b"").decode("utf-8", "replace"), f.type, f.offset, f.count))
    sids = {S_INPUTS, S_OUTPUTS, S_CONFIG, S_STATE} | {r[2] >> 8 for r in rows if r[2] & 0xFF == T_STRUCT}
    sizes = {sid: int(lib.ffr_sizeof(sid)) for sid in sorted(sids)}
    names: dict[int, tuple[str, ...]] = {}
    for kind in range(256):
        cnt = ctypes.c_uint32(0)
        p = lib.ffr_names(kind, ctypes.byref(cnt))
        if p and cnt.value:
            names[kind] = tuple((p[i] or b"").decode("utf-8", "replace") for i in range(cnt.value))
    fw_name = (lib.ffr_firmware_name() or b"").decode("utf-8", "replace")
    return LibraryLayout(int(lib.ffr_version()), sizes, rows, int(lib.ffr_layout_hash()), names, fw_name, path)


def contract_hash(layout: LibraryLayout) -> int:
    """The contract's layout hash (docs/contract.md) over what the library describes: equal to its
    ``ffr_layout_hash()`` for a firmware that follows the documented recipe (ours does)."""
    h = 2166136261

    def fnv(v: int, nbytes: int) -> None:
        nonlocal h
        for i in range(nbytes):
            h ^= (v >> (8 * i)) & 0xFF
            h = (h * 16777619) & 0xFFFFFFFF

    def fnv_str(s: str) -> None:
        for ch in s.encode():
            fnv(ch, 1)
        fnv(0, 1)

    for sid, name, t, off, cnt in layout.rows:
        for ch in name.encode():
            fnv(ch, 1)
        for v in (sid, t, off, cnt):
            fnv(v, 2)
    for sid in (S_INPUTS, S_OUTPUTS, S_CONFIG):
        fnv(layout.sizes.get(sid, 0), 4)
    for _, _, t, _, _ in layout.rows:
        if t & 0xFF == T_STRUCT:
            fnv(layout.sizes.get(t >> 8, 0), 4)
    for kind in sorted(layout.names):
        names = layout.names[kind]
        fnv(kind, 2)
        fnv(len(names), 2)
        for s in names:
            fnv_str(s)
    fnv_str(layout.firmware_name)
    return h


def _struct_dtype(layout: LibraryLayout, sid: int, source: str, depth: int = 0) -> np.dtype:
    """A struct's dtype from the library's rows: names, element types, offsets, its size."""
    what = STRUCT_NAMES.get(sid, f"struct {sid}")
    if depth > 4:
        raise FirmwareLayoutError(f"{source}: {what}: sub-structs nested too deep")
    size = layout.sizes.get(sid, 0)
    names, formats, offsets = [], [], []
    for s, name, t, off, cnt in layout.rows:
        if s != sid:
            continue
        if not name.isidentifier() or name in names:
            raise FirmwareLayoutError(f"{source}: {what}.{name!r}: not a valid, unique field name")
        if t & 0xFF == T_STRUCT:
            sub = t >> 8
            if sub < S_OWN or sub == S_STATE or layout.sizes.get(sub, 0) == 0:
                raise FirmwareLayoutError(f"{source}: {what}.{name}: sub-struct id {sub} unknown to ffr_sizeof")
            base = _struct_dtype(layout, sub, source, depth + 1)
        elif t in TYPE_CODES:
            base = np.dtype("<" + TYPE_CODES[t])
        else:
            raise FirmwareLayoutError(f"{source}: {what}.{name}: unknown type code {t}")
        if cnt < 1 or off + base.itemsize * cnt > size:
            raise FirmwareLayoutError(
                f"{source}: {what}.{name}: {cnt} x {base.itemsize} bytes at offset {off} outside its {size} bytes")
        names.append(name)
        formats.append((base, (cnt,)) if cnt > 1 else base)
        offsets.append(off)
    try:
        return np.dtype({"names": names, "formats": formats, "offsets": offsets, "itemsize": size})
    except ValueError as exc:  # overlapping fields
        raise FirmwareLayoutError(f"{source}: {what}: {exc}") from None


def check_layout(layout: LibraryLayout, source: str) -> None:
    """Raise FirmwareLayoutError when ``layout`` does not meet the contract: the version's major,
    the fixed I/O field by field (naming the first that differs), the config's limits, the names.
    Fills ``layout.dtypes`` with the config's (and its sub-structs') dtypes, read from the table."""
    major = layout.version >> 16
    if major != CONTRACT_MAJOR:
        raise FirmwareLayoutError(
            f"{source}: firmware contract {major}.{layout.version & 0xFFFF}, the harness speaks "
            f"{CONTRACT_MAJOR}.x (docs/contract.md)")
    for sid, (fields, dtype) in EXPECTED.items():
        sname = STRUCT_NAMES[sid]
        have = [(name, type_code(t), off, cnt) for s, name, t, off, cnt in layout.rows if s == sid]
        for i, (name, code, count) in enumerate(fields):
            want_off = dtype.fields[name][1]  # type: ignore[index]
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
        if layout.sizes.get(sid) != dtype.itemsize:
            raise FirmwareLayoutError(
                f"{source}: {sname}: size {layout.sizes.get(sid)} in the library, {dtype.itemsize} expected")
    csize = layout.sizes.get(S_CONFIG, 0)
    if not 0 < csize <= CONFIG_MAX:
        raise FirmwareLayoutError(f"{source}: config: size {csize}, 1..{CONFIG_MAX} (FFR_CONFIG_MAX) allowed")
    if layout.sizes.get(S_STATE, 0) == 0:
        raise FirmwareLayoutError(f"{source}: state: ffr_sizeof(99) is 0")
    if not layout.state_names:
        raise FirmwareLayoutError(f"{source}: ffr_names(FFR_NAMES_STATE) is empty")
    if not layout.fail_names or layout.fail_names[0] != "":
        raise FirmwareLayoutError(f"{source}: ffr_names(FFR_NAMES_FAIL) must start with \"\" (code 0 = none)")
    layout.dtypes[S_CONFIG] = _struct_dtype(layout, S_CONFIG, source)
