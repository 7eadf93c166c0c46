"""One mission's per-tick trace as text: where the robot truly was and what the firmware did.

    python -m harness.mission_trace "ffr run --room 4 --noise realistic --seed 31" [--from S] [--to S]
                                    [--every N] [--sensors]

The command is a replay line as ``ffr sweep`` prints it for each failure (or any ``ffr run``
command for one mission). A line is printed when the firmware's state, route step or wall contact
changes, and every N-th tick (default 10) in between: time, the plant's true pose (x, y in m,
heading in degrees), state, step, contact, and with ``--sensors`` what the firmware read (the five
rangers in mV, the two flame sensors in counts, the line bit, the encoder counts). It is how the
failure analyses of docs/robustness.md look at a mission tick by tick.
"""

from __future__ import annotations

import math
import sys
from collections.abc import Sequence

from harness.cli_args import EXIT_INPUT, UsageError, _Parser
from harness.loop import F_T, F_TH, F_X, F_Y, I_CONTACT, I_SENS, I_STATE, I_STEP, Trace
from sim_plant.broken_pipe import exit_with
from sim_plant.errors import FfrInputError
from sim_plant.sensors.channels import CH_ENC_L, CH_ENC_R, CH_FLAME_L, CH_FLAME_R, CH_IR, CH_LINE

HEAD = "     t      x      y  heading  state        step contact"
SENS_HEAD = "   ir CF   LF   RF   LR   RR  flame L    R line  enc L    R"


def lines(trace: Trace, t_from: float, t_to: float, every: int, sensors: bool) -> list[str]:
    """The trace's text lines between two times (s): changes and every ``every``-th tick."""
    names = trace.names_of_states()
    out = [HEAD + (SENS_HEAD if sensors else "")]
    last: tuple[int, int, int] | None = None
    for k in range(len(trace.f)):
        t = float(trace.f[k, F_T])
        if t < t_from - 1e-9 or t > t_to + 1e-9:
            continue
        code, step, contact = (int(trace.i[k, c]) for c in (I_STATE, I_STEP, I_CONTACT))
        key = (code, step, contact)
        if key == last and k % every:
            continue
        last = key
        state = names[code] if code < len(names) else str(code)
        text = (f"{t:6.2f} {trace.f[k, F_X]:6.3f} {trace.f[k, F_Y]:6.3f} "
                f"{math.degrees(float(trace.f[k, F_TH])):8.1f}  {state:12s} {step:4d} {'C' if contact else '-':>7s}")
        if sensors:
            s = trace.i[k, I_SENS:]
            ir = " ".join(f"{int(s[c]):4d}" for c in CH_IR)
            text += (f"   {ir}  {int(s[CH_FLAME_L]):7d} {int(s[CH_FLAME_R]):4d} {int(s[CH_LINE]):4d}"
                     f" {int(s[CH_ENC_L]):6d} {int(s[CH_ENC_R]):4d}")
        out.append(text)
    return out


def main(argv: Sequence[str] | None = None) -> int:
    ap = _Parser(prog="python -m harness.mission_trace",
                 description="one mission's per-tick trace: true pose, state, route step, contact")
    ap.add_argument("command", help="an 'ffr run ...' command (a sweep's replay line)")
    ap.add_argument("--from", dest="t_from", type=float, default=0.0, help="first time (s)")
    ap.add_argument("--to", dest="t_to", type=float, default=math.inf, help="last time (s)")
    ap.add_argument("--every", type=int, default=10, help="a line every N ticks besides the changes")
    ap.add_argument("--sensors", action="store_true", help="also what the firmware read")
    try:
        args = ap.parse_args(argv)
        if args.every < 1:
            raise UsageError(f"--every = {args.every}: expected at least 1")
        from harness.failure_places import replay_of

        scenario, link = replay_of(args.command)
    except (UsageError, FfrInputError, ValueError) as exc:
        print(f"python -m harness.mission_trace: error: {exc}", file=sys.stderr)
        return EXIT_INPUT
    from harness.failure_places import link_errors
    from harness.loop import run_mission

    try:
        res, trace = run_mission(scenario, link)
    except link_errors() as exc:  # the replay's link: bad input, one line
        print(f"python -m harness.mission_trace: error: {exc}", file=sys.stderr)
        return EXIT_INPUT
    print(f"outcome {res.outcome}" + (f": {res.detail}" if res.detail else ""))
    print("\n".join(lines(trace, args.t_from, args.t_to, args.every, args.sensors)))
    return 0


if __name__ == "__main__":
    exit_with(main)
