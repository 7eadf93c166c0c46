"""The firmware stands calibration error (turn_calibration.c, home_orient.c, wall_direction.c).

The plant's true wheel radius x {0.97 .. 1.03} and track width x {0.95 .. 1.05} while the firmware is
told the nominal values, every room, nominal sensors: every mission home with no wall contact.
``python -m tests.scenario.start_sweep calibration`` runs the same grid as a table (``--noise`` too).
"""

from __future__ import annotations

import pytest
from start_sweep import TRACK_SCALES, WHEEL_SCALES, calibration_overrides

from harness.scenario import make_scenario

CASES = [(room, w, t) for room in (1, 2, 3, 4) for w in WHEEL_SCALES for t in TRACK_SCALES]


def test_the_grid_spans_the_stated_error_range() -> None:
    assert min(WHEEL_SCALES) == pytest.approx(0.97) and max(WHEEL_SCALES) == pytest.approx(1.03)
    assert min(TRACK_SCALES) == pytest.approx(0.95) and max(TRACK_SCALES) == pytest.approx(1.05)
    truth, belief = calibration_overrides(1.03, 0.95)
    assert truth["track.wheel_radius"] == pytest.approx(belief["wheel_radius_mm"] * 1.03e-3)
    assert truth["track.track_width"] == pytest.approx(belief["track_width_mm"] * 0.95e-3)


@pytest.mark.parametrize(("room", "wheel", "track"), CASES,
                         ids=[f"room{r}-wheel{w:.3f}-track{t:.3f}" for r, w, t in CASES])
def test_calibration_error_every_room_home(ffr_mission, room: int, wheel: float, track: float) -> None:
    truth, belief = calibration_overrides(wheel, track)
    scn = make_scenario(room=room, robot_overrides=truth, firmware=belief)
    res, _ = ffr_mission(scn, record=False)
    assert res.outcome == "home", res.detail
    assert res.wall_contacts == 0
