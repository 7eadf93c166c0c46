"""The Plant object the harness steps: API, time, PWM hold, agreement of step sizes."""

from __future__ import annotations

import math

import numpy as np
import pytest

from sim_plant.arena import load_arena
from sim_plant.errors import FfrInputError
from sim_plant.plant import Plant
from sim_plant.robot import load_robot

ARENA = load_arena()
ROBOT = load_robot()
TICK = 0.010
HOME = ARENA.home_center
RT = ROBOT.track.wheel_radius


def make(plant_dt=0.001, theta=math.pi / 2, x=None, y=None):
    return Plant(ARENA, ROBOT, HOME[0] if x is None else x, HOME[1] if y is None else y, theta,
                 plant_dt=plant_dt)


def ticks(p, pwm_l, pwm_r, n):
    for _ in range(n):
        p.apply(pwm_l, pwm_r)
        p.integrate(TICK)


def test_initial_state_and_types():
    p = make()
    assert (p.x, p.y, p.theta) == (HOME[0], HOME[1], math.pi / 2)
    for name in ("x", "y", "theta", "phi_l", "phi_r", "omega_l", "omega_r", "i_l", "i_r", "t",
                 "min_clearance", "path_length"):
        assert type(getattr(p, name)) is float, name
    assert type(p.contacts) is int and type(p.in_contact) is bool
    assert (p.t, p.contacts, p.in_contact, p.path_length, p.phi_l, p.omega_r) == (
        0.0, 0, False, 0.0, 0.0, 0.0)
    assert p.min_clearance > 0.01
    assert p.footprint_polygon().shape == (4, 2)


def test_time_advances_by_whole_steps():
    p = make()
    for k in range(1, 1001):
        p.integrate(TICK)
        assert p.t == pytest.approx(k * TICK, abs=1e-12)
    assert p.t == 10.0
    p.integrate(0.0)
    assert p.t == 10.0
    with pytest.raises(ValueError, match="multiple"):
        p.integrate(0.0105)
    with pytest.raises(ValueError):
        p.integrate(-TICK)
    coarse = make(plant_dt=TICK)
    with pytest.raises(ValueError):
        coarse.integrate(0.001)


def test_at_rest_stays_at_rest_exactly():
    p = make()
    ticks(p, 0, 0, 100)
    assert (p.x, p.y, p.theta, p.phi_l, p.phi_r, p.omega_l, p.i_r) == (
        HOME[0], HOME[1], math.pi / 2, 0.0, 0.0, 0.0, 0.0)


def test_pwm_is_held_until_the_next_apply():
    a, b = make(), make()
    a.apply(600, 400)
    for _ in range(50):
        a.integrate(TICK)
    ticks(b, 600, 400, 50)
    assert (a.x, a.y, a.theta, a.phi_l) == (b.x, b.y, b.theta, b.phi_l)
    assert a.pwm == (600, 400)


def test_pwm_is_clipped():
    a, b = make(), make()
    ticks(a, 5000, -5000, 30)
    ticks(b, 1000, -1000, 30)
    assert (a.theta, a.phi_l, a.phi_r) == (b.theta, b.phi_l, b.phi_r)


def test_straight_drive_encoders_and_path_length():
    p = make()
    ticks(p, 600, 600, 100)
    assert p.omega_l == pytest.approx(p.omega_r, abs=0) and p.omega_l > 5.0
    assert p.x == HOME[0] and p.theta == math.pi / 2
    travelled = p.y - HOME[1]
    assert travelled == pytest.approx(p.phi_l * RT, rel=1e-12)  # eq. (1) with equal wheels
    assert p.path_length == pytest.approx(travelled, rel=1e-12)
    assert p.i_l > 0


def test_spin_in_place_wraps_heading_and_adds_no_path():
    p = make(theta=0.0, x=2.19, y=1.6)
    ticks(p, -700, 700, 500)
    assert p.x == pytest.approx(2.19, abs=1e-12) and p.y == pytest.approx(1.6, abs=1e-12)
    turned = (p.phi_r - p.phi_l) * RT / ROBOT.track.track_width  # eq. (2) integrated
    assert turned > 4 * math.pi
    assert -math.pi <= p.theta < math.pi
    assert math.remainder(p.theta - turned, 2 * math.pi) == pytest.approx(0.0, abs=1e-9)
    assert p.path_length < 1e-12
    assert p.contacts == 0


def test_one_exact_10ms_step_matches_ten_1ms_steps_in_the_arena():
    """What lets the harness use substeps = 1: both step sizes give the same mission."""
    fine, coarse = make(x=2.19, y=1.25), make(plant_dt=TICK, x=2.19, y=1.25)
    seq = [(600, 600)] * 40 + [(450, 700)] * 40 + [(300, -300)] * 30 + [(0, 0)] * 30 \
        + [(650, 700)] * 60
    worst = 0.0
    for pl, pr in seq:
        for p in (fine, coarse):
            p.apply(pl, pr)
            p.integrate(TICK)
        worst = max(worst, math.hypot(fine.x - coarse.x, fine.y - coarse.y))
        assert abs(fine.omega_l - coarse.omega_l) < 1e-6
        assert abs(fine.phi_r - coarse.phi_r) < 1e-7
    assert worst < 1e-4
    assert fine.contacts == coarse.contacts == 0
    assert fine.path_length == pytest.approx(coarse.path_length, abs=1e-4)
    assert fine.min_clearance == pytest.approx(coarse.min_clearance, abs=2e-4)


def test_footprint_polygon_follows_the_pose():
    p = make()
    ticks(p, 300, 700, 50)
    poly = p.footprint_polygon()
    centre_front = 0.5 * (poly[0] + poly[1])
    f = ROBOT.body.length_front
    np.testing.assert_allclose(centre_front, [p.x + f * math.cos(p.theta),
                                              p.y + f * math.sin(p.theta)], atol=1e-12)
    poly[:] = 0.0  # a copy: the plant is unaffected
    assert p.footprint_polygon()[0, 0] != 0.0


@pytest.mark.parametrize("dt", [0.0, -0.001, math.inf, math.nan])
def test_bad_plant_dt(dt):
    with pytest.raises(FfrInputError, match="plant_dt"):
        make(plant_dt=dt)
