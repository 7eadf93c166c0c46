"""The lockstep loop: sensors -> firmware -> plant, one firmware tick at a time.

One tick (docs/architecture.md): the sensors sample the plant into hardware units, the
link steps the firmware once with them, the firmware's PWM and fan command are
applied to the plant, which integrates over the tick. The firmware never runs
ahead of the plant; each inputs frame carries the tick time and a sequence
number and gets exactly one outputs frame back.

The per-tick work is a handful of compiled kernels (sensors, plant) and one
ctypes call; packing the inputs and recording the trace are compiled too,
because at ~15,000 ticks per mission every microsecond of Python shows.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numba as nb
import numpy as np

from harness.events import EventRunner
from harness.firmware_abi import (
    FAIL_NAMES,
    INPUTS_DTYPE,
    OUTPUTS_DTYPE,
    ST_DONE,
    ST_FAILED,
)
from harness.firmware_config import build_config
from harness.links import FirmwareLink, open_link
from harness.links.base import LinkError, new_inputs, new_outputs
from harness.scenario import Scenario
from harness.scoring import MissionResult, ScoringRules, contest_score
from sim_plant.candle import Candle
from sim_plant.plant import Plant
from sim_plant.sensors import N_CHANNELS, SensorSuite, new_output

# Byte offsets the compiled packer writes to, taken from the checked dtypes.
_IN = {k: INPUTS_DTYPE.fields[k][1] for k in INPUTS_DTYPE.names}  # type: ignore[index,union-attr]
_OUT = {k: OUTPUTS_DTYPE.fields[k][1] for k in OUTPUTS_DTYPE.names}  # type: ignore[index,union-attr]
assert (_IN["t_ms"], _IN["seq"], _IN["enc"], _IN["ir_mv"], _IN["flame"], _IN["line"], _IN["start"]) == (
    0, 4, 8, 16, 26, 30, 31), "inputs layout changed: update _pack"
assert (_OUT["pwm"], _OUT["fan"], _OUT["state"], _OUT["flags"], _OUT["step"]) == (4, 8, 9, 13, 14), \
    "outputs layout changed: update _record"

# Trace columns.
F_T, F_X, F_Y, F_TH = range(4)
N_F = 4
I_PWM_L, I_PWM_R, I_FAN, I_STATE, I_FLAGS, I_STEP, I_CONTACT = range(7)
I_SENS = 7  # then the N_CHANNELS sensor channels
N_I = I_SENS + N_CHANNELS


@nb.njit(cache=True)
def _pack(u32: np.ndarray, i32: np.ndarray, u16: np.ndarray, u8: np.ndarray,
          t_ms: int, seq: int, hw: np.ndarray, start: int) -> None:
    u32[0] = t_ms
    u32[1] = seq
    i32[2] = hw[8]
    i32[3] = hw[9]
    for i in range(5):
        u16[8 + i] = hw[i]
    u16[13] = hw[5]
    u16[14] = hw[6]
    u8[30] = hw[7]
    u8[31] = start


@nb.njit(cache=True)
def _record(tf: np.ndarray, ti: np.ndarray, k: int, t: float, x: float, y: float, th: float,
            o16: np.ndarray, o8: np.ndarray, hw: np.ndarray, contact: int) -> None:
    tf[k, 0] = t
    tf[k, 1] = x
    tf[k, 2] = y
    tf[k, 3] = th
    ti[k, 0] = o16[2]
    ti[k, 1] = o16[3]
    ti[k, 2] = o8[8]
    ti[k, 3] = o8[9]
    ti[k, 4] = o8[13]
    ti[k, 5] = o8[14]
    ti[k, 6] = contact
    for c in range(hw.shape[0]):
        ti[k, 7 + c] = hw[c]


@dataclass
class Trace:
    """Per-tick record of a mission: ``f`` floats (t, x, y, theta), ``i`` ints
    (pwm_l, pwm_r, fan, state, flags, step, in_contact, then the sensor channels)."""

    f: np.ndarray
    i: np.ndarray

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


@dataclass
class Mission:
    """A scenario wired to a plant, sensors, candle and a firmware link."""

    scenario: Scenario
    link: FirmwareLink
    rules: ScoringRules

    @classmethod
    def create(cls, scn: Scenario, link: FirmwareLink | str = "ctypes:",
               rules: ScoringRules | None = None) -> Mission:
        if isinstance(link, str):
            link = open_link(link)
        return cls(scn, link, rules or ScoringRules.load())

    def run(self, record: bool = True) -> tuple[MissionResult, Trace]:
        scn = self.scenario
        tm = scn.timing
        period_ms = tm.firmware_period_ms
        period = period_ms / 1000.0
        plant = Plant(scn.arena, scn.robot, *scn.start, plant_dt=tm.plant_dt_ms / 1000.0,
                      source=scn.source)
        candle = Candle(scn.candle[0], scn.candle[1], scn.robot, scn.arena)
        rng = np.random.default_rng(scn.seed)
        sensors = SensorSuite(scn.arena, scn.robot, candle, scn.noise, rng)
        events = EventRunner(scn.events, rng) if scn.events else None
        cfg = build_config(scn.robot, scn.firmware, scn.source)
        link = self.link
        counters0 = link.link_counters()
        link.reset(cfg)

        inp, out = new_inputs(), new_outputs()
        in_bytes = inp.reshape(1).view(np.uint8)
        u32, i32, u16 = in_bytes.view(np.uint32), in_bytes.view(np.int32), in_bytes.view(np.uint16)
        out_bytes = out.reshape(1).view(np.uint8)
        o16 = out_bytes.view(np.int16)
        hw = new_output()
        fast = getattr(link, "step_bound", None)
        if fast is not None:
            link.bind(inp, out)  # type: ignore[attr-defined]

        limit_s = tm.find_limit_s + tm.return_limit_s
        max_ticks = int(math.ceil(limit_s / period)) + 2
        tf = np.zeros((max_ticks if record else 1, N_F))
        ti = np.zeros((max_ticks if record else 1, N_I), dtype=np.int32)
        start_tick = int(math.ceil(tm.start_delay_ms / period_ms))

        outcome = ""
        detail = ""
        done_t: float | None = None
        stuck_s = 0.0
        k = 0
        t = 0.0
        state = 0
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
            state = int(out_bytes[9])
            if record:
                _record(tf, ti, k, t, plant.x, plant.y, plant.theta, o16, out_bytes, hw,
                        1 if plant.in_contact else 0)
            k += 1
            if state == ST_DONE:
                done_t = t
                break
            if state == ST_FAILED:
                # the firmware gave up; if the flame is out it is still "extinguished" (below)
                outcome = "failed"
                detail = "firmware: " + FAIL_NAMES.get(int(out_bytes[15]), f"code {int(out_bytes[15])}")
                break
            plant.apply(pwm_l, pwm_r)
            plant.integrate(period)
            candle.update(t + period, period, fan, plant.x, plant.y, plant.theta)
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
        )
        result.score = contest_score(self.rules, outcome, ext, rooms_searched, plant.contacts)
        n = k if record else 0
        return result, Trace(tf[:n].copy(), ti[:n].copy())


def run_mission(scn: Scenario, link: FirmwareLink | str = "ctypes:", record: bool = True,
                rules: ScoringRules | None = None) -> tuple[MissionResult, Trace]:
    own = isinstance(link, str)
    m = Mission.create(scn, link, rules)
    try:
        return m.run(record=record)
    finally:
        if own:
            m.link.close()
