"""Benchmarks (``make bench``): measured, never asserted.

One run prints, each goal beside its measured number and whether it is met:

* per-tick cost of each part inside compiled code (sensors, plant, the
  firmware call), replaying a recorded room 4 mission; the "firmware alone"
  floor (``ffr_step`` in a tight compiled loop over the mission's inputs);
* a whole mission, in-process (``ctypes:``): room 4 through the compiled loop
  (harness/tick.py) and through the Python loop, real-time factors;
* room 4 with the realistic profile (seeds 0-2) against the nominal mission:
  the goal is at most 2x the time per simulated second (CPU time);
* ``ffr sweep``'s engine with typical noise, in missions per minute: one core
  in this process, two forked worker processes (the local default), and local
  Dask clusters of one and two workers; then the realistic profile on two
  forked workers, at most 2x the CPU per mission of typical noise;
* start-up: ``python -m harness run --room 1`` as a whole process, warm cache
  (numba's and the .pyc files), beside the numba floor (import numpy and
  numba, call one cached kernel) that any such process pays.

``FFR_BENCH_MISSIONS`` (default 1000) sets the sweep size; ``FFR_BENCH_QUICK=1``
a smaller everything (a smoke run). Timings on a shared machine are noisy:
every number is the best of several runs.
"""

from __future__ import annotations

import dataclasses
import itertools
import os
import subprocess
import sys
import time
from collections.abc import Callable
from pathlib import Path

import numba as nb
import numpy as np

from harness.loop import I_SENS, run_mission
from harness.scenario import make_scenario
from harness.tick import _call_step
from sim_plant.broken_pipe import exit_with
from sim_plant.drivetrain import build_params, run_free
from sim_plant.plant import _advance
from sim_plant.robot import RobotParams
from sim_plant.sensors import NoiseProfile, load_noise_profile
from sim_plant.sensors.suite import _sample_kernel

REPO = Path(__file__).resolve().parents[1]

GOAL_RTF = 5000.0  # room 4 mission, times real time (90 s in under 18 ms)
GOAL_SWEEP_PER_MIN = 5000.0  # typical noise, the 2 cores
GOAL_STARTUP_S = 0.5  # `ffr run --room 1`, whole process, warm cache
GOAL_REAL_RATIO = 2.0  # the realistic profile at most this many times slower than nominal


def _best(fn: Callable[[], object], repeat: int = 5) -> float:
    best = float("inf")
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t0)
    return best


def _best_wall_cpu(fn: Callable[[], object], repeat: int = 5) -> tuple[float, float]:
    """Best wall time and best CPU time of this process (the CPU time is what a
    contended machine does not inflate: other processes' turns are not in it)."""
    wall = cpu = float("inf")
    for _ in range(repeat):
        c0 = time.process_time()
        t0 = time.perf_counter()
        fn()
        wall = min(wall, time.perf_counter() - t0)
        cpu = min(cpu, time.process_time() - c0)
    return wall, cpu


def _goal(label: str, value: str, met: bool, goal: str) -> None:
    print(f"  {label:44s} {value:>14s}   goal {goal:>12s}   {'MET' if met else 'NOT MET'}")


# -- the parts, in compiled loops over a recorded mission ------------------------

@nb.njit(cache=True)
def _sensors_loop(tf: np.ndarray, phi: np.ndarray, lit: np.ndarray, hw: np.ndarray,
                  ir_cfg: np.ndarray, ir_state: np.ndarray, cfg: np.ndarray, st: np.ndarray,
                  edges: np.ndarray, wall_polys: np.ndarray, doors: np.ndarray, npar: np.ndarray,
                  normals: np.ndarray, uniforms: np.ndarray, npos: np.ndarray,
                  srcs: np.ndarray, beam: np.ndarray, scratch: np.ndarray,
                  enorm: np.ndarray, esoa: np.ndarray, wsoa: np.ndarray, keep: np.ndarray) -> None:
    for k in range(tf.shape[0]):
        if _sample_kernel(tf[k, 0], tf[k, 1], tf[k, 2], tf[k, 3], phi[k, 0], phi[k, 1], lit[k],
                          hw, ir_cfg, ir_state, cfg, st, edges, wall_polys, doors, npar,
                          normals, uniforms, npos, srcs, beam, scratch, enorm, esoa, wsoa, keep):
            npos[0] = 0  # reuse the block: the cost is the same, the numbers need not be
            npos[1] = 0


@nb.njit(cache=True)
def _plant_loop(pwm: np.ndarray, S: np.ndarray, P: np.ndarray, poly: np.ndarray,
                walls: np.ndarray, bbox: np.ndarray, n_sub: int) -> None:
    for k in range(pwm.shape[0]):
        _advance(S, P, poly, walls, bbox, pwm[k, 0], pwm[k, 1], n_sub)


@nb.njit(cache=True)
def _drive_loop(pwm: np.ndarray, S: np.ndarray, P: np.ndarray, n_sub: int) -> None:
    for k in range(pwm.shape[0]):
        run_free(S, P, pwm[k, 0], pwm[k, 1], n_sub)


@nb.njit(cache=True)
def _firmware_loop(fn: int, st: int, inputs: int, in_size: int, out: int, n: int) -> None:
    for k in range(n):
        _call_step(fn, st, inputs + k * in_size, out)


def bench_parts(repeat: int) -> float:
    """Per-tick costs in compiled loops; returns the firmware-alone cost (us/tick)."""
    from ffr_link.abi import INPUTS_DTYPE
    from ffr_link.base import new_outputs
    from ffr_link.ctypes_link import CtypesLink
    from harness.firmware_config import build_config
    from sim_plant.candle import Candle
    from sim_plant.plant import Plant
    from sim_plant.sensors import SensorSuite, new_output

    scn = make_scenario(room=4, noise="typical", seed=1)
    res, tr = run_mission(scn)
    n = len(tr.f)
    tm = scn.timing
    # what each part saw, tick by tick
    phi = np.zeros((n, 2))
    plant = Plant(scn.arena, scn.robot, *scn.start, plant_dt=tm.plant_dt_ms / 1000.0)
    n_sub = plant.steps_for(tm.firmware_period_ms / 1000.0)
    S0 = plant.kernel_args()[0].copy()
    pwm = tr.i[:, :2].astype(np.int64)
    for k in range(n):  # wheel angles along the recorded drive (the plant is deterministic)
        phi[k] = plant.phi_l, plant.phi_r
        plant.apply(int(pwm[k, 0]), int(pwm[k, 1]))
        plant.integrate(tm.firmware_period_ms / 1000.0)
    ext = res.time_to_extinguish_s if res.time_to_extinguish_s is not None else np.inf
    lit = tr.f[:, 0] < ext

    def sensors_with(noise: NoiseProfile, sources: np.ndarray | None = None) -> Callable[[], None]:
        def run() -> None:
            candle = Candle(*scn.candle, scn.robot, scn.arena)
            s = SensorSuite(scn.arena, scn.robot, candle, noise, np.random.default_rng(1),
                            ir_sources=sources)
            _sensors_loop(tr.f, phi, lit, new_output(), *s.kernel_args())
        return run

    sensors = sensors_with(scn.noise)
    # the same noise with the pre-issue-12 single ray, and with every sensor model of the
    # realistic profile (beam, latency, per-part timing; flame strength, flicker, wall
    # reflections, afterglow) plus one lamp (docs/sensors.md)
    real = load_noise_profile("realistic")
    single = dataclasses.replace(scn.noise, ranger=load_noise_profile("single_ray").ranger)
    rich = dataclasses.replace(scn.noise, ranger=real.ranger, flame_world=real.flame_world)
    sensors_single = sensors_with(single)
    sensors_rich = sensors_with(rich, np.array([[2.2, 0.5, 0.3, 1.5]]))

    def plant_run() -> None:
        p = Plant(scn.arena, scn.robot, *scn.start, plant_dt=tm.plant_dt_ms / 1000.0)
        S, P, poly, walls, bbox = p.kernel_args()
        S[:] = S0
        _plant_loop(pwm, S, P, poly, walls, bbox, n_sub)

    # Drive-train reality (sim_plant/reality.py): a realistic room 4 mission (seed 2 ends home
    # without a contact) replayed through its own drawn plant (slip, scrub, per-side constants,
    # battery sag, wall friction on) and through the ideal plant; and the drive train alone (no
    # walls) on that PWM, ideal vs reality on, the fair per-step comparison.
    rscn = make_scenario(room=4, noise="realistic", seed=2)
    real_robot = rscn.noise.reality.draw(rscn.robot, np.random.default_rng(rscn.seed))
    _, rtr = run_mission(rscn)
    rpwm = rtr.i[:, :2].astype(np.int64)
    nr = len(rpwm)

    def plant_on(robot: RobotParams) -> Callable[[], None]:
        def run() -> None:
            p = Plant(scn.arena, robot, *scn.start, plant_dt=tm.plant_dt_ms / 1000.0)
            S, P, poly, walls, bbox = p.kernel_args()
            _plant_loop(rpwm, S, P, poly, walls, bbox, n_sub)
        return run

    def drive_on(robot: RobotParams) -> Callable[[], None]:
        P = build_params(robot, tm.plant_dt_ms / 1000.0)

        def run() -> None:
            _drive_loop(rpwm, np.zeros(9), P, n_sub)
        return run

    plant_real, plant_ideal = plant_on(real_robot), plant_on(scn.robot)
    drive_real, drive_ideal = drive_on(real_robot), drive_on(scn.robot)

    link = CtypesLink()
    inputs = np.zeros(n, dtype=INPUTS_DTYPE)
    inputs["t_ms"] = np.arange(n) * tm.firmware_period_ms
    inputs["seq"] = np.arange(n)
    hw = tr.i[:, I_SENS:]
    inputs["ir_mv"] = hw[:, 0:5]
    inputs["flame"] = hw[:, 5:7]
    inputs["line"] = hw[:, 7]
    inputs["enc"] = hw[:, 8:10]
    inputs["start"] = 1
    out = new_outputs()
    cfg = build_config(scn.robot, scn.firmware, scn.source, start_area=scn.start_area)

    def firmware() -> None:
        link.reset(cfg)
        _firmware_loop(link.step_address, link.state_address, inputs.ctypes.data,
                       INPUTS_DTYPE.itemsize, out.ctypes.data, n)

    def firmware_ctypes() -> None:
        link.reset(cfg)
        step = link.lib.ffr_step
        st = link.state_address
        base = inputs.ctypes.data
        size = INPUTS_DTYPE.itemsize
        o = out.ctypes.data
        for k in range(n):
            step(st, base + k * size, o)

    for fn in (sensors, sensors_single, sensors_rich, plant_run, plant_real, drive_real, firmware):
        fn()  # compile / load
    print(f"per tick, inside compiled code, replaying a room 4 mission with typical noise "
          f"({n} ticks, best of {repeat}):")
    rows = (("sensors (5 rangers, 2 flame, line, encoders)", sensors),
            (f"plant ({n_sub} x {tm.plant_dt_ms:g} ms steps, walls, contacts)", plant_run),
            ("firmware ffr_step (the 'firmware alone' floor)", firmware),
            ("sensors, rangers as one ray (before issue 12)", sensors_single),
            ("sensors, every realistic sensor model and a lamp", sensors_rich))
    costs = {}
    for name, fn in rows:
        costs[name] = _best(fn, repeat) / n * 1e6
        print(f"  {name:52s} {costs[name]:6.2f} us")
    fw = costs[rows[2][0]]
    print(f"drive-train reality, a realistic room 4 mission's PWM ({nr} ticks, best of {repeat}):")
    for name, fn in (("plant, ideal drive train (the default)", plant_ideal),
                     ("plant, reality on (its own drawn robot)", plant_real),
                     ("drive train alone, no walls, ideal", drive_ideal),
                     ("drive train alone, no walls, reality on", drive_real)):
        print(f"  {name:52s} {_best(fn, repeat) / nr * 1e6:6.2f} us")
    print(f"  {'firmware ffr_step through ctypes from Python':52s} "
          f"{_best(firmware_ctypes, max(1, repeat // 2)) / n * 1e6:6.2f} us")
    floor = fw * n / 1e6
    print(f"  firmware alone over this mission: {floor * 1e3:.1f} ms for {res.sim_time_s:.1f} s "
          f"= {res.sim_time_s / floor:,.0f}x real time (the floor of any loop around it)")
    return fw


# -- whole missions ----------------------------------------------------------------

def bench_missions(repeat: int) -> tuple[float, float]:
    """Room 4 through both loops, and the four rooms compiled, and room 4 with the realistic
    profile; returns room 4's real-time factor and realistic / nominal (CPU time)."""
    print(f"whole missions, in-process ctypes: link, trace recorded (best of {repeat}):")
    rtf4 = 0.0
    ratio = float("nan")
    for room in (1, 2, 3, 4):
        scn = make_scenario(room=room)
        res, _ = run_mission(scn)  # warm-up (numba cache, library load)
        wall, cpu = _best_wall_cpu(lambda scn=scn: run_mission(scn), repeat)
        ticks = round(res.sim_time_s / (scn.timing.firmware_period_ms / 1000.0)) + 1
        print(f"  room {room}, compiled loop: {res.sim_time_s:5.1f} s simulated in {wall * 1e3:6.1f} ms "
              f"= {res.sim_time_s / wall:7,.0f}x real time, {wall / ticks * 1e6:5.2f} us/tick "
              f"(CPU {cpu * 1e3:5.1f} ms = {res.sim_time_s / cpu:7,.0f}x)")
        if room == 4:
            rtf4 = res.sim_time_s / wall
            pwall, pcpu = _best_wall_cpu(lambda scn=scn: run_mission(scn, compiled=False), max(1, repeat // 2))
            print(f"  room 4, Python loop:   {res.sim_time_s:5.1f} s simulated in {pwall * 1e3:6.1f} ms "
                  f"= {res.sim_time_s / pwall:7,.0f}x real time, {pwall / ticks * 1e6:5.2f} us/tick "
                  f"(CPU {pcpu * 1e3:5.1f} ms = {res.sim_time_s / pcpu:7,.0f}x)")
            _goal("room 4 mission, compiled, real-time factor", f"{rtf4:,.0f}x", rtf4 >= GOAL_RTF,
                  f">= {GOAL_RTF:,.0f}x")
            _goal("  the same as wall time for a 90 s mission", f"{90.0 / rtf4 * 1e3:.1f} ms",
                  rtf4 >= GOAL_RTF, f"< {90.0 / GOAL_RTF * 1e3:.0f} ms")
            _goal("  the same on CPU time", f"{res.sim_time_s / cpu:,.0f}x", res.sim_time_s / cpu >= GOAL_RTF,
                  f">= {GOAL_RTF:,.0f}x")
            ratio = bench_realistic_mission(repeat, res.sim_time_s / cpu)
    return rtf4, ratio


def bench_realistic_mission(repeat: int, rtf_nominal_cpu: float) -> float:
    """Room 4 with the realistic profile (drawn robot, slip, scrub, battery sag, the datasheet
    sensors, latency, flicker, reflections), seeds 0-2 together, against the nominal mission:
    CPU-time real-time factors (what the machine's other load does not inflate)."""
    scns = [make_scenario(room=4, noise="realistic", seed=seed) for seed in (0, 1, 2)]
    sim = sum(run_mission(scn)[0].sim_time_s for scn in scns)  # warm-up

    def all3() -> None:
        for scn in scns:
            run_mission(scn)
    wall, cpu = _best_wall_cpu(all3, repeat)
    rtf = sim / cpu
    print(f"  room 4, realistic profile, seeds 0-2: {sim:5.1f} s simulated in {wall * 1e3:6.1f} ms "
          f"= {sim / wall:7,.0f}x real time (CPU {cpu * 1e3:5.1f} ms = {rtf:7,.0f}x)")
    ratio = rtf_nominal_cpu / rtf
    _goal("  realistic / nominal, time per simulated s", f"{ratio:.2f}x", ratio <= GOAL_REAL_RATIO,
          f"<= {GOAL_REAL_RATIO:g}x")
    return ratio


# -- sweeps ------------------------------------------------------------------------

def _cpu_s() -> float:
    """CPU seconds of this process and its reaped children: on a shared machine the
    cores we got, beside the wall time."""
    import resource

    tot = 0.0
    for who in (resource.RUSAGE_SELF, resource.RUSAGE_CHILDREN):
        r = resource.getrusage(who)
        tot += r.ru_utime + r.ru_stime
    return tot


def bench_sweep(n: int) -> tuple[float, float]:
    """``ffr sweep``'s engine, typical noise: 1 core, 2 forked workers, Dask with 1 and 2 workers."""
    from harness import sweep as sw

    per_room = max(1, n // 4)
    spec = sw.SweepSpec(candles="random", n_candles=per_room, seeds=(0,), noise="typical")
    jobs = sw.build_jobs(spec)[:n]
    print(f"sweep: {len(jobs)} missions (random legal candles, typical noise), {os.cpu_count()} cores here, "
          f"start and stop of the workers included:")
    sw.run_local_serial(jobs[:4])  # warm this process
    rates: dict[str, float] = {}
    cpu2 = float("nan")
    runs = (("1 core, this process", lambda: sw.run_local_serial(jobs)),
            ("2 cores, forked workers (ffr sweep's default)", lambda: sw.execute(jobs, workers=2)),
            ("local Dask cluster, 1 worker", lambda: sw.execute(jobs, workers=1, engine="dask")),
            ("local Dask cluster, 2 workers", lambda: sw.execute(jobs, workers=2, engine="dask")))
    for name, fn in runs:
        c0 = _cpu_s()
        t0 = time.perf_counter()
        rows = fn()
        wall = time.perf_counter() - t0
        cpu = _cpu_s() - c0
        rates[name] = len(rows) / wall * 60
        if name.startswith("2 cores"):
            cpu2 = cpu / len(rows)
        ok = sum(1 for r in rows if r["success"])
        print(f"  {name:46s} {rates[name]:7,.0f} missions/min ({wall:5.1f} s wall, "
              f"{cpu / len(rows) * 1e3:5.1f} ms CPU/mission, {cpu / wall:4.2f} cores busy, {ok} succeeded)")
    one, two, d1, d2 = (rates[name] for name, _ in runs)
    print(f"  on two free cores the forked workers' CPU time alone would allow "
          f"{2 * 60.0 / cpu2:,.0f} missions/min (worker start and stop not counted)")
    print(f"  scaling: 2 forked workers / 1 core {two / one:.2f}x; Dask 2 workers / 1 worker {d2 / d1:.2f}x; "
          f"Dask 2 workers / forked 2 workers {d2 / two:.2f}x")
    _goal("sweep on the 2 cores (ffr sweep, forked workers)", f"{two:,.0f}/min", two >= GOAL_SWEEP_PER_MIN,
          f">= {GOAL_SWEEP_PER_MIN:,.0f}/min")
    _goal("  the same on a local Dask cluster, 2 workers", f"{d2:,.0f}/min", d2 >= GOAL_SWEEP_PER_MIN,
          f">= {GOAL_SWEEP_PER_MIN:,.0f}/min")
    # the realistic profile: the same missions, each on its own drawn robot
    rspec = dataclasses.replace(spec, noise="realistic")
    rjobs = sw.build_jobs(rspec)[:n]
    sw.run_local_serial(rjobs[:4])
    c0 = _cpu_s()
    t0 = time.perf_counter()
    rows = sw.execute(rjobs, workers=2)
    wall = time.perf_counter() - t0
    rcpu = (_cpu_s() - c0) / len(rows)
    real = len(rows) / wall * 60
    print(f"  {'realistic profile, 2 forked workers':46s} {real:7,.0f} missions/min ({wall:5.1f} s wall, "
          f"{rcpu * 1e3:5.1f} ms CPU/mission, {sum(1 for r in rows if r['success'])} succeeded)")
    ratio = rcpu / cpu2
    _goal("  realistic / typical, CPU per mission", f"{ratio:.2f}x", ratio <= GOAL_REAL_RATIO,
          f"<= {GOAL_REAL_RATIO:g}x")
    return two, ratio


# -- the arena's checks --------------------------------------------------------------

def bench_arena(repeat: int) -> tuple[float, float]:
    """The arena's checks (sim_plant/arena.py, validate_arena): paid for every jittered arena a sweep
    draws, and for every row that ``python -m harness.start_room`` or ``failure_places`` rebuilds."""
    from sim_plant.arena import DEFAULT_ARENA, load_arena, validate_arena
    from sim_plant.arena_jitter import jitter_arena

    arena = load_arena(DEFAULT_ARENA)
    seeds = itertools.count()  # each draw its own jitter
    check = _best(lambda: validate_arena(arena), repeat)
    draw = _best(lambda: jitter_arena(arena, 0.025, np.random.default_rng(next(seeds))), repeat)
    print(f"arena: the 2004 arena's checks {check * 1e3:.1f} ms; a +-2.5 cm jittered arena drawn and checked "
          f"{draw * 1e3:.1f} ms (best of {repeat})")
    return check, draw


# -- start-up ----------------------------------------------------------------------

def _proc_s(argv: list[str], repeat: int, extra_env: dict[str, str] | None = None) -> tuple[float, float]:
    """Best wall and best CPU seconds of a whole child process."""
    import resource

    env = _startup_env(extra_env)
    wall = cpu = float("inf")
    for _ in range(repeat):
        r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
        t0 = time.perf_counter()
        subprocess.run(argv, cwd=REPO, env=env, check=True, stdout=subprocess.DEVNULL)
        wall = min(wall, time.perf_counter() - t0)
        r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpu = min(cpu, r1.ru_utime - r0.ru_utime + r1.ru_stime - r0.ru_stime)
    return wall, cpu


def _startup_env(extra_env: dict[str, str] | None) -> dict[str, str]:
    # a warm cache is numba's and Python's own: let the child write its .pyc files
    env = {k: v for k, v in os.environ.items() if k != "PYTHONDONTWRITEBYTECODE"}
    env["PYTHONPATH"] = str(REPO)
    env["FFR_NO_SERVER"] = "1"
    env.update(extra_env or {})
    return env


def bench_startup(repeat: int) -> float:
    import tempfile

    py = sys.executable
    run = [py, "-m", "harness", "run", "--room", "1"]
    floor = [py, "-c", "import numpy as np; from sim_plant.geometry import point_in_convex; "
                       "point_in_convex(0.0, 0.0, np.zeros((4, 2)))"]
    _proc_s(run, 1)  # warm the caches (numba's and the .pyc files)
    _proc_s(floor, 1)
    print(f"start-up, whole processes, warm caches (best of {repeat}):")
    for label, argv in (("python (nothing imported)", [py, "-c", "pass"]),
                        ("python -c 'import numpy'", [py, "-c", "import numpy"]),
                        ("python -c 'import numba'", [py, "-c", "import numba"]),
                        ("numba floor: import + one cached kernel call", floor),
                        ("python -c 'import harness.loop'", [py, "-c", "import harness.loop"])):
        w, c = _proc_s(argv, repeat)
        print(f"  {label:44s} {w:6.3f} s (CPU {c:.3f} s)")
        if argv is floor:
            fw, fc = w, c
    s, c = _proc_s(run, repeat)
    print(f"  ffr run --room 1, no server (FFR_NO_SERVER=1)  {s:6.3f} s (CPU {c:.3f} s)")
    print(f"    of which the numba floor {fw:.3f} s (CPU {fc:.3f} s); ffr run's own part {s - fw:.3f} s "
          f"(CPU {c - fc:.3f} s)")
    # The same command with a warm server (`ffr server start`, harness/server.py): this process
    # only hands the command over; the CPU is the server's fork's, not counted here.
    with tempfile.TemporaryDirectory(prefix="ffrb-", dir="/tmp") as d:
        served = {"FFR_SERVER_DIR": d, "FFR_NO_SERVER": "0"}
        t0 = time.perf_counter()
        subprocess.run([py, "-m", "harness", "server", "start"], cwd=REPO, env=_startup_env(served), check=True,
                       stdout=subprocess.DEVNULL)
        ready = time.perf_counter() - t0
        try:
            w, _ = _proc_s(run, repeat, served)
        finally:
            subprocess.run([py, "-m", "harness", "server", "stop"], cwd=REPO, env=_startup_env(served),
                           check=True, stdout=subprocess.DEVNULL)
    print(f"  ffr server start (once; the server then waits, up to an hour idle)  {ready:6.3f} s")
    _goal("ffr run --room 1, warm server (python -m harness)", f"{w:.3f} s", w < GOAL_STARTUP_S,
          f"< {GOAL_STARTUP_S} s")
    return w


PARTS = ("parts", "missions", "arena")


def main(argv: list[str] | None = None) -> int:
    """``python -m harness.bench``: everything and the goals (``make bench``);
    ``python -m harness.bench parts missions arena``: only those sections, no goal summary (to set
    two trees side by side: run it in each, alternately)."""
    args = sys.argv[1:] if argv is None else argv
    quick = os.environ.get("FFR_BENCH_QUICK", "") not in ("", "0")
    repeat = 2 if quick else 5
    if args:
        bad = [a for a in args if a not in PARTS]
        if bad:
            print(f"python -m harness.bench: error: unknown section {bad[0]!r} (sections: {', '.join(PARTS)})",
                  file=sys.stderr)
            return 2
        if "parts" in args:
            bench_parts(repeat)
        if "missions" in args:
            bench_missions(repeat)
        if "arena" in args:
            bench_arena(repeat)
        return 0
    n = int(os.environ.get("FFR_BENCH_MISSIONS", "40" if quick else "1000"))
    bench_parts(repeat)
    bench_arena(repeat)
    rtf, mreal = bench_missions(repeat)
    rate, sreal = bench_sweep(n)
    start = bench_startup(repeat)
    print("goals:")
    _goal("room 4 mission, real-time factor", f"{rtf:,.0f}x", rtf >= GOAL_RTF, f">= {GOAL_RTF:,.0f}x")
    _goal("sweep, typical noise, 2 cores", f"{rate:,.0f}/min", rate >= GOAL_SWEEP_PER_MIN,
          f">= {GOAL_SWEEP_PER_MIN:,.0f}/min")
    _goal("realistic / nominal, room 4 mission", f"{mreal:.2f}x", mreal <= GOAL_REAL_RATIO,
          f"<= {GOAL_REAL_RATIO:g}x")
    _goal("realistic / typical, sweep", f"{sreal:.2f}x", sreal <= GOAL_REAL_RATIO, f"<= {GOAL_REAL_RATIO:g}x")
    _goal("start-up, ffr run --room 1 (warm server)", f"{start:.3f} s", start < GOAL_STARTUP_S, f"< {GOAL_STARTUP_S} s")
    if not quick:
        from harness.bench_links import bench_links
        bench_links()
    return 0


if __name__ == "__main__":
    exit_with(main)
