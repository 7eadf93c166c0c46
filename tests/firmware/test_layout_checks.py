"""The layout table's type codes are checked against the struct members at compile time
(FFR_CHECK_* in firmware/include/ffr_contract.h): a wrong row must fail the build, under the
project's C flags, and the right one must build."""

from __future__ import annotations

import os
import shutil
import subprocess
from pathlib import Path

import pytest
from ffr_firmware.build import CSTD

REPO = Path(__file__).resolve().parents[2]
CC = shutil.which("cc")
pytestmark = pytest.mark.skipif(CC is None and not os.environ.get("CI"),  # CI has cc: missing fails there
                                reason="needs a C compiler (cc)")
FLAGS = [f for f in CSTD if not f.startswith("-I")] + [
    f"-I{REPO / 'firmware' / 'include'}", f"-I{REPO / 'firmware' / 'src'}", "-c"]

_STRUCT = """
#include "ffr_contract.h"
typedef struct { uint8_t a; int16_t b; uint16_t c[3]; int32_t d; uint32_t e; float f[2]; } demo_t;
typedef struct { demo_t items[4]; float g; } outer_t;
"""
_RIGHT = [
    "FFR_CHECK_ROW(demo_t, a, U8);", "FFR_CHECK_ROW(demo_t, b, I16);", "FFR_CHECK_ARRAY(demo_t, c, U16, 3);",
    "FFR_CHECK_ROW(demo_t, d, I32);", "FFR_CHECK_ROW(demo_t, e, U32);", "FFR_CHECK_ARRAY(demo_t, f, F32, 2);",
    "FFR_CHECK_STRUCTS(outer_t, items, demo_t, 4);", "FFR_CHECK_ROW(outer_t, g, F32);",
]


def _compile(tmp_path: Path, source: str) -> subprocess.CompletedProcess[str]:
    src = tmp_path / "t.c"
    src.write_text(source)
    return subprocess.run([CC, *FLAGS, str(src), "-o", str(tmp_path / "t.o")], capture_output=True, text=True,
                          timeout=120)


def test_right_rows_compile(tmp_path: Path) -> None:
    res = _compile(tmp_path, _STRUCT + "\n".join(_RIGHT) + "\n")
    assert res.returncode == 0, res.stderr


@pytest.mark.parametrize("row", [
    "FFR_CHECK_ROW(demo_t, b, F32);",          # float for an int16_t
    "FFR_CHECK_ROW(demo_t, b, U16);",          # signedness
    "FFR_CHECK_ROW(demo_t, e, I32);",          # signedness, 32 bits
    "FFR_CHECK_ROW(demo_t, a, U16);",          # size
    "FFR_CHECK_ROW(demo_t, d, F32);",          # same size, integer vs float
    "FFR_CHECK_ROW(demo_t, f, F32);",          # a scalar row for an array
    "FFR_CHECK_ARRAY(demo_t, c, U16, 2);",     # wrong count
    "FFR_CHECK_ARRAY(demo_t, a, U8, 1);",      # an array row for a scalar
    "FFR_CHECK_STRUCTS(outer_t, items, demo_t, 3);",
    "FFR_CHECK_STRUCTS(outer_t, g, demo_t, 1);",
])
def test_a_wrong_row_is_refused_by_the_compiler(tmp_path: Path, row: str) -> None:
    res = _compile(tmp_path, _STRUCT + row + "\n")
    assert res.returncode != 0, f"{row} compiled"
    assert "error" in res.stderr


@pytest.mark.parametrize(("right", "wrong"), [
    ("S(pwm_limit, I16)", "S(pwm_limit, U16)"),
    ("S(cruise_speed_mm_s, F32)", "S(cruise_speed_mm_s, U32)"),
    ("A(ir_x_mm, F32, FFR_IR_COUNT)", "A(ir_x_mm, F32, 4)"),
    ("S(param, I16)", "S(param, U8)"),
])
def test_our_layout_table_with_a_wrong_type_code_fails_to_build(tmp_path: Path, right: str, wrong: str) -> None:
    layout = (REPO / "firmware" / "src" / "layout.c").read_text()
    assert layout.count(right) == 1
    ok = _compile(tmp_path, layout)
    assert ok.returncode == 0, ok.stderr
    res = _compile(tmp_path, layout.replace(right, wrong))
    assert res.returncode != 0 and "error" in res.stderr
