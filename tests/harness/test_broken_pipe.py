"""A reader that leaves early (``python -m harness.failure_places S.csv | head -1``): every command-line
tool ends quietly, no traceback and no "Exception ignored" at exit, with status 141 as a process killed
by SIGPIPE (sim_plant/broken_pipe.py, and its copy hil_bridge/broken_pipe.py)."""

from __future__ import annotations

import csv
import os
import subprocess
import sys
from pathlib import Path

import pytest

from sim_plant.broken_pipe import EXIT_BROKEN_PIPE

REPO = Path(__file__).resolve().parents[2]
HELPERS = ("sim_plant.broken_pipe", "hil_bridge.broken_pipe")
PIPE_BUFFER = 64 * 1024  # Linux's pipe: a tool printing more than this (and a reader's chunk) must block
# start seed 105 of `--start random` (tests/harness/test_start_room.py)
NEAR = "ffr run --candle 1.83,1.53 --seed 105 --start random"


def _env(buffered: bool = True) -> dict[str, str]:
    """A user's environment: stdout into a pipe is block-buffered, unless PYTHONUNBUFFERED says not."""
    env = {k: v for k, v in os.environ.items() if k != "PYTHONUNBUFFERED"}
    if not buffered:
        env["PYTHONUNBUFFERED"] = "1"
    return env


def _head_1(argv: list[str], env: dict[str, str] | None = None, timeout: float = 120.0) -> tuple[str, int, str]:
    """Run argv as ``argv | head -1`` would: read one line, then close the pipe. (first line, status, stderr)"""
    p = subprocess.Popen(argv, cwd=REPO, env=env or _env(), stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    assert p.stdout is not None and p.stderr is not None
    first = p.stdout.readline().decode()
    p.stdout.close()
    err = p.stderr.read().decode()
    p.stderr.close()
    return first, p.wait(timeout=timeout), err


def _closed_at_once(argv: list[str], timeout: float = 120.0) -> tuple[int, str]:
    """Run argv with its reader gone before it prints anything (``argv | true``). (status, stderr)"""
    p = subprocess.Popen(argv, cwd=REPO, env=_env(), stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    assert p.stdout is not None and p.stderr is not None
    p.stdout.close()
    err = p.stderr.read().decode()
    p.stderr.close()
    return p.wait(timeout=timeout), err


def test_the_status_is_a_sigpipe_death() -> None:
    assert EXIT_BROKEN_PIPE == 141


def test_the_two_copies_of_the_helper_are_the_same() -> None:
    # sim_plant and hil_bridge may not import each other (tests/architecture/test_import_graph.py)
    assert (REPO / "sim_plant/broken_pipe.py").read_text() == (REPO / "hil_bridge/broken_pipe.py").read_text()


def _script(helper: str, body: str) -> list[str]:
    return [sys.executable, "-c", f"from {helper} import exit_with\n\ndef main():\n{body}\n\nexit_with(main)\n"]


@pytest.mark.parametrize("buffered", [True, False], ids=["buffered", "unbuffered"])
@pytest.mark.parametrize("helper", HELPERS)
def test_exit_with_a_reader_that_left_mid_output(helper: str, buffered: bool) -> None:
    body = f"    for k in range({4 * PIPE_BUFFER // 10}):\n        print(f'{{k:9d}}')\n    return 0"
    first, status, err = _head_1(_script(helper, body), _env(buffered))
    assert first == f"{0:9d}\n"
    assert (status, err) == (EXIT_BROKEN_PIPE, "")


@pytest.mark.parametrize("buffered", [True, False], ids=["buffered", "unbuffered"])
@pytest.mark.parametrize("helper", HELPERS)
def test_exit_with_a_reader_gone_before_a_short_output(helper: str, buffered: bool) -> None:
    # buffered, the one line would only be written by the interpreter's flush at exit
    p = subprocess.Popen(_script(helper, "    print('one line')"), cwd=REPO, env=_env(buffered),
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    assert p.stdout is not None and p.stderr is not None
    p.stdout.close()
    err = p.stderr.read().decode()
    p.stderr.close()
    assert (p.wait(timeout=60), err) == (EXIT_BROKEN_PIPE, "")


@pytest.mark.parametrize("body, status, out", [
    ("    print('x')\n    return 3", 3, "x\n"),
    ("    print('x')", 0, "x\n"),  # a main that returns None
    ("    print('x')\n    raise SystemExit(2)", 2, "x\n"),  # argparse's way out
])
@pytest.mark.parametrize("helper", HELPERS)
def test_exit_with_passes_the_status_of_main_on(helper: str, body: str, status: int, out: str) -> None:
    res = subprocess.run(_script(helper, body), cwd=REPO, env=_env(), capture_output=True, text=True, timeout=60)
    assert (res.returncode, res.stdout, res.stderr) == (status, out, "")


def test_failure_places(tmp_path: Path) -> None:
    # one failed row, run again; its detail (under csv's 128 KiB field limit) is printed on its group's
    # line, longer than the pipe holds
    detail = "x" * 120_000
    assert len(detail) > PIPE_BUFFER + 8192
    path = tmp_path / "s.csv"
    with path.open("w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["room", "candle_x", "candle_y", "seed", "success", "outcome", "detail", "replay"])
        w.writerow([1, 1.83, 1.53, 0, False, "home", detail, "ffr run --candle 1.83,1.53 --seed 0"])
    first, status, err = _head_1([sys.executable, "-m", "harness.failure_places", str(path)])
    assert first.startswith("1 failed missions (of 1 failed rows")
    assert "Traceback" not in err
    assert (status, err) == (EXIT_BROKEN_PIPE, "")


def test_start_room(tmp_path: Path) -> None:
    # one start, 4,000 gap bands: a line each, some 200 kB
    path = tmp_path / "s.csv"
    with path.open("w", newline="") as fh:
        csv.writer(fh).writerows([["id", "room", "seed", "success", "replay"], [0, 1, 105, False, NEAR]])
    bins = ",".join(str(b) for b in range(1, 4001))
    first, status, err = _head_1([sys.executable, "-m", "harness.start_room", str(path), "--bins", bins])
    assert first.startswith("1 start poses, 1 missions, 0 succeeded")
    assert "Traceback" not in err
    assert (status, err) == (EXIT_BROKEN_PIPE, "")


def test_reality_report() -> None:
    # 2,000 seeds: a line each, some 300 kB
    first, status, err = _head_1([sys.executable, "-m", "sim_plant.reality_report", "0:2000"])
    assert first.startswith("seed     0  chi0")
    assert "Traceback" not in err
    assert (status, err) == (EXIT_BROKEN_PIPE, "")


@pytest.mark.parametrize("argv", [
    ["hil_bridge.dbc"],
    ["hil_bridge.vectors"],
    ["sim_plant.arena_report"],
    ["harness", "run", "--room", "1"],  # ffr itself, whose few lines wait in the buffer until it ends
], ids=lambda argv: argv[0] if len(argv) == 1 else "ffr")
def test_a_tool_whose_reader_is_gone_before_it_prints(argv: list[str]) -> None:
    status, err = _closed_at_once([sys.executable, "-m", *argv])
    assert "Traceback" not in err
    assert (status, err) == (EXIT_BROKEN_PIPE, "")
