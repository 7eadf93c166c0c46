"""Sweeps: many missions over candle positions x seeds x parameters, on a Dask cluster.

``ffr sweep`` builds a list of jobs (plain dicts: candle, start, seed, noise,
firmware and robot settings), cuts it into chunks and hands the chunks to a
``dask.distributed`` client: the cluster at ``--scheduler tcp://HOST:PORT``,
or a ``LocalCluster`` of one single-threaded worker process per core
(``--engine dask``). Both go through the same code (``execute``), so a sweep
that runs here runs on a cluster unchanged. Local sweeps with the in-process
link default to worker processes forked from this one once it is warm
(``--engine processes``): the same chunks and rows without Dask's seconds of
worker start-up. Dask rather than a home-made pool: it is the established
engine for Python task farms, its workers are plain processes started with
``dask worker tcp://...`` on any machine, and it reports worker deaths and
re-runs lost tasks.

Each worker keeps its arena, robot and firmware link between chunks (the
in-process link is a shared library, loaded once per process); a mission is
one ``run_mission`` without trace. Results come back as rows (``ROW_FIELDS``
plus one column per swept parameter), chunk by chunk as they finish (``run_on``'s
``sink``: ``ffr sweep`` streams them to its CSV, ``harness.sweep_store``), and are
written as CSV or Parquet, with a summary and pictures.
"""

from __future__ import annotations

import contextlib
import csv
import functools
import io
import itertools
import json
import math
import multiprocessing
import os
import shlex
import signal
import sys
import threading
import time
from collections import Counter
from collections.abc import Callable, Iterable, Iterator, Sequence
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from harness.atomic import write_bytes_atomic
from harness.sigint_guard import sigint_deferred
from sim_plant.errors import FfrInputError

ROW_FIELDS = ["id", "room", "candle_x", "candle_y", "seed", "noise", "start_x", "start_y", "start_heading_deg",
              "arena_jitter", "jitter_seed", "furniture", "outcome", "success", "detail",
              "time_to_extinguish_s", "total_time_s", "wall_contacts", "min_wall_clearance_m",
              "path_length_m", "sim_time_s", "replay"]


SHOW_REPLAYS = 10  # failures whose replay command the summary prints (all are in --out and --json)


@dataclass(frozen=True)
class Param:
    """One swept setting: ``firmware.NAME`` or ``robot.PATH`` over values (or a range)."""

    key: str  # "firmware.cruise_speed_mm_s", "robot.ir.LF.angle_deg"
    values: tuple[float, ...]
    lo: float
    hi: float

    @property
    def group(self) -> str:
        return self.key.partition(".")[0]

    @property
    def name(self) -> str:
        return self.key.partition(".")[2]


def parse_param(text: str) -> Param:
    """``KEY=LO:HI:N`` (N values, evenly spaced) or ``KEY=V1,V2,...``."""
    key, sep, spec = text.partition("=")
    group, dot, name = key.partition(".")
    bad = f"--param = {text!r}: expected firmware.NAME=LO:HI:N, robot.PATH=LO:HI:N or KEY=V1,V2,..."
    if not sep or not dot or group not in ("firmware", "robot") or not name:
        raise ValueError(bad)
    try:
        if ":" in spec:
            parts = spec.split(":")
            if len(parts) != 3:
                raise ValueError
            lo, hi, n = float(parts[0]), float(parts[1]), int(parts[2])
            if n < 1 or not (math.isfinite(lo) and math.isfinite(hi)):
                raise ValueError
            vals = tuple(float(v) for v in np.linspace(lo, hi, n)) if n > 1 else (lo,)
        else:
            vals = tuple(float(v) for v in spec.split(","))
            if not vals or not all(math.isfinite(v) for v in vals):
                raise ValueError
            lo, hi = min(vals), max(vals)
    except ValueError:
        raise ValueError(bad) from None
    # integers stay integers (firmware integer fields refuse 3.0 only if not whole; keep it clean)
    vals = tuple(int(v) if float(v).is_integer() else v for v in vals)
    return Param(key, vals, lo, hi)


@dataclass
class SweepSpec:
    rooms: tuple[int, ...] = (1, 2, 3, 4)
    candles: str = "random"  # "default" (the room's spot), "random" (n_candles per room), "grid"
    n_candles: int = 10  # random: per room; grid: spacing in cm if > 0
    grid_step_m: float = 0.10
    seeds: tuple[int, ...] = (0,)
    noise: str = "none"
    params: tuple[Param, ...] = ()
    mode: str = "grid"  # params: "grid" = every combination, "random" = n_random draws in the ranges
    n_random: int = 0
    sweep_seed: int = 0  # the draws that place random candles and random parameters
    firmware: dict[str, Any] = field(default_factory=dict)  # fixed settings for every mission
    robot: dict[str, Any] = field(default_factory=dict)
    link: str = "ctypes:"
    arena: str | None = None
    robot_file: str | None = None
    start: tuple[float, float, float] | str | None = None  # a pose, "random" (from each mission's seed), None
    arena_jitter: float = 0.0  # m: each mission's arena jittered, drawn from its seed
    furniture: int = 0  # pieces standing in the rooms, drawn from each mission's seed


def candle_positions(spec: SweepSpec) -> list[tuple[int, float, float]]:
    from sim_plant.arena import load_arena
    from sim_plant.errors import CandlePlacementError

    arena = load_arena(spec.arena)
    out: list[tuple[int, float, float]] = []
    rng = np.random.default_rng(spec.sweep_seed)
    for rid in spec.rooms:
        room = arena.room(rid)
        if spec.candles == "default":
            out.append((rid, *room.default_candle))
        elif spec.candles == "random":
            out += [(rid, *arena.random_candle(rid, rng)) for _ in range(spec.n_candles)]
        else:  # grid: cell centres of a square grid, the legal ones
            lo, hi = room.polygon.min(axis=0), room.polygon.max(axis=0)
            h = spec.grid_step_m
            for x in np.arange(lo[0] + h / 2, hi[0], h):
                for y in np.arange(lo[1] + h / 2, hi[1], h):
                    try:
                        arena.check_candle(float(x), float(y))
                    except CandlePlacementError:
                        continue
                    out.append((rid, round(float(x), 4), round(float(y), 4)))
    return out


def param_sets(spec: SweepSpec) -> list[dict[str, Any]]:
    if not spec.params:
        return [{}]
    if spec.mode == "random":
        rng = np.random.default_rng([spec.sweep_seed, 1])
        return [{p.key: float(rng.uniform(p.lo, p.hi)) for p in spec.params} for _ in range(spec.n_random)]
    return [dict(zip([p.key for p in spec.params], combo, strict=True))
            for combo in itertools.product(*[p.values for p in spec.params])]


def build_jobs(spec: SweepSpec) -> list[dict[str, Any]]:
    """Every mission of the sweep as a plain (picklable) dict."""
    jobs = []
    for (room, cx, cy), params, seed in itertools.product(candle_positions(spec), param_sets(spec), spec.seeds):
        fw = dict(spec.firmware) | {k.partition(".")[2]: v for k, v in params.items() if k.startswith("firmware.")}
        ro = dict(spec.robot) | {k.partition(".")[2]: v for k, v in params.items() if k.startswith("robot.")}
        jobs.append({"id": len(jobs), "room": room, "candle": (cx, cy), "seed": seed, "noise": spec.noise,
                     "firmware": fw, "robot": ro, "params": params, "link": spec.link,
                     "arena": spec.arena, "robot_file": spec.robot_file,
                     "start": list(spec.start) if isinstance(spec.start, tuple) else spec.start,
                     "arena_jitter": spec.arena_jitter, "furniture": spec.furniture})
    return jobs


def replay_command(job: dict[str, Any]) -> str:
    """The one-line ``ffr run`` that replays a job's mission."""
    cx, cy = job["candle"]
    argv = ["ffr", "run", "--candle", f"{cx!r},{cy!r}", "--seed", str(job["seed"])]
    if job["noise"] != "none":
        argv += ["--noise", job["noise"]]
    for group in ("firmware", "robot"):
        for k, v in job[group].items():
            argv += ["--set", f"{group}.{k}={json.dumps(v)}"]
    if job.get("arena"):
        argv += ["--arena", job["arena"]]
    start = job.get("start")
    if start in ("random", "hallway"):
        argv += ["--start", start]
    elif start is not None:
        from harness.scenario import _degrees_exact
        argv += ["--start", f"{start[0]!r},{start[1]!r},{_degrees_exact(start[2])!r}"]
    if job.get("arena_jitter"):
        argv += ["--arena-jitter", repr(job["arena_jitter"])]
    if job.get("furniture"):
        argv += ["--furniture", str(job["furniture"])]
    if job.get("robot_file"):
        argv += ["--robot", job["robot_file"]]
    if job.get("link", "ctypes:") != "ctypes:":
        argv += ["--link", job["link"]]
    return shlex.join(argv)


# -- the worker side ------------------------------------------------------------

@functools.lru_cache(maxsize=4)
def _world(arena_file: str | None, robot_file: str | None) -> tuple[Any, Any]:
    from sim_plant.arena import load_arena
    from sim_plant.robot import load_robot
    return load_arena(arena_file), load_robot(robot_file)


@functools.cache
def _link(url: str) -> Any:
    """One open link per URL and worker, kept for its missions."""
    from ffr_link import open_link
    return open_link(url)


def run_job(job: dict[str, Any], local: dict[str, str] | None = None) -> dict[str, Any]:
    """One mission; a row of results. Bad settings become an 'error' row, not a crash.

    ``local`` maps the client's file paths to this worker's copies (``harness.sweep_payload``); the row
    keeps the client's paths.
    """
    from harness.loop import run_mission
    from harness.scenario import make_scenario
    from harness.sweep_payload import local_name, localise_link

    here = local or {}

    def mine(name: Any) -> Any:  # this worker's copy of a file the client named
        return local_name(name, here)

    jitter = float(job.get("arena_jitter") or 0.0)
    row: dict[str, Any] = {"id": job["id"], "room": job["room"], "candle_x": job["candle"][0],
                           "candle_y": job["candle"][1], "seed": job["seed"], "noise": job["noise"],
                           "arena_jitter": jitter, "jitter_seed": job["seed"] if jitter > 0.0 else None,
                           "furniture": int(job.get("furniture") or 0),
                           "replay": replay_command(job)}
    row |= job["params"]
    start = job.get("start")
    try:
        arena, robot = _world(mine(job.get("arena")), mine(job.get("robot_file")))
        scn = make_scenario(arena=arena, robot=robot, candle=tuple(job["candle"]), seed=job["seed"],
                            noise=mine(job["noise"]), firmware=job["firmware"], robot_overrides=job["robot"],
                            source="sweep", start=tuple(start) if isinstance(start, list) else start,
                            arena_jitter=jitter, furniture=int(job.get("furniture") or 0))
        row |= {"start_x": scn.start[0], "start_y": scn.start[1], "start_heading_deg": math.degrees(scn.start[2])}
        res, _ = run_mission(scn, _link(localise_link(job["link"], here)), record=False)
    except FfrInputError as exc:
        blank = {k: None for k in ROW_FIELDS if k not in row}  # every column there, as for a mission that ran
        return row | blank | {"outcome": "error", "success": False, "detail": str(exc)}
    return row | {
        "outcome": res.outcome, "success": res.outcome == "home" and res.wall_contacts == 0,
        "detail": res.detail, "time_to_extinguish_s": res.time_to_extinguish_s,
        "total_time_s": res.total_time_s, "wall_contacts": res.wall_contacts,
        "min_wall_clearance_m": res.min_wall_clearance_m, "path_length_m": res.path_length_m,
        "sim_time_s": res.sim_time_s,
    }


def run_chunk(jobs: list[dict[str, Any]], payload: Any = None) -> list[dict[str, Any]]:
    """A chunk's rows; ``payload`` (a ``sweep_payload.Payload``) brings the files the jobs name."""
    from harness.sweep_payload import materialise

    local = materialise(payload)
    rows = []
    for j in jobs:
        _test_hold(j["id"])
        rows.append(run_job(j, local))
    return rows


def _test_hold(job_id: int) -> None:
    """Tests only: with ``FFR_SWEEP_TEST_HOLD=PATH:ID`` in a worker's environment, missions from ID on wait
    while PATH exists, so a test can interrupt a sweep at a known point instead of racing it."""
    hold = os.environ.get("FFR_SWEEP_TEST_HOLD")
    if not hold:
        return
    path, _, first = hold.rpartition(":")
    while job_id >= int(first) and os.path.exists(path):
        time.sleep(0.05)


# -- the client side ------------------------------------------------------------

def chunked(jobs: Sequence[dict[str, Any]], n_workers: int, target: int = 16) -> list[list[dict[str, Any]]]:
    """Chunks big enough to amortise a task's overhead, small enough to balance the workers."""
    size = max(1, min(target, math.ceil(len(jobs) / max(1, 4 * n_workers))))
    return [list(jobs[i:i + size]) for i in range(0, len(jobs), size)]


class ClusterUnreachableError(OSError):
    """No cluster at ``--scheduler`` (an OSError, as the connection errors it replaces)."""


class ClusterLostError(Exception):
    """The cluster went away mid-sweep: the scheduler's connection lost, or a mission that kills its workers."""


@contextmanager
def _sigint_held() -> Iterator[None]:
    """Ctrl-C held back, not lost, while the local cluster starts: its worker processes inherit the blocked
    signal, so a Ctrl-C reaching the whole process group never interrupts them half-started (tracebacks);
    the sweep's own process gets it the moment the cluster is up."""
    hold = hasattr(signal, "pthread_sigmask") and threading.current_thread() is threading.main_thread()
    if hold:
        signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT})
    try:
        yield
    finally:
        if hold:
            signal.pthread_sigmask(signal.SIG_UNBLOCK, {signal.SIGINT})


@contextmanager
def dask_client(scheduler: str | None = None, workers: int | None = None) -> Iterator[Any]:
    """A client of the cluster at ``scheduler``, or of a local one (127.0.0.1) started and stopped here."""
    from dask.distributed import Client, LocalCluster

    cluster = client = None
    try:
        if scheduler:
            try:
                client = Client(scheduler, timeout="5s")
            except (OSError, TimeoutError) as exc:
                raise ClusterUnreachableError(str(exc)) from None
        else:
            n = workers or os.cpu_count() or 1
            with _sigint_held():
                # the preload makes workers the cluster restarts later ignore Ctrl-C too
                cluster = LocalCluster(n_workers=n, threads_per_worker=1, processes=True, dashboard_address=":0",
                                       host="127.0.0.1", silence_logs=50, preload=["harness.sweep_worker"])
            client = Client(cluster)
        yield client
    finally:
        # best effort and bounded: after Ctrl-C or a lost scheduler the rows are already on disk
        if client is not None:
            with contextlib.suppress(Exception):
                client.close(timeout=10)
        if cluster is not None:
            with contextlib.suppress(Exception):
                cluster.close(timeout=20)


def run_on(client: Any, jobs: Sequence[dict[str, Any]], workers: int | None = None,
           progress: Callable[[int], None] | None = None,
           sink: Callable[[list[dict[str, Any]]], None] | None = None) -> list[dict[str, Any]]:
    """Run the jobs on the client's cluster; each chunk's rows go to ``sink`` as it finishes; rows in job order.

    Raises ``ClusterLostError`` when the cluster goes away; every chunk that finished before has reached ``sink``.
    """
    from concurrent.futures import CancelledError

    from dask.distributed import KilledWorker, as_completed
    from distributed.comm.core import CommClosedError

    n_workers = max(1, len(client.scheduler_info().get("workers", {})) or (workers or 1))
    chunks = chunked(jobs, n_workers)
    from harness.sweep_payload import collect

    # the files the missions read travel with the work: a worker needs only `pip install ffr`
    payload = collect(jobs)
    shipped = client.scatter(payload, broadcast=True, hash=False) if payload else None
    futures = client.map(run_chunk, chunks, pure=False, payload=shipped)
    rows: list[dict[str, Any]] = []
    try:
        for fut in as_completed(futures):
            part = fut.result()
            rows += part
            if sink:
                sink(part)
            if progress:
                progress(len(part))
    except CommClosedError:
        # the scheduler died while a result was being fetched through it
        raise ClusterLostError("connection closed") from None
    except KilledWorker:
        raise ClusterLostError("a chunk of missions killed the workers that ran it") from None
    except CancelledError as exc:
        # a dead scheduler cancels every future with the reason "scheduler-connection-lost"
        raise ClusterLostError(getattr(exc, "reason", None) or "missions cancelled") from None
    return sorted(rows, key=lambda r: r["id"])


ENGINES = ("dask", "processes")


def pick_engine(jobs: Sequence[dict[str, Any]], scheduler: str | None, engine: str | None) -> str:
    """``dask`` for a scheduler or on request; else ``processes`` where it applies.

    ``processes`` (local worker processes forked from this warm process) is the
    default for a local sweep of in-process (``ctypes:``) missions on a system
    that can fork: a local Dask cluster spends ~5 s starting its workers,
    warming each (imports, numba caches) and stopping them, which is as long as
    600 missions take on two cores; forked workers start warm in milliseconds.
    Wire links keep Dask (a forked worker would share the parent's open port).
    """
    if engine is not None:
        if engine not in ENGINES:
            raise ValueError(f"engine = {engine!r}: expected one of {ENGINES}")
        if engine == "processes" and scheduler:
            raise ValueError("engine 'processes' is local: not with a scheduler")
        return engine
    # fork only on Linux: macOS lists it, but its system libraries are not fork-safe
    forkable = sys.platform.startswith("linux") and "fork" in multiprocessing.get_all_start_methods()
    in_process = all(str(j.get("link", "ctypes:")).startswith("ctypes:") for j in jobs)
    return "processes" if not scheduler and forkable and in_process else "dask"


def _forked_worker_init() -> None:
    # Ctrl-C reaches the whole process group: the sweep's own process keeps the finished rows
    # and stops the pool, so its workers ignore it instead of printing tracebacks
    signal.signal(signal.SIGINT, signal.SIG_IGN)


def run_forked(jobs: Sequence[dict[str, Any]], n: int, progress: Callable[[int], None] | None = None,
               sink: Callable[[list[dict[str, Any]]], None] | None = None) -> list[dict[str, Any]]:
    """Run the jobs on ``n`` local processes forked from this one; each chunk's rows go to ``sink``
    as it finishes; rows in job order. Ctrl-C stops the workers; what finished has reached ``sink``."""
    if not jobs:
        return []

    def done(part: list[dict[str, Any]]) -> None:
        rows.extend(part)
        if sink:
            sink(part)
        if progress:
            progress(len(part))

    rows: list[dict[str, Any]] = []
    # Warm this process first (modules, numba caches, the firmware library): the
    # workers inherit it all at the fork. The first job's row is kept.
    done(run_chunk(list(jobs[:1])))
    rest = jobs[1:]
    if n <= 1 or len(rest) < 2:
        for j in rest:
            done(run_chunk([j]))
        return sorted(rows, key=lambda r: r["id"])
    pool = None
    # Ctrl-C is only noted while the pool runs, and the loop below stops on it: raised as an
    # exception it could land inside Pool's own code (between a lock's acquire and its `with`),
    # leaving a lock held that terminate() then waits on for ever. It is raised after the pool
    # has stopped, with every finished chunk's rows already in `sink`.
    with sigint_deferred() as interrupted:
        try:
            # Ctrl-C held back while the workers are forked: one that came before a worker ran its
            # initializer would kill it half-started
            with _sigint_held():
                pool = multiprocessing.get_context("fork").Pool(n, initializer=_forked_worker_init)
            parts = pool.imap_unordered(run_chunk, chunked(rest, n))
            while not interrupted.is_set():
                try:
                    part = parts.next(timeout=0.1)
                except multiprocessing.TimeoutError:
                    continue
                except StopIteration:
                    break
                done(part)
            pool.close()
        finally:
            if pool is not None:
                pool.terminate()
                pool.join()
    return sorted(rows, key=lambda r: r["id"])


def execute(jobs: Sequence[dict[str, Any]], scheduler: str | None = None, workers: int | None = None,
            progress: Callable[[int], None] | None = None,
            sink: Callable[[list[dict[str, Any]]], None] | None = None,
            engine: str | None = None) -> list[dict[str, Any]]:
    """Run the jobs; rows in job order, the same rows whichever engine ran them (``pick_engine``)."""
    if pick_engine(jobs, scheduler, engine) == "processes":
        return run_forked(jobs, workers or os.cpu_count() or 1, progress, sink)
    with dask_client(scheduler, workers) as client:
        return run_on(client, jobs, workers, progress, sink)


def run_local_serial(jobs: Iterable[dict[str, Any]]) -> list[dict[str, Any]]:
    """The same missions in this process (tests, debugging)."""
    return [run_job(j) for j in jobs]


# -- results ---------------------------------------------------------------

def columns(rows: Sequence[dict[str, Any]]) -> list[str]:
    extra = sorted({k for r in rows for k in r} - set(ROW_FIELDS))
    return ROW_FIELDS[:-1] + extra + ["replay"]


def header(params: Sequence[Param]) -> list[str]:
    """The columns of a sweep's rows before any has run (``columns`` of its rows: one per swept key)."""
    return ROW_FIELDS[:-1] + sorted({p.key for p in params} - set(ROW_FIELDS)) + ["replay"]


def write_results(path: str | Path, rows: Sequence[dict[str, Any]]) -> None:
    """CSV (``.csv``) or Parquet (``.parquet``, needs pyarrow), written atomically."""
    cols = columns(rows)
    if str(path).endswith(".parquet"):
        import pyarrow as pa  # optional: only for Parquet output
        import pyarrow.parquet as pq
        table = pa.table({c: [r.get(c) for r in rows] for c in cols})
        buf = pa.BufferOutputStream()
        pq.write_table(table, buf)
        write_bytes_atomic(path, buf.getvalue().to_pybytes())
        return
    out = io.StringIO()
    w = csv.DictWriter(out, fieldnames=cols, lineterminator="\n")
    w.writeheader()
    for r in rows:
        w.writerow({c: ("" if r.get(c) is None else r.get(c)) for c in cols})
    write_bytes_atomic(path, out.getvalue().encode())


def read_results(path: str | Path) -> list[dict[str, Any]]:
    with open(path, encoding="utf-8", newline="") as fh:
        return list(csv.DictReader(fh))


def summary(rows: Sequence[dict[str, Any]], params: Sequence[Param] = (), wall_s: float | None = None) -> str:
    n = len(rows)
    ok = sum(1 for r in rows if r["success"])
    lines = [f"{n} missions: {ok} succeeded ({100.0 * ok / max(1, n):.1f} %) "
             f"- success = home with no wall touched"]
    if wall_s:
        lines.append(f"wall time {wall_s:.1f} s: {n / wall_s:.1f} missions/s")
    lines.append("room  missions  success   flame out p50/p90/max (s)   home p50/p90/max (s)")
    for room in sorted({r["room"] for r in rows}):
        rr = [r for r in rows if r["room"] == room]
        good = sum(1 for r in rr if r["success"])

        def pct(key: str, rr: list[dict[str, Any]] = rr) -> str:
            v = np.array([r[key] for r in rr if r[key] is not None], dtype=float)
            if not len(v):
                return f"{'-':>18}"
            p50, p90, mx = np.percentile(v, 50), np.percentile(v, 90), v.max()
            return f"{p50:6.1f}{p90:6.1f}{mx:6.1f}"

        lines.append(f"{room:>4}  {len(rr):>8}  {100.0 * good / len(rr):6.1f} %   "
                     f"{pct('time_to_extinguish_s'):>24}   {pct('total_time_s'):>20}")
    causes = Counter(_cause(r) for r in rows if not r["success"])
    if causes:
        lines.append("failure causes:")
        lines += [f"  {c:>5}  {k}" for k, c in causes.most_common()]
        failed = [r for r in rows if not r["success"]]
        lines.append(f"replay the first: {failed[0]['replay']}")
        if len(failed) > 1:
            shown = failed[1:SHOW_REPLAYS]
            lines.append(f"replay the next {len(shown)} of {len(failed) - 1} more failures:")
            lines += [f"  {r['replay']}" for r in shown]
    for p in params:
        lines.append(f"{p.key}:")
        for label, rr in param_groups(rows, p):
            if not rr:
                continue
            good = sum(1 for r in rr if r["success"])
            times = [r["total_time_s"] for r in rr if r["total_time_s"] is not None]
            lines.append(f"  {label:>21}: {100.0 * good / len(rr):6.1f} % of {len(rr)}, "
                         f"mean home time {np.mean(times) if times else float('nan'):6.1f} s")
    return "\n".join(lines)


def param_groups(rows: Sequence[dict[str, Any]], p: Param, bins: int = 5) -> list[tuple[str, list[dict[str, Any]]]]:
    """Rows by the value of a swept parameter; a random sweep's values in ``bins`` equal bins."""
    vals = sorted({float(r[p.key]) for r in rows})
    if len(vals) <= 12:
        return [(f"{v:.4g}", [r for r in rows if float(r[p.key]) == v]) for v in vals]
    edges = np.linspace(p.lo, p.hi, bins + 1)
    out = []
    for k in range(bins):
        lo, hi = edges[k], edges[k + 1]
        last = k == bins - 1
        out.append((f"{lo:.4g}..{hi:.4g}", [r for r in rows if lo <= float(r[p.key]) < hi
                                              or (last and float(r[p.key]) == hi)]))
    return out


def _cause(r: dict[str, Any]) -> str:
    if r["outcome"] == "home":
        return "home, but touched a wall"
    detail = str(r["detail"] or "")
    return f"{r['outcome']}: {detail}" if detail else r["outcome"]


def plot(path: str | Path, rows: Sequence[dict[str, Any]], params: Sequence[Param], arena_file: str | None) -> None:
    """Success rate and mean time over the arena's candle positions, and over each swept parameter."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.patches import Polygon

    from sim_plant.arena import load_arena

    arena = load_arena(arena_file)
    by_pos: dict[tuple[float, float], list[dict[str, Any]]] = {}
    for r in rows:
        by_pos.setdefault((float(r["candle_x"]), float(r["candle_y"])), []).append(r)
    xy = np.array(list(by_pos), dtype=float).reshape(-1, 2)
    rate = np.array([np.mean([bool(r["success"]) for r in v]) for v in by_pos.values()])
    mean_t = np.array([np.mean([r["total_time_s"] for r in v if r["total_time_s"] is not None] or [np.nan])
                       for v in by_pos.values()])
    ncol = 2 + len(params)
    fig, axes = plt.subplots(1, ncol, figsize=(5.2 * ncol, 5.0), squeeze=False)
    for ax, vals, title, cmap, lim in ((axes[0, 0], 100 * rate, "success rate (%)", "RdYlGn", (0, 100)),
                                       (axes[0, 1], mean_t, "mean time until home (s)", "viridis", (None, None))):
        for poly in arena.wall_polys:
            ax.add_patch(Polygon(poly, closed=True, color="#404040"))
        hx, hy = arena.home_center
        ax.add_patch(plt.Circle((hx, hy), arena.home_radius, fill=False, ec="#404040"))
        sc = ax.scatter(xy[:, 0], xy[:, 1], c=vals, cmap=cmap, vmin=lim[0], vmax=lim[1], s=28,
                        edgecolors="black", linewidths=0.3, zorder=3)
        fig.colorbar(sc, ax=ax, shrink=0.8)
        ax.set_xlim(0, arena.size[0])
        ax.set_ylim(0, arena.size[1])
        ax.set_aspect("equal")
        ax.set_title(f"{title} by candle position")
    for k, p in enumerate(params):
        ax = axes[0, 2 + k]
        vs = sorted({float(r[p.key]) for r in rows})
        if len(vs) > 12:  # random sweep: the values in bins
            edges = np.linspace(p.lo, p.hi, 11)
            centers = 0.5 * (edges[1:] + edges[:-1])
            groups = [g for _, g in param_groups(rows, p, bins=10)]
        else:
            centers = np.array(vs)
            groups = [[r for r in rows if float(r[p.key]) == v] for v in vs]
        rate_p = [100.0 * np.mean([bool(r["success"]) for r in g]) if g else np.nan for g in groups]
        time_p = [np.mean([r["total_time_s"] for r in g if r["total_time_s"] is not None] or [np.nan])
                  for g in groups]
        ax.plot(centers, rate_p, "o-", color="tab:green")
        ax.set_ylim(-5, 105)
        ax.set_ylabel("success rate (%)", color="tab:green")
        ax.set_xlabel(p.key)
        ax2 = ax.twinx()
        ax2.plot(centers, time_p, "s--", color="tab:blue")
        ax2.set_ylabel("mean time until home (s)", color="tab:blue")
        ax.set_title(p.key)
    fig.tight_layout()
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=90)
    plt.close(fig)
    write_bytes_atomic(path, buf.getvalue())


def timed_execute(jobs: Sequence[dict[str, Any]], scheduler: str | None, workers: int | None,
                  show_progress: bool, engine: str | None = None) -> tuple[list[dict[str, Any]], float]:
    from tqdm import tqdm

    t0 = time.perf_counter()
    with tqdm(total=len(jobs), unit="mission", disable=not show_progress, smoothing=0.1) as bar:
        rows = execute(jobs, scheduler, workers, progress=bar.update, engine=engine)
    return rows, time.perf_counter() - t0
