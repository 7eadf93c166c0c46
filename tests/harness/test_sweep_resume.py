"""A long sweep loses nothing: rows stream to --out, Ctrl-C / a killed worker / a lost scheduler keep every
finished mission, and --resume completes the file into exactly the uninterrupted sweep's.

The interrupted sweeps run with ``FFR_SWEEP_TEST_HOLD=PATH:6`` in their workers' environment: missions 6 and
on wait while PATH exists, so the test interrupts at a known point (some rows written, the rest unable to
finish) by polling the output file, never by sleeping a guessed time.
"""

from __future__ import annotations

import csv
import io
import os
import re
import shutil
import signal
import socket
import subprocess
import sys
import time
from collections.abc import Iterator
from pathlib import Path

import pytest

from harness import sweep_store as store
from harness.cli import main

REPO = Path(__file__).resolve().parents[2]
BINDIR = Path(sys.executable).parent
# 2 rooms x 2 random candles x 3 seeds = 12 missions, in chunks of 2 on two workers
SWEEP = ["sweep", "--rooms", "1,2", "-n", "2", "--seeds", "0:3", "--noise", "typical", "--no-progress"]
N_MISSIONS, HELD_FROM = 12, 6
TIMEOUT = 240.0  # generous: two busy cores shared with other work


@pytest.fixture(scope="module")
def reference_file(tmp_path_factory) -> Path:
    """The file of the same sweep run without interruption (and its FILE.sweep.json)."""
    out = tmp_path_factory.mktemp("ref") / "ref.csv"
    assert main([*SWEEP, "--workers", "2", "--out", str(out)]) == 0
    return out


@pytest.fixture()
def reference(reference_file) -> bytes:
    return reference_file.read_bytes()


def _copy_reference(reference_file: Path, out: Path, data: bytes | None = None) -> None:
    """The reference's sidecar beside ``out``, which holds ``data`` (the reference's rows, or some of them)."""
    out.write_bytes(reference_file.read_bytes() if data is None else data)
    shutil.copy(store.sidecar_path(reference_file), store.sidecar_path(out))


def _records(path: Path) -> list[list[str]]:
    """The whole rows in a file being written (header included); a line still being written is left out."""
    if not path.exists():
        return []
    text = path.read_text(encoding="utf-8")
    return list(csv.reader(io.StringIO(text[: text.rfind("\n") + 1], newline="")))


def _wait_rows(path: Path, n: int, proc: subprocess.Popen[str]) -> list[list[str]]:
    deadline = time.monotonic() + TIMEOUT
    while time.monotonic() < deadline:
        recs = _records(path)
        if len(recs) - 1 >= n:
            return recs
        if proc.poll() is not None:
            pytest.fail(f"the sweep ended (status {proc.returncode}) before {n} rows: {proc.communicate()}")
        time.sleep(0.1)
    pytest.fail(f"no {n} rows in {path} after {TIMEOUT} s")


def _held_env(hold: Path) -> dict[str, str]:
    hold.touch()
    return os.environ | {"FFR_SWEEP_TEST_HOLD": f"{hold}:{HELD_FROM}"}


def _spawn(argv: list[str], env: dict[str, str] | None = None) -> subprocess.Popen[str]:
    # PYTHONPATH: `dask worker` imports harness from this checkout, not from where the venv was installed;
    # its own session: signals (and the clean-up) reach it and every process it starts, as a terminal's Ctrl-C
    env = (env or dict(os.environ)) | {"PYTHONPATH": str(REPO)}
    return subprocess.Popen(argv, cwd=REPO, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            start_new_session=True)


def _stop(procs: list[subprocess.Popen[str]]) -> None:
    for p in procs:
        if p.poll() is None:
            os.killpg(p.pid, signal.SIGKILL)
    for p in procs:
        p.communicate(timeout=60)


def _check_kept(recs: list[list[str]], reference: bytes, finished: int) -> None:
    """The interrupted file: the reference's header, and whole rows that are the reference's (none missing)."""
    ref = list(csv.reader(io.StringIO(reference.decode(), newline="")))
    assert recs[0] == ref[0]
    kept = recs[1:]
    assert len(kept) == finished and 1 <= finished <= HELD_FROM
    assert all(int(rec[0]) < HELD_FROM for rec in kept)  # the held missions could not finish
    assert all(rec in ref[1:] for rec in kept) and len({rec[0] for rec in kept}) == finished


@pytest.mark.parametrize("engine", ["processes", "dask"])
def test_ctrl_c_keeps_the_finished_rows_and_resume_completes_them(tmp_path, reference, engine: str) -> None:
    out = tmp_path / "s.csv"
    sweep = _spawn([sys.executable, "-m", "harness", *SWEEP, "--workers", "2", "--engine", engine,
                    "--out", str(out)], _held_env(tmp_path / "hold"))
    try:
        _wait_rows(out, 1, sweep)
        os.killpg(sweep.pid, signal.SIGINT)  # the whole group, as Ctrl-C in a terminal
        _, err = sweep.communicate(timeout=TIMEOUT)
    finally:
        _stop([sweep])
    assert sweep.returncode == 130, err
    where = re.escape(str(out))
    m = re.fullmatch(rf"ffr: interrupted: (\d+) of {N_MISSIONS} missions finished and are kept in {where}, "
                     rf"(\d+) missing; the same command with --resume {where} runs only those\n", err)
    assert m, err
    finished = int(m[1])
    assert finished + int(m[2]) == N_MISSIONS
    assert out.read_bytes().endswith(b"\n")  # whole rows only
    _check_kept(_records(out), reference, finished)
    assert main([*SWEEP, "--workers", "2", "--resume", str(out)]) == 0
    assert out.read_bytes() == reference


@pytest.fixture()
def cluster(tmp_path) -> Iterator[tuple[str, subprocess.Popen[str], list[subprocess.Popen[str]], Path]]:
    """A scheduler and two worker processes (no nanny, so a killed worker stays dead), all on loopback, their
    missions held from HELD_FROM on; stopped by the test."""
    with socket.socket() as s:  # a free loopback port
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    addr = f"tcp://127.0.0.1:{port}"
    hold = tmp_path / "hold"
    env = _held_env(hold)
    scheduler = _spawn([str(BINDIR / "dask"), "scheduler", "--host", "127.0.0.1", "--port", str(port),
                        "--no-dashboard"])
    workers = [_spawn([str(BINDIR / "dask"), "worker", addr, "--nthreads", "1", "--no-nanny", "--host",
                       "127.0.0.1", "--no-dashboard"], env) for _ in range(2)]
    try:
        from dask.distributed import Client
        with Client(addr, timeout="60s") as c:
            c.wait_for_workers(2, timeout=TIMEOUT)
        yield addr, scheduler, workers, hold
    finally:
        _stop([scheduler, *workers])


def test_a_killed_worker_loses_nothing(tmp_path, reference, cluster) -> None:
    """One of two workers killed mid-sweep, in a mission: Dask runs its chunk again on the other one, the rows
    already written stay, and the sweep ends complete, its file the uninterrupted one."""
    from dask.distributed import Client

    addr, _, workers, hold = cluster
    out = tmp_path / "s.csv"
    sweep = _spawn([sys.executable, "-m", "harness", *SWEEP, "--scheduler", addr, "--out", str(out)])
    try:
        _wait_rows(out, 1, sweep)
        with Client(addr, timeout="60s") as c:
            pids = c.run(os.getpid)
            deadline = time.monotonic() + TIMEOUT
            while not (busy := [w for w, keys in c.processing().items() if keys]):  # a worker in a held mission
                assert time.monotonic() < deadline, "no worker busy"
                time.sleep(0.1)
        victim = next(p for p in workers if p.pid == pids[busy[0]])
        os.killpg(victim.pid, signal.SIGKILL)
        victim.wait(timeout=60)
        before = _records(out)
        hold.unlink()  # the survivor runs the rest, the dead worker's chunk included
        _, err = sweep.communicate(timeout=TIMEOUT)
    finally:
        _stop([sweep])
    assert sweep.returncode == 0, err
    assert 1 <= len(before) - 1 <= HELD_FROM  # rows written before the kill, the held missions not among them
    assert out.read_bytes() == reference


def test_a_lost_scheduler_keeps_the_finished_rows_and_resume_completes_them(tmp_path, reference, cluster) -> None:
    """The scheduler killed mid-sweep: exit 1 with the count on one line, every finished row kept; --resume
    on another cluster (here a local one) runs only the missing missions."""
    addr, scheduler, workers, _ = cluster
    out = tmp_path / "s.csv"
    sweep = _spawn([sys.executable, "-m", "harness", *SWEEP, "--scheduler", addr, "--out", str(out)])
    try:
        _wait_rows(out, 1, sweep)
        os.killpg(scheduler.pid, signal.SIGKILL)
        _, err = sweep.communicate(timeout=TIMEOUT)
    finally:
        _stop([sweep])
    assert sweep.returncode == 1, err
    m = re.fullmatch(rf"ffr: error: lost the Dask cluster \((scheduler-connection-lost|connection closed)\): (\d+) of "
                     rf"{N_MISSIONS} missions finished and are kept in .*, (\d+) missing; .*\n", err)
    assert m, err
    assert out.read_bytes().endswith(b"\n")
    assert int(m[2]) + int(m[3]) == N_MISSIONS
    _check_kept(_records(out), reference, int(m[2]))
    _stop(workers)
    assert main([*SWEEP, "--workers", "2", "--resume", str(out)]) == 0
    assert out.read_bytes() == reference


def test_resume_drops_a_row_cut_short_and_sorts_the_file(tmp_path, reference_file, reference) -> None:
    """A client killed mid-write: the cut row is run again; rows in completion order end in mission order."""
    recs = list(csv.reader(io.StringIO(reference.decode(), newline="")))
    out = tmp_path / "s.csv"
    cut = store._csv_text([recs[0], *reversed(recs[1:9])]) + store._csv_text([recs[9]])[:40]
    _copy_reference(reference_file, out, cut.encode())
    assert main([*SWEEP, "--workers", "1", "--resume", str(out)]) == 0
    assert out.read_bytes() == reference


def test_resume_of_a_complete_file_runs_nothing(tmp_path, reference_file, reference, capsys) -> None:
    out = tmp_path / "s.csv"
    _copy_reference(reference_file, out)
    assert main([*SWEEP, "--resume", str(out)]) == 0
    assert f"{N_MISSIONS} already in" in capsys.readouterr().out and out.read_bytes() == reference


@pytest.mark.parametrize(("change", "needle"), [
    (["--seeds", "0:4"], "made by a different sweep (--seeds [0, 1, 2] there, [0, 1, 2, 3] here)"),
    (["--noise", "datasheet"], 'made by a different sweep (--noise "typical" there, "datasheet" here)'),
    (["--set", "firmware.cruise_speed_mm_s=280"], "made by a different sweep (--set [] there"),
    (["--sweep-seed", "3"], "made by a different sweep (--sweep-seed 0 there, 3 here)"),
])
def test_resume_refuses_another_sweeps_file(tmp_path, reference_file, reference, capsys, change, needle) -> None:
    out = tmp_path / "s.csv"
    _copy_reference(reference_file, out, reference[: reference.index(b"\n", 400) + 1])
    before = out.read_bytes()
    assert main([*SWEEP, *change, "--resume", str(out)]) == 2  # the later --seeds, --noise win
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith("ffr: error: --resume") and needle in err, err
    assert out.read_bytes() == before


def test_resume_refuses_a_file_without_record_or_with_foreign_rows(tmp_path, reference_file, reference,
                                                                   capsys) -> None:
    out = tmp_path / "s.csv"
    assert main([*SWEEP, "--resume", str(out)]) == 2
    assert "no such file" in capsys.readouterr().err
    out.write_bytes(reference)
    assert main([*SWEEP, "--resume", str(out)]) == 2
    assert "no s.csv.sweep.json beside it" in capsys.readouterr().err
    _copy_reference(reference_file, out, reference.replace(b"--seed 2", b"--seed 7", 1))
    assert main([*SWEEP, "--resume", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "is not a mission of this sweep" in err
    assert main([*SWEEP, "--resume", str(tmp_path / "s.parquet")]) == 2
    assert main([*SWEEP, "--resume", str(out), "--out", str(tmp_path / "other.csv")]) == 2
    assert "--resume appends to its own file" in capsys.readouterr().err
