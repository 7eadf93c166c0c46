"""The ``ffr`` command line (also ``python -m harness``).

    ffr run [--room N | --candle X,Y | --scenario FILE.toml] [--seed S] [--link URL]
            [--json FILE|-] [--plot FILE.png] [--replay FILE.html] [--noise NAME] [--set KEY=VALUE ...]
    ffr table1 [--seed S] [--link URL] [--json FILE|-] [--plot FILE.png] [--replay-dir DIR]
    every command that runs missions also takes [--start X,Y,DEG|random] [--arena-jitter METRES]

Exit status: 0 every mission ended "home"; 1 a mission ended otherwise;
2 bad input (scenario, arena or robot file, argument) or a firmware/link
that cannot be used; the message is one line naming file, field and value.
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from harness.atomic import check_outputs, write_json
from harness.cli_args import (
    EXIT_INPUT,
    EXIT_MISSION,
    EXIT_OK,
    UsageError,
    _candle,
    _Parser,
    _seed,
    _setting,
    add_arena_options,
    firmware_link,
    library_of_link,
)
from sim_plant.broken_pipe import silence_stdout
from sim_plant.errors import FfrInputError

# The paper's Table 1 (its robot, its parameters).
PAPER_TABLE1 = {
    1: (40.8, 82.6),
    2: (84.2, 123.6),
    3: (120.6, 161.1),
    4: (156.8, 196.3),
}

def build_parser() -> argparse.ArgumentParser:
    p = _Parser(prog="ffr", description="Firmware-in-the-loop missions for a fire-fighting robot.")
    sub = p.add_subparsers(dest="command", required=True, parser_class=_Parser)

    def common(sp: argparse.ArgumentParser, link: str = "ctypes:",
               link_help: str = "firmware link URL (default ctypes:, in-process)") -> None:
        sp.add_argument("--seed", type=_seed, default=None, help="random seed (default 0 or the scenario's)")
        sp.add_argument("--link", default=link, help=link_help)
        sp.add_argument("--firmware", metavar="LIB.so", default=None,
                        help="a firmware library to run in-process (the same as --link ctypes:LIB.so)")
        sp.add_argument("--json", metavar="FILE|-", help="write the result(s) as JSON")
        sp.add_argument("--plot", metavar="FILE.png", help="draw the arena and the robot's path(s)")
        sp.add_argument("--noise", default=None,
                        help="sensor noise profile (none, typical, datasheet, envelope, harsh, FILE.toml; "
                             "realistic: also a robot and its calibration drawn from the seed)")
        sp.add_argument("--arena", default=None, help="arena TOML file (default: the 2004 arena)")
        sp.add_argument("--robot", default=None, help="robot TOML file (default: the shipped robot)")
        sp.add_argument("--set", dest="settings", type=_setting, action="append", default=[],
                        metavar="KEY=VALUE", help="firmware.NAME=V or robot.PATH=V (repeatable)")
        add_arena_options(sp)

    def where(sp: argparse.ArgumentParser) -> None:
        g = sp.add_mutually_exclusive_group()
        g.add_argument("--room", type=int, help="candle at the arena's default spot in room N")
        g.add_argument("--candle", type=_candle, help="candle at X,Y (metres)")
        g.add_argument("--scenario", help="scenario TOML file")

    run = sub.add_parser("run", help="run one mission")
    where(run)
    common(run)
    run.add_argument("--replay", metavar="FILE.html", help="write an interactive 3D replay (one offline HTML file)")
    run.add_argument("--list-firmware-config", action="store_true",
                     help="list the firmware's settable config fields (type, default) and exit")
    t1 = sub.add_parser("table1", help="the four-room missions beside the paper's Table 1")
    common(t1)
    t1.add_argument("--replay-dir", metavar="DIR", help="write each room's replay as DIR/replay_roomN.html")
    b2b = sub.add_parser("b2b", help="the same mission through two firmware builds: are the actuator traces identical?")
    where(b2b)
    common(b2b, "qemu:mps2-an386", "the build under test (default qemu:mps2-an386, the Cortex-M4 build on QEMU)")
    b2b.add_argument("--reference", default="ctypes:", help="the reference build (default ctypes:, the host library)")
    from harness.sweep_cli import add_sweep_parser
    add_sweep_parser(sub)
    bd = sub.add_parser("build", help="compile a firmware for the host: its library (ctypes:) and host board program")
    bd.add_argument("--src", default=None, metavar="DIR",
                    help="a firmware tree: DIR/src/*.c and DIR/include/*.h (default: ffr's own firmware)")
    bd.add_argument("--out", default="build/host", metavar="DIR", help="where to put them (default build/host)")
    bd.add_argument("--no-board", action="store_true", help="only the library")
    sv = sub.add_parser("server", help="keep a warm process that runs ffr commands without numba's start-up "
                                         "(docs/architecture.md)")
    sv.add_argument("action", choices=("start", "stop", "status"))
    sv.add_argument("--idle", type=_idle_seconds, default=3600.0, metavar="SECONDS",
                    help="start: end after this long without a command (default 3600)")
    return p


def _idle_seconds(text: str) -> float:
    try:
        v = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r}: expected seconds, a number > 0") from None
    if not v > 0 or v == float("inf"):
        raise argparse.ArgumentTypeError(f"{text!r}: expected seconds, a number > 0")
    return v


def _execute_build(args: argparse.Namespace) -> int:
    from ffr_firmware.build import HERE, BuildError, Tree, build

    src = Path(args.src) if args.src else HERE
    if not (src / "src").is_dir():
        raise UsageError(f"--src = {args.src!r}: no src/ directory of C sources there")
    out = Path(args.out)
    if out.exists() and not out.is_dir():
        raise UsageError(f"--out = {args.out!r}: not a directory")
    try:
        built = build(Tree(src.resolve()), out, board=not args.no_board)
    except BuildError as exc:
        raise UsageError(str(exc)) from None
    for kind, path in built.items():
        print(f"{kind}: {path}")
    return EXIT_OK


def _scenarios(args: argparse.Namespace, rooms: Sequence[int | None]) -> list[Any]:
    from harness.scenario import load_scenario, make_scenario
    from sim_plant.arena import load_arena
    from sim_plant.robot import load_robot

    fw = {k: v for g, k, v in args.settings if g == "firmware"}
    ro = {k: v for g, k, v in args.settings if g == "robot"}
    out = []
    if getattr(args, "scenario", None):
        scn = load_scenario(args.scenario, seed=args.seed, start=args.start, arena_jitter=args.arena_jitter,
                            furniture=args.furniture)
        if args.noise:
            from sim_plant.sensors import load_noise_profile
            scn.noise = load_noise_profile(args.noise)
        if fw:
            from ffr_link.ctypes_link import default_config, firmware_info
            from harness.firmware_config import apply_overrides
            lib = library_of_link(args.link)
            apply_overrides(default_config(lib), fw, "--set", firmware_info(lib))  # validate early
            scn.firmware.update(fw)
        if ro:
            from sim_plant.robot import override
            for k, v in ro.items():
                scn.robot = override(scn.robot, k, v, "--set")
        return [scn]
    arena = load_arena(args.arena)
    robot = load_robot(args.robot)
    for room in rooms:
        out.append(make_scenario(arena=arena, robot=robot, room=room,
                                 candle=getattr(args, "candle", None), seed=args.seed or 0,
                                 noise=args.noise or "none", firmware=fw, robot_overrides=ro,
                                 source="--set" if args.settings else "command line",
                                 start=args.start, arena_jitter=args.arena_jitter or 0.0,
                                 furniture=args.furniture))
    return out


def _fmt(v: float | None) -> str:
    from harness.scoring import seconds_text

    return seconds_text(v)  # as its JSON value prints


def _summary(res: Any) -> str:
    return (f"{res.scenario}: {res.outcome}"
            f"{' (' + res.detail + ')' if res.detail else ''}; flame out {_fmt(res.time_to_extinguish_s)} s, "
            f"home {_fmt(res.total_time_s)} s, wall contacts {res.wall_contacts}, "
            f"min clearance {res.min_wall_clearance_m * 100:.1f} cm, path {res.path_length_m:.2f} m, "
            f"score {res.score:.1f}")


def table1_text(results: Sequence[Any]) -> str:
    rooms = [r.room for r in results]
    w = 9
    head = f"{'':<28}" + "".join(f"{'room ' + str(n):>{w}}" for n in rooms)
    rows = [head]

    def row(label: str, vals: Sequence[str]) -> None:
        rows.append(f"{label:<28}" + "".join(f"{v:>{w}}" for v in vals))

    row("time to put flame out (s)", [_fmt(r.time_to_extinguish_s) for r in results])
    row("  paper", [_fmt(PAPER_TABLE1.get(n, (None, None))[0]) for n in rooms])
    row("total time until home (s)", [_fmt(r.total_time_s) for r in results])
    row("  paper", [_fmt(PAPER_TABLE1.get(n, (None, None))[1]) for n in rooms])
    row("outcome", [r.outcome for r in results])
    row("wall contacts", [str(r.wall_contacts) for r in results])
    row("min wall clearance (cm)", [f"{r.min_wall_clearance_m * 100:.1f}" for r in results])
    row("contest score", [f"{r.score:.1f}" for r in results])
    return "\n".join(rows)


def _beside_reference(args: argparse.Namespace, scenarios: Sequence[Any]) -> str:
    """``ffr table1 --firmware LIB.so`` of another firmware than ours: our firmware's table first,
    then (the caller prints it) the library's, each under its firmware's name (docs/teams.md). The
    JSON, plot and replays are the library's only. Without --firmware: nothing (the table as ever)."""
    from dataclasses import replace

    from ffr_link.ctypes_link import firmware_info
    from harness.loop import run_mission

    if not getattr(args, "firmware", None):
        return ""
    theirs = firmware_info(args.firmware)
    if theirs.is_reference:
        return ""
    ours = firmware_info(None)
    # the scenario's [firmware] settings are the library's fields, not ours
    results = [run_mission(replace(scn, firmware={}), "ctypes:", record=False)[0] for scn in scenarios]
    return (f"{ours.firmware_name} (ffr's firmware)\n{table1_text(results)}\n\n"
            f"{theirs.firmware_name} ({args.firmware})\n")


def _execute_b2b(args: argparse.Namespace) -> int:
    from ffr_link import LinkError, open_link
    from harness.b2b import back_to_back
    from harness.loop import warm_up

    scn = _scenarios(args, [args.room])[0]
    warm_up(scn, record=True)  # compile before a board waits
    target = open_link(args.link)
    reference = open_link(args.reference)
    try:
        rep = back_to_back(scn, target, reference)
    finally:
        target.close()
        reference.close()
    for res in rep.results:
        if res.outcome == "error" and res.detail.startswith(f"{res.link}:"):
            raise LinkError(res.detail)
    verdict = ("identical" if rep.identical else
               f"DIFFERENT from tick {rep.first_tick} (t = {rep.first_time_s} s), "
               f"largest PWM difference {rep.max_pwm_diff} per mille")
    print(f"{scn.name}: {rep.reference} vs {rep.target}: {verdict}; {rep.detail}")
    print(f"  outcomes: {rep.results[0].outcome} / {rep.results[1].outcome}; "
          f"ticks {rep.ticks_reference} / {rep.ticks_target}")
    payload = rep.to_json()
    prof = getattr(target, "profile", None)
    if prof is not None:
        print(f"  ffr_step on the target: mean {prof.mean_insn:.0f}, worst {prof.max_insn} instructions "
              f"over {prof.steps} steps")
        payload["target_profile"] = {"steps": prof.steps, "mean_insn": round(prof.mean_insn, 1),
                                     "max_insn": prof.max_insn}
    if args.json:
        write_json(args.json, payload)
    return EXIT_OK if rep.identical else EXIT_MISSION


def _list_firmware_config(args: argparse.Namespace) -> int:
    """``ffr run --list-firmware-config``: the loaded firmware's settable fields, from its library."""
    from ffr_link.ctypes_link import firmware_info
    from harness.firmware_config import describe_fields

    fw = firmware_info(library_of_link(args.link))
    print(f"# {fw.firmware_name} (contract {fw.version >> 16}.{fw.version & 0xFFFF}): inputs {fw.sizes[0]} bytes, "
          f"outputs {fw.sizes[1]}, config {fw.sizes[2]}, state {fw.sizes[99]}; layout hash 0x{fw.layout_hash:08x}")
    print("# config fields (--set firmware.NAME=V): name, type[count], kind, default (ffr_config_default)")
    for line in describe_fields(fw):
        print(line)
    return EXIT_OK


def _execute(args: argparse.Namespace) -> int:
    if args.command == "server":
        from harness.server import ServerError, command

        try:
            return command(args.action, args.idle)
        except ServerError as exc:
            raise UsageError(str(exc)) from None
    from ffr_link import LinkError, open_link
    from harness.loop import run_mission, warm_up

    if args.command == "build":
        return _execute_build(args)
    bad = check_outputs(args, "json", "plot", "out")
    if bad:
        raise UsageError(bad)
    if getattr(args, "firmware", None):
        if args.command == "b2b":
            args.reference = firmware_link("ctypes:", args.firmware)  # the library is the reference side
        else:
            args.link = firmware_link(args.link, args.firmware)
    if getattr(args, "list_firmware_config", False):
        return _list_firmware_config(args)
    if args.command == "b2b":
        return _execute_b2b(args)
    if args.command == "sweep":
        from harness.sweep_cli import run_sweep
        return run_sweep(args)

    if args.command == "table1":
        from sim_plant.arena import load_arena
        rooms: list[int | None] = [r.id for r in load_arena(args.arena).rooms]
    else:
        rooms = [args.room]
    scenarios = _scenarios(args, rooms)
    replays = _replay_paths(args, scenarios)  # checked before the missions run
    if not args.link.startswith("ctypes:"):
        warm_up(scenarios[0], record=bool(args.plot or replays))  # compile before a board waits
    link = open_link(args.link)
    missions = []
    try:
        for scn in scenarios:
            res, trace = run_mission(scn, link, record=bool(args.plot or replays))
            if res.outcome == "error" and res.detail.startswith(f"{link.url}:"):
                raise LinkError(res.detail)  # the link failed, not the mission: exit 2, one line
            missions.append((scn, trace, res))
    finally:
        link.close()
    results = [m[2] for m in missions]
    if args.command == "table1":
        print(_beside_reference(args, scenarios) + table1_text(results))
        payload: Any = []
        for r in results:
            d = r.to_json()
            paper = PAPER_TABLE1.get(r.room or 0)
            d["paper_time_to_extinguish_s"] = paper[0] if paper else None
            d["paper_total_time_s"] = paper[1] if paper else None
            payload.append(d)
    else:
        payload = results[0].to_json()
        if args.json != "-":
            print(_summary(results[0]))
    if args.json:
        write_json(args.json, payload)
    if args.plot:
        from harness.plot import save_missions
        save_missions(args.plot, missions)
    if replays:
        from harness.replay import save_replay
        for path, (scn, trace, res) in zip(replays, missions, strict=True):
            try:
                save_replay(path, scn, trace, res)
            except OSError as exc:  # written atomically: nothing is left half-written
                raise UsageError(f"{path}: cannot write the replay: {exc.strerror or exc}") from None
            except ValueError as exc:  # a mission that stopped before its first tick
                raise UsageError(f"{path}: no replay: {exc}") from None
    return EXIT_OK if all(r.outcome == "home" for r in results) else EXIT_MISSION


def _replay_paths(args: argparse.Namespace, scenarios: Sequence[Any]) -> list[Path]:
    """Where the replays go (one per scenario), or []; a one-line UsageError for a path that cannot be written."""
    if getattr(args, "replay", None):
        paths = [Path(args.replay)]
        if paths[0].suffix.lower() not in (".html", ".htm"):
            raise UsageError(f"--replay = {args.replay!r}: expected a file name ending in .html")
    elif getattr(args, "replay_dir", None):
        d = Path(args.replay_dir)
        if d.exists() and not d.is_dir():
            raise UsageError(f"--replay-dir = {args.replay_dir!r}: not a directory")
        paths = [d / f"replay_{s.name}.html" for s in scenarios]
    else:
        return []
    from harness.atomic import check_target

    for p in paths:
        why = check_target(p)
        if why:
            flag = "--replay" if getattr(args, "replay", None) else "--replay-dir"
            raise UsageError(f"{flag} = {str(args.replay if flag == '--replay' else args.replay_dir)!r}: {why}")
    return paths


def main(argv: Sequence[str] | None = None) -> int:
    from ffr_link import LinkError
    from ffr_link.abi import FirmwareLayoutError

    try:
        args = build_parser().parse_args(argv)
        if args.command in ("run", "b2b") and args.room is None and args.candle is None and args.scenario is None:
            args.room = 1
        status = _execute(args)
        sys.stdout.flush()  # here, not at exit, so that a reader that left is caught below
        return status
    except UsageError as exc:
        print(f"ffr: error: {exc}", file=sys.stderr)
        return EXIT_INPUT
    except (FfrInputError, FirmwareLayoutError, LinkError) as exc:
        print(f"ffr: error: {exc}", file=sys.stderr)
        return EXIT_INPUT
    except KeyboardInterrupt:
        print("ffr: interrupted", file=sys.stderr)
        return 130
    except BrokenPipeError:  # `ffr table1 | head`: the reader left; no traceback, and none at exit either
        return silence_stdout()  # 141, as a process killed by SIGPIPE


if __name__ == "__main__":
    sys.exit(main())
