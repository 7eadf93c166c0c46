"""Where a sweep's failed missions went wrong: each failed row of an ``ffr sweep --out`` CSV run again,
and the firmware's route step and state at the first wall contact (else at the mission's end).

    python -m harness.failure_places SWEEP.csv [--skip-seeds N,N,...] [--rows FILE.tsv] [--motion]

Prints one line per group, most missions first: missions, room, route step (the program counter of
the route, ``firmware/src/config_default.c``), firmware state, and ``contact`` or the run's detail.
``--motion`` groups by how the robot was moving in the 0.3 s before that tick too (``turn in
place``, ``straight forward``, ``straight back``, ``arc forward``, ``arc back``, ``standing``: from
the wheels' commands) and whether it had moved off its start by then (``moved`` or ``at start``,
5 mm): a start's sweep turning into a wall at once reads ``turn in place, at start``.
``--rows`` also writes every failed row (room, seed, candle, step, state, contact, true pose at that
tick, time, outcome, detail, and with ``--motion`` the motion) as tab-separated text.
``--skip-seeds`` leaves out rows of those noise seeds (robots known to fail elsewhere). Each row is
run from its own ``replay`` column, the ``ffr run`` command the sweep wrote for it, read by the
CLI's own parser: a row of any sweep (random or hallway start, jittered arena, furniture, another
arena or robot, ``--set``) runs as it ran, on the row's own firmware link (its ``--link`` or
``--firmware``: a sweep of a team's library is placed with that library, not ours). A link that
cannot be opened is one line and exit status 2.
"""

from __future__ import annotations

import csv
import math
import shlex
import sys
from collections import Counter
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from sim_plant.broken_pipe import exit_with

NEEDED = ("room", "candle_x", "candle_y", "seed", "success", "outcome", "detail", "replay")


@dataclass(frozen=True)
class Place:
    """One failed mission: where (route step, state) and how it failed."""

    room: str
    seed: int
    candle: tuple[float, float]
    step: int
    state: str
    contact: bool
    pose: tuple[float, float, float]  # true x, y (m), heading (deg) at that tick
    t_s: float
    outcome: str
    detail: str
    motion: str = ""  # how it was moving then (motion_at), and whether it had left its start

    def key(self, motion: bool = False) -> tuple[str, ...]:
        k = (self.room, str(self.step), self.state, "contact" if self.contact else self.detail)
        return k + (self.motion,) if motion else k


MOTION_WINDOW_S = 0.3  # the commands averaged before the tick: a few firmware periods
AT_START_M = 0.005     # nearer its start pose than this: it had not moved off it


def motion_at(pwm: np.ndarray, t: np.ndarray, k: int) -> str:
    """How the robot was driven over the MOTION_WINDOW_S before tick k, from the wheels' mean
    commands (``pwm`` (n, 2) left, right): a turn in place when their sum is under a quarter of their
    sizes' sum, straight when their difference is, else an arc; forward or back by the sum's sign."""
    sel = (t >= t[k] - MOTION_WINDOW_S) & (t <= t[k])
    left, right = (float(v) for v in pwm[sel].mean(axis=0))
    size = abs(left) + abs(right)
    if size == 0.0:
        return "standing"
    if abs(left + right) < 0.25 * size:
        return "turn in place"
    way = "forward" if left + right > 0 else "back"
    return f"straight {way}" if abs(left - right) < 0.25 * size else f"arc {way}"


def sweep_rows(path: Path, needed: Sequence[str] = NEEDED) -> list[dict[str, str]]:
    """The rows of an ``ffr sweep --out`` CSV; ValueError naming the file if a needed column is
    missing or the file is no UTF-8 text."""
    try:
        with path.open(newline="", encoding="utf-8") as fh:
            reader = csv.DictReader(fh)
            missing = [c for c in needed if c not in (reader.fieldnames or [])]
            if missing:
                raise ValueError(f"{path}: column {missing[0]!r} missing (an ffr sweep --out CSV is needed)")
            return list(reader)
    except UnicodeDecodeError as exc:
        raise ValueError(f"{path}: not a CSV text file ({exc.reason} at byte {exc.start})") from None


def rows_target_problem(rows: Path, csv_path: Path) -> str | None:
    """Why a tool's ``--rows`` file cannot be written (check_target's reasons, or it is the sweep's
    own CSV), or None: asked before any mission runs again."""
    from harness.atomic import check_target

    why = check_target(rows)
    if why is None and rows.resolve() == csv_path.resolve():
        why = "it is the sweep's own CSV"
    return why


def write_rows(prog: str, rows: Path, lines: Sequence[str], option: str = "--rows") -> bool:
    """A tool's tab-separated output file (its ``option``, ``--rows`` by default): the lines, whole
    or not at all. False after one line on stderr (``prog: error: option = ...: why``) when it cannot
    be written."""
    from harness.atomic import write_text_atomic

    try:
        write_text_atomic(rows, "".join(f"{line}\n" for line in lines))
    except OSError as exc:
        print(f"{prog}: error: {option} = {str(rows)!r}: {exc.strerror}", file=sys.stderr)
        return False
    return True


def failed(row: dict[str, str]) -> bool:
    """A sweep row's mission did not succeed."""
    return row["success"].strip().lower() not in ("true", "1")


def _failed_rows(path: Path) -> list[dict[str, str]]:
    return [r for r in sweep_rows(path) if failed(r)]


def replay_of(command: str) -> tuple[Any, str]:
    """The scenario and firmware link of a replay line (``ffr run ...``, as a sweep writes it),
    through the CLI's own parser. ValueError (naming the command) if it is no ``ffr run`` command;
    the parser's own errors (UsageError, FfrInputError) as ``ffr run`` would give them."""
    from harness.cli import _scenarios, build_parser
    from harness.cli_args import firmware_link

    try:
        argv = shlex.split(command)
    except ValueError as exc:
        raise ValueError(f"replay = {command!r}: {exc}") from None
    if argv[:2] != ["ffr", "run"]:
        raise ValueError(f"replay = {command!r}: expected an 'ffr run ...' command")
    args = build_parser().parse_args(argv[1:])
    if args.room is None and args.candle is None and args.scenario is None:
        args.room = 1  # as `ffr run` does
    return _scenarios(args, [args.room])[0], firmware_link(args.link, args.firmware)


def link_errors() -> tuple[type[Exception], ...]:
    """What opening a replay's firmware link may raise: bad input (one line, exit status 2), as
    ``ffr run`` treats it. Imported here, not at the top: the tools start without the link layer."""
    from ffr_link import LinkError
    from ffr_link.abi import FirmwareLayoutError

    return (LinkError, FirmwareLayoutError)


def scenario_of(row: dict[str, str]) -> Any:
    """The scenario of a sweep row, from its replay command through the CLI's own parser."""
    return replay_of(row["replay"])[0]


def place_of(row: dict[str, str]) -> Place:
    """Run one sweep row again and find where it failed."""
    from harness.loop import I_CONTACT, I_PWM_L, I_PWM_R, I_STATE, I_STEP, run_mission

    candle = (float(row["candle_x"]), float(row["candle_y"]))
    scn, link = replay_of(row["replay"])
    _, tr = run_mission(scn, link)
    names = tr.names_of_states()
    hits = np.nonzero(tr.i[:, I_CONTACT])[0]
    k = int(hits[0]) if len(hits) else len(tr.i) - 1
    code = int(tr.i[k, I_STATE])
    moved = math.hypot(float(tr.f[k, 1] - tr.f[0, 1]), float(tr.f[k, 2] - tr.f[0, 2])) >= AT_START_M
    motion = f"{motion_at(tr.i[:, I_PWM_L:I_PWM_R + 1], tr.t, k)}, {'moved' if moved else 'at start'}"
    return Place(room=row["room"], seed=int(row["seed"]), candle=candle, step=int(tr.i[k, I_STEP]),
                 state=names[code] if code < len(names) else str(code), contact=bool(len(hits)),
                 pose=(float(tr.f[k, 1]), float(tr.f[k, 2]), math.degrees(float(tr.f[k, 3]))),
                 t_s=float(tr.f[k, 0]), outcome=row["outcome"], detail=row["detail"], motion=motion)


def main(argv: Sequence[str] | None = None) -> int:
    from harness.cli_args import UsageError, _Parser

    ap = _Parser(prog="python -m harness.failure_places", description=__doc__.split("\n")[0])
    ap.add_argument("csv", type=Path)
    ap.add_argument("--skip-seeds", default="")
    ap.add_argument("--rows", type=Path)
    ap.add_argument("--motion", action="store_true")
    try:
        args = ap.parse_args(argv)
        if args.rows is not None and (why := rows_target_problem(args.rows, args.csv)):
            raise UsageError(f"--rows = {str(args.rows)!r}: {why}")
    except UsageError as e:
        print(f"python -m harness.failure_places: error: {e}", file=sys.stderr)
        return 2
    try:
        skip = {int(s) for s in args.skip_seeds.split(",") if s.strip()}
    except ValueError:
        print(f"--skip-seeds: {args.skip_seeds!r} is not a list of integers", file=sys.stderr)
        return 2
    try:
        rows = _failed_rows(args.csv)
    except (OSError, ValueError) as e:
        print(str(e) if isinstance(e, ValueError) else f"{args.csv}: {e.strerror}", file=sys.stderr)
        return 2
    try:
        places = [place_of(r) for r in rows if int(r["seed"]) not in skip]
    except (ValueError, *link_errors()) as e:
        print(f"{args.csv}: {e}", file=sys.stderr)
        return 2
    if args.rows and not write_rows("python -m harness.failure_places", args.rows, [
            "\t".join([p.room, str(p.seed), f"{p.candle[0]},{p.candle[1]}", str(p.step), p.state,
                       "C" if p.contact else "-", "{:.3f},{:.3f},{:.0f}".format(*p.pose), f"{p.t_s:.1f}",
                       p.outcome, p.detail] + ([p.motion] if args.motion else [])) for p in places]):
        return 2
    print(f"{len(places)} failed missions (of {len(rows)} failed rows; seeds left out: "
          f"{','.join(map(str, sorted(skip))) or 'none'})")
    print("missions\troom\tstep\tstate\tcontact or detail" + ("\tmotion" if args.motion else ""))
    for key, n in Counter(p.key(args.motion) for p in places).most_common():
        print(n, *key, sep="\t")
    return 0


if __name__ == "__main__":
    exit_with(main)
