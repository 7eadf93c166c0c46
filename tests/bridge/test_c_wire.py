"""The C side of the wire: its unit tests (sanitizers on) with the shared
vectors, the firmware's coding rules, and the Cortex-M4 build of a board."""

from __future__ import annotations

import re
import shutil
import subprocess
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
WIRE_TESTS = REPO / "build/host/ffr_wire_tests"
VECTORS = "tests/bridge/vectors/wire_vectors.txt"
# the C wire tests: suites (one a file but main.c) and named tests (firmware/tests/wire/main.c prints both)
WIRE_SUITES = 3
WIRE_TESTS_COUNT = 52


def _build() -> None:
    build = subprocess.run(["make", "-s", "build/host/ffr_wire_tests"], cwd=REPO, capture_output=True, text=True,
                           timeout=600)
    assert build.returncode == 0, build.stderr


def _run(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run([str(WIRE_TESTS), *args], cwd=REPO, capture_output=True, text=True, timeout=120)


def _vector_lines() -> int:
    lines = (REPO / VECTORS).read_text().splitlines()
    return sum(1 for line in lines if line and not line.startswith("#"))


def test_c_wire_tests_pass_with_the_shared_vectors() -> None:
    _build()
    run = _run("--vectors", VECTORS)
    assert run.returncode == 0, run.stdout + run.stderr
    m = re.search(r"wire: (\d+) shared vectors checked", run.stdout)
    # every vector line of the file (pytest checks the Python codec against the same lines)
    assert m and int(m.group(1)) == _vector_lines() > 100, run.stdout
    m = re.search(r"wire: (\d+) suites, (\d+) tests \((\d+) failed\), (\d+) checks passed, (\d+) failed",
                  run.stdout)
    assert m, run.stdout
    # exact: a suite or test added (or lost) changes these; update them with it
    assert (int(m.group(1)), int(m.group(2))) == (WIRE_SUITES, WIRE_TESTS_COUNT)
    assert m.group(3) == "0" and m.group(5) == "0" and int(m.group(4)) > 1000
    listed = _run("--list").stdout.split()
    assert len(listed) == WIRE_TESTS_COUNT and len(set(listed)) == WIRE_TESTS_COUNT  # every test named, once
    assert {name.split(".")[0] for name in listed} == {"codec", "board_link", "vectors"}
    # one suite a file, every file's suite run (main.c lists them)
    assert len(list((REPO / "firmware/tests/wire").glob("test_*.c"))) == WIRE_SUITES


def test_a_failed_c_wire_check_names_its_test() -> None:
    _build()
    run = _run("--demo-failure")
    assert run.returncode == 1
    assert re.search(r"^FAIL firmware/tests/wire/main\.c:\d+: wire_demo\.a_check_that_fails_on_purpose: 1 \+ 1 == 3$",
                     run.stdout, re.M), run.stdout


def test_a_bad_shared_vector_fails_its_kind_s_test_naming_its_line(tmp_path: Path) -> None:
    _build()
    lines = (REPO / VECTORS).read_text().splitlines()
    k = next(i for i, line in enumerate(lines) if line.startswith("frame "))
    kind, msg, frame = lines[k].split()
    # one bit flipped in the frame's last byte before its delimiter
    lines[k] = f"{kind} {msg} {frame[:-4]}{(int(frame[-4:-2], 16) ^ 1):02x}{frame[-2:]}"
    bad = tmp_path / "vectors.txt"
    bad.write_text("\n".join(lines) + "\n")
    run = _run("--vectors", str(bad))
    assert run.returncode == 1
    assert f"{bad}:{k + 1}: frame vector failed" in run.stdout, run.stdout
    test = "vectors.every_frame_vector_encodes_and_decodes"
    assert re.search(rf"^FAIL firmware/tests/wire/test_vectors\.c:\d+: {re.escape(test)}: ok$", run.stdout, re.M), \
        run.stdout
    assert f"wire: {WIRE_SUITES} suites, {WIRE_TESTS_COUNT} tests (1 failed)" in run.stdout


def test_one_c_wire_test_runs_alone_by_its_name() -> None:
    _build()
    run = _run("board_link.watchdog_zero_is_off")
    assert run.returncode == 0, run.stdout
    assert "wire: 1 suites, 1 tests (0 failed), 1 checks passed, 0 failed" in run.stdout
    run = _run("no_such_suite")
    assert run.returncode == 1 and "wire: 0 suites, 0 tests" in run.stdout


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
