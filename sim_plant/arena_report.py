"""An arena's measures in cm, as docs/arena.md quotes them: ``python -m sim_plant.arena_report [FILE]``
(the default arena without FILE). Apart from arena.py, which arena_jitter.py builds on."""

from __future__ import annotations

import math

import numpy as np

from sim_plant.arena import Arena, load_arena
from sim_plant.arena_jitter import MAX_JITTER, MERGE_GAP, _axis_knots
from sim_plant.broken_pipe import exit_with
from sim_plant.errors import CandlePlacementError, FfrInputError
from sim_plant.file_schemas import PLACEMENT_RULES


def describe(arena: Arena) -> str:
    """The arena's measures in cm, as docs/arena.md quotes them (``python -m sim_plant.arena [FILE]``)."""
    lines = [f"{arena.name} ({arena.source})",
             f"outer square {arena.size[0] * 100:.1f} x {arena.size[1] * 100:.1f} cm, "
             f"walls {min(w.t for w in arena.walls) * 100:.2f}-{max(w.t for w in arena.walls) * 100:.2f} cm thick, "
             f"placement rule {arena.placement!r}",
             f"home circle at ({arena.home_center[0] * 100:.1f}, {arena.home_center[1] * 100:.1f}) cm, "
             f"radius {arena.home_radius * 100:.1f} cm, start heading {math.degrees(arena.home_heading):.0f} deg",
             "hallway widths (cm): " + ", ".join(
                 f"{h.name} {min(np.ptp(h.polygon[:, 0]), np.ptp(h.polygon[:, 1])) * 100:.1f}"
                 for h in arena.hallways)]
    for axis in (0, 1):
        knots = _axis_knots(arena, axis)
        lines.append(f"jitter: {'xy'[axis]} lines at " + ", ".join(
            (f"{c * 100:.1f}" if h <= 0.0105 else f"{(c - h) * 100:.1f}-{(c + h) * 100:.1f}")
            + (" fixed" if fixed else "")
            for c, h, fixed in knots) + " cm")
    lines.append(f"jitter: lines closer than {MERGE_GAP * 100:.0f} cm move as one; at most {MAX_JITTER * 100:.0f} cm")
    saved = arena.placement
    try:
        for r in arena.rooms:
            verdict = []
            for rule in PLACEMENT_RULES:
                arena.placement = rule
                try:
                    arena.check_candle(*r.default_candle)
                    verdict.append(f"{rule}: legal")
                except CandlePlacementError as exc:
                    verdict.append(f"{rule}: refused ({exc.rule})")
            lines.append(f"room {r.id} {r.name}: door {math.dist(*r.door) * 100:.1f} cm, default candle "
                         f"({r.default_candle[0] * 100:.1f}, {r.default_candle[1] * 100:.1f}) cm, "
                         + "; ".join(verdict))
    finally:
        arena.placement = saved
    return "\n".join(lines)


def main() -> int:
    """``python -m sim_plant.arena_report [FILE]``: the arena's measures, or one line and status 2."""
    import sys

    try:
        print(describe(load_arena(sys.argv[1] if len(sys.argv) > 1 else None)))
    except FfrInputError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    exit_with(main)
