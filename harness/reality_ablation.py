"""What each part of a noise profile's imperfection costs: a sweep per part made ideal.

One sweep runs with the profile as it is, then one per part of it made ideal
(``python -m harness.reality_ablation``).

    python -m harness.reality_ablation [--profile realistic] [--only NAME,...] -- SWEEP OPTIONS

The sweep options are ``ffr sweep``'s (``--start hallway -n 5 --seeds 220:320 --workers 2``); the tool adds
``--noise`` (a profile written to a temporary file per row) and ``--json``. Each row names what was made
ideal and prints the sweep's success count and its change against the profile as it is.

The profile's ``reality`` group draws one fixed block of uniforms per mission (``sim_plant/reality.py``), so
a row that zeroes a reality range runs the same robots with that one part ideal. A row that zeroes a sensor
spread or the rangers' timing skips those draws, and every later draw of the mission changes with it: its
rate is comparable, its missions are not one for one (docs/robustness.md, "What each part of the realistic
robot costs").
"""

from __future__ import annotations

import argparse
import copy
import sys
import tempfile
import tomllib
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from harness.acceptance import run_ffr
from sim_plant.broken_pipe import exit_with
from sim_plant.sensors.noise import DEFAULT_PROFILES

PROG = "python -m harness.reality_ablation"


@dataclass(frozen=True)
class Ablation:
    key: str
    what: str
    fields: tuple[tuple[str, str, Any], ...]  # (group, field, ideal value); field "*": drop the group


ABLATIONS: tuple[Ablation, ...] = (
    Ablation("parts", "GP2D12 part spread (each part's gain and offset)",
             (("ir", "unit_offset_spread", 0.0), ("ir", "unit_gain_spread", 0.0))),
    Ablation("mounts", "ranger mounts (position and aim off the drawing)",
             (("reality", "ir_mount_mm", 0.0), ("reality", "ir_mount_deg", 0.0))),
    Ablation("timing", "ranger timing (latency, period spread, phase)",
             (("ranger", "latency", False), ("ranger", "period_spread", 0.0), ("ranger", "random_phase", False))),
    Ablation("turn-slip", "skid-steer turn slip (effective track width factor 1)",
             (("reality", "track_factor", [1.0, 1.0]),)),
    Ablation("sides", "left/right mismatch (motor, track friction, wheel radius)",
             (("reality", "side_motor", 0.0), ("reality", "side_friction", 0.0),
              ("reality", "side_wheel_radius", 0.0))),
    Ablation("calibration", "the team's calibration error (wheel radius, turn scale)",
             (("reality", "cal_wheel_radius", 0.0), ("reality", "cal_track_width", 0.0))),
    Ablation("creep", "longitudinal creep slip", (("reality", "creep", [0.0, 0.0]),)),
    Ablation("reality", "the whole reality group (the drive train and its calibration ideal)",
             (("reality", "*", None),)),
)


class AblationError(ValueError):
    """Bad input: one line, exit status 2."""


def builtin_profile(name: str) -> dict[str, Any]:
    """The named profile of ``sim_plant/data/noise_profiles.toml`` as its TOML tables."""
    with DEFAULT_PROFILES.open("rb") as fh:
        profiles = tomllib.load(fh)
    if name not in profiles:
        raise AblationError(f"--profile = {name!r}: not a shipped profile (one of {', '.join(sorted(profiles))})")
    return profiles[name]


def ablated(profile: dict[str, Any], ab: Ablation) -> dict[str, Any] | None:
    """The profile with one part made ideal; None when the profile has nothing of that part."""
    out = copy.deepcopy(profile)
    changed = False
    for group, field, value in ab.fields:
        table = out.get(group)
        if not isinstance(table, dict):
            continue
        if field == "*":
            del out[group]
            changed = True
        elif field in table and table[field] != value:
            table[field] = value
            changed = True
    return out if changed else None


def profile_toml(name: str, profile: dict[str, Any]) -> str:
    """One profile as a noise file (``--noise FILE.toml``), by the scenario files' table writer."""
    from harness.scenario import _toml_table

    lines: list[str] = []
    _toml_table(lines, name, profile)
    return "\n".join(lines).lstrip("\n") + "\n"


Runner = Callable[[list[str]], Any]


def table(profile_name: str, profile: dict[str, Any], ablations: Sequence[Ablation], sweep_argv: list[str],
          runner: Runner = run_ffr, log: Callable[[str], None] | None = None) -> str:
    """The Markdown table: the profile as it is, then each part made ideal."""
    rows: list[tuple[str, dict[str, Any] | None]] = [("nothing (the profile as it is)", profile)]
    rows += [(ab.what, ablated(profile, ab)) for ab in ablations]
    out = [f"| `{profile_name}`, made ideal | missions | succeeded | change |", "|---|---:|---:|---:|"]
    base: int | None = None
    with tempfile.TemporaryDirectory() as tmp:
        for i, (what, prof) in enumerate(rows):
            if prof is None:
                out.append(f"| {what} | - | not in the profile | - |")
                continue
            path = Path(tmp) / f"p{i}.toml"
            path.write_text(profile_toml(profile_name, prof), encoding="utf-8")
            data = runner(["sweep", *sweep_argv, "--noise", str(path), "--no-progress"])
            n, k = int(data["missions"]), int(data["succeeded"])
            if log:
                log(f"{what}: {k} of {n}")
            base = k if base is None else base
            change = "" if i == 0 else f"{k - base:+,}"
            out.append(f"| {what} | {n:,} | {k:,} = {100.0 * k / n:.1f} % | {change} |")
    return "\n".join(out)


def main(argv: list[str] | None = None) -> int:
    argv = list(sys.argv[1:] if argv is None else argv)
    sweep_argv: list[str] = []
    if "--" in argv:
        i = argv.index("--")
        argv, sweep_argv = argv[:i], argv[i + 1:]
    ap = argparse.ArgumentParser(prog=PROG, description=__doc__.splitlines()[0],
                                 epilog="after --: the ffr sweep options (e.g. -- --start hallway -n 5 "
                                        "--seeds 220:320 --workers 2)")
    ap.add_argument("--profile", default="realistic", help="a shipped noise profile (default realistic)")
    ap.add_argument("--only", default=None, metavar="NAME,...",
                    help="these parts only: " + ", ".join(a.key for a in ABLATIONS))
    args = ap.parse_args(argv)
    try:
        for opt in ("--noise", "--json", "--out", "--resume"):
            if any(a == opt or a.startswith(opt + "=") for a in sweep_argv):
                raise AblationError(f"sweep option {opt}: set by the tool, leave it out")
        profile = builtin_profile(args.profile)
        chosen = list(ABLATIONS)
        if args.only:
            keys = [k.strip() for k in args.only.split(",") if k.strip()]
            known = {a.key: a for a in ABLATIONS}
            bad = [k for k in keys if k not in known]
            if bad or not keys:
                raise AblationError(f"--only = {args.only!r}: expected names among {', '.join(known)}")
            chosen = [known[k] for k in keys]
        text = table(args.profile, profile, chosen, sweep_argv,
                     log=lambda s: print(s, file=sys.stderr, flush=True))
    except (AblationError, RuntimeError) as exc:
        print(f"{PROG}: {exc}", file=sys.stderr)
        return 2
    print(f"`ffr sweep {' '.join(sweep_argv)}`, one row per part of the `{args.profile}` profile made ideal")
    print()
    print(text)
    return 0


if __name__ == "__main__":
    exit_with(main)
