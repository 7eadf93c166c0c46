"""Profile the compiled tick with Linux ``perf``: numba's functions named, not bare addresses.

``perf`` names JIT code from ``/tmp/perf-PID.map`` (one line per function: start, size, name).
This module compiles the mission kernel in-process (a fresh numba cache, so every function is
compiled here and has its LLVM IR), writes that map from the functions' addresses, then runs
missions in a loop so that ``perf`` can sample the steady state:

    python -m harness.perf_map --room 4 --seconds 20 &
    # after it prints "ready PID":
    perf record -F 4000 -p PID -o tick.perf -- sleep 8
    perf report -i tick.perf --no-children --sort symbol

A function's size is taken up to the next function's start (the map needs one); code inlined
into a function counts as that function's (docs/architecture.md, "Third pass").
"""

from __future__ import annotations

import os
import re
import sys
import tempfile
import time

from harness.cli_args import EXIT_INPUT, UsageError, _Parser
from sim_plant.broken_pipe import exit_with


def _write_map(path: str) -> int:
    from harness import tick

    syms: dict[int, str] = {}
    for cres in tick.mission_kernel.overloads.values():
        lib = cres.library
        for name in set(re.findall(r'^define [^@]*@"?([^"(]+)"?\(', lib.get_llvm_str(), re.M)):
            try:
                addr = lib.get_pointer_to_function(name)
            except Exception:  # a declaration-only symbol: nothing to name
                continue
            if addr:
                syms[addr] = name
    starts = sorted(syms)
    with open(path, "w", encoding="utf-8") as fh:
        for i, a in enumerate(starts):
            size = min(starts[i + 1] - a, 1 << 20) if i + 1 < len(starts) else 1 << 12
            fh.write(f"{a:x} {size:x} {syms[a]}\n")
    return len(starts)


def main(argv: list[str] | None = None) -> int:
    ap = _Parser(prog="python -m harness.perf_map", description=__doc__.splitlines()[0])
    ap.add_argument("--room", type=int, default=4, choices=(1, 2, 3, 4))
    ap.add_argument("--seconds", type=float, default=20.0, help="how long to loop missions")
    try:
        args = ap.parse_args(argv)
        if not args.seconds > 0:
            raise UsageError(f"--seconds = {args.seconds}: expected > 0")
    except UsageError as exc:
        print(f"python -m harness.perf_map: error: {exc}", file=sys.stderr)
        return EXIT_INPUT
    # a cache of our own: functions loaded from numba's cache have no IR to read names from
    os.environ["NUMBA_CACHE_DIR"] = tempfile.mkdtemp(prefix="ffr-perf-map-")
    from harness.loop import run_mission
    from harness.scenario import make_scenario

    scn = make_scenario(room=args.room)
    run_mission(scn)
    n = _write_map(f"/tmp/perf-{os.getpid()}.map")
    print(f"ready {os.getpid()}: {n} functions in /tmp/perf-{os.getpid()}.map", flush=True)
    end = time.monotonic() + args.seconds
    k = 0
    while time.monotonic() < end:
        run_mission(scn)
        k += 1
    print(f"{k} room {args.room} missions", flush=True)
    return 0


if __name__ == "__main__":
    exit_with(main)
