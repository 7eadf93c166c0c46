"""``ffr sweep``: the command line of ``harness.sweep`` (kept apart so cli.py stays small)."""

from __future__ import annotations

import argparse
import contextlib
import os
import sys
import time
from pathlib import Path
from typing import Any

from harness.cli_args import _setting, add_arena_options, firmware_link
from sim_plant.errors import FfrInputError


def _int_list(text: str, what: str) -> tuple[int, ...]:
    """``0:10`` (0..9), ``3`` or ``1,2,5``."""
    try:
        if ":" in text:
            a, b = text.split(":")
            vals = tuple(range(int(a), int(b)))
        else:
            vals = tuple(int(v) for v in text.split(","))
        if not vals or min(vals) < 0:
            raise ValueError
    except ValueError:
        raise argparse.ArgumentTypeError(f"{what} = {text!r}: expected A:B (A..B-1) or N,N,... (N >= 0)") from None
    return vals


def _param(text: str) -> Any:
    from harness.sweep import parse_param
    try:
        return parse_param(text)
    except ValueError as exc:
        raise argparse.ArgumentTypeError(str(exc)) from None


def add_sweep_parser(sub: Any) -> None:
    sp = sub.add_parser("sweep", help="many missions: candle positions x seeds x parameters, on all cores or a "
                                      "Dask cluster")
    sp.add_argument("--rooms", type=lambda t: _int_list(t, "--rooms"), default=(1, 2, 3, 4),
                    help="rooms to place candles in (default 1,2,3,4)")
    sp.add_argument("--candles", choices=("default", "random", "grid"), default="random",
                    help="the room's default spot, N random legal spots per room, or a grid of legal spots")
    sp.add_argument("-n", "--n-candles", type=int, default=10, help="random candles per room (default 10)")
    sp.add_argument("--grid-step", type=float, default=0.10, help="grid spacing in m (default 0.10)")
    sp.add_argument("--seeds", type=lambda t: _int_list(t, "--seeds"), default=(0,),
                    help="noise seeds: A:B or N,N,... (default 0)")
    sp.add_argument("--noise", default="none",
                    help="noise profile (none, typical, datasheet, envelope, harsh, FILE.toml; realistic: "
                         "datasheet sensors on a robot and its calibration drawn from each seed)")
    sp.add_argument("--param", type=_param, action="append", default=[], metavar="KEY=LO:HI:N",
                    help="swept setting, firmware.NAME or robot.PATH; LO:HI:N or V1,V2,... (repeatable)")
    sp.add_argument("--mode", choices=("grid", "random"), default="grid",
                    help="parameters: every combination, or --samples random draws within the ranges")
    sp.add_argument("--samples", type=int, default=20, help="random mode: parameter draws (default 20)")
    sp.add_argument("--sweep-seed", type=int, default=0, help="seed of the candle and parameter draws")
    sp.add_argument("--set", dest="settings", type=_setting, action="append", default=[], metavar="KEY=VALUE",
                    help="fixed setting for every mission (repeatable)")
    sp.add_argument("--link", default="ctypes:", help="firmware link URL (default ctypes:)")
    sp.add_argument("--firmware", metavar="LIB.so", default=None,
                    help="a firmware library to run in-process (the same as --link ctypes:LIB.so)")
    sp.add_argument("--arena", default=None, help="arena TOML file")
    sp.add_argument("--robot", default=None, help="robot TOML file")
    sp.add_argument("--scheduler", default=None, metavar="tcp://HOST:PORT",
                    help="run on this Dask cluster (default: a local one, one worker per core)")
    sp.add_argument("--workers", type=int, default=None, help="local workers (default: all cores)")
    sp.add_argument("--engine", choices=("dask", "processes"), default=None,
                    help="local runs: worker processes forked warm from this one (the default for "
                         "ctypes: links) or a local Dask cluster; --scheduler always uses Dask")
    sp.add_argument("--out", default=None, metavar="FILE.csv|FILE.parquet",
                    help="one row per mission (CSV: written as missions finish)")
    sp.add_argument("--resume", default=None, metavar="FILE.csv",
                    help="run only the missions missing from FILE (an interrupted --out of the same sweep), "
                         "appending them")
    sp.add_argument("--plot", default=None, metavar="FILE.png", help="success and time over the arena and params")
    sp.add_argument("--json", default=None, metavar="FILE|-", help="the summary numbers as JSON")
    sp.add_argument("--min-success", type=float, default=None, metavar="PCT",
                    help="exit 1 when fewer than PCT %% of the missions succeed")
    sp.add_argument("--no-progress", action="store_true", help="no progress bar")
    add_arena_options(sp)


def _check(args: argparse.Namespace) -> None:
    """Every setting and parameter value checked before any mission starts."""
    from ffr_link.ctypes_link import default_config, firmware_info
    from harness.cli_args import UsageError, library_of_link
    from harness.firmware_config import apply_overrides
    from sim_plant.arena import load_arena
    from sim_plant.robot import load_robot, override

    args.link = firmware_link(args.link, args.firmware)
    from sim_plant.sensors import load_noise_profile

    if args.n_candles < 1:
        raise UsageError(f"--n-candles = {args.n_candles}: expected >= 1")
    if not args.grid_step > 0.0:
        raise UsageError(f"--grid-step = {args.grid_step}: expected > 0")
    if args.mode == "random" and args.samples < 1:
        raise UsageError(f"--samples = {args.samples}: expected >= 1")
    if args.workers is not None and args.workers < 1:
        raise UsageError(f"--workers = {args.workers}: expected >= 1")
    if args.scheduler and args.engine == "processes":
        raise UsageError("--engine = 'processes': local only, not with --scheduler")
    if args.scheduler and not args.scheduler.startswith(("tcp://", "tls://", "inproc://")):
        raise UsageError(f"--scheduler = {args.scheduler!r}: expected tcp://HOST:PORT")
    for path, what in ((args.out, "--out"), (args.plot, "--plot")):
        if path and what == "--out" and not path.endswith((".csv", ".parquet")):
            raise UsageError(f"--out = {path!r}: expected a .csv or .parquet file")
    if args.out and args.out.endswith(".parquet"):
        try:
            import pyarrow  # noqa: F401
        except ImportError:
            raise UsageError(f"--out = {args.out!r}: Parquet needs pyarrow (pip install 'ffr[parquet]'); "
                             "or write .csv") from None
    load_noise_profile(args.noise)
    arena = load_arena(args.arena)
    for r in args.rooms:
        arena.room(r)
    robot = load_robot(args.robot)
    lib = library_of_link(args.link)
    fw_info = firmware_info(lib)
    cfg = default_config(lib)
    fixed_fw = {k: v for g, k, v in args.settings if g == "firmware"}
    apply_overrides(cfg, fixed_fw, "--set", fw_info)
    for g, k, v in args.settings:
        if g == "robot":
            robot = override(robot, k, v, "--set")
    if isinstance(args.start, tuple):
        from harness.start_pose import check_start
        check_start(arena, robot, args.start, "--start", "--start")
    for p in args.param:
        for v in p.values:
            if p.group == "firmware":
                apply_overrides(default_config(lib), {p.name: v}, "--param", fw_info)
            else:
                override(robot, p.name, v, "--param")


def sweep_identity(args: argparse.Namespace, jobs: list[dict[str, Any]]) -> dict[str, Any]:
    """What decides a sweep's missions: its arguments (those that matter), the mission list and the files read.

    Stored beside a streamed ``--out`` (``FILE.sweep.json``) and compared by ``--resume``; how the sweep runs
    (``--scheduler``, ``--workers``, outputs, progress) is not part of it.
    """
    from harness import sweep_store as store

    rnd_candles = args.candles == "random"
    rnd_params = bool(args.param) and args.mode == "random"
    files = {f: store.file_digest(f) for f in (args.arena, args.robot, args.noise) if f and Path(f).is_file()}
    return {
        "--rooms": list(args.rooms), "--candles": args.candles,
        "--n-candles": args.n_candles if rnd_candles else None,
        "--grid-step": args.grid_step if args.candles == "grid" else None,
        "--seeds": list(args.seeds), "--noise": args.noise,
        "--param": [[p.key, list(p.values), p.lo, p.hi] for p in args.param],
        "--mode": args.mode if args.param else None, "--samples": args.samples if rnd_params else None,
        "--sweep-seed": args.sweep_seed if rnd_candles or rnd_params else None,
        "--set": [[g, k, v] for g, k, v in args.settings], "--link": args.link,
        "--arena": args.arena, "--robot": args.robot, "files": files,
        "--start": list(args.start) if isinstance(args.start, tuple) else args.start,
        "--arena-jitter": args.arena_jitter or 0.0,
        "--furniture": args.furniture or 0,
        "missions": len(jobs), "jobs_sha256": store.jobs_digest(jobs),
    }


def _quiet_distributed_logs() -> None:
    """The client's reconnect attempts after a lost scheduler would bury the one-line report in tracebacks;
    distributed sets its loggers' levels one by one when imported, so each is quietened after that."""
    import logging

    import distributed  # noqa: F401

    for name in list(logging.root.manager.loggerDict):
        if name.partition(".")[0] == "distributed":
            logging.getLogger(name).setLevel(logging.CRITICAL)


def run_sweep(args: argparse.Namespace) -> int:
    from harness import sweep as sw
    from harness import sweep_store as store
    from harness.atomic import write_json
    from harness.cli_args import UsageError

    _check(args)
    if args.resume is not None:
        if not args.resume.endswith(".csv"):
            raise UsageError(f"--resume = {args.resume!r}: expected the .csv file of an interrupted sweep")
        if args.out is not None and args.out != args.resume:
            raise UsageError(f"--out = {args.out!r}: --resume appends to its own file; leave --out out")
        args.out = args.resume
    spec = sw.SweepSpec(
        rooms=args.rooms, candles=args.candles, n_candles=args.n_candles, grid_step_m=args.grid_step,
        seeds=args.seeds, noise=args.noise, params=tuple(args.param), mode=args.mode, n_random=args.samples,
        sweep_seed=args.sweep_seed, firmware={k: v for g, k, v in args.settings if g == "firmware"},
        robot={k: v for g, k, v in args.settings if g == "robot"}, link=args.link, arena=args.arena,
        robot_file=args.robot, start=args.start, arena_jitter=args.arena_jitter or 0.0,
        furniture=args.furniture or 0)
    jobs = sw.build_jobs(spec)
    if not jobs:
        raise UsageError("the sweep has no missions (no legal candle position?)")
    stream_csv = bool(args.out) and args.out.endswith(".csv")
    cols = sw.header(spec.params)
    identity = sweep_identity(args, jobs) if stream_csv else {}
    kept: list[dict[str, Any]] = []
    if args.resume is not None:
        try:
            kept = [store.typed_row(r) for r in
                    store.load_for_resume(args.resume, identity, [sw.replay_command(j) for j in jobs], cols)]
        except store.ResumeError as exc:
            raise UsageError(str(exc)) from None
    done_ids = {r["id"] for r in kept}
    todo = [j for j in jobs if j["id"] not in done_ids]
    where = args.scheduler or "the local cores"
    if args.resume is not None:
        print(f"sweep: {len(jobs)} missions, {len(done_ids)} already in {args.resume}, "
              f"{len(todo)} to run on {where}", flush=True)
    else:
        print(f"sweep: {len(jobs)} missions on {where}", flush=True)
    _quiet_distributed_logs()
    rows: list[dict[str, Any]] = []
    stream: store.RowStream | None = None
    ran = [0]  # missions back from the workers in this run (for the report when nothing is kept)
    t0 = time.perf_counter()
    try:
        if todo:
            engine = sw.pick_engine(todo, args.scheduler, args.engine)
            with (sw.dask_client(args.scheduler, args.workers) if engine == "dask"
                  else contextlib.nullcontext()) as client:
                if stream_csv:  # opened once the cluster is up: bad input or no cluster leaves no file
                    try:
                        stream = (store.RowStream.append(args.out, cols) if args.resume is not None
                                  else store.RowStream.create(args.out, cols, identity))
                    except OSError as exc:
                        raise UsageError(f"--out = {args.out!r}: cannot write ({exc.strerror or exc})") from None
                from tqdm import tqdm
                with tqdm(total=len(todo), unit="mission", disable=args.no_progress, smoothing=0.1) as bar:
                    def progress(n: int) -> None:
                        ran[0] += n
                        bar.update(n)

                    sink = stream.write if stream else None
                    if client is None:  # forked local workers
                        rows = sw.run_forked(todo, args.workers or os.cpu_count() or 1, progress, sink)
                    else:
                        rows = sw.run_on(client, todo, args.workers, progress=progress, sink=sink)
    except sw.ClusterUnreachableError as exc:
        raise UsageError(f"--scheduler = {args.scheduler!r}: cannot reach the cluster ({exc})") from None
    except KeyboardInterrupt:
        print(f"ffr: interrupted: {_lost_line(args, len(jobs), stream, len(kept), ran[0])}", file=sys.stderr)
        return EXIT_INTERRUPTED
    except sw.ClusterLostError as exc:
        print(f"ffr: error: lost the Dask cluster ({exc}): "
              f"{_lost_line(args, len(jobs), stream, len(kept), ran[0])}", file=sys.stderr)
        return EXIT_CLUSTER_LOST
    finally:
        if stream is not None:
            stream.close()
    wall = time.perf_counter() - t0
    rows = sorted(kept + rows, key=lambda r: r["id"])
    # the throughput is that of the missions run now, not of those a resumed file already held
    print(sw.summary(rows, spec.params, wall if not kept else None))
    if kept and todo:
        print(f"wall time {wall:.1f} s for the {len(todo)} missions run now: {len(todo) / wall:.1f} missions/s")
    if stream_csv:
        store.finish(args.out)
    elif args.out:
        sw.write_results(args.out, rows)
    if args.plot:
        sw.plot(args.plot, rows, spec.params, args.arena)
    n_ok = sum(1 for r in rows if r["success"])
    rate = 100.0 * n_ok / len(rows)
    if args.json:
        payload = {"missions": len(rows), "succeeded": n_ok, "success_rate_pct": rate, "wall_s": wall,
                   "missions_per_s": len(todo) / wall if todo and wall > 0 else None,
                   "failures": [{"outcome": r["outcome"], "detail": r["detail"], "replay": r["replay"]}
                                for r in rows if not r["success"]]}
        write_json(args.json, payload)
    if args.min_success is not None and rate < args.min_success:
        return 1
    return 0


# Ctrl-C: the shell's 128 + SIGINT. A cluster lost mid-sweep: 1, as for a sweep whose missions did not all
# succeed (the missing ones did not), kept apart from 2 (bad input), which promises that nothing was written.
EXIT_INTERRUPTED, EXIT_CLUSTER_LOST = 130, 1


def _lost_line(args: argparse.Namespace, total: int, stream: Any, kept: int, ran: int) -> str:
    """How many missions finished and how many are missing, and how to get the rest (one line)."""
    if stream is not None or args.resume is not None:  # the file holds every finished mission
        done = stream.on_disk() if stream is not None else kept
        return (f"{done} of {total} missions finished and are kept in {args.out}, {total - done} "
                f"missing; the same command with --resume {args.out} runs only those")
    if args.out and args.out.endswith(".csv"):  # stopped while the cluster started: no file yet
        return f"0 of {total} missions finished, {total} missing; {args.out} not written"
    return f"{ran} of {total} missions finished, {total - ran} missing; none kept (no --out FILE.csv)"


__all__ = ["FfrInputError", "add_sweep_parser", "run_sweep"]
