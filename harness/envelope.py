"""Measure the noise envelope: success rate per kind of noise and level (``make envelope``).

Each kind of sensor noise or fault is scaled from a reference level (``REFERENCE``,
scale 1.0) on its own, then all of them together; every cell runs the same
missions (random legal candles in every room x seeds) through the sweep
engine (``harness.sweep.execute``: a local Dask cluster, or ``--scheduler``).
The envelope of a kind is the largest scale whose success rate stays at or
above ``--target`` (99 % by default). Success: home, flame out, no wall
touched. Prints a Markdown table (docs/robustness.md keeps the last one).

    python -m harness.envelope [--scales 0.5,1,1.5,2] [-n 5] [--seeds 0:5] [--out FILE.csv]
"""

from __future__ import annotations

import argparse
import sys
import tempfile
from pathlib import Path
from typing import Any

from harness import sweep as sw
from sim_plant.broken_pipe import exit_with

# One noise kind per entry: its profile groups at scale 1.0.
REFERENCE: dict[str, dict[str, dict[str, Any]]] = {
    "ir sigma 20 mV": {"ir": {"sigma": 20.0, "quant_step": 4.883}},
    "ir bias +30 mV": {"ir": {"bias": 30.0, "quant_step": 4.883}},
    "ir bias -30 mV": {"ir": {"bias": -30.0, "quant_step": 4.883}},
    "ir dropouts 1 %": {"ir": {"dropout_prob": 0.01, "dropout_mode": "zero"}},
    "ir spikes 1 % x 300 mV": {"ir": {"spike_prob": 0.01, "spike_amp": 300.0}},
    "GP2D12 part spread (datasheet)": {"ir": {"unit_gain_spread": 0.125, "unit_offset_spread": 150.0,
                                              "unit_pivot": 420.0}},
    "flame sigma 10 counts": {"flame": {"sigma": 10.0}},
    "flame bias +15 counts": {"flame": {"bias": 15.0}},
    "flame part spread 20 %": {"flame": {"unit_gain_spread": 0.2, "unit_offset_spread": 10.0, "unit_pivot": 40.0}},
    "line misreads 0.2 %": {"line": {"flip_prob": 0.002}},
    "encoder slip 2 % x 0.3 (typical)": {"encoder": {"slip_prob": 0.02, "slip_fraction": 0.3}},
}
# Fields that scale with the level (the rest, e.g. quant_step and pivots, stay).
_SCALED = {"sigma", "bias", "dropout_prob", "spike_prob", "unit_gain_spread", "unit_offset_spread", "flip_prob",
           "slip_prob"}


def scaled(groups: dict[str, dict[str, Any]], s: float) -> dict[str, dict[str, Any]]:
    out: dict[str, dict[str, Any]] = {}
    for g, fields in groups.items():
        d = out.setdefault(g, {})
        for k, v in fields.items():
            d[k] = min(v * s, 0.95) if k in _SCALED and k.endswith("_prob") else (v * s if k in _SCALED else v)
    return out


def combined(s: float) -> dict[str, dict[str, Any]]:
    """Every kind at once (the positive IR bias stands for the bias)."""
    out: dict[str, dict[str, Any]] = {}
    for name, groups in REFERENCE.items():
        if name == "ir bias -30 mV":
            continue
        for g, fields in scaled(groups, s).items():
            out.setdefault(g, {}).update(fields)
    return out


def _toml(name: str, groups: dict[str, dict[str, Any]]) -> str:
    from harness.scenario import _toml_value
    lines = []
    for g, fields in groups.items():
        lines.append(f"[{name}.{g}]")
        lines += [f"{k} = {_toml_value(v)}" for k, v in fields.items()]
    return "\n".join(lines) + "\n"


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m harness.envelope", description=__doc__.splitlines()[0])
    ap.add_argument("--scales", default="0.5,1,1.5,2")
    ap.add_argument("-n", "--n-candles", type=int, default=5, help="random candles per room")
    ap.add_argument("--seeds", default="0:5", help="A:B")
    ap.add_argument("--target", type=float, default=99.0)
    ap.add_argument("--scheduler", default=None)
    ap.add_argument("--workers", type=int, default=None)
    ap.add_argument("--out", default=None, help="rows as CSV")
    ap.add_argument("--kinds", default=None, help="comma-separated subset of the kinds (and 'all together')")
    args = ap.parse_args(argv)
    scales = [float(v) for v in args.scales.split(",")]
    a, b = (int(v) for v in args.seeds.split(":"))
    kinds = dict(REFERENCE)
    names = [*kinds, "all together"]
    if args.kinds:
        names = [k for k in names if k in args.kinds.split(",")]
    with tempfile.TemporaryDirectory() as tmp:
        jobs: list[dict[str, Any]] = []
        for ki, name in enumerate(names):
            for si, s in enumerate(scales):
                pname = f"k{ki}s{si}"
                groups = combined(s) if name == "all together" else scaled(kinds[name], s)
                path = Path(tmp) / f"{pname}.toml"
                path.write_text(_toml(pname, groups))
                spec = sw.SweepSpec(candles="random", n_candles=args.n_candles, seeds=tuple(range(a, b)),
                                    noise=str(path))
                for j in sw.build_jobs(spec):
                    j["id"] = len(jobs)
                    j["params"] = {"kind": name, "scale": s}
                    jobs.append(j)
        print(f"envelope: {len(names)} kinds x {len(scales)} scales, {len(jobs)} missions", file=sys.stderr)
        rows, wall = sw.timed_execute(jobs, args.scheduler, args.workers, show_progress=sys.stderr.isatty())
    if args.out:
        sw.write_results(args.out, [{k: v for k, v in r.items() if k != "replay"} | {"replay": ""} for r in rows])
    per = len(rows) // (len(names) * len(scales))
    print(f"success rate (%) of {per} missions per cell ({args.n_candles} random legal candles in each room x "
          f"seeds {a}..{b - 1}); {len(rows)} missions in {wall:.0f} s")
    print()
    print("| noise (scale 1.0) | " + " | ".join(f"x{s:g}" for s in scales) + f" | envelope (>= {args.target:g} %) |")
    print("|---|" + "---:|" * len(scales) + "---|")
    for name in names:
        rates = []
        for s in scales:
            rr = [r for r in rows if r["kind"] == name and r["scale"] == s]
            rates.append(100.0 * sum(1 for r in rr if r["success"]) / len(rr))
        ok = [s for s, r in zip(scales, rates, strict=True) if r >= args.target]
        # the envelope: the largest scale below which every tested scale passes
        env = 0.0
        for s, r in zip(scales, rates, strict=True):
            if r < args.target:
                break
            env = s
        print(f"| {name} | " + " | ".join(f"{r:.1f}" for r in rates) + f" | x{env:g} |"
              + ("" if ok or env else ""))
    return 0


if __name__ == "__main__":
    exit_with(main)
