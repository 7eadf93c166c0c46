"""The C side of the wire: its unit tests (sanitizers on) with the shared
vectors, the firmware's coding rules, and the Cortex-M4 build of a board."""

from __future__ import annotations

import re
import shutil
import subprocess
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]


def test_c_wire_tests_pass_with_the_shared_vectors() -> None:
    build = subprocess.run(["make", "-s", "build/host/ffr_wire_tests"], cwd=REPO, capture_output=True, text=True,
                           timeout=600)
    assert build.returncode == 0, build.stderr
    run = subprocess.run([str(REPO / "build/host/ffr_wire_tests"), "tests/bridge/vectors/wire_vectors.txt"],
                         cwd=REPO, capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stdout + run.stderr
    m = re.search(r"wire: (\d+) shared vectors checked", run.stdout)
    assert m and int(m.group(1)) > 100
    m = re.search(r"wire: (\d+) passed, (\d+) failed", run.stdout)
    assert m and int(m.group(1)) > 1000 and m.group(2) == "0"


def test_codec_and_board_link_follow_the_firmware_rules() -> None:
    files = [*REPO.glob("firmware/codec/*.c"), *REPO.glob("firmware/link/*.c"),
             REPO / "firmware/include/ffr_codec.h", REPO / "firmware/include/ffr_link.h"]
    assert len(files) >= 8
    for src in files:
        code = re.sub(r"/\*.*?\*/", "", src.read_text(), flags=re.S)
        assert not re.search(r"\b(malloc|calloc|realloc|free)\s*\(", code), src
        assert not re.search(r"\bdouble\b", code), src
        assert not re.search(r"^static\s+(?!const)(?!.*\()", code, flags=re.M), f"{src}: a mutable global"
        for inc in re.findall(r'#include\s*[<"]([^>"]+)[>"]', code):
            # the contract only, never our firmware's ffr.h: the wire carries any contract firmware
            assert inc in {"ffr_contract.h", "ffr_codec.h", "ffr_link.h", "stdint.h", "stddef.h"}, (src, inc)


@pytest.mark.skipif(shutil.which("arm-none-eabi-gcc") is None,
                    reason="arm-none-eabi-gcc not installed (CI installs gcc-arm-none-eabi)")
def test_a_cortex_m4_board_with_the_wire_builds_without_warnings() -> None:
    res = subprocess.run(["make", "-s", "firmware-arm"], cwd=REPO, capture_output=True, text=True, timeout=600)
    assert res.returncode == 0 and "warning" not in res.stderr.lower(), res.stderr
    m = re.search(r"cortex-m4 with the wire board link: flash (\d+) bytes, RAM (\d+) bytes", res.stdout)
    assert m, res.stdout
    assert int(m.group(1)) < 64 * 1024 and int(m.group(2)) < 16 * 1024
