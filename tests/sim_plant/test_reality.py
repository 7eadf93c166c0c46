"""Drive-train reality (docs/drivetrain.md "Reality"): each effect against a hand calculation.

Skid-steer effective track width and creep slip, scrub torque, per-side parameters, battery
internal resistance and wall contact with friction. Every effect is off in the default robot
(the paper's equations), so each test switches its effect on by a robot-file parameter.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from sim_plant.arena import load_arena
from sim_plant.collision import CONTACT_TOL, footprint_polygon, limit_move, slide_along
from sim_plant.drivetrain import (
    G_ACCEL,
    P_REAL,
    P_SIDE,
    P_SIZE,
    DriveConstants,
    battery_voltages,
    body_motion,
    body_motion_real,
    build_params,
    creep_slip,
    run_free,
)
from sim_plant.geometry import convex_overlap
from sim_plant.plant import Plant
from sim_plant.robot import load_robot, override, robot_from_dict, robot_to_dict

ROBOT = load_robot()
RT = ROBOT.track.wheel_radius
B = ROBOT.track.track_width
H = 0.001
ARENA = load_arena()
TOP_FACE = 2.42    # inner face of the outer top wall


def with_(**kv: float):
    r = ROBOT
    for k, v in kv.items():
        r = override(r, k.replace("__", "."), v)
    return r


def test_default_robot_is_the_ideal_limit():
    P = build_params(ROBOT, H)
    assert ROBOT.ideal_drive and P[P_REAL] == 0.0 and P.shape == (P_SIZE,)
    # both sides' blocks are the same numbers: the paper's identical sides
    assert np.array_equal(P[:P_SIDE], P[P_SIDE:2 * P_SIDE])
    assert not with_(slip__track_factor=1.5).ideal_drive


@settings(max_examples=60, deadline=None)
@given(st.floats(-0.5, 0.5), st.floats(-0.5, 0.5))
def test_real_kinematics_with_every_effect_at_its_ideal_value_is_eqs_1_2(dl, dr):
    P = build_params(with_(slip__wall_mu=0.3), H)  # switches the real path on, no slip
    assert P[P_REAL] == 1.0
    ds, dth = body_motion_real(dl, dr, 5.0, -5.0, P)
    ds0, dth0 = body_motion(dl, dr, P)
    assert ds == pytest.approx(ds0, rel=1e-12, abs=1e-15)
    assert dth == pytest.approx(dth0, rel=1e-12, abs=1e-15)


@settings(max_examples=100, deadline=None)
@given(chi0=st.floats(1.2, 2.0), rho_c=st.floats(0.02, 1.0), wl=st.floats(-10, 10), wr=st.floats(-10, 10))
def test_effective_track_width_over_the_published_range(chi0, rho_c, wl, wr):
    """Turn rate (v_r - v_l)/(chi B) with chi = 1 + (chi_0 - 1)/(1 + |rho|/rho_c), rho the turn
    radius (B/2)(v_r + v_l)/(v_r - v_l) -- computed here from the speeds, not by the kernel."""
    P = build_params(with_(slip__track_factor=chi0, slip__turn_radius=rho_c), H)
    h = 0.01
    ds, dth = body_motion_real(wl * h, wr * h, 0.0, 0.0, P)
    vl, vr = wl * RT, wr * RT
    assert ds == pytest.approx(0.5 * (vl + vr) * h, rel=1e-12, abs=1e-15)
    if vr == vl:
        assert dth == 0.0
        return
    rho = B / 2 * (vr + vl) / (vr - vl)
    chi = 1 + (chi0 - 1) / (1 + abs(rho) / rho_c)
    assert dth == pytest.approx((vr - vl) * h / (chi * B), rel=1e-9, abs=1e-15)
    assert 1.0 <= chi <= chi0


@pytest.mark.parametrize("chi0", [1.2, 1.5, 2.0])
def test_spin_in_place_turns_chi_times_slower_while_the_encoders_count_the_same(chi0):
    ideal = np.zeros(9)
    real = np.zeros(9)
    run_free(ideal, build_params(ROBOT, H), -400, 400, 1000)
    run_free(real, build_params(with_(slip__track_factor=chi0), H), -400, 400, 1000)
    assert np.array_equal(ideal[3:9], real[3:9])  # wheel states, encoder angles: identical
    turned = RT * (real[8] - real[5]) / (chi0 * B)  # eq. (2) with chi B for B
    assert real[2] == pytest.approx(math.remainder(turned, 2 * math.pi), abs=1e-9)
    assert abs(real[2]) < abs(ideal[2])


@settings(max_examples=60, deadline=None)
@given(creep=st.floats(0.0, 0.5), mu=st.floats(0.2, 1.2), a=st.floats(-20, 20))
def test_creep_slip_grows_with_traction_demand_up_to_the_limit(creep, mu, a):
    P = build_params(with_(slip__creep=creep, slip__floor_mu=mu), H)
    limit = mu * 9.81
    expect = creep * abs(a) / limit if abs(a) < limit else creep
    assert creep_slip(a, P) == pytest.approx(expect, rel=1e-12, abs=1e-15)


def test_constant_acceleration_below_the_traction_limit_gives_the_stated_slip():
    """A rim accelerating at a = 0.5 mu g: each track moves (1 - creep a/(mu g)) of its rim travel."""
    creep, mu = 0.2, 0.5
    P = build_params(with_(slip__creep=creep, slip__floor_mu=mu), H)
    a = 0.5 * mu * G_ACCEL
    dphi = 0.01
    ds, dth = body_motion_real(dphi, dphi, a, a, P)
    assert ds == pytest.approx(RT * dphi * (1 - creep * 0.5), rel=1e-12)
    assert dth == 0.0


def test_slip_over_counts_the_encoders_under_acceleration():
    """Full PWM from rest: the encoders count the same rotation as on an ideal floor (what the
    motor turned), the body travels less than R phi, and more than R phi (1 - creep)."""
    ideal = np.zeros(9)
    real = np.zeros(9)
    run_free(ideal, build_params(ROBOT, H), 1000, 1000, 500)
    run_free(real, build_params(with_(slip__creep=0.2), H), 1000, 1000, 500)
    assert np.array_equal(ideal[3:9], real[3:9])
    travel = RT * real[5]
    dist = math.hypot(real[0], real[1])
    assert travel * (1 - 0.2) < dist < travel - 1e-4


def _steady_spin_speed(robot, pwm, t_scrub, wc):
    """Hand calculation of the steady spin-in-place wheel speed: G Kt i = B w + T_f + T_s sat(2w/wc),
    i = (E - Kb w)/R, solved for w on the saturated branch and on the linear one."""
    dc = DriveConstants.from_robot(robot)
    E = pwm / 1000 * robot.motor.battery
    drive = dc.Kt_w * E / dc.R - dc.T_f
    damp = dc.Kt_w * dc.Kb_w / dc.R + dc.B_eff
    w = (drive - t_scrub) / damp
    if 2 * w >= wc:
        return w
    return drive / (damp + 2 * t_scrub / wc)


@pytest.mark.parametrize("mu_s", [0.3, 0.6, 1.0])
@pytest.mark.parametrize("pwm", [250, 500, 900])
def test_scrub_torque_slows_a_spin_as_calculated(mu_s, pwm):
    robot = with_(slip__scrub_mu=mu_s)
    P = build_params(robot, H)
    m = robot.slip
    t_scrub = mu_s * robot.body.mass * 9.81 * m.contact_length / 4 / B * RT  # M = mu m g l / 4
    S = np.zeros(9)
    run_free(S, P, -pwm, pwm, 3000)
    w = _steady_spin_speed(robot, pwm, t_scrub, P[P_REAL + 6])
    assert S[7] == pytest.approx(w, rel=1e-6, abs=1e-9)
    assert S[4] == pytest.approx(-w, rel=1e-6, abs=1e-9)
    free = np.zeros(9)
    run_free(free, build_params(ROBOT, H), -pwm, pwm, 3000)
    assert S[7] < free[7]  # turning in place needs more PWM for the same rate
    # straight driving feels no scrub
    S2 = np.zeros(9)
    F2 = np.zeros(9)
    run_free(S2, P, pwm, pwm, 1000)
    run_free(F2, build_params(ROBOT, H), pwm, pwm, 1000)
    assert S2[4] == pytest.approx(F2[4], rel=1e-12)


@settings(max_examples=25, deadline=None)
@given(km_l=st.floats(0.95, 1.05), km_r=st.floats(0.95, 1.05), kf_l=st.floats(0.9, 1.1),
       kr_l=st.floats(0.97, 1.03), kr_r=st.floats(0.97, 1.03))
def test_per_side_parameters_give_each_side_its_own_steady_speed(km_l, km_r, kf_l, kr_l, kr_r):
    robot = with_(sides__left_motor=km_l, sides__right_motor=km_r, sides__left_friction=kf_l,
                  sides__left_wheel_radius=kr_l, sides__right_wheel_radius=kr_r)
    P = build_params(robot, H)
    S = np.zeros(9)
    run_free(S, P, 700, 700, 2000)
    m, t = robot.motor, robot.track
    n_c = t.k / (2 * (t.L_r + t.k)) * robot.body.mass * 9.81
    E = 0.7 * m.battery
    for b, km, kf, kr in ((3, km_l, kf_l, kr_l), (6, km_r, 1.0, kr_r)):
        kt, kb = m.Kt * km, m.Kb * km
        tf = t.mu * n_c * t.wheel_radius * kr * kf
        w = (kt * E / m.R - tf) / (kt * kb / m.R + m.B)  # steady state of (10)-(11) per side
        assert S[b + 1] == pytest.approx(w, rel=1e-6)
    vl, vr = S[4] * RT * kr_l, S[7] * RT * kr_r
    ds, dth = body_motion_real(S[4] * H, S[7] * H, 0.0, 0.0, P)
    assert dth == pytest.approx((vr - vl) * H / B, rel=1e-9, abs=1e-15)


def test_battery_voltage_sags_with_the_current_it_delivers():
    robot = with_(battery__internal_resistance=0.5)
    P = build_params(robot, H)
    S = np.zeros(9)
    S[3], S[6] = 0.8, 0.3
    vl, vr = battery_voltages(S, P, 600, -250)
    vb = 9.0
    v = vb - 0.5 * (0.6 * 0.8 + (-0.25) * 0.3)  # H-bridge: battery current d_l i_l + d_r i_r
    assert vl == pytest.approx(0.6 * v, rel=1e-12)
    assert vr == pytest.approx(-0.25 * v, rel=1e-12)


def test_the_running_fan_adds_its_current_to_the_sag():
    robot = with_(battery__internal_resistance=0.5, battery__fan_current=0.4)
    P = build_params(robot, H)
    S = np.zeros(9)
    S[3], S[6] = 0.8, 0.3
    off = battery_voltages(S, P, 600, 600, 0.0)
    on = battery_voltages(S, P, 600, 600, 1.0)
    v_off = 9.0 - 0.5 * (0.6 * 0.8 + 0.6 * 0.3)
    assert off[0] == pytest.approx(0.6 * v_off, rel=1e-12)
    assert on[0] == pytest.approx(0.6 * (v_off - 0.5 * 0.4), rel=1e-12)
    # in the plant: the fan, held by apply(), slows the robot only while it runs
    speeds = []
    for fan in (False, True):
        plant = Plant(ARENA, robot, 1.2, 2.2, 0.0)
        for _ in range(100):
            plant.apply(600, 600, fan)
            plant.integrate(0.01)
        speeds.append(plant.omega_l)
    assert speeds[1] < speeds[0]


@pytest.mark.parametrize("r_int", [0.2, 1.0, 3.0])
@pytest.mark.parametrize("pwm", [400, 1000])
def test_battery_sag_lowers_the_steady_speed_as_calculated(r_int, pwm):
    """Straight, steady: i = (B w + T_f)/Kt, V = Vb - 2 d R_int i, w = (d V - R i)/Kb; linear in w."""
    robot = with_(battery__internal_resistance=r_int)
    S = np.zeros(9)
    run_free(S, build_params(robot, H), pwm, pwm, 3000)
    dc = DriveConstants.from_robot(robot)
    d = pwm / 1000
    a, c = dc.B_eff / dc.Kt_w, dc.T_f / dc.Kt_w
    k = 2 * d * d * r_int + dc.R
    w = (d * robot.motor.battery - k * c) / (dc.Kb_w + k * a)
    assert S[4] == pytest.approx(w, rel=1e-6)
    assert S[7] == pytest.approx(w, rel=1e-6)


def _pressed(beta, mu):
    """A robot heading at beta from the top wall's direction (+x), pushed onto it: its contact pose."""
    P = build_params(with_(slip__wall_mu=mu), H)
    poly = np.empty((4, 2))
    # in the top hallway (y 1.96..2.42, x 0.74..2.42), the highest corner 1 cm below the wall
    top = footprint_polygon(0.0, 0.0, beta, P)[:, 1].max()
    x0, y0 = 1.0, TOP_FACE - 0.01 - top
    x, y, th, frac = limit_move(poly, x0, y0, beta, 0.02 / math.sin(beta), 0.0, P,
                                ARENA.wall_polys, ARENA.wall_bbox)
    assert frac < 1.0
    return P, poly, (x, y, th)


@settings(max_examples=40, deadline=None)
@given(beta_deg=st.floats(5.0, 85.0), mu=st.floats(0.0, 1.0))
def test_wall_slide_at_an_angle_with_coulomb_friction(beta_deg, mu):
    """Pushing d into the wall at angle beta: the wall takes d sin(beta), friction mu d sin(beta) of
    the tangential d cos(beta): the robot slides d (cos beta - mu sin beta), or not at all."""
    beta = math.radians(beta_deg)
    P, poly, (x, y, th) = _pressed(beta, mu)
    d = 0.004
    cx, cy, cth, frac = limit_move(poly, x, y, th, d, 0.0, P, ARENA.wall_polys, ARENA.wall_bbox)
    assert frac * d <= 2 * CONTACT_TOL  # already pressed: the move is blocked at once
    nx, ny, nth, slid = slide_along(poly, cx, cy, cth, x, y, th, d, 0.0, P,
                                    ARENA.wall_polys, ARENA.wall_bbox)
    rest = d * (1 - frac)
    expect = max(0.0, rest * (math.cos(beta) - mu * math.sin(beta)))
    assert nx - cx == pytest.approx(expect, abs=1e-9)
    assert ny == pytest.approx(cy, abs=1e-12) and nth == cth
    assert slid == pytest.approx(expect, abs=1e-9)
    assert not any(convex_overlap(footprint_polygon(nx, ny, nth, P), w) for w in ARENA.wall_polys)


def test_a_robot_pushed_along_a_wall_slides_and_its_encoders_count_the_wheels():
    beta = math.radians(30)
    out = {}
    for mu in (-1.0, 0.3):
        robot = with_(slip__wall_mu=mu)
        plant = Plant(ARENA, robot, 1.0, TOP_FACE - 0.2, beta)
        for _ in range(300):
            plant.apply(500, 500)
            plant.integrate(0.01)
        out[mu] = plant
    stuck, slid = out[-1.0], out[0.3]
    assert stuck.in_contact and slid.in_contact
    assert slid.x > stuck.x + 0.05  # slid along the wall; without friction contact it stops dead
    # the tracks keep turning against the wall in both, as on an open floor: the encoders count
    # the wheels' rotation (about 7 rad/s x 3 s), not the body's travel
    free = np.zeros(9)
    run_free(free, build_params(ROBOT, H), 500, 500, 3000)
    for p in (stuck, slid):
        assert p.phi_l == pytest.approx(free[5], rel=1e-9) and p.phi_r == pytest.approx(free[8], rel=1e-9)
    assert free[5] * RT > slid.path_length + 0.1


def test_new_sections_round_trip_and_reject_bad_values():
    robot = with_(slip__track_factor=1.4, sides__left_motor=1.03, battery__internal_resistance=0.4,
                  calibration__wheel_radius=0.0285)
    again = robot_from_dict(robot_to_dict(robot), "again")
    assert again == robot
    from sim_plant.errors import FfrInputError
    for key, bad in (("slip.track_factor", 0.8), ("sides.left_motor", 0.0), ("slip.creep", 1.0),
                     ("battery.internal_resistance", -0.1)):
        with pytest.raises(FfrInputError, match=key.split(".")[1]):
            override(ROBOT, key, bad)
    data = robot_to_dict(ROBOT)
    data["slip"] = {"tracks_factor": 1.2}
    with pytest.raises(FfrInputError, match="slip.tracks_factor"):
        robot_from_dict(data, "bad")
