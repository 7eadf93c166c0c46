"""The firmware's own C unit tests (plain inputs, no plant), built with
AddressSanitizer and UndefinedBehaviorSanitizer, and the Cortex-M4 build."""

from __future__ import annotations

import re
import shutil
import subprocess
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
# the C unit tests: suites (one a file) and named tests (firmware/tests/main.c prints both)
C_SUITES = 20
C_TESTS = 190


def _make(target: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run(["make", "-s", target], cwd=REPO, capture_output=True, text=True, timeout=600)


def _passing_run(target: str) -> None:
    """Build the C unit tests as `target` and run them all: every check passes, and the exact
    numbers of suites and tests (a suite or test added, or lost, changes these: update them with it)."""
    build = _make(target)
    assert build.returncode == 0, build.stderr
    run = subprocess.run([str(REPO / target)], capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stdout + run.stderr
    m = re.search(r"firmware: (\d+) suites, (\d+) tests \((\d+) failed\), (\d+) checks passed, (\d+) failed",
                  run.stdout)
    assert m, run.stdout
    assert (int(m.group(1)), int(m.group(2))) == (C_SUITES, C_TESTS)
    assert m.group(3) == "0" and m.group(5) == "0" and int(m.group(4)) > 1000


def test_c_unit_tests_pass() -> None:
    _passing_run("build/host/ffr_unit_tests")
    listed = subprocess.run([str(REPO / "build/host/ffr_unit_tests"), "--list"], capture_output=True, text=True,
                            timeout=60).stdout.split()
    assert len(listed) == C_TESTS and len(set(listed)) == C_TESTS  # every test named, no name twice
    assert len({name.split(".")[0] for name in listed}) == C_SUITES
    # one suite a file, every file's suite run (main.c lists them)
    assert len(list((REPO / "firmware" / "tests").glob("test_*.c"))) == C_SUITES


def test_c_unit_tests_pass_with_the_home_fold_rules_built_in() -> None:
    # FFR_HOME_FOLD_MM (off as shipped) compiles in the orientation's own probe; its tests run here
    _passing_run("build/host/ffr_unit_tests_homefold")
    # the build differs: the default build's checks of the probe's return are skipped there
    one = subprocess.run([str(REPO / "build/host/ffr_unit_tests_homefold"),
                          "home_orient.the_looks_probe_finding_the_wall_as_read_returns_to_where_it_stood"],
                         capture_output=True, text=True, timeout=60)
    assert one.returncode == 0, one.stdout
    n = re.search(r"(\d+) checks passed", one.stdout)
    assert n and int(n.group(1)) > 10, one.stdout


def test_a_failed_c_check_names_its_test() -> None:
    build = _make("build/host/ffr_unit_tests")
    assert build.returncode == 0, build.stderr
    run = subprocess.run([str(REPO / "build/host/ffr_unit_tests"), "--demo-failure"], capture_output=True,
                         text=True, timeout=60)
    assert run.returncode == 1
    assert re.search(r"^FAIL firmware/tests/main\.c:\d+: unit_demo\.a_check_that_fails_on_purpose: 1 \+ 1 == 3$",
                     run.stdout, re.M), run.stdout


def test_one_c_test_runs_alone_by_its_name() -> None:
    build = _make("build/host/ffr_unit_tests")
    assert build.returncode == 0, build.stderr
    run = subprocess.run([str(REPO / "build/host/ffr_unit_tests"), "odometry.counter_wrap_around_is_harmless"],
                         capture_output=True, text=True, timeout=60)
    assert run.returncode == 0, run.stdout
    assert "firmware: 1 suites, 1 tests (0 failed)" in run.stdout


@pytest.mark.skipif(shutil.which("arm-none-eabi-gcc") is None,
                    reason="arm-none-eabi-gcc not installed (CI installs gcc-arm-none-eabi)")
def test_cortex_m4_build_without_warnings() -> None:
    res = _make("firmware-arm")
    assert res.returncode == 0, res.stderr
    assert "warning" not in res.stderr.lower()
    m = re.search(r"cortex-m4: flash (\d+) bytes .* RAM (\d+) bytes", res.stdout)
    assert m, res.stdout
    assert int(m.group(1)) < 64 * 1024 and int(m.group(2)) < 16 * 1024


def test_no_heap_no_double_no_platform_headers() -> None:
    srcs = [*(REPO / "firmware" / "src").glob("*.[ch]"), *(REPO / "firmware" / "include").glob("ffr_contract*.h")]
    for src in srcs:
        text = src.read_text()
        code = re.sub(r"/\*.*?\*/", "", text, flags=re.S)
        assert not re.search(r"\b(malloc|calloc|realloc|free)\s*\(", code), src
        assert not re.search(r"\bdouble\b", code), src
        for inc in re.findall(r'#include\s*[<"]([^>"]+)[>"]', code):
            assert inc in {"ffr.h", "ffr_internal.h", "ffr_contract.h", "ffr_contract_hash.h", "stdint.h",
                           "stddef.h"}, (src, inc)
