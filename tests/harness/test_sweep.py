"""ffr sweep: jobs, the Dask path (a local cluster of worker processes on loopback), results, CLI."""

from __future__ import annotations

import csv
import json
import os
import socket
import subprocess
import sys
import time
from pathlib import Path

import pytest

from harness import sweep as sw
from harness.cli import main

REPO = Path(__file__).resolve().parents[2]
# a team's own noise file (a profile of one part: only ranger scatter)
FLOOR_NOISE = "[floor]\n[floor.ir]\nsigma = 10.0\n"


def test_parse_param() -> None:
    p = sw.parse_param("firmware.cruise_speed_mm_s=200:400:3")
    assert p.values == (200, 300, 400) and p.group == "firmware" and p.name == "cruise_speed_mm_s"
    q = sw.parse_param("robot.ir.LF.angle_deg=30,45.5")
    assert q.values == (30, 45.5) and (q.lo, q.hi) == (30, 45.5)
    for bad in ("cruise=1:2:3", "firmware.x=1:2", "firmware.x=a,b", "motor.R=1,2", "firmware.x=1:2:0"):
        with pytest.raises(ValueError):
            sw.parse_param(bad)


def test_jobs_are_the_product_of_candles_params_seeds() -> None:
    spec = sw.SweepSpec(rooms=(1, 3), candles="random", n_candles=2, seeds=(0, 1),
                        params=(sw.parse_param("firmware.cruise_speed_mm_s=250,300,350"),))
    jobs = sw.build_jobs(spec)
    assert len(jobs) == 2 * 2 * 3 * 2
    assert {j["room"] for j in jobs} == {1, 3}
    assert {j["firmware"]["cruise_speed_mm_s"] for j in jobs} == {250, 300, 350}
    assert sw.build_jobs(spec) == jobs  # the candle draws are seeded
    grid = sw.candle_positions(sw.SweepSpec(rooms=(4,), candles="grid", grid_step_m=0.1))
    assert len(grid) > 20 and all(r == 4 for r, _, _ in grid)


def test_random_mode_draws_within_the_ranges() -> None:
    spec = sw.SweepSpec(rooms=(1,), candles="default", params=(sw.parse_param("robot.motor.R=6:8:2"),),
                        mode="random", n_random=5)
    vals = [j["robot"]["motor.R"] for j in sw.build_jobs(spec)]
    assert len(vals) == 5 and all(6 <= v <= 8 for v in vals) and len(set(vals)) == 5


def test_local_dask_cluster_gives_the_serial_results(tmp_path) -> None:
    """The same rows through a LocalCluster of two worker processes (127.0.0.1) as in this process."""
    spec = sw.SweepSpec(rooms=(1, 2), candles="random", n_candles=2, seeds=(0, 1), noise="typical")
    jobs = sw.build_jobs(spec)
    done = []
    rows = sw.execute(jobs, workers=2, progress=done.append, engine="dask")
    assert sum(done) == len(jobs) == len(rows) == 8
    assert rows == sw.run_local_serial(jobs)
    assert all(r["success"] for r in rows)


def test_forked_local_processes_give_the_serial_results() -> None:
    """The default local engine for ctypes: sweeps: workers forked warm from this process."""
    spec = sw.SweepSpec(rooms=(1, 2), candles="random", n_candles=3, seeds=(0, 1), noise="typical")
    jobs = sw.build_jobs(spec)
    assert sw.pick_engine(jobs, None, None) == "processes"
    assert sw.pick_engine(jobs, "tcp://127.0.0.1:8786", None) == "dask"
    assert sw.pick_engine([j | {"link": "host-board:serial"} for j in jobs], None, None) == "dask"
    done = []
    rows = sw.execute(jobs, workers=2, progress=done.append)
    assert sum(done) == len(jobs) == len(rows) == 12
    assert rows == sw.run_local_serial(jobs)


def test_a_remote_cluster_runs_a_teams_library_it_never_saw(tmp_path) -> None:
    """`--scheduler tcp://...` with a scheduler and two `dask worker` processes started from another
    directory, with their own cache: the team's library and noise file travel with the work (the workers
    hold the same bytes in their cache afterwards), and the rows equal those of a local run."""
    from ffr_link.ctypes_link import DEFAULT_LIB

    client_dir, worker_dir, worker_cache = tmp_path / "team", tmp_path / "elsewhere", tmp_path / "wcache"
    for d in (client_dir, worker_dir):
        d.mkdir()
    lib = client_dir / "libteam.so"
    lib.write_bytes(Path(DEFAULT_LIB).read_bytes())
    noise = client_dir / "floor.toml"
    noise.write_text(FLOOR_NOISE)
    with socket.socket() as s:  # a free loopback port
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    addr = f"tcp://127.0.0.1:{port}"
    bindir = Path(sys.executable).parent
    env = {k: v for k, v in os.environ.items() if k not in ("FFR_FIRMWARE_LIB", "FFR_HOST_BOARD")}
    env["FFR_CACHE"] = str(worker_cache)
    procs = [subprocess.Popen([str(bindir / "dask"), "scheduler", "--host", "127.0.0.1", "--port", str(port),
                               "--no-dashboard"], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                              cwd=worker_dir, env=env)]
    try:
        time.sleep(1.5)
        for _ in range(2):
            procs.append(subprocess.Popen([str(bindir / "dask"), "worker", addr, "--nthreads", "1",
                                           "--host", "127.0.0.1", "--no-dashboard"],
                                          stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                                          cwd=worker_dir, env=env))
        from dask.distributed import Client
        with Client(addr, timeout="20s") as c:
            c.wait_for_workers(2, timeout=60)
        argv = ["sweep", "--rooms", "1", "--candles", "default", "--seeds", "0:4", "--firmware", str(lib),
                "--noise", str(noise), "--no-progress"]
        remote, local = tmp_path / "remote.csv", tmp_path / "local.csv"
        assert main([*argv, "--scheduler", addr, "--out", str(remote)]) == 0
        assert main([*argv, "--workers", "1", "--out", str(local)]) == 0
        rows = list(csv.DictReader(remote.open()))
        assert len(rows) == 4 and all(r["outcome"] == "home" for r in rows)
        assert remote.read_text() == local.read_text()  # the replay commands name the client's files
        assert str(lib) in rows[0]["replay"]
        shipped = {p.name: p.read_bytes() for p in (worker_cache / "shipped").glob("*/*")}
        assert shipped["libteam.so"] == lib.read_bytes() and shipped["floor.toml"] == noise.read_bytes()
    finally:
        for p in procs:
            p.terminate()
        for p in procs:
            p.wait(timeout=30)


def test_a_chunk_runs_on_the_shipped_files_not_the_clients_paths(tmp_path, monkeypatch) -> None:
    """The worker side alone: the job names a library and a noise file that do not exist on this
    machine; the payload's bytes are what runs, and the row keeps the client's names."""
    from ffr_link.ctypes_link import DEFAULT_LIB
    from harness.sweep_payload import Payload

    monkeypatch.setenv("FFR_CACHE", str(tmp_path / "cache"))
    lib, noise = "/nowhere/client/libteam.so", "/nowhere/client/floor.toml"
    data, text = Path(DEFAULT_LIB).read_bytes(), FLOOR_NOISE.encode()
    payload = Payload({lib: ("a" * 64, data), noise: ("b" * 64, text)})
    job = sw.build_jobs(sw.SweepSpec(rooms=(1,), candles="default", seeds=(0,), noise=noise,
                                     link=f"ctypes:{lib}"))[0]
    row = sw.run_chunk([job], payload)[0]
    assert row["outcome"] == "home" and row["noise"] == noise and lib in row["replay"]
    assert (tmp_path / "cache" / "shipped" / ("a" * 64) / "libteam.so").read_bytes() == data
    bare = sw.run_chunk([job])[0]  # without the payload the client's files are unknown here
    assert bare["outcome"] == "error" and "/nowhere/client/floor.toml" in bare["detail"]


def test_cli_sweep_outputs_summary_csv_plot_json(tmp_path, capsys) -> None:
    out, png, js = tmp_path / "r.csv", tmp_path / "p.png", tmp_path / "s.json"
    code = main(["sweep", "--rooms", "1", "--candles", "default", "--seeds", "0:2", "--workers", "2",
                 "--param", "firmware.cruise_speed_mm_s=280:320:2", "--out", str(out), "--plot", str(png),
                 "--json", str(js), "--no-progress"])
    assert code == 0
    text = capsys.readouterr().out
    assert "4 missions: 4 succeeded (100.0 %)" in text and "firmware.cruise_speed_mm_s:" in text
    rows = list(csv.DictReader(out.open()))
    assert len(rows) == 4 and {r["firmware.cruise_speed_mm_s"] for r in rows} == {"280", "320"}
    assert all(r["replay"].startswith("ffr run --candle") for r in rows)
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert json.loads(js.read_text())["success_rate_pct"] == 100.0


def test_a_failure_is_summarised_with_its_replay(capsys) -> None:
    """A sweep that breaks the robot: the summary names the causes and a replay that fails the same way."""
    code = main(["sweep", "--rooms", "2", "--candles", "default", "--workers", "1", "--no-progress",
                 "--set", "firmware.front_stop_mm=60", "--min-success", "50"])
    text = capsys.readouterr().out
    assert code == 1 and "failure causes:" in text
    replay = text.split("replay the first: ")[1].splitlines()[0]
    argv = replay.split()[1:]
    assert argv[0] == "run" and main(argv) == 1


@pytest.mark.parametrize(("argv", "needle"), [
    (["--param", "firmware.nope=1:2:2"], "firmware.nope"),
    (["--param", "robot.motor.R=-1,2"], "robot.motor.R"),
    (["--param", "cruise=1"], "--param"),
    (["--rooms", "9"], "room = 9"),
    (["--seeds", "x"], "--seeds"),
    (["--noise", "loud"], "loud"),
    (["--out", "r.txt"], "--out"),
    (["--scheduler", "http://x"], "--scheduler"),
    (["--scheduler", "tcp://127.0.0.1:9", "--engine", "processes"], "--engine"),
    (["--engine", "threads"], "--engine"),
])
def test_sweep_bad_input_one_line_exit_2_nothing_written(tmp_path, capsys, argv, needle) -> None:
    out = tmp_path / "r.csv"
    args = ["sweep", *argv] + ([] if "--out" in argv else ["--out", str(out)])
    assert main(args) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith("ffr: error:") and needle in err
    assert not out.exists()


def test_unreachable_scheduler_is_one_line(capsys) -> None:
    assert main(["sweep", "--scheduler", "tcp://127.0.0.1:9", "--rooms", "1", "--candles", "default",
                 "--no-progress"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "cannot reach" in err


def test_envelope_table(capsys) -> None:
    """`make envelope`'s tool: one kind, one scale, a few missions, through the same Dask path."""
    from harness import envelope

    assert envelope.scaled({"ir": {"sigma": 20.0, "quant_step": 4.883}}, 1.5) == {
        "ir": {"sigma": 30.0, "quant_step": 4.883}}
    code = envelope.main(["--kinds", "ir sigma 20 mV", "--scales", "0.5,1", "-n", "1", "--seeds", "0:1",
                          "--workers", "1"])
    out = capsys.readouterr().out
    assert code == 0
    row = next(line for line in out.splitlines() if line.startswith("| ir sigma 20 mV |"))
    assert row == "| ir sigma 20 mV | 100.0 | 100.0 | x1 |"


def test_a_parquet_sweep_holds_the_csv_rows(tmp_path) -> None:
    import pyarrow.parquet as pq  # the `parquet` extra (also in `test`)

    argv = ["sweep", "--rooms", "1", "--candles", "default", "--seeds", "0:2", "--workers", "1", "--no-progress"]
    assert main([*argv, "--out", str(tmp_path / "r.csv")]) == 0
    assert main([*argv, "--out", str(tmp_path / "r.parquet")]) == 0
    rows = list(csv.DictReader((tmp_path / "r.csv").open()))
    table = pq.read_table(tmp_path / "r.parquet").to_pylist()
    assert len(table) == len(rows) == 2
    for got, want in zip(table, rows, strict=True):
        assert list(got) == list(want)
        assert {k: "" if v is None else str(v) for k, v in got.items()} == want


def test_a_sweep_runs_another_firmware_library(capsys) -> None:
    from ffr_link.ctypes_link import DEFAULT_LIB

    assert main(["sweep", "--rooms", "1", "--candles", "default", "--firmware", str(DEFAULT_LIB),
                 "--workers", "1", "--no-progress"]) == 0
    assert "1 missions: 1 succeeded" in capsys.readouterr().out
