"""Back-to-back equivalence: the same scenario through two firmware builds.

The reference is the host library in process (``ctypes:``); the target is
any other link, typically the Cortex-M4 build on an emulated board
(``qemu:mps2-an386``). Both runs see the same plant and sensors for as long
as the firmware commands the same actuators, so the first tick where the
actuator commands differ is where the builds diverge. Bit-identical is the
goal: float32 on both sides, the same sources, portable math (fmath.c).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from ffr_link import FirmwareLink
from harness.loop import I_FAN, I_PWM_L, I_PWM_R, I_STATE, Trace, run_mission
from harness.scenario import Scenario
from harness.scoring import MissionResult


@dataclass
class B2BReport:
    reference: str
    target: str
    ticks_reference: int
    ticks_target: int
    identical: bool
    first_tick: int | None  # first tick whose commands differ (or where one run ended)
    first_time_s: float | None
    max_pwm_diff: int  # per mille, over the common ticks
    fan_mismatches: int
    state_mismatches: int
    detail: str
    results: tuple[MissionResult, MissionResult]

    def to_json(self) -> dict[str, Any]:
        return {
            "reference": self.reference, "target": self.target, "identical": self.identical,
            "ticks_reference": self.ticks_reference, "ticks_target": self.ticks_target,
            "first_tick": self.first_tick, "first_time_s": self.first_time_s,
            "max_pwm_diff": self.max_pwm_diff, "fan_mismatches": self.fan_mismatches,
            "state_mismatches": self.state_mismatches, "detail": self.detail,
            "outcome_reference": self.results[0].outcome, "outcome_target": self.results[1].outcome,
        }


def _name(names: tuple[str, ...], code: int) -> str:
    return names[code] if 0 <= code < len(names) else f"state {code}"


def compare_traces(ref: Trace, tgt: Trace) -> tuple[bool, int | None, int, int, int, str]:
    """(identical, first differing tick, max |pwm| diff, fan and state mismatches, detail)."""
    n = min(len(ref.i), len(tgt.i))
    a, b = ref.i[:n], tgt.i[:n]
    cmd = [I_PWM_L, I_PWM_R, I_FAN, I_STATE]
    diff_rows = np.flatnonzero(np.any(a[:, cmd] != b[:, cmd], axis=1))
    pwm = np.abs(a[:, [I_PWM_L, I_PWM_R]].astype(np.int64) - b[:, [I_PWM_L, I_PWM_R]])
    max_pwm = int(pwm.max()) if n else 0
    fan = int(np.count_nonzero(a[:, I_FAN] != b[:, I_FAN]))
    state = int(np.count_nonzero(a[:, I_STATE] != b[:, I_STATE]))
    if len(diff_rows):
        k = int(diff_rows[0])
        rn, tn = ref.names_of_states(), tgt.names_of_states()
        detail = (f"tick {k}: reference pwm {tuple(int(v) for v in a[k, [I_PWM_L, I_PWM_R]])} "
                  f"{_name(rn, a[k, I_STATE])}, target pwm {tuple(int(v) for v in b[k, [I_PWM_L, I_PWM_R]])} "
                  f"{_name(tn, b[k, I_STATE])}")
        return False, k, max_pwm, fan, state, detail
    if len(ref.i) != len(tgt.i):
        return False, n, max_pwm, fan, state, f"one run ended at tick {n}, the other ran on"
    # same commands, same plant: the traces must then agree in every column
    if ref.f.tobytes() != tgt.f.tobytes() or ref.i.tobytes() != tgt.i.tobytes():
        return False, None, max_pwm, fan, state, "same commands but different traces"
    return True, None, 0, 0, 0, f"{n} ticks identical"


def back_to_back(scn: Scenario, target: FirmwareLink | str, reference: FirmwareLink | str = "ctypes:") -> B2BReport:
    ref_res, ref_tr = run_mission(scn, reference)
    tgt_res, tgt_tr = run_mission(scn, target)
    ok, first, max_pwm, fan, state, detail = compare_traces(ref_tr, tgt_tr)
    period = scn.timing.firmware_period_ms / 1000.0
    return B2BReport(
        reference=ref_res.link, target=tgt_res.link, ticks_reference=len(ref_tr.i), ticks_target=len(tgt_tr.i),
        identical=ok, first_tick=first, first_time_s=None if first is None else round(first * period, 3),
        max_pwm_diff=max_pwm, fan_mismatches=fan, state_mismatches=state, detail=detail,
        results=(ref_res, tgt_res),
    )
