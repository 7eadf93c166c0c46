"""Figures in the README and docs are what their commands print now.

A number quoted from a command drifts the moment the code changes; these
tests run the command and compare, so a stale figure fails here with the
line to paste instead of misleading a reader."""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
README = (REPO / "README.md").read_text(encoding="utf-8")
PIL_DOC = (REPO / "docs" / "pil.md").read_text(encoding="utf-8")


def _make(*targets: str) -> str:
    res = subprocess.run(["make", "-s", *targets], cwd=REPO, capture_output=True, text=True, timeout=600)
    assert res.returncode == 0, res.stderr
    return res.stdout


def test_readme_results_table_is_what_make_run_prints() -> None:
    block = re.search(r"## Results \(`make run`\)\s*```\n(.*?)```", README, re.S)
    assert block, "README: the Results block is missing"
    res = subprocess.run([sys.executable, "-m", "harness", "table1"], cwd=REPO, capture_output=True, text=True,
                         timeout=300)
    assert res.returncode == 0, res.stderr
    assert block.group(1).strip() == res.stdout.strip(), f"README Results: paste\n{res.stdout}"


needs_arm = pytest.mark.skipif(
    shutil.which("arm-none-eabi-gcc") is None and not os.environ.get("CI"),
    reason="needs arm-none-eabi-gcc (CI installs it)")


@needs_arm
def test_readme_cortex_m4_size_is_what_the_build_prints() -> None:
    line = next(ln for ln in _make("firmware-arm").splitlines() if ln.startswith("cortex-m4: flash"))
    assert f"`{line}`" in README, f"README, section Firmware: quote `{line}`"


@needs_arm
def test_pil_doc_board_size_is_what_the_build_prints() -> None:
    # -B: the size line is printed when the image is linked, also when it was up to date
    line = next(ln for ln in _make("-B", "build/arm/mps2-an386-board.elf").splitlines()
                if ln.startswith("mps2-an386 board: flash"))
    assert f"`{line}`" in PIL_DOC, f"docs/pil.md: quote `{line}`"


@needs_arm
@pytest.mark.parametrize("board", ["mps2-an386", "netduinoplus2", "microbit"])
def test_boards_doc_sizes_are_what_the_build_prints(board: str) -> None:
    doc = (REPO / "docs" / "boards.md").read_text(encoding="utf-8")
    line = next(ln for ln in _make("-B", f"build/arm/{board}-board.elf").splitlines()
                if ln.startswith(f"{board} board: flash"))
    assert f"`{line}`" in doc, f"docs/boards.md: quote `{line}`"


def test_arena_doc_measures_are_what_the_arena_command_prints() -> None:
    """docs/arena.md quotes `python -m sim_plant.arena_report [FILE]`: its measures of both shipped arenas."""
    doc = (REPO / "docs" / "arena.md").read_text(encoding="utf-8")

    def describe(*argv: str) -> str:
        res = subprocess.run([sys.executable, "-m", "sim_plant.arena_report", *argv], cwd=REPO, capture_output=True,
                             text=True, timeout=120)
        assert res.returncode == 0, res.stderr
        return res.stdout

    text_2004, text_2001 = describe(), describe("sim_plant/data/arena_2001.toml")
    for text, size, home, heading in ((text_2004, "244.0", "(211.0, 117.0)", "90"),
                                      (text_2001, "248.9", "(228.1, 116.8)", "180")):
        assert f"outer square {size} x {size} cm" in text and f"| {size} cm |" in doc
        assert f"home circle at {home} cm" in text and f"start heading {heading} deg" in text
        assert f"{home} cm, start facing {heading}°" in doc
    hall_line = text_2001.split("hallway widths (cm): ")[1].split("\n")[0]
    halls = [float(v) for v in re.findall(r"[a-z]+ (\d+\.\d)", hall_line)]
    doors = [float(v) for v in re.findall(r"door (\d+\.\d) cm", text_2001)]
    assert f"hallways are {min(halls):.1f} to {max(halls):.1f} cm" in doc.replace("\n", " ")
    assert f"doors {min(doors):.1f} to {max(doors):.1f} cm" in doc.replace("\n", " ")
    assert "lines closer than 12 cm move as one; at most 5 cm" in text_2004
    assert "Lines closer than 12 cm move as one" in doc and "the largest tolerance, 5 cm" in doc.replace("\n", " ")
    for rid in (1, 2):
        line = next(ln for ln in text_2001.splitlines() if ln.startswith(f"room {rid} "))
        assert "entry-depth: refused (entry-depth); door-line: legal" in line
