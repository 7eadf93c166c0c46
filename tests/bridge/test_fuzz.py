"""The C decoder under libFuzzer with AddressSanitizer and UndefinedBehavior-
Sanitizer, for a bounded time (CI also runs ``make fuzz`` for 60 s)."""

from __future__ import annotations

import re
import shutil
import subprocess
import tempfile
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]


def _libfuzzer_missing() -> str | None:
    if shutil.which("clang") is None:
        return "clang not installed (CI installs clang and libclang-rt-dev)"
    with tempfile.TemporaryDirectory() as d:
        src = Path(d) / "p.c"
        src.write_text("int LLVMFuzzerTestOneInput(const unsigned char *d, unsigned long n) { return 0; }\n")
        r = subprocess.run(["clang", "-fsanitize=fuzzer,address,undefined", "-o", str(Path(d) / "p"), str(src)],
                           capture_output=True, text=True)
    return None if r.returncode == 0 else "libFuzzer runtime missing (CI installs libclang-rt-dev)"


@pytest.mark.skipif(_libfuzzer_missing() is not None, reason=str(_libfuzzer_missing()))
def test_fuzzing_the_decoder_finds_nothing() -> None:
    r = subprocess.run(["make", "-s", "fuzz", "FUZZ_SECONDS=8"], cwd=REPO, capture_output=True, text=True, timeout=300)
    out = r.stdout + r.stderr
    assert r.returncode == 0, out[-3000:]
    assert "AddressSanitizer" not in out and "runtime error" not in out
    m = re.search(r"stat::number_of_executed_units: (\d+)", out)
    assert m and int(m.group(1)) > 2000, out[-2000:]
