"""Link URL options: ``scheme:target#key=value&key=value``.

Everything after ``#`` configures our side of the link (timeouts, retries,
faults, CAN FD); the rest of the URL goes to pyserial or python-can untouched,
so any of their URLs keeps working.
"""

from __future__ import annotations

from dataclasses import dataclass, field, fields

from ffr_link.base import LinkError
from hil_bridge.faults import FaultSpec


@dataclass
class WireOptions:
    # first wait for an answer, after each silence twice as long. 0.25 s, like TCP's 200 ms floor
    # on its retransmission timeout: a busy machine stalls a process for tens of ms, and a retry
    # that a stall caused would be an error on a clean link. A lossy line can ask for less.
    timeout_s: float = 0.25
    retries: int = 10                # send an inputs frame again at most this often ...
    # ... and within this time: a board alive but answering nothing usable for 2 s is broken
    # (one line, exit 2); a board whose process or line has gone is known at once, within 1 s
    step_budget_s: float = 2.0
    # HELLO -> INFO and RESET -> READY: first wait (never more than timeout_s), doubled after each
    # silence, and the bound on all tries. The first wait is short because a RESET is 82 classic CAN
    # frames: where 2% of frames are lost, one in five gets through whole, so it may be sent often.
    handshake_try_s: float = 0.25
    handshake_timeout_s: float = 2.0
    watchdog_ms: int = 0             # asked of the board in HELLO (0: the board's own)
    baud: int = 115200               # serial: real ports only
    fd: bool = False                 # CAN FD: 64-byte segments
    bitrate: int = 0                 # CAN: passed to python-can when set
    step_delay_us: int = 0           # host board: answer this much later (a slow board)
    transport: str = "pty"           # host-board:serial: pty or tcp
    log: str = ""                    # host board: its stderr to this file
    faults: FaultSpec = field(default_factory=FaultSpec)
    given: frozenset[str] = frozenset()  # the options the URL named (the rest are defaults)


# The link watchdog asked of a simulated board (host-board:, qemu:) when the URL names none. It
# stops a real robot's motors when its host falls silent; a simulated board's motors are the
# plant's, which waits for the host, and a host stalled by a busy machine (seen: 0.5 s at a load
# of 8 on 2 cores) is no robot running away. A real board (serial:, can:) keeps its own (500 ms).
SIMULATED_WATCHDOG_MS = 5000
# The first wait for a simulated board's answer when the URL names none. Its transport (a pty, a
# local socket) loses nothing, so a silence is a stall, not a loss: a board process or QEMU thread
# not scheduled for a while on a busy machine must not cost a retry. Seen: 0.25 s on a fresh CI
# machine, then over 1 s on 2 cores running two test suites and two busy loops at once, and a
# retry at 2 s in the PIL test at a load of 11 on 2 cores. A board that has gone is still known at
# once: the wait looks for that every tenth of a second (wire_link.GONE_POLL_S). The step budget
# leaves room for one retry after such a wait.
SIMULATED_TIMEOUT_S = 5.0
SIMULATED_STEP_BUDGET_S = 15.0
# ... but a link with injected faults (drop, corrupt, duplicate, delay) loses frames on purpose:
# there a long first wait would leave the step budget room for two tries only (seen: a CAN link
# with duplicates and delays ended "no OUTPUTS after 2 tries in 15 s"), so it keeps 2 s and 6 s.
SIMULATED_FAULTY_TIMEOUT_S = 2.0
SIMULATED_FAULTY_STEP_BUDGET_S = 6.0


def simulated_board(opts: WireOptions) -> WireOptions:
    if not opts.watchdog_ms:
        opts.watchdog_ms = SIMULATED_WATCHDOG_MS
    faulty = opts.faults.active
    if "timeout_s" not in opts.given:
        opts.timeout_s = SIMULATED_FAULTY_TIMEOUT_S if faulty else SIMULATED_TIMEOUT_S
    if "step_budget_s" not in opts.given:
        budget = SIMULATED_FAULTY_STEP_BUDGET_S if faulty else SIMULATED_STEP_BUDGET_S
        opts.step_budget_s = max(opts.step_budget_s, budget)
    if not faulty:
        # the handshake waits like a step: its first wait is timeout_s, within the step budget. Seen:
        # a READY later than the real-line 0.25 s first try, on 2 cores running the test suite beside
        # a second one and two busy loops, cost two retries and two stale READYs
        if "handshake_try_s" not in opts.given:
            opts.handshake_try_s = opts.timeout_s
        if "handshake_timeout_s" not in opts.given:
            opts.handshake_timeout_s = max(opts.handshake_timeout_s, SIMULATED_STEP_BUDGET_S)
    return opts


_BOOL = {"1": True, "true": True, "yes": True, "0": False, "false": False, "no": False}


def parse_url(url: str) -> tuple[str, WireOptions]:
    """'serial:loop://#timeout_s=0.1&drop=0.01' -> ('loop://', options)."""
    rest = url.partition(":")[2]
    target, _, frag = rest.partition("#")
    opts = WireOptions()
    fault_kw: dict[str, float | int] = {}
    known = {f.name: f for f in fields(WireOptions) if f.name not in ("faults", "given")}
    given: set[str] = set()
    for item in filter(None, frag.split("&")):
        key, eq, raw = item.partition("=")
        if not eq:
            raise LinkError(f"--link = {url!r}: option {item!r}: expected key=value")
        given.add(key)
        try:
            if key in FaultSpec.names():
                fault_kw[key] = int(raw) if key == "seed" else float(raw)
            elif key in known:
                kind = type(getattr(opts, key))
                if kind is bool:
                    if raw.lower() not in _BOOL:
                        raise ValueError
                    setattr(opts, key, _BOOL[raw.lower()])
                else:
                    setattr(opts, key, kind(raw))
            else:
                raise LinkError(f"--link = {url!r}: unknown option '{key}', known: "
                                f"{sorted(set(known) | FaultSpec.names())}")
        except ValueError:
            raise LinkError(f"--link = {url!r}: option {key} = {raw!r}: not a valid value") from None
    try:
        opts.faults = FaultSpec(**fault_kw)  # type: ignore[arg-type]
    except ValueError as exc:
        raise LinkError(f"--link = {url!r}: {exc}") from None
    if (opts.timeout_s <= 0 or opts.retries < 0 or opts.handshake_try_s <= 0 or opts.handshake_timeout_s <= 0
            or opts.step_budget_s <= 0):
        raise LinkError(f"--link = {url!r}: timeouts must be > 0 and retries >= 0")
    opts.given = frozenset(given)
    return target, opts
