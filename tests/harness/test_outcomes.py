"""Every mission outcome of the JSON contract, and the contest score."""

from __future__ import annotations

import pytest

from harness.events import parse_events
from harness.loop import run_mission
from harness.scenario import make_scenario
from harness.scoring import ScoringRules, contest_score


def test_firmware_gives_up_is_error_with_reason() -> None:
    # a flame threshold no sensor can reach: every room is searched, none has a flame
    scn = make_scenario(room=1, firmware={"flame_detect": 60000})
    res, trace = run_mission(scn)
    assert res.outcome == "error"
    assert res.detail == "firmware: no flame found"
    assert res.rooms_searched == 4
    assert res.score == ScoringRules.load().incomplete_score
    assert tuple(trace.actuators[-1, :2]) == (0, 0)


@pytest.mark.parametrize("at_s", [14.9, 15.2])
def test_flame_gone_during_the_approach_is_flame_lost(at_s: float) -> None:
    # room 1's approach runs 14.83-15.91 s, its fans on from 15.33 s (docs/firmware.md, "Room 1's
    # time"); both flame sensors read 0 from at_s on, before the fans: the flame, seen near and
    # approached, is gone without being put out and a re-scan does not find it (fail code 5)
    ev = parse_events([{"at_s": at_s, "sensor": s, "fault": "dead"} for s in ("flame.L", "flame.R")], "test")
    res, _ = run_mission(make_scenario(room=1, events=ev), record=False)
    assert res.outcome == "error"
    assert res.detail == "firmware: flame lost"
    assert res.time_to_extinguish_s is None and res.rooms_searched == 0
    # not before FFR_FLAME_LOST_MS (2 s) after the loss, nor long after (one re-scan turn: 2.4 s)
    assert 2.0 <= res.sim_time_s - at_s <= 3.0


def test_flame_sensors_dead_under_the_fans_is_a_flame_still_burning() -> None:
    # the same two sensors dead from 15.5 s, with the approach's fans already on: to the firmware the
    # flame went out under its fans (it cannot tell a dead sensor from a blown-out flame), it goes
    # home, and the plant's truth scores it: the flame still burns
    ev = parse_events([{"at_s": 15.5, "sensor": s, "fault": "dead"} for s in ("flame.L", "flame.R")], "test")
    res, _ = run_mission(make_scenario(room=1, events=ev), record=False)
    assert res.outcome == "error"
    assert res.detail == "firmware stopped with the flame still burning"
    assert res.time_to_extinguish_s is None and res.rooms_searched == 1


def test_timeout_when_the_flame_still_burns() -> None:
    scn = make_scenario(room=4)
    scn.timing.find_limit_s = 20.0
    res, _ = run_mission(scn, record=False)
    assert res.outcome == "timeout"
    assert res.time_to_extinguish_s is None and res.total_time_s is None
    assert res.sim_time_s == pytest.approx(20.0, abs=0.02)


def test_extinguished_but_not_home_in_time() -> None:
    scn = make_scenario(room=1)
    scn.timing.return_limit_s = 3.0
    res, _ = run_mission(scn, record=False)
    assert res.outcome == "extinguished"
    assert res.time_to_extinguish_s is not None and res.total_time_s is None
    assert "not home" in res.detail


@pytest.mark.parametrize("stop_on_contact", [True, False])
def test_collision(stop_on_contact: bool) -> None:
    # never stop for the wall ahead: the robot drives into the north wall
    scn = make_scenario(room=1, firmware={"front_stop_mm": 0, "front_slow_mm": 0, "approach_stop_mm": 0},
                        stop_on_contact=stop_on_contact)
    res, _ = run_mission(scn, record=False)
    assert res.outcome == "collision"
    assert res.wall_contacts >= 1
    assert res.min_wall_clearance_m == 0.0
    assert ("stop_on_contact" in res.detail) == stop_on_contact


def test_contest_score_rules() -> None:
    rules = ScoringRules(incomplete_score=600.0, room_factor={1: 1.0, 2: 0.85, 3: 0.5, 4: 0.35},
                         return_trip_factor=0.8, wall_contact_penalty=50.0)
    assert contest_score(rules, "home", 20.0, 1, 0) == pytest.approx(16.0)
    assert contest_score(rules, "extinguished", 20.0, 2, 1) == pytest.approx(20 * 0.85 + 50)
    assert contest_score(rules, "timeout", None, 4, 0) == 600.0
    assert contest_score(rules, "error", 10.0, 1, 0) == 600.0
