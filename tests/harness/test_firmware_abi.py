"""The Python view of the firmware's structs against the library's own layout."""

from __future__ import annotations

import dataclasses

import pytest

from ffr_link import LinkError, open_link
from ffr_link.abi import (
    INPUTS_DTYPE,
    OUTPUTS_DTYPE,
    S_CONFIG,
    S_INPUTS,
    S_OUTPUTS,
    FirmwareLayoutError,
    check_layout,
)
from ffr_link.ctypes_link import DEFAULT_LIB, default_config, load_library


def test_library_layout_matches() -> None:
    _, layout = load_library(str(DEFAULT_LIB))
    check_layout(layout, "lib")
    assert layout.sizes[S_INPUTS] == INPUTS_DTYPE.itemsize == 32
    assert layout.sizes[S_CONFIG] == layout.config_dtype.itemsize == 652
    assert OUTPUTS_DTYPE.itemsize == 24
    assert layout.version >> 16 == 2


def _doctored(**change):
    _, layout = load_library(str(DEFAULT_LIB))
    rows = list(layout.rows)
    for i, f in enumerate(rows):
        if f[0] == change["sid"] and f[1] == change["name"]:
            rows[i] = (f[0], change.get("rename", f[1]), change.get("type", f[2]),
                       f[3] + change.get("shift", 0), f[4])
    return dataclasses.replace(layout, rows=rows, dtypes={})


@pytest.mark.parametrize(
    ("change", "expect"),
    [
        ({"sid": S_INPUTS, "name": "flame", "shift": 2}, "inputs.flame: offset"),
        ({"sid": S_OUTPUTS, "name": "pwm", "type": 4}, "outputs.pwm: type i4"),
        ({"sid": S_CONFIG, "name": "cruise_speed_mm_s", "type": 9}, "config.cruise_speed_mm_s: unknown type code 9"),
        ({"sid": S_CONFIG, "name": "return_start", "shift": 640}, "config.return_start: 4 x 1 bytes at offset"),
        ({"sid": S_INPUTS, "name": "line", "rename": "lines"}, "inputs.line: the library has field 'lines'"),
    ],
)
def test_mismatched_library_refused_naming_the_field(change, expect: str) -> None:
    with pytest.raises(FirmwareLayoutError, match=expect):
        check_layout(_doctored(**change), "libffr.so")


def test_missing_library_is_a_clear_error(tmp_path) -> None:
    with pytest.raises(LinkError, match="not found"):
        open_link(f"ctypes:{tmp_path / 'nope.so'}")


def test_defaults_come_from_the_firmware() -> None:
    cfg = default_config()
    assert cfg["route_len"] > 20
    assert cfg["ir_k_mv_mm"] == pytest.approx(332000.0)
    assert list(cfg["return_start"]) == sorted(cfg["return_start"])


def test_unknown_link_scheme() -> None:
    with pytest.raises(LinkError, match="unknown scheme"):
        open_link("carrier-pigeon:1")
