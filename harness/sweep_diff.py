"""Two sweeps of the same missions, mission by mission: which were won and which lost.

    python -m harness.sweep_diff BEFORE.csv AFTER.csv [--rows FILE.tsv]

Two ``ffr sweep --out`` CSVs of the same sweep run with two firmware builds (``--firmware``, or
two checkouts): each mission is matched by what defines it, not by its row number (room, candle,
seed, noise profile, start pose, arena jitter and its seed, furniture: the CSV's columns before
``outcome``, less ``id``). It prints both success counts, the missions won (lost before, succeeded
after) and lost (the other way), and the noise seeds of each with their missions (``1118x39``:
39 of that seed's missions). A firmware change's "won / lost" in docs/robustness.md is this
command's. Chaos: a change to one decision moves later ticks of every mission that makes it, so
a change that helps some starts also flips a few others both ways; the lists show which.

``--rows`` also writes one tab-separated line per changed mission: ``won`` or ``lost``, room,
seed, candle, the before and after outcome and detail, and the after row's replay command.
Missions in one CSV only are counted and named by the first few; a CSV that holds one mission
twice, or lacks a column, is one line and status 2.
"""

from __future__ import annotations

import sys
from collections import Counter
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

from harness.sweep import ROW_FIELDS
from sim_plant.broken_pipe import exit_with

# the columns that define a mission in an ffr sweep CSV: harness/sweep.py's ROW_FIELDS before the
# outcome, less the row number (room, candle and seed are in every sweep's CSV)
KEY_FIELDS = tuple(ROW_FIELDS[1:ROW_FIELDS.index("outcome")])
NEEDED = ("room", "candle_x", "candle_y", "seed", "success", "outcome", "detail", "replay")
SHOWN = 5  # missions in one CSV only: this many named


@dataclass(frozen=True)
class Change:
    """One mission whose success differs between the two sweeps."""

    won: bool
    before: dict[str, str]
    after: dict[str, str]


@dataclass(frozen=True)
class Diff:
    before_ok: int
    before_n: int
    after_ok: int
    after_n: int
    changes: list[Change]
    only_before: list[tuple[str, ...]]
    only_after: list[tuple[str, ...]]

    def won(self) -> list[Change]:
        return [c for c in self.changes if c.won]

    def lost(self) -> list[Change]:
        return [c for c in self.changes if not c.won]


def _missions(path: Path) -> tuple[dict[tuple[str, ...], dict[str, str]], tuple[str, ...]]:
    """The CSV's rows by their mission key, and the key's columns. ValueError naming the file."""
    from harness.failure_places import sweep_rows

    rows = sweep_rows(path, NEEDED)
    fields = tuple(f for f in KEY_FIELDS if rows and f in rows[0])
    out: dict[tuple[str, ...], dict[str, str]] = {}
    for n, r in enumerate(rows, start=2):  # line 1 is the header
        key = tuple(r[f] for f in fields)
        if key in out:
            raise ValueError(f"{path}: line {n}: the mission of room {r['room']}, seed {r['seed']}, candle "
                             f"{r['candle_x']},{r['candle_y']} is in the file twice (one sweep's CSV is needed)")
        out[key] = r
    return out, fields


def diff(before: Path, after: Path) -> Diff:
    """Match the two sweeps' missions; ValueError naming a file if they cannot be matched."""
    from harness.failure_places import failed

    a, fa = _missions(before)
    b, fb = _missions(after)
    if a and b and fa != fb:
        raise ValueError(f"{after}: its missions are told by columns {', '.join(fb)}, {before}'s by "
                         f"{', '.join(fa)} (two CSVs of one sweep are needed)")
    changes = [Change(failed(a[k]), a[k], b[k]) for k in a if k in b and failed(a[k]) != failed(b[k])]
    return Diff(sum(not failed(r) for r in a.values()), len(a), sum(not failed(r) for r in b.values()), len(b),
                changes, [k for k in a if k not in b], [k for k in b if k not in a])


def seeds_text(changes: Sequence[Change]) -> str:
    """The changed missions' seeds, in order of first appearance, ``SEEDxN`` for N missions of one seed."""
    counts = Counter(c.after["seed"] for c in changes)
    return " ".join(s if n == 1 else f"{s}x{n}" for s, n in counts.items())


def report(d: Diff, before: Path, after: Path) -> str:
    def line(name: str, ok: int, n: int, path: Path) -> str:
        share = f" ({100.0 * ok / n:.1f} %)" if n else ""
        return f"{name} {n} missions, {ok} succeeded{share}: {path}"

    won, lost = d.won(), d.lost()
    out = [line("before:", d.before_ok, d.before_n, before), line("after: ", d.after_ok, d.after_n, after),
           f"in both: {d.before_n - len(d.only_before)} missions; won {len(won)}, lost {len(lost)}",
           f"won:  {seeds_text(won) or '-'}", f"lost: {seeds_text(lost) or '-'}"]
    for name, keys in (("before", d.only_before), ("after", d.only_after)):
        if keys:
            shown = "; ".join(" ".join(k[:4]) for k in keys[:SHOWN])
            out.append(f"only in {name}: {len(keys)} missions (room, candle, seed: {shown}"
                       f"{'; ...' if len(keys) > SHOWN else ''})")
    return "\n".join(out)


def main(argv: Sequence[str] | None = None) -> int:
    from harness.cli_args import EXIT_INPUT, UsageError, _Parser
    from harness.failure_places import rows_target_problem, write_rows

    prog = "python -m harness.sweep_diff"
    ap = _Parser(prog=prog, description=__doc__.split("\n")[0])
    ap.add_argument("before", type=Path, help="an ffr sweep --out CSV")
    ap.add_argument("after", type=Path, help="an ffr sweep --out CSV of the same sweep")
    ap.add_argument("--rows", type=Path, help="also one tab-separated line per changed mission to this file")
    try:
        args = ap.parse_args(argv)
        if args.rows is not None:
            for csv_path in (args.before, args.after):
                if why := rows_target_problem(args.rows, csv_path):
                    raise UsageError(f"--rows = {str(args.rows)!r}: {why}")
        d = diff(args.before, args.after)
    except OSError as exc:
        print(f"{prog}: error: {exc.filename}: {exc.strerror}", file=sys.stderr)
        return EXIT_INPUT
    except (UsageError, ValueError) as exc:
        print(f"{prog}: error: {exc}", file=sys.stderr)
        return EXIT_INPUT
    if args.rows and not write_rows(prog, args.rows, [
            "\t".join(("won" if c.won else "lost", c.after["room"], c.after["seed"],
                       f"{c.after['candle_x']},{c.after['candle_y']}", c.before["outcome"], c.before["detail"],
                       c.after["outcome"], c.after["detail"], c.after["replay"])) for c in d.changes]):
        return EXIT_INPUT
    print(report(d, args.before, args.after))
    return 0


if __name__ == "__main__":
    exit_with(main)
