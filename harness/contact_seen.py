"""Did a ranger see the wall a failed mission touched, and at what true range?

    python -m harness.contact_seen SWEEP.csv [--near MM] [--rows FILE.tsv] [--span N [--at-start [--starts FILE.tsv]]]

Each failed row of an ``ffr sweep --out`` CSV that touched a wall is run again (its own ``replay``
command, as ``python -m harness.failure_places`` does) to its first wall contact. There, the point
of the wall the body touched is found (the plant's geometry: the body's footprint and the walls as
drawn, jitter and furniture included), and every earlier tick is searched for the rangers whose
beam (the plant's true centre ray from the true pose) met a wall within ``--near`` mm (default 30)
of that point. A line per mission: seed, room, contact time (s), the body corner that touched
(FL, FR, RL, RR, or ``side`` when no corner is within 10 mm of the point), then the last such
sighting's ranger, true range (mm) and reading (mV), and the first one's: how long before the
contact, the ranger, its true range and reading; or ``unseen``. The summary counts the contacts
seen, those seen by the touching corner's own ranger, and those last seen at a true range below
the GP2D12's fold-back peak (80 mm: the output falls again nearer than that, so such a reading
looks like a wall farther off; sim_plant/sensors/gp2d12.py). docs/robustness.md uses it to say
what the orientation at the start misjudges. Each row runs on its own firmware link (its replay's
``--link`` or ``--firmware``); a link that cannot be opened is one line and exit status 2.

``--span N`` also runs the sweep's first N rows (failed or not) and counts, over every tick of
their orientation (state ORIENT, up to any contact), the readings each ranger gave within the
fold-back span the firmware watches (above its span's bottom, ``ir_min_mm``, up to 160 mm,
``FFR_FOLD_MAX_MM``; through the firmware's own curve): how many came from a wall truly within
the fold-back peak's 80 mm (a wall nearly touching, read folded back) and how many from one
farther off (read as it is). Such a reading alone cannot tell the two apart. With ``--at-start``
only each row's first tick counts: the readings the orientation starts from, before any move;
``--starts FILE.tsv`` then writes them, a line per row (seed, room, success, and per ranger the
reading through the firmware's curve and the true range, mm), for any filter a question needs.
"""

from __future__ import annotations

import math
import sys
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from sim_plant.broken_pipe import exit_with

FOLD_PEAK_MM = 80.0  # the GP2D12 model's fold-back peak (sim_plant/sensors/gp2d12.py, D_PEAK)
FOLD_SPAN_MM = 160.0  # the firmware's fold-back span's top (FFR_FOLD_MAX_MM, firmware/src/ffr_internal.h)
CORNERS = ("FR", "FL", "RL", "RR")  # harness.start_pose.footprint's order
CORNER_MM = 10.0  # a corner this near the point touched is the part that touched


@dataclass(frozen=True)
class Sighting:
    """A tick before a contact when a ranger's beam met the wall near the point touched."""

    ranger: str
    before_s: float
    true_mm: float
    read_mv: int


@dataclass(frozen=True)
class Contact:
    """One failed mission's first wall contact and who saw it coming."""

    seed: int
    room: str
    t_s: float
    part: str
    seen: Sighting | None   # the last sighting
    first: Sighting | None  # the first


def _closest_on_segment(p: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    ab = b - a
    den = float(np.dot(ab, ab))
    t = 0.0 if den <= 0.0 else min(1.0, max(0.0, float(np.dot(p - a, ab)) / den))
    return a + t * ab


def touch_point(body: np.ndarray, wall_polys: Sequence[np.ndarray]) -> tuple[np.ndarray, str]:
    """The wall point nearest the body (the body's corners against the walls' edges, the walls'
    corners against the body's edges) and the body corner that touched it ('side' if none is
    within CORNER_MM)."""
    best, point = math.inf, body[0]
    for wp in wall_polys:
        n = len(wp)
        for p in body:
            for j in range(n):
                q = _closest_on_segment(p, wp[j], wp[(j + 1) % n])
                d = float(np.linalg.norm(p - q))
                if d < best:
                    best, point = d, q
        for v in wp:
            for i in range(4):
                d = float(np.linalg.norm(v - _closest_on_segment(v, body[i], body[(i + 1) % 4])))
                if d < best:
                    best, point = d, np.array(v, dtype=float)
    gaps = [float(np.linalg.norm(c - point)) for c in body]
    k = int(np.argmin(gaps))
    return point, CORNERS[k] if gaps[k] * 1000.0 <= CORNER_MM else "side"


def _beam(robot: Any, name: str, x: float, y: float, th: float) -> tuple[float, float, float, float]:
    """Ranger ``name``'s true centre ray at the body pose (x, y, th): origin and unit direction."""
    ir = robot.ir[name]
    c, s = math.cos(th), math.sin(th)
    a = th + math.radians(ir.angle_deg)
    return x + c * ir.x - s * ir.y, y + s * ir.x + c * ir.y, math.cos(a), math.sin(a)


def contact_of(replay: str, seed: int, room: str, near_m: float) -> Contact | None:
    """Run one replay line to its first wall contact (None: it touched none) and look back."""
    from harness.failure_places import replay_of
    from harness.loop import F_T, F_TH, F_X, F_Y, I_CONTACT, I_SENS, run_mission
    from harness.start_pose import footprint
    from sim_plant.geometry import polygon_edges, ray_cast
    from sim_plant.robot import IR_NAMES
    from sim_plant.sensors.channels import CH_IR

    scn, link = replay_of(replay)
    _, tr = run_mission(scn, link)
    hits = np.flatnonzero(tr.i[:, I_CONTACT])
    if not len(hits):
        return None
    kc = int(hits[0])
    polys = [np.asarray(w, dtype=float) for w in scn.arena.wall_polys]
    point, part = touch_point(footprint(scn.robot, *tr.f[kc, [F_X, F_Y, F_TH]]), polys)
    edges = polygon_edges(np.asarray(scn.arena.wall_polys))
    seen: list[Sighting] = []
    for k in range(kc):
        x, y, th = (float(v) for v in tr.f[k, [F_X, F_Y, F_TH]])
        for i, name in enumerate(IR_NAMES):
            ox, oy, dx, dy = _beam(scn.robot, name, x, y, th)
            t = float(ray_cast(ox, oy, dx, dy, edges, 1.5))
            if math.hypot(ox + t * dx - point[0], oy + t * dy - point[1]) <= near_m:
                seen.append(Sighting(name, float(tr.f[kc, F_T] - tr.f[k, F_T]), t * 1000.0,
                                     int(tr.i[k, I_SENS + CH_IR[i]])))
    return Contact(seed, room, float(tr.f[kc, F_T]), part, seen[-1] if seen else None,
                   seen[0] if seen else None)


def contacts_of(path: Path, near_m: float) -> tuple[int, list[Contact]]:
    """(failed rows, the contacts among them) of a sweep CSV."""
    from harness.failure_places import failed, sweep_rows

    rows = [r for r in sweep_rows(path, ("seed", "room", "success", "replay")) if failed(r)]
    out = []
    for n, r in enumerate(rows):
        try:
            c = contact_of(r["replay"], int(r["seed"]), r["room"], near_m)
        except ValueError as exc:
            raise ValueError(f"{path}: failed row {n + 1}: replay = {r.get('replay')!r}: {exc}") from None
        if c is not None:
            out.append(c)
    return len(rows), out


def fields(c: Contact) -> list[str]:
    """One contact's line as its fields: seed, room, contact_s, part, then the last sighting's
    ranger, before_s, true_mm, read_mV, or 'unseen'."""
    head = [str(c.seed), c.room, f"{c.t_s:.2f}", c.part]
    if c.seen is None or c.first is None:
        return [*head, "unseen"]
    return [*head, c.seen.ranger, f"{c.seen.true_mm:.0f}", str(c.seen.read_mv), f"{c.first.before_s:.2f}",
            c.first.ranger, f"{c.first.true_mm:.0f}", str(c.first.read_mv)]


STARTS_HEADER = ("seed", "room", "success", "CF_read_mm", "CF_true_mm", "LF_read_mm", "LF_true_mm", "RF_read_mm",
                 "RF_true_mm", "LR_read_mm", "LR_true_mm", "RR_read_mm", "RR_true_mm")
HEADER = ("seed", "room", "contact_s", "part", "last_ranger", "true_mm", "read_mV", "first_before_s",
          "first_ranger", "true_mm", "read_mV")


def report(n_failed: int, contacts: list[Contact], near_mm: float) -> str:
    seen = [c for c in contacts if c.seen is not None]
    own = [c for c in seen if c.part != "side" and c.seen is not None and c.seen.ranger == _corner_ranger(c.part)]
    fold = [c for c in seen if c.seen is not None and c.seen.true_mm < FOLD_PEAK_MM]
    lines = [f"{n_failed} failed missions, {len(contacts)} touched a wall; {len(seen)} of the points touched "
             f"were seen by a ranger's beam within {near_mm:g} mm before the contact, {len(own)} by the "
             f"touching corner's own ranger; {len(fold)} last at a true range below {FOLD_PEAK_MM:.0f} mm "
             f"(the GP2D12's fold-back side of its peak)",
             "  ".join(HEADER)]
    lines += ["  ".join(fields(c)) for c in contacts]
    return "\n".join(lines)


def _corner_ranger(part: str) -> str:
    """The ranger mounted at a body corner (the default layout's names: LF at the front left...)."""
    return {"FL": "LF", "FR": "RF", "RL": "LR", "RR": "RR"}[part]


def span_counts(path: Path, n_rows: int, at_start: bool = False,
                starts: list[list[str]] | None = None) -> dict[str, tuple[int, int]]:
    """Per ranger: (readings within the fold-back span from a wall truly within FOLD_PEAK_MM,
    from one farther off) over the orientation of the sweep's first n_rows rows (``at_start``: their
    first tick only, before the robot has moved). ``starts``, if given, gets a line per row: seed,
    room, success, then each ranger's first reading through the firmware's curve and its true range
    (mm; ``-`` for no reading), in STARTS_HEADER's order."""
    from ffr_link.library import default_config
    from harness.failure_places import replay_of, sweep_rows
    from harness.loop import F_TH, F_X, F_Y, I_CONTACT, I_SENS, I_STATE, run_mission
    from sim_plant.geometry import polygon_edges, ray_cast
    from sim_plant.robot import IR_NAMES
    from sim_plant.sensors.channels import CH_IR

    counts = {name: [0, 0] for name in IR_NAMES}
    for r in sweep_rows(path, ("seed", "room", "success", "replay"))[:n_rows]:
        scn, link = replay_of(r["replay"])
        lib = link.split(":", 1)[1] if link.startswith("ctypes:") else ""
        cfg = default_config(lib or None)  # the firmware's own curve (a board's: ours, as the wire's)
        k_mv, off, d0, lo = (float(cfg[f]) for f in ("ir_k_mv_mm", "ir_offset_mv", "ir_d0_mm", "ir_min_mm"))
        _, tr = run_mission(scn, link)
        orient = tr.names_of_states().index("ORIENT")
        edges = polygon_edges(np.asarray(scn.arena.wall_polys))
        for k in range(1 if at_start else len(tr.f)):
            if int(tr.i[k, I_STATE]) != orient or tr.i[k, I_CONTACT]:
                break
            x, y, th = (float(v) for v in tr.f[k, [F_X, F_Y, F_TH]])
            line = [r["seed"], r["room"], r["success"]] if starts is not None and k == 0 else None
            for i, name in enumerate(IR_NAMES):
                mv = float(tr.i[k, I_SENS + CH_IR[i]])
                mm = k_mv / (mv - off) - d0 if mv > off else math.inf
                in_span = lo + 0.5 < mm <= FOLD_SPAN_MM
                if not in_span and line is None:
                    continue
                t_mm = 1000.0 * float(ray_cast(*_beam(scn.robot, name, x, y, th), edges, 1.5))
                if line is not None:
                    line += [f"{mm:.0f}" if math.isfinite(mm) else "-", f"{t_mm:.0f}"]
                if in_span:
                    counts[name][0 if t_mm < FOLD_PEAK_MM else 1] += 1
            if line is not None and starts is not None:
                starts.append(line)
    return {k: (v[0], v[1]) for k, v in counts.items()}


def span_report(n_rows: int, counts: dict[str, tuple[int, int]], at_start: bool = False) -> str:
    when = "the first tick" if at_start else "the orientation"
    lines = [f"readings within the fold-back span ({FOLD_SPAN_MM:.0f} mm) over {when} of {n_rows} "
             f"rows: ranger, from a wall truly within {FOLD_PEAK_MM:.0f} mm, from one farther off"]
    for name, (near, far) in counts.items():
        share = f"{100.0 * near / (near + far):.1f} % near" if near + far else "-"
        lines.append(f"  {name}  {near:7d}  {far:7d}  ({share})")
    return "\n".join(lines)


def main(argv: Sequence[str] | None = None) -> int:
    from harness.cli_args import EXIT_INPUT, UsageError, _Parser
    from harness.failure_places import link_errors, rows_target_problem, write_rows
    from sim_plant.errors import FfrInputError

    ap = _Parser(prog="python -m harness.contact_seen", description=__doc__.split("\n")[0])
    ap.add_argument("csv", type=Path, help="an ffr sweep --out CSV")
    ap.add_argument("--near", type=float, default=30.0, help="a beam's hit this near the point touched, mm")
    ap.add_argument("--rows", type=Path, help="also the lines as tab-separated text to this file")
    ap.add_argument("--span", type=int, default=0, metavar="N",
                    help="also count the fold-back span's readings over the first N rows' orientation")
    ap.add_argument("--at-start", action="store_true",
                    help="with --span: count only each row's first tick, before the robot has moved")
    ap.add_argument("--starts", type=Path, metavar="FILE.tsv",
                    help="with --at-start: also each row's first readings and true ranges, tab-separated")
    try:
        args = ap.parse_args(argv)
        if not (math.isfinite(args.near) and args.near > 0.0):
            raise UsageError(f"--near = {args.near}: expected a distance in mm above 0")
        if args.span < 0:
            raise UsageError(f"--span = {args.span}: expected a number of rows, 0 or more")
        if args.at_start and not args.span:
            raise UsageError("--at-start: counts the span's readings, so it needs --span N")
        if args.starts is not None and not args.at_start:
            raise UsageError(f"--starts = {str(args.starts)!r}: the first tick's readings need --span N --at-start")
        if args.rows is not None and args.starts is not None and args.rows.resolve() == args.starts.resolve():
            raise UsageError(f"--starts = {str(args.starts)!r}: the same file as --rows")
        for opt, target in (("--rows", args.rows), ("--starts", args.starts)):
            if target is not None and (why := rows_target_problem(target, args.csv)):
                raise UsageError(f"{opt} = {str(target)!r}: {why}")
        n_failed, contacts = contacts_of(args.csv, args.near / 1000.0)
        starts: list[list[str]] | None = [] if args.starts is not None else None
        span = span_counts(args.csv, args.span, args.at_start, starts) if args.span else None
    except OSError as exc:
        print(f"python -m harness.contact_seen: error: {args.csv}: {exc.strerror}", file=sys.stderr)
        return EXIT_INPUT
    except (UsageError, FfrInputError, ValueError, *link_errors()) as exc:
        print(f"python -m harness.contact_seen: error: {exc}", file=sys.stderr)
        return EXIT_INPUT
    text = report(n_failed, contacts, args.near)
    if args.rows is not None and not write_rows("python -m harness.contact_seen", args.rows,
                                                ["\t".join(f) for f in [list(HEADER), *map(fields, contacts)]]):
        return EXIT_INPUT
    if starts is not None and not write_rows("python -m harness.contact_seen", args.starts,
                                             ["\t".join(f) for f in [list(STARTS_HEADER), *starts]], "--starts"):
        return EXIT_INPUT
    print(text)
    if span is not None:
        print(span_report(args.span, span, args.at_start))
    return 0


if __name__ == "__main__":
    exit_with(main)
