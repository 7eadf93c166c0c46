"""The firmware finds its way from any start pose in the home circle (home_orient.c).

Anywhere in the circle where the body fits (``test_anywhere_in_the_circle``: positions uniform over
the WHOLE circle, as ``harness.start_pose.draw_start``, also where the robot has no room to turn in
place): at least the measured share home with no contact; the goal, every one, is not reached yet
(docs/firmware.md, "Start").

Start headings over the whole 0-360 degrees (24 slots, each heading drawn within its slot), positions
drawn uniformly in the home circle where the robot has room to turn in place, every room, nominal
sensors: every mission home with no wall contact. The draw is seeded (start_sweep.start_poses), so
a failure replays; ``python -m tests.scenario.start_sweep poses`` runs the same draw (and others,
``--seed``, ``--n``) as a table.
"""

from __future__ import annotations

import math

import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st
from start_sweep import ok, start_poses, turn_radius_m

from harness.scenario import make_scenario
from sim_plant.arena import load_arena

ARENA = load_arena()
HEADINGS = 24
CASES = [(room, pose) for room in (1, 2, 3, 4) for pose in start_poses(HEADINGS, seed=room)]


def test_the_draw_covers_the_circle_and_every_heading() -> None:
    hx, hy = ARENA.home_center
    for room in (1, 2, 3, 4):
        poses = start_poses(HEADINGS, seed=room)
        slots = sorted(int(math.degrees(h) // (360 / HEADINGS)) for _, _, h in poses)
        assert slots == list(range(HEADINGS))  # one heading in every 15-degree slot
        for x, y, _ in poses:
            assert math.hypot(x - hx, y - hy) <= ARENA.home_radius
            assert ARENA.wall_distance(x, y) >= turn_radius_m()
    # positions spread over the circle, not bunched at its centre
    rs = [math.hypot(x - hx, y - hy) for room in (1, 2, 3, 4) for x, y, _ in start_poses(HEADINGS, seed=room)]
    assert max(rs) > 0.6 * ARENA.home_radius


@pytest.mark.parametrize(("room", "pose"), CASES,
                         ids=[f"room{r}-{math.degrees(p[2]):.0f}deg-({p[0]:.3f},{p[1]:.3f})" for r, p in CASES])
def test_any_start_pose_finds_the_way(ffr_mission, room: int, pose) -> None:
    res, trace = ffr_mission(make_scenario(room=room, start=pose), record=True)
    assert res.outcome == "home", res.detail
    assert res.wall_contacts == 0
    # it oriented itself first (state ORIENT), then ran the route
    from ffr_link.ctypes_link import firmware_info
    STATE_NAMES = firmware_info().state_names  # noqa: N806
    states = trace.state
    assert states[1] == STATE_NAMES.index("ORIENT")


@settings(max_examples=8, deadline=None, derandomize=True, database=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.filter_too_much])
@given(heading=st.floats(0.0, 360.0, exclude_max=True), r=st.floats(0.0, 1.0), a=st.floats(0.0, 2 * math.pi),
       room=st.integers(1, 4))
def test_property_any_heading_any_spot(ffr_mission, heading: float, r: float, a: float, room: int) -> None:
    """Heading uniform over 0-360 degrees, position uniform in the home circle (where the robot can
    turn in place)."""
    hx, hy = ARENA.home_center
    # r = 1 puts the centre on the circle, where rounding can land it a hair outside and
    # make_scenario rightly refuses it (a fresh-clone CI run drew that): stay a nanometre in
    rr = min(math.sqrt(r), 1.0 - 1e-9)
    x = hx + ARENA.home_radius * rr * math.cos(a)
    y = hy + ARENA.home_radius * rr * math.sin(a)
    assume(ARENA.wall_distance(x, y) >= turn_radius_m() + 0.01)  # room to turn in place (docs/firmware.md)
    res, _ = ffr_mission(make_scenario(room=room, start=(x, y, math.radians(heading))), record=False)
    assert res.outcome == "home", res.detail
    assert res.wall_contacts == 0


@pytest.mark.parametrize("room", [1, 2, 3, 4])
def test_the_home_circles_edge_facing_165_degrees_finds_the_way(ffr_mission, room: int) -> None:
    """A pose the property above drew in a fresh-clone CI run (heading 165, on the circle's edge at
    3.5625 rad): a change to home_orient.c's straight-away rule sent all four rooms to "doorway line
    not found" from here, though its own sweeps of 1,200 random starts got no worse. Kept as a named
    case so that the next such change meets it every run, not when the draw happens to land here."""
    hx, hy = ARENA.home_center
    x = hx + ARENA.home_radius * math.cos(3.5625)
    y = hy + ARENA.home_radius * math.sin(3.5625)
    res, _ = ffr_mission(make_scenario(room=room, start=(x, y, math.radians(165.0))), record=False)
    assert res.outcome == "home", res.detail
    assert res.wall_contacts == 0


def _bench_start_goes_home(ffr_mission, seed: int) -> None:
    """A start of the orientation bench (`ffr sweep --arena-jitter 0.025 --start random --noise
    datasheet --rooms 1 --candles default`): home with no wall contact."""
    scn = make_scenario(room=1, seed=seed, noise="datasheet", start="random", arena_jitter=0.025)
    res, _ = ffr_mission(scn, record=False)
    assert res.outcome == "home", res.detail
    assert res.wall_contacts == 0


@pytest.mark.parametrize("seed", [7683, 9417, 10458])
def test_a_front_corner_at_a_wall_across_the_front_finds_the_way(ffr_mission, seed: int) -> None:
    """Starts of the orientation bench (docs/robustness.md, "The sweep's direction") with a front
    corner 0.5-8.4 mm from a wall across the front (python -m harness.start_room), its ranger and
    the centre one both reading within the fold-back span: the sweep turned away from the corner's
    side and swung it into the wall. Kept as named cases: each failed before home_orient.c turned
    toward that side."""
    _bench_start_goes_home(ffr_mission, seed)


@pytest.mark.parametrize("seed", [4412, 6380, 8343])
def test_a_move_back_stops_when_a_rear_ranger_passes_its_peak(ffr_mission, seed: int) -> None:
    """Starts of the orientation bench (docs/robustness.md, "A wall behind passed into fold-back")
    whose moves back in ORIENT, an escape's S or the shift, brought a rear ranger past its output's
    peak: its reading came down and rose again as the wall came nearer, and the rear corner met the
    wall. Kept as named cases: each failed before home_orient.c stopped such a move
    (rear_passed)."""
    _bench_start_goes_home(ffr_mission, seed)


@pytest.mark.parametrize("seed", [4116, 7878, 13581])
def test_a_shift_backward_stops_where_a_rear_ranger_reaches_its_bottom(ffr_mission, seed: int) -> None:
    """Starts of the orientation bench (docs/robustness.md, "A shift backward stopped at a rear
    ranger's bottom") whose shift backward went on with a rear ranger at its span's bottom, the rear
    pair's chord no longer measured, and the aim's turn met the wall behind. Kept as named cases:
    each failed before home_orient.c stopped such a shift (rear_at_bottom_behind)."""
    _bench_start_goes_home(ffr_mission, seed)


@pytest.mark.parametrize("seed", [4694, 9803, 11851])
def test_a_front_ranger_read_folded_back_backs_off_before_the_sweep(ffr_mission, seed: int) -> None:
    """Starts of the orientation bench (docs/robustness.md, "The front fold move") with a front
    ranger folded back: the right front corner ranger (4694), the centre one (9803) or the left
    front corner ranger (11851) reads 108-138 mm of a wall 45-49 mm off it. Every wall as read was
    clear of the turning circle, and the sweep's turn met that wall at once. Kept as named cases:
    each failed before home_orient.c backed straight 30 mm first (front_fold_move)."""
    _bench_start_goes_home(ffr_mission, seed)


ANYWHERE = [(room, pose) for room in (1, 2, 3, 4) for pose in start_poses(HEADINGS, seed=room, anywhere=True)]
ANYWHERE_MIN = 92  # of 96: measured with home_orient.c's escape (81 before it); raise it as it improves


def test_the_whole_circle_draw_includes_starts_with_no_room_to_turn() -> None:
    from harness.start_pose import start_problem
    from sim_plant.robot import load_robot

    hx, hy = ARENA.home_center
    robot = load_robot()
    near = 0
    for _, (x, y, h) in ANYWHERE:
        assert math.hypot(x - hx, y - hy) <= ARENA.home_radius
        assert start_problem(ARENA, robot, (x, y, h)) is None  # the footprint fits
        near += ARENA.wall_distance(x, y) < turn_radius_m()
    assert near >= 5  # some starts too close to a wall to turn in place


def test_anywhere_in_the_circle(ffr_mission) -> None:
    """Every heading slot, positions uniform over the whole circle where the footprint fits, every
    room: at least ANYWHERE_MIN of the 96 missions home with no wall contact."""
    failed = []
    for room, pose in ANYWHERE:
        res, _ = ffr_mission(make_scenario(room=room, start=pose), record=False)
        if not ok(res):
            failed.append((room, [round(v, 4) for v in pose], res.outcome, res.detail))
    assert len(ANYWHERE) - len(failed) >= ANYWHERE_MIN, failed
