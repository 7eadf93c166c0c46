"""How much room each start of a sweep left the robot, and how the starts fared by it.

    python -m harness.start_room SWEEP.csv [--bins 10,20,40,80] [--along DEG] [--rows FILE.tsv]

Reads an ``ffr sweep --out`` CSV of a random or hallway start (``--start random|hallway``, any
arena, jitter or robot) and, for each start pose, measures in the mission's own arena (jittered
as the mission's was, from its replay command; a start is one seed's pose in one arena: with
jitter, one seed's missions may start in several, as the arena is drawn again while a candle is
not legal in it):

- **gap**: the body's footprint to the nearest wall (mm), the plant's own clearance;
- **angle**: between the body's axis and that wall (degrees, 0 = parallel, 90 = square on);
- **axle**: the axle midpoint to the nearest wall (mm). Below the turning radius (the farthest
  body corner from the axle) the robot cannot turn in place before it has moved away.
- **wall**: where the wall point nearest the axle lies: ``behind`` (beyond the rear face, where
  no ranger of the default layout looks), ``ahead`` (beyond the front face), else ``left`` or
  ``right`` (beside the body).

It prints the starts and missions per gap band with their success rate, the same for the starts
that must move before they can turn and for those that can turn in place, and every failed start
(seed, gap, angle, axle, wall, missions failed of run), and the failed starts that must move
counted by where their wall is. ``--along DEG`` adds the gap bands of the starts
within DEG degrees of parallel to their nearest wall: the body along a wall, the case where an arc
away from it swings the rear corner toward it (docs/robustness.md). ``--rows`` writes one tab-separated line per
start. Geometry only: no mission is run again (seconds for thousands of rows; about a minute for
2,000 rows of a jittered sweep, whose arenas are drawn again row by row). docs/robustness.md uses
it to say which starts are left.
"""

from __future__ import annotations

import math
import re
import sys
from collections import Counter
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import NamedTuple

import numpy as np

from sim_plant.arena import Arena
from sim_plant.broken_pipe import exit_with
from sim_plant.robot import RobotParams

NEEDED = ("seed", "success", "replay")
WALL_SIDES = ("behind", "left", "right", "ahead")
DEFAULT_BINS = (10.0, 20.0, 40.0, 80.0)  # mm: band edges of the gap (chosen: the fold-back span and twice it)


class StartGeometry(NamedTuple):
    """Where a start left the body, in its mission's arena."""

    pose: tuple[float, float, float]  # x, y (m), heading (deg)
    gap_mm: float
    angle_deg: float
    axle_mm: float
    turn_radius_mm: float
    wall: str  # where the wall point nearest the axle lies: ahead, behind, left or right


@dataclass(frozen=True)
class Start:
    """One start pose of the sweep and how its missions went."""

    seed: int
    pose: tuple[float, float, float]  # x, y (m), heading (deg)
    gap_mm: float
    angle_deg: float
    axle_mm: float
    turn_radius_mm: float
    wall: str
    missions: int
    failed: int

    @property
    def must_move(self) -> bool:
        """The axle is nearer a wall than the body's farthest corner: no turn in place from here."""
        return self.axle_mm < self.turn_radius_mm


def _nearest_wall(poly: np.ndarray, arena: Arena) -> tuple[float, int]:
    from sim_plant.geometry import clearance

    best, k = math.inf, -1
    for i in range(len(arena.wall_polys)):
        d = float(clearance(poly, arena.wall_polys[i:i + 1], arena.wall_bbox[i:i + 1], 10.0))
        if d < best:
            best, k = d, i
    return best, k


def _wall_side(arena: Arena, robot: RobotParams, x: float, y: float, th: float) -> str:
    """Where the wall point nearest (x, y) lies in the body's frame: beyond the front or rear face,
    else on the left or right."""
    e = arena.wall_edges  # the walls' faces as segments (x1, y1, x2, y2), derived once by the arena
    a, ab = e[:, 0:2], e[:, 2:4] - e[:, 0:2]
    t = np.clip(((x - a[:, 0]) * ab[:, 0] + (y - a[:, 1]) * ab[:, 1]) / np.maximum((ab * ab).sum(axis=1), 1e-18),
                0.0, 1.0)
    q = a + t[:, None] * ab
    k = int(np.argmin(np.hypot(q[:, 0] - x, q[:, 1] - y)))
    px, py = float(q[k, 0]), float(q[k, 1])
    c, s = math.cos(th), math.sin(th)
    u, v = (px - x) * c + (py - y) * s, (py - y) * c - (px - x) * s
    front, rear, _, _ = robot.footprint()
    return "ahead" if u > front else "behind" if u < rear else "left" if v > 0.0 else "right"


def measure(replay: str) -> StartGeometry:
    """Where a replay line's start left the body."""
    from harness.failure_places import replay_of
    from harness.start_pose import footprint

    scn = replay_of(replay)[0]
    x, y, th = scn.start
    arena, robot = scn.arena, scn.robot
    gap, k = _nearest_wall(footprint(robot, x, y, th), arena)
    w = arena.walls[k]
    rel = abs(math.degrees(th - math.atan2(w.b[1] - w.a[1], w.b[0] - w.a[0]))) % 180.0
    return StartGeometry((x, y, math.degrees(th) % 360.0), gap * 1000.0, min(rel, 180.0 - rel),
                         arena.wall_distance(x, y) * 1000.0, robot.turn_radius() * 1000.0,
                         _wall_side(arena, robot, x, y, th))


def _start_key(replay: str) -> str | None:
    """The replay line without its candle: every mission of one start seed shares it, unless the
    arena is jittered (None): a jittered arena is drawn again while the candle is not legal in it
    (sim_plant/arena_jitter.py), so one seed's missions can start in different arenas and poses."""
    if "--arena-jitter" in replay:
        return None
    return " ".join(re.sub(r"--candle \S+", "", replay).split())


def _row_error(path: Path, n: int, row: dict[str, str], exc: Exception) -> ValueError:
    return ValueError(f"{path}: row {n}: replay = {row.get('replay')!r}: {exc}")


def starts_of(path: Path) -> list[Start]:
    """The sweep's starts: one per seed and pose (and arena), its missions counted."""
    from harness.cli_args import UsageError
    from harness.failure_places import failed, sweep_rows
    from sim_plant.errors import FfrInputError

    cache: dict[str, StartGeometry] = {}
    missions: Counter[tuple[int, StartGeometry]] = Counter()
    lost: Counter[tuple[int, StartGeometry]] = Counter()
    for n, r in enumerate(sweep_rows(path, NEEDED), start=2):  # row 1 is the header
        try:
            if any(r.get(c) is None for c in NEEDED) or None in r:
                raise ValueError("expected as many cells as the header names")
            if "--start" not in r["replay"]:
                raise ValueError("not a random or hallway start")
            seed = int(r["seed"])
            key = _start_key(r["replay"])
            g = cache.get(key) if key is not None else None
            if g is None:
                g = measure(r["replay"])
                if key is not None:
                    cache[key] = g
        except (ValueError, UsageError, FfrInputError) as exc:
            raise _row_error(path, n, r, exc) from None
        missions[seed, g] += 1
        lost[seed, g] += failed(r)
    out = [Start(seed, *g, missions=m, failed=lost[seed, g]) for (seed, g), m in missions.items()]
    return sorted(out, key=lambda s: (s.seed, s.pose))


def _band_lines(starts: list[Start], bins: Sequence[float]) -> list[str]:
    edges = [0.0, *bins, math.inf]
    lines = [f"{'gap (mm)':>10s} {'starts':>7s} {'missions':>9s} {'success':>8s} {'failed starts':>14s}"]
    for lo, hi in zip(edges[:-1], edges[1:], strict=True):
        sel = [s for s in starts if lo <= s.gap_mm < hi]
        n = sum(s.missions for s in sel)
        ok = n - sum(s.failed for s in sel)
        band = f"{lo:.0f}-{hi:.0f}" if hi < math.inf else f"{lo:.0f}+"
        rate = f"{100.0 * ok / n:7.1f}%" if n else "      -"
        lines.append(f"{band:>10s} {len(sel):7d} {n:9d} {rate:>8s} {sum(s.failed > 0 for s in sel):14d}")
    return lines


def report(starts: list[Start], bins: Sequence[float], along_deg: float | None = None) -> str:
    n = sum(s.missions for s in starts)
    ok = n - sum(s.failed for s in starts)
    turn = starts[0].turn_radius_mm if starts else 0.0
    lines = [f"{len(starts)} start poses, {n} missions, {ok} succeeded"
             + (f" ({100.0 * ok / n:.1f} %)" if n else ""), *_band_lines(starts, bins)]
    if along_deg is not None:
        lines.append(f"along a wall (the axis within {along_deg:g} degrees of its nearest wall):")
        lines += _band_lines([s for s in starts if s.angle_deg <= along_deg], bins)
    for must, what in ((True, f"must move before turning (axle nearer a wall than the turning radius, "
                               f"{turn:.0f} mm)"), (False, "can turn in place")):
        sel = [s for s in starts if s.must_move == must]
        mn = sum(s.missions for s in sel)
        mok = mn - sum(s.failed for s in sel)
        lines.append(f"{what}: {len(sel)} starts, {mn} missions"
                     + (f", {mok} succeeded ({100.0 * mok / mn:.1f} %)" if mn else ""))
    bad = [s for s in starts if s.failed]
    sides = Counter(s.wall for s in bad if s.must_move)
    if sides:
        lines.append("failed starts that must move, by where the axle's nearest wall is: "
                     + ", ".join(f"{w} {sides[w]}" for w in WALL_SIDES))
    if bad:
        lines.append("failed starts: seed  x, y (m), heading (deg)  gap (mm)  angle (deg)  axle (mm)  wall  failed")
        for s in bad:
            lines.append(f"  {s.seed:5d}  {s.pose[0]:.3f}, {s.pose[1]:.3f}, {s.pose[2]:5.1f}  {s.gap_mm:6.1f}"
                         f"  {s.angle_deg:5.1f}  {s.axle_mm:6.1f}  {s.wall:6s}  {s.failed}/{s.missions}")
    return "\n".join(lines)


def _bins(text: str) -> tuple[float, ...]:
    try:
        vals = tuple(float(v) for v in text.split(","))
    except ValueError:
        raise ValueError(f"--bins = {text!r}: expected increasing numbers of mm, e.g. 10,20,40,80") from None
    if (not vals or any(not math.isfinite(v) or v <= 0 for v in vals)
            or any(b <= a for a, b in zip(vals, vals[1:], strict=False))):
        raise ValueError(f"--bins = {text!r}: expected increasing numbers of mm above 0, e.g. 10,20,40,80")
    return vals


def main(argv: Sequence[str] | None = None) -> int:
    from harness.cli_args import EXIT_INPUT, UsageError, _Parser
    from harness.failure_places import rows_target_problem, write_rows
    from sim_plant.errors import FfrInputError

    ap = _Parser(prog="python -m harness.start_room", description=__doc__.split("\n")[0])
    ap.add_argument("csv", type=Path, help="an ffr sweep --out CSV of --start random or hallway")
    ap.add_argument("--bins", default=",".join(f"{b:.0f}" for b in DEFAULT_BINS),
                    help="the gap bands' edges, mm (default 10,20,40,80)")
    ap.add_argument("--along", type=float, metavar="DEG",
                    help="also the gap bands of the starts within DEG degrees of parallel to their nearest wall")
    ap.add_argument("--rows", type=Path, help="also one tab-separated line per start to this file")
    try:
        args = ap.parse_args(argv)
        bins = _bins(args.bins)
        if args.along is not None and not 0.0 < args.along <= 90.0:
            raise UsageError(f"--along = {args.along!r}: expected degrees above 0, at most 90")
        if args.rows is not None and (why := rows_target_problem(args.rows, args.csv)):
            raise UsageError(f"--rows = {str(args.rows)!r}: {why}")
        starts = starts_of(args.csv)
    except OSError as exc:
        print(f"python -m harness.start_room: error: {args.csv}: {exc.strerror}", file=sys.stderr)
        return EXIT_INPUT
    except (UsageError, FfrInputError, ValueError) as exc:
        print(f"python -m harness.start_room: error: {exc}", file=sys.stderr)
        return EXIT_INPUT
    text = report(starts, bins, args.along)
    if args.rows:
        lines = ["\t".join(("seed", "x", "y", "heading_deg", "gap_mm", "angle_deg", "axle_mm", "wall",
                            "missions", "failed"))]
        lines += ["\t".join((str(s.seed), f"{s.pose[0]:.4f}", f"{s.pose[1]:.4f}", f"{s.pose[2]:.2f}",
                             f"{s.gap_mm:.1f}", f"{s.angle_deg:.1f}", f"{s.axle_mm:.1f}", s.wall, str(s.missions),
                             str(s.failed))) for s in starts]
        if not write_rows("python -m harness.start_room", args.rows, lines):
            return EXIT_INPUT
    print(text)
    return 0


if __name__ == "__main__":
    exit_with(main)
