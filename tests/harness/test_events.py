"""Scenario events: a sensor that dies, sticks or turns noisy, a wheel that slips."""

from __future__ import annotations

import numpy as np
import pytest

from harness.events import Event, EventRunner, parse_events
from harness.loop import I_SENS, run_mission
from harness.scenario import load_scenario, make_scenario
from sim_plant.errors import FfrInputError
from sim_plant.sensors import CH_ENC_L, CH_ENC_R, CH_FLAME_L, CH_IR, CH_LINE, new_output


def _hw(enc_l: int = 0, enc_r: int = 0) -> np.ndarray:
    hw = new_output()
    hw[:5] = [1000, 1100, 1200, 1300, 1400]
    hw[CH_FLAME_L], hw[CH_FLAME_L + 1] = 500, 600
    hw[CH_LINE] = 1
    hw[CH_ENC_L], hw[CH_ENC_R] = enc_l, enc_r
    return hw


def test_dead_stuck_noisy_act_only_in_their_window() -> None:
    evs = [Event(1.0, "ir.RF", "dead", duration_s=1.0), Event(1.0, "flame.L", "stuck"),
           Event(0.5, "line", "dead", value=0.0), Event(2.5, "ir.CF", "noisy", sigma=50.0)]
    run = EventRunner(evs, np.random.default_rng(0))
    seen = []
    for k in range(40):
        t = k * 0.1
        hw = _hw()
        hw[CH_FLAME_L] = 500 + k  # a changing reading, to see the stuck one hold
        run.apply(t, hw)
        seen.append(hw.copy())
    s = np.array(seen)
    rf = CH_IR[2]
    assert (s[:10, rf] == 1200).all() and (s[10:20, rf] == 0).all() and (s[20:, rf] == 1200).all()
    assert (s[:10, CH_FLAME_L] == 500 + np.arange(10)).all() and (s[10:, CH_FLAME_L] == 510).all()
    assert (s[:5, CH_LINE] == 1).all() and (s[5:, CH_LINE] == 0).all()
    assert (s[:25, 0] == 1000).all() and np.std(s[25:, 0]) > 20  # noisy from 2.5 s
    assert (s[:, CH_IR[1]] == 1100).all()  # the others untouched


def test_slip_over_counts_and_a_dead_encoder_loses_counts_for_good() -> None:
    run = EventRunner([Event(1.0, "wheel.L", "slip", duration_s=1.0, fraction=0.5),
                       Event(1.0, "encoder.R", "dead", duration_s=1.0)], np.random.default_rng(0))
    last = None
    for k in range(31):
        hw = _hw(enc_l=10 * k, enc_r=10 * k)  # both wheels turn 10 counts per 0.1 s
        run.apply(k * 0.1, hw)
        last = hw
    assert last is not None
    # left: 10 s of rotation at 1/(1-0.5) = 2x for 1 s -> 100 extra counts
    assert last[CH_ENC_L] == 300 + 100
    # right: the counts of the dead second are lost
    assert last[CH_ENC_R] == 300 - 100


@pytest.mark.parametrize(("text", "field"), [
    ('[[events]]\nat_s = 1\nsensor = "ir.XX"\nfault = "dead"\n', "events[0].sensor"),
    ('[[events]]\nat_s = 1\nsensor = "ir.RF"\nfault = "melted"\n', "events[0].fault"),
    ('[[events]]\nat_s = -1\nsensor = "ir.RF"\nfault = "dead"\n', "events[0].at_s"),
    ('[[events]]\nsensor = "ir.RF"\nfault = "dead"\n', "events[0].at_s"),
    ('[[events]]\nat_s = 1\nsensor = "ir.RF"\nfault = "noisy"\n', "events[0].sigma"),
    ('[[events]]\nat_s = 1\nsensor = "wheel.L"\nfault = "slip"\nfraction = 1.5\n', "events[0].fraction"),
    ('[[events]]\nat_s = 1\nsensor = "ir.RF"\nfault = "slip"\nfraction = 0.2\n', "events[0].sensor"),
    ('[[events]]\nat_s = 1\nsensor = "ir.RF"\nfault = "dead"\nsigma = 3\n', "events[0].sigma"),
    ('[[events]]\nat_s = 1\nsensor = "ir.RF"\nfault = "dead"\nduration_s = 0\n', "events[0].duration_s"),
    ('[[events]]\nat_s = 1\nsensor = "ir.RF"\nfault = "dead"\nwhen = 3\n', "events[0].when"),
    ('events = 3\n', "events"),
])
def test_bad_events_one_line_naming_file_field_value(tmp_path, text: str, field: str) -> None:
    p = tmp_path / "ev.toml"
    p.write_text(text)
    with pytest.raises(FfrInputError) as exc:
        load_scenario(p)
    msg = str(exc.value)
    assert "\n" not in msg and str(p) in msg and f"{field} = " in msg


def test_events_reach_the_firmware_in_a_mission() -> None:
    """The right-front ranger fails at 5 s: the firmware reads 0 mV from then on, the plant is untouched."""
    ev = parse_events([{"at_s": 5, "sensor": "ir.RF", "fault": "dead"}], "test")
    scn = make_scenario(room=1, events=ev)
    scn.timing.find_limit_s = 8.0
    _, tr = run_mission(scn)
    rf = tr.i[:, I_SENS + CH_IR[2]]
    assert (rf[tr.t >= 5.0] == 0).all() and (rf[tr.t < 5.0] > 0).all()
    ref = make_scenario(room=1)
    ref.timing.find_limit_s = 8.0
    _, tr0 = run_mission(ref)
    n = int(np.searchsorted(tr.t, 5.0))
    assert np.array_equal(tr.f[:n], tr0.f[:n])  # identical until the fault


def test_right_front_ranger_fails_at_30_s_the_mission_still_ends_home() -> None:
    """What the firmware does when a ranger dies mid-mission: room 1's candle is out by then; the way
    home follows the left wall and the front ranger, so the dead right-front ranger must not matter."""
    ev = parse_events([{"at_s": 25, "sensor": "ir.RF", "fault": "dead"}], "test")
    res, _ = run_mission(make_scenario(room=1, events=ev), record=False)
    assert res.outcome == "home" and res.wall_contacts == 0, res.detail
