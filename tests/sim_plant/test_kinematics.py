"""Kinematics, eqs. (1)-(3): the pose integrator driven by prescribed wheel speeds."""

from __future__ import annotations

import math
import os

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from sim_plant.drivetrain import arc_step, body_motion, build_params, wrap_angle
from sim_plant.robot import load_robot

ROBOT = load_robot()
P = build_params(ROBOT, 0.001)
RT = ROBOT.track.wheel_radius
TR = ROBOT.track.track_width


def drive(wl: float, wr: float, t_end: float, h: float, pose=(0.3, 0.4, 0.7)):
    """Integrate constant wheel speeds (rad/s) for t_end with step h; returns all poses."""
    x, y, th = pose
    out = [(x, y, th)]
    for _ in range(round(t_end / h)):
        ds, dth = body_motion(wl * h, wr * h, P)
        x, y, th = arc_step(x, y, th, ds, dth)
        out.append((x, y, th))
    return np.array(out)


@pytest.mark.parametrize("h", [0.001, 0.01, 0.5])
def test_straight_line(h):
    w = 7.0
    x0, y0, th0 = 0.3, 0.4, 0.7
    poses = drive(w, w, 2.0, h)
    v = w * RT  # eq. (1)
    t = np.arange(len(poses)) * h
    np.testing.assert_allclose(poses[:, 0], x0 + v * t * math.cos(th0), atol=1e-12)
    np.testing.assert_allclose(poses[:, 1], y0 + v * t * math.sin(th0), atol=1e-12)
    np.testing.assert_allclose(poses[:, 2], th0, atol=0)


@pytest.mark.parametrize("h", [0.001, 0.01, 0.5])
def test_spin_in_place(h):
    w = 5.0
    poses = drive(-w, w, 2.0, h)
    r = 2.0 * w * RT / TR  # eq. (2)
    t = np.arange(len(poses)) * h
    np.testing.assert_allclose(poses[:, 0], 0.3, atol=1e-15)
    np.testing.assert_allclose(poses[:, 1], 0.4, atol=1e-15)
    np.testing.assert_allclose(poses[:, 2], 0.7 + r * t, atol=1e-12)


@pytest.mark.parametrize("h", [0.001, 0.01, 0.5])
def test_arc_radius_from_speed_ratio(h):
    wl, wr = 4.0, 6.0
    x0, y0, th0 = 0.3, 0.4, 0.7
    poses = drive(wl, wr, 3.0, h)
    u = (wr + wl) * RT / 2.0
    r = (wr - wl) * RT / TR
    radius = TR / 2.0 * (wr + wl) / (wr - wl)
    assert radius == pytest.approx(u / r)
    # Centre of the circle: to the left of the start heading.
    cx = x0 - radius * math.sin(th0)
    cy = y0 + radius * math.cos(th0)
    np.testing.assert_allclose(np.hypot(poses[:, 0] - cx, poses[:, 1] - cy), radius, atol=1e-12)
    t = np.arange(len(poses)) * h
    th = th0 + r * t
    np.testing.assert_allclose(poses[:, 2], th, atol=1e-12)
    np.testing.assert_allclose(poses[:, 0], cx + radius * np.sin(th), atol=1e-12)
    np.testing.assert_allclose(poses[:, 1], cy - radius * np.cos(th), atol=1e-12)


@settings(max_examples=200, deadline=None, derandomize=bool(os.environ.get("CI")))  # same examples on CI
@given(ds=st.floats(-0.5, 0.5), dth=st.floats(-7.0, 7.0), th=st.floats(-4.0, 4.0))
def test_arc_step_is_exact_for_constant_u_r(ds, dth, th):
    """Two half steps of a constant-curvature move land where one full step does."""
    one = arc_step(0.1, -0.2, th, ds, dth)
    a = arc_step(0.1, -0.2, th, ds / 2, dth / 2)
    two = arc_step(a[0], a[1], a[2], ds / 2, dth / 2)
    np.testing.assert_allclose(one, two, rtol=0, atol=1e-12)


def test_arc_step_small_angle_branch_is_continuous():
    """The series used for tiny turns joins the sin(x)/x form without a jump."""
    for dth in (1.999e-4, 2.001e-4, -1.999e-4, -2.001e-4):
        x, y, _ = arc_step(0.0, 0.0, 0.0, 1.0, dth)
        assert x == pytest.approx(2 / dth * math.sin(dth / 2) * math.cos(dth / 2), abs=1e-15)
        assert y == pytest.approx(2 / dth * math.sin(dth / 2) * math.sin(dth / 2), abs=1e-15)


@pytest.mark.parametrize("th", [0.0, 3.0, -3.0, math.pi, -math.pi, 7.0, -7.0, 100.0])
def test_wrap_angle(th):
    w = wrap_angle(th)
    assert -math.pi <= w < math.pi
    assert math.cos(w) == pytest.approx(math.cos(th), abs=1e-12)
    assert math.sin(w) == pytest.approx(math.sin(th), abs=1e-12)
