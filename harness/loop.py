"""The lockstep loop: sensors -> firmware -> plant, one firmware tick at a time.

One tick (docs/architecture.md): the sensors sample the plant into hardware units, the
link steps the firmware once with them, the firmware's PWM and fan command are
applied to the plant, which integrates over the tick. The firmware never runs
ahead of the plant; each inputs frame carries the tick time and a sequence
number and gets exactly one outputs frame back.

With the in-process ``ctypes:`` link the whole loop runs in one compiled call
(``harness/tick.py``: ~2 us a tick instead of ~11); every other link, and
``Mission.run(compiled=False)``, takes the Python loop below (``_python_loop``),
one call per part per tick: the reference the compiled loop is tested against
bit for bit (tests/harness/test_compiled_tick.py).
"""

from __future__ import annotations

import math
import threading
from dataclasses import dataclass, field

import numpy as np

from ffr_link import FirmwareLink, open_link
from ffr_link.abi import (
    FLAG_DONE,
    FLAG_FAILED,
    INPUTS_DTYPE,
    OUTPUTS_DTYPE,
)
from ffr_link.base import LinkError, new_inputs, new_outputs
from ffr_link.ctypes_link import CtypesLink
from harness.events import N_EV_STATE, EventRunner, pack_events
from harness.firmware_config import build_config
from harness.scenario import Scenario
from harness.scoring import MissionResult, ScoringRules, contest_score
from harness.sigint_guard import sigint_deferred
from harness.tick import (
    END_CANDLE,
    END_CONTACT,
    END_DONE,
    END_FAILED,
    END_FIND_LIMIT,
    END_RETURN_LIMIT,
    END_STUCK,
    _pack,
    _record,
    mission_kernel,
)
from sim_plant.candle import Candle
from sim_plant.plant import Plant
from sim_plant.robot import RobotParams
from sim_plant.sensors import N_CHANNELS, SensorSuite, new_output

# Byte offsets the compiled packer writes to, taken from the checked dtypes.
_IN = {k: INPUTS_DTYPE.fields[k][1] for k in INPUTS_DTYPE.names}  # type: ignore[index,union-attr]
_OUT = {k: OUTPUTS_DTYPE.fields[k][1] for k in OUTPUTS_DTYPE.names}  # type: ignore[index,union-attr]
assert (_IN["t_ms"], _IN["seq"], _IN["enc"], _IN["ir_mv"], _IN["flame"], _IN["line"], _IN["start"]) == (
    0, 4, 8, 16, 26, 30, 31), "inputs layout changed: update _pack"
assert (_OUT["pwm"], _OUT["fan"], _OUT["state"], _OUT["flags"], _OUT["step"], _OUT["fail_code"]) == (
    4, 8, 9, 13, 14, 15), \
    "outputs layout changed: update _record"

# The detail of a run ended by knocking the candle over (outcome "collision", docs/sensors.md).
CANDLE_KNOCKED = "knocked the candle over"

# Trace columns.
F_T, F_X, F_Y, F_TH = range(4)
N_F = 4
I_PWM_L, I_PWM_R, I_FAN, I_STATE, I_FLAGS, I_STEP, I_CONTACT = range(7)
I_SENS = 7  # then the N_CHANNELS sensor channels
N_I = I_SENS + N_CHANNELS


@dataclass
class Trace:
    """Per-tick record of a mission: ``f`` floats (t, x, y, theta), ``i`` ints
    (pwm_l, pwm_r, fan, state, flags, step, in_contact, then the sensor channels)."""

    f: np.ndarray
    i: np.ndarray
    # the firmware's state names (index = the state column's code), from its library (ffr_names)
    state_names: tuple[str, ...] = field(default=(), compare=False)

    def names_of_states(self) -> tuple[str, ...]:
        """The state names of the firmware that made this trace (else of the default firmware)."""
        if self.state_names:
            return self.state_names
        from ffr_link.ctypes_link import firmware_info

        return firmware_info().state_names

    @property
    def t(self) -> np.ndarray:
        return self.f[:, F_T]

    @property
    def xy(self) -> np.ndarray:
        return self.f[:, F_X:F_Y + 1]

    @property
    def actuators(self) -> np.ndarray:
        """(n, 3) pwm_l, pwm_r, fan: what the firmware commanded, tick by tick."""
        return self.i[:, I_PWM_L:I_FAN + 1]

    @property
    def state(self) -> np.ndarray:
        return self.i[:, I_STATE]


_BUFFERS = threading.local()


def _trace_buffers(rows: int) -> tuple[np.ndarray, np.ndarray]:
    """The trace's work arrays, reused by every mission of this thread: both loops write every
    column of rows 0..k-1 and the result copies those out, so the rest need no zeroing. A fresh
    ~2 MB pair cost each mission ~0.7 ms of page faults (3-4 % of a room-4 mission)."""
    have = getattr(_BUFFERS, "pair", None)
    if have is None or have[0].shape[0] < rows:
        have = _BUFFERS.pair = (np.empty((rows, N_F)), np.empty((rows, N_I), dtype=np.int32))
    return have[0][:rows], have[1][:rows]


@dataclass
class Mission:
    """A scenario wired to a plant, sensors, candle and a firmware link."""

    scenario: Scenario
    link: FirmwareLink
    rules: ScoringRules
    # set by run(): the plant's truth (the scenario's robot, or the realistic draw) and the
    # configuration the firmware was given (from the truth's calibration only)
    truth: RobotParams | None = field(default=None, repr=False)
    config: np.ndarray | None = field(default=None, repr=False)

    @classmethod
    def create(cls, scn: Scenario, link: FirmwareLink | str = "ctypes:",
               rules: ScoringRules | None = None) -> Mission:
        if isinstance(link, str):
            link = open_link(link)
        return cls(scn, link, rules or ScoringRules.load())

    def run(self, record: bool = True, compiled: bool | None = None) -> tuple[MissionResult, Trace]:
        """Run the mission to its end. ``compiled``: the whole loop in one numba call
        (harness/tick.py); None = whenever the link is the in-process ``CtypesLink`` itself,
        False = the Python loop, one call per part per tick (any link)."""
        link = self.link
        if compiled is None:
            # exactly CtypesLink: a subclass may override step, which the kernel would bypass
            compiled = type(link) is CtypesLink
        elif compiled and not isinstance(link, CtypesLink):
            raise ValueError(f"{link.url}: the compiled loop needs the in-process ctypes: link")
        scn = self.scenario
        tm = scn.timing
        period_ms = tm.firmware_period_ms
        period = period_ms / 1000.0
        rng = np.random.default_rng(scn.seed)
        # The plant's truth: the scenario's robot, or under a profile with a reality group
        # (``realistic``) a robot drawn from the seed carrying the team's calibration of it. The
        # firmware's configuration comes from the calibration only (firmware_config.py).
        robot = scn.noise.reality.draw(scn.robot, rng) if scn.noise.reality.enabled else scn.robot
        self.truth = robot
        plant = Plant(scn.arena, robot, *scn.start, plant_dt=tm.plant_dt_ms / 1000.0,
                      source=scn.source)
        candle = Candle(scn.candle[0], scn.candle[1], robot, scn.arena)
        sensors = SensorSuite(scn.arena, robot, candle, scn.noise, rng,
                              ir_sources=scn.ir_source_array())
        cfg = build_config(robot, scn.firmware, scn.source, firmware=link.firmware,
                           start_area=scn.start_area)
        self.config = cfg
        if not compiled:
            warm_up(scn, record)  # before the reset: a board's watchdog runs from there
        counters0 = link.link_counters()
        link.reset(cfg)

        inp, out = new_inputs(), new_outputs()
        in_bytes = inp.reshape(1).view(np.uint8)
        u32, i32, u16 = in_bytes.view(np.uint32), in_bytes.view(np.int32), in_bytes.view(np.uint16)
        out_bytes = out.reshape(1).view(np.uint8)
        o16 = out_bytes.view(np.int16)
        hw = new_output()

        limit_s = tm.find_limit_s + tm.return_limit_s
        max_ticks = int(math.ceil(limit_s / period)) + 2
        tf, ti = _trace_buffers(max_ticks if record else 1)
        start_tick = int(math.ceil(tm.start_delay_ms / period_ms))

        outcome = ""
        detail = ""
        done_t: float | None = None
        if compiled:
            assert isinstance(link, CtypesLink)
            n_sub = plant.steps_for(period)
            cp, cs = candle.pack()
            ev = pack_events(scn.events)
            with sigint_deferred():  # numba takes the Generator in: a Ctrl-C there is a SIGSEGV
                end, k, t = mission_kernel(
                    link.step_address, link.state_address, inp.ctypes.data, out.ctypes.data,
                    u32, i32, u16, in_bytes, o16, out_bytes, hw, tf, ti, record,
                    *sensors.kernel_args(), rng,
                    ev, np.zeros((N_CHANNELS, N_EV_STATE)), np.zeros(len(ev), dtype=np.int64),
                    *plant.kernel_args(), n_sub, cs, cp, period_ms, start_tick, max_ticks,
                    float(tm.find_limit_s), float(tm.return_limit_s), bool(scn.stop_on_contact),
                    FLAG_DONE, FLAG_FAILED)
            link.steps += k
            candle.unpack(cs)
            plant.apply(int(o16[2]), int(o16[3]), bool(out_bytes[8]))
            if end == END_DONE:
                done_t = t
            elif end == END_FAILED:
                outcome = "failed"
                detail = "firmware: " + link.firmware.fail_name(int(out_bytes[15]))
            elif end == END_CANDLE:
                outcome, detail = "collision", CANDLE_KNOCKED
            elif end == END_CONTACT:
                outcome, detail = "collision", "wall contact (stop_on_contact)"
            elif end == END_STUCK:
                outcome, detail = "collision", "pushed against a wall for 5 s"
            elif end == END_FIND_LIMIT:
                outcome, detail = "timeout", f"flame still burning after {tm.find_limit_s:g} s"
            elif end == END_RETURN_LIMIT:
                outcome, detail = "extinguished", f"not home {tm.return_limit_s:g} s after the flame went out"
            else:
                outcome, detail = "timeout", "time limit"
        else:
            k, t, done_t, outcome, detail = self._python_loop(
                plant, candle, sensors, EventRunner(scn.events, rng) if scn.events else None,
                inp, out, u32, i32, u16, in_bytes, o16, out_bytes, hw, tf, ti, record,
                start_tick, max_ticks)

        ext = candle.extinguished_at if not candle.lit else None
        if outcome == "failed":
            outcome = "extinguished" if ext is not None else "error"
        if not outcome:
            hx, hy = scn.arena.home_center
            at_home = math.hypot(plant.x - hx, plant.y - hy) <= scn.arena.home_radius
            if ext is not None and at_home:
                outcome = "home"
            elif ext is not None:
                outcome, detail = "extinguished", "stopped outside the home circle"
            else:
                outcome, detail = "error", "firmware stopped with the flame still burning"
        rooms = int(out_bytes[11])
        # the candle's room counts as searched even when the robot never left it
        rooms_searched = rooms + (1 if ext is not None else 0)
        result = MissionResult(
            outcome=outcome, room=scn.room, candle=scn.candle,
            time_to_extinguish_s=ext,
            total_time_s=done_t if outcome == "home" else None,
            wall_contacts=plant.contacts, min_wall_clearance_m=plant.min_clearance,
            path_length_m=plant.path_length, seed=scn.seed, rooms_searched=rooms_searched,
            detail=detail, scenario=scn.name, link=link.url, sim_time_s=t,
            final_pose=(plant.x, plant.y, plant.theta),
            link_counters=(link.link_counters() - counters0).as_dict(),
            start_pose=scn.start, arena_jitter=scn.arena_jitter, modes=scn.modes,
            furniture=[p.as_list() for p in scn.furniture], candle_knocked=candle.knocked,
        )
        result.score = contest_score(self.rules, outcome, ext, rooms_searched, plant.contacts, scn.modes,
                                     candle.knocked)
        n = k if record else 0
        return result, Trace(tf[:n].copy(), ti[:n].copy(), link.firmware.state_names)


    def _python_loop(self, plant: Plant, candle: Candle, sensors: SensorSuite,
                     events: EventRunner | None, inp: np.ndarray, out: np.ndarray, u32: np.ndarray,
                     i32: np.ndarray, u16: np.ndarray, in_bytes: np.ndarray, o16: np.ndarray,
                     out_bytes: np.ndarray, hw: np.ndarray, tf: np.ndarray, ti: np.ndarray,
                     record: bool, start_tick: int, max_ticks: int,
                     ) -> tuple[int, float, float | None, str, str]:
        """One Python-level call per part per tick: the loop for the wire links, and the
        reference the compiled loop is tested against."""
        scn = self.scenario
        tm = scn.timing
        period_ms = tm.firmware_period_ms
        period = period_ms / 1000.0
        link = self.link
        fast = getattr(link, "step_bound", None)
        if fast is not None:
            link.bind(inp, out)  # type: ignore[attr-defined]
        outcome = ""
        detail = ""
        done_t: float | None = None
        stuck_s = 0.0
        k = 0
        t = 0.0
        flags = 0
        while True:
            t_ms = k * period_ms
            t = t_ms / 1000.0
            sensors.sample(t, plant.x, plant.y, plant.theta, plant.phi_l, plant.phi_r, hw)
            if events is not None:
                events.apply(t, hw)
            _pack(u32, i32, u16, in_bytes, t_ms, k, hw, 1 if k >= start_tick else 0)
            try:
                if fast is not None:
                    fast()
                else:
                    link.step(inp, out)
            except LinkError as exc:
                outcome, detail = "error", str(exc)
                break
            pwm_l = int(o16[2])
            pwm_r = int(o16[3])
            fan = bool(out_bytes[8])
            flags = int(out_bytes[13])
            if record:
                _record(tf, ti, k, t, plant.x, plant.y, plant.theta, o16, out_bytes, hw,
                        1 if plant.in_contact else 0)
            k += 1
            if flags & FLAG_DONE:  # the contract: a mission ends on DONE or FAILED in flags
                done_t = t
                break
            if flags & FLAG_FAILED:
                # the firmware gave up; if the flame is out it is still "extinguished" (below)
                outcome = "failed"
                detail = "firmware: " + link.firmware.fail_name(int(out_bytes[15]))
                break
            plant.apply(pwm_l, pwm_r, fan)
            plant.integrate(period)
            candle.update(t + period, period, fan, plant.x, plant.y, plant.theta)
            if candle.knocked:
                outcome, detail = "collision", CANDLE_KNOCKED
                break
            if scn.stop_on_contact and plant.contacts > 0:
                outcome, detail = "collision", "wall contact (stop_on_contact)"
                break
            stuck_s = stuck_s + period if plant.in_contact else 0.0
            if stuck_s >= 5.0:
                outcome, detail = "collision", "pushed against a wall for 5 s"
                break
            if candle.lit and t + period >= tm.find_limit_s:
                outcome, detail = "timeout", f"flame still burning after {tm.find_limit_s:g} s"
                break
            if (not candle.lit and candle.extinguished_at is not None
                    and t + period - candle.extinguished_at >= tm.return_limit_s):
                outcome, detail = "extinguished", f"not home {tm.return_limit_s:g} s after the flame went out"
                break
            if k >= max_ticks:
                outcome, detail = "timeout", "time limit"
                break
        return k, t, done_t, outcome, detail


def warm_up(scn: Scenario, record: bool) -> None:
    """One tick of every kernel the Python loop calls, on throwaway objects and a throwaway
    random stream: a cold numba cache compiles them here, not between two firmware ticks,
    where a board's link watchdog would see the host go silent for seconds. The CLI calls it
    before it opens a wire link too, so that no board waits for a compiling host."""
    plant = Plant(scn.arena, scn.robot, *scn.start, plant_dt=scn.timing.plant_dt_ms / 1000.0,
                  source=scn.source)
    candle = Candle(scn.candle[0], scn.candle[1], scn.robot, scn.arena)
    rng = np.random.default_rng(0)
    hw = new_output()
    SensorSuite(scn.arena, scn.robot, candle, scn.noise, rng,
                ir_sources=scn.ir_source_array()).sample(
        0.0, plant.x, plant.y, plant.theta, plant.phi_l, plant.phi_r, hw)
    if scn.events:
        EventRunner(scn.events, rng).apply(0.0, hw)
    inp, out = new_inputs(), new_outputs()
    b = inp.reshape(1).view(np.uint8)
    _pack(b.view(np.uint32), b.view(np.int32), b.view(np.uint16), b, 0, 0, hw, 0)
    if record:
        ob = out.reshape(1).view(np.uint8)
        _record(np.zeros((1, N_F)), np.zeros((1, N_I), dtype=np.int32), 0, 0.0, plant.x, plant.y,
                plant.theta, ob.view(np.int16), ob, hw, 0)
    period = scn.timing.firmware_period_ms / 1000.0
    plant.apply(0, 0)
    plant.integrate(period)
    candle.update(period, period, False, plant.x, plant.y, plant.theta)


def run_mission(scn: Scenario, link: FirmwareLink | str = "ctypes:", record: bool = True,
                rules: ScoringRules | None = None, compiled: bool | None = None,
                ) -> tuple[MissionResult, Trace]:
    own = isinstance(link, str)
    m = Mission.create(scn, link, rules)
    try:
        return m.run(record=record, compiled=compiled)
    finally:
        if own:
            m.link.close()
