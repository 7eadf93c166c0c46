"""Footprint against the walls: blocking, contact counting, slipping tracks, clearance."""

from __future__ import annotations

import math

import numpy as np
import pytest

from sim_plant.arena import load_arena
from sim_plant.collision import (
    CONTACT_RELEASE,
    CONTACT_TOL,
    first_wall_hit,
    footprint_polygon,
    limit_move,
)
from sim_plant.drivetrain import build_params
from sim_plant.errors import FfrInputError
from sim_plant.geometry import convex_overlap
from sim_plant.plant import Plant
from sim_plant.robot import load_robot

ARENA = load_arena()
ROBOT = load_robot()
P = build_params(ROBOT, 0.001)
FRONT = ROBOT.body.length_front
TICK = 0.010
# The hallway east of the middle room: x 1.96..2.42, its top end closed by the
# outer wall whose inner face is at y = 2.42.
HALL_X = 2.19
TOP_FACE = 2.42


def overlaps_any(poly):
    return any(convex_overlap(poly, w) for w in ARENA.wall_polys)


def test_footprint_corners():
    poly = footprint_polygon(1.0, 2.0, 0.0, P)
    w = ROBOT.body.width / 2
    np.testing.assert_allclose(poly, [[1 + FRONT, 2 - w], [1 + FRONT, 2 + w],
                                      [1 - ROBOT.body.length_rear, 2 + w],
                                      [1 - ROBOT.body.length_rear, 2 - w]])
    turned = footprint_polygon(1.0, 2.0, math.pi / 2, P)
    np.testing.assert_allclose(turned[0], [1 + w, 2 + FRONT], atol=1e-15)
    x, y = turned[:, 0], turned[:, 1]
    area = 0.5 * np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y)
    assert area == pytest.approx((FRONT + ROBOT.body.length_rear) * 2 * w)  # CCW, positive


def test_first_wall_hit_broad_and_narrow_phase():
    assert first_wall_hit(footprint_polygon(HALL_X, 1.6, math.pi / 2, P),
                          ARENA.wall_polys, ARENA.wall_bbox) == -1
    hit = first_wall_hit(footprint_polygon(HALL_X, TOP_FACE - FRONT + 0.01, math.pi / 2, P),
                         ARENA.wall_polys, ARENA.wall_bbox)
    assert ARENA.walls[hit].name == "outer_top"


def test_limit_move_stops_at_the_wall():
    y0 = TOP_FACE - FRONT - 0.003
    poly = np.empty((4, 2))
    x, y, th, frac = limit_move(poly, HALL_X, y0, math.pi / 2, 0.010, 0.0, P,
                                ARENA.wall_polys, ARENA.wall_bbox)
    assert 0.0 < frac < 1.0
    assert not overlaps_any(footprint_polygon(x, y, th, P))
    assert TOP_FACE - (y + FRONT) <= CONTACT_TOL
    # Away from the wall the whole move is made.
    _, y2, _, frac2 = limit_move(poly, HALL_X, y0, math.pi / 2, -0.010, 0.0, P,
                                 ARENA.wall_polys, ARENA.wall_bbox)
    assert frac2 == 1.0 and y2 == pytest.approx(y0 - 0.010)


def test_limit_move_holds_a_pressed_robot():
    poly = np.empty((4, 2))
    y0 = TOP_FACE - FRONT - 0.5 * CONTACT_TOL
    assert limit_move(poly, HALL_X, y0, math.pi / 2, 0.001, 0.0, P,
                      ARENA.wall_polys, ARENA.wall_bbox) == (HALL_X, y0, math.pi / 2, 0.0)


@pytest.fixture(params=[0.001, 0.010], ids=["10_substeps", "1_substep"])
def plant_dt(request):
    return request.param


def drive(plant, pwm_l, pwm_r, seconds, each=None):
    for _ in range(round(seconds / TICK)):
        plant.apply(pwm_l, pwm_r)
        plant.integrate(TICK)
        if each is not None:
            each(plant)


def test_drive_into_wall_stops_there_and_counts_once(plant_dt):
    p = Plant(ARENA, ROBOT, HALL_X, 1.9, math.pi / 2, plant_dt=plant_dt)
    never_in_wall = []
    drive(p, 700, 700, 4.0, each=lambda q: never_in_wall.append(not overlaps_any(
        q.footprint_polygon())))
    assert all(never_in_wall)
    assert p.y + FRONT == pytest.approx(TOP_FACE, abs=2 * CONTACT_TOL)
    assert p.x == pytest.approx(HALL_X, abs=1e-12) and p.theta == pytest.approx(math.pi / 2)
    assert p.contacts == 1
    assert p.in_contact
    assert p.min_clearance == 0.0
    assert p.path_length == pytest.approx(TOP_FACE - FRONT - 1.9, abs=2 * CONTACT_TOL)


def test_encoders_keep_counting_while_pushing(plant_dt):
    p = Plant(ARENA, ROBOT, HALL_X, 2.1, math.pi / 2, plant_dt=plant_dt)
    drive(p, 700, 700, 2.0)
    assert p.in_contact
    y, phi_l, phi_r = p.y, p.phi_l, p.phi_r
    drive(p, 700, 700, 1.0)
    assert p.y == y  # held at the wall
    # The tracks slip at the free-running wheel speed: a whole second of rotation.
    assert p.phi_l - phi_l == pytest.approx(p.omega_l * 1.0, rel=1e-6)
    assert p.phi_r - phi_r == pytest.approx(p.omega_r * 1.0, rel=1e-6)
    assert p.omega_l > 5.0
    assert p.contacts == 1


def test_two_separate_touches_count_twice(plant_dt):
    p = Plant(ARENA, ROBOT, HALL_X, 2.1, math.pi / 2, plant_dt=plant_dt)
    drive(p, 700, 700, 1.5)
    assert p.contacts == 1
    drive(p, -700, -700, 0.5)
    assert not p.in_contact
    assert TOP_FACE - (p.y + FRONT) > CONTACT_RELEASE
    drive(p, 700, 700, 1.5)
    assert p.contacts == 2
    assert p.in_contact


def test_resting_against_the_wall_is_one_contact(plant_dt):
    """Stopping at the wall and pushing again is the same contact episode."""
    p = Plant(ARENA, ROBOT, HALL_X, 2.1, math.pi / 2, plant_dt=plant_dt)
    drive(p, 700, 700, 1.5)
    drive(p, 0, 0, 1.0)
    assert p.in_contact
    drive(p, 700, 700, 1.0)
    assert p.contacts == 1


def test_turning_into_a_wall_is_blocked(plant_dt):
    """A spin whose corner would sweep into a wall holds the pose; encoders still count."""
    p = Plant(ARENA, ROBOT, HALL_X, TOP_FACE - FRONT - 0.005, math.pi / 2, plant_dt=plant_dt)
    never_in_wall = []
    drive(p, -500, 500, 1.0, each=lambda q: never_in_wall.append(not overlaps_any(
        q.footprint_polygon())))
    assert all(never_in_wall)
    assert p.contacts == 1
    assert p.phi_r > 1.0 and p.phi_l < -1.0
    assert abs(p.theta - math.pi / 2) < 0.2  # it turned only until the corner met the wall


def test_clearance_decreases_towards_a_wall(plant_dt):
    p = Plant(ARENA, ROBOT, HALL_X, 2.0, math.pi / 2, plant_dt=plant_dt)
    start = p.clearance_now()  # to the hallway's side walls
    assert p.min_clearance == pytest.approx(start)
    seen = []
    drive(p, 500, 500, 1.2, each=lambda q: seen.append(
        (q.clearance_now(), q.min_clearance, TOP_FACE - q.y - FRONT)))
    now, mins, gaps = np.array(seen).T
    assert np.all(np.diff(now) <= 1e-12)
    assert np.all(np.diff(now[gaps < start]) < 0.0)
    assert 0.0 < now[-1] < 0.1
    np.testing.assert_allclose(now, np.minimum(gaps, start), atol=1e-12)
    np.testing.assert_allclose(mins, now, atol=1e-12)
    assert p.contacts == 0


def test_start_pose_in_a_wall_is_an_input_error():
    with pytest.raises(FfrInputError) as err:
        Plant(ARENA, ROBOT, HALL_X, TOP_FACE - FRONT + 0.001, math.pi / 2, source="scenario.toml")
    e = err.value
    assert e.field == "start" and e.source == "scenario.toml"
    assert "outer_top" in str(e) and "\n" not in str(e)
    with pytest.raises(FfrInputError, match="outside the arena"):
        Plant(ARENA, ROBOT, 3.5, 3.5, 0.0)
    with pytest.raises(FfrInputError, match="start"):
        Plant(ARENA, ROBOT, math.nan, 1.0, 0.0)


def test_first_open_point_skips_points_in_a_polygon_or_near_the_segment() -> None:
    from sim_plant.geometry import first_open_point

    square = np.array([[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]])  # counter-clockwise
    # in the square; on its edge (counts as in); within reach 0.1 of the segment (2,0)-(2,1); open; open
    xs = np.array([0.5, 1.0, 2.05, 3.0, 4.0])
    ys = np.array([0.5, 0.5, 0.5, 0.5, 0.5])
    assert first_open_point(xs, ys, square, 2.0, 0.0, 2.0, 1.0, 0.1) == 3
    assert first_open_point(xs[:3], ys[:3], square, 2.0, 0.0, 2.0, 1.0, 0.1) == -1
    # a reach that no longer covers the third point: it is the first open one
    assert first_open_point(xs, ys, square, 2.0, 0.0, 2.0, 1.0, 0.04) == 2
    # no polygons: only the segment's reach keeps a point
    assert first_open_point(xs, ys, square[:0], 2.0, 0.0, 2.0, 1.0, 0.1) == 0
