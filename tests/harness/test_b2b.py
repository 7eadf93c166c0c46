"""The back-to-back comparison itself (the emulated-board runs are in tests/pil)."""

from __future__ import annotations

from harness.b2b import back_to_back, compare_traces
from harness.loop import I_PWM_R, run_mission
from harness.scenario import make_scenario


def _trace():
    scn = make_scenario(room=1)
    scn.timing.find_limit_s = 8.0
    return scn, run_mission(scn)[1]


def test_identical_runs_report_identical() -> None:
    scn, _ = _trace()
    rep = back_to_back(scn, "ctypes:")
    assert rep.identical and rep.first_tick is None and rep.max_pwm_diff == 0
    assert rep.ticks_reference == rep.ticks_target > 700
    assert rep.to_json()["identical"] is True


def test_first_difference_and_largest_difference() -> None:
    _, a = _trace()
    _, b = _trace()
    b.i[300, I_PWM_R] += 7
    b.i[500, I_PWM_R] -= 20
    ok, first, max_pwm, fan, state, detail = compare_traces(a, b)
    assert not ok and first == 300 and max_pwm == 20 and fan == 0 and state == 0
    assert detail.startswith("tick 300")


def test_a_run_that_ends_early_differs() -> None:
    _, a = _trace()
    _, b = _trace()
    b.i = b.i[:400]
    b.f = b.f[:400]
    ok, first, *_ = compare_traces(a, b)
    assert not ok and first == 400
