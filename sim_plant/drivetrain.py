"""Drive train: two DC motors, tracked wheels with Coulomb friction, and the kinematics.

Per side (left and right are identical) the state is the armature current i
(A), the wheel speed omega (rad/s) and the cumulative wheel angle phi (rad,
what the encoder reads). With G the gear ratio (motor turns per wheel turn):

    L di/dt        = E - R i - Kb G omega                      armature circuit
    J_eff domega/dt = G Kt i - B_eff omega - T_f sign(omega)   paper (10), (11), (6)-(7)
    dphi/dt        = omega

    J_eff = (J G^2 + I_wheels)(2 + L_2/R_t) [+ m/2 R_t^2 if track.body_inertia]
    B_eff = B G^2
    T_f   = F_si R_t = mu k/(2(L_r + k)) m g R_t               paper (4), (5)

Why an exact discretisation: L/R is about 0.7 ms, so at the 1-10 ms plant
steps explicit methods are unstable or need sub-millisecond steps. Between
friction events the system is linear with a constant (zero-order-hold) input,
so x(t+h) = Phi(h) x(t) + Gamma(h) u with Phi = e^{A h} and Gamma = int_0^h e^{A s} ds B
is exact for any h; Phi and Gamma are computed once per step size (``expm``
below, scaling and squaring of a Taylor series) and a step is a few multiply-adds.

Coulomb friction changes the input (the sign of T_f) when omega crosses zero,
and a stopped wheel sticks while |G Kt i| <= T_f. Those events are located
inside a step by bisection on dyadic sub-steps h/2^k, k = 0..K_LEVELS, whose
Phi, Gamma are tabulated too, so the event time is found to h/2^24 and every
piece is still propagated exactly. A step with no event costs one table look-up.

The pose follows eqs. (1)-(3) from the exact wheel-angle increments: the
heading change is exact (theta is linear in phi_r - phi_l) and the position
moves along the arc that constant u, r would give over the step.

All kernels work on flat float64 arrays (state ``S``, parameter table ``P``)
so the plant can run a whole tick inside one compiled call.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import numba as nb
import numpy as np

from sim_plant.robot import RobotParams

G_ACCEL = 9.81  # m/s^2

# Bisection depth for friction events: event times are found to h / 2**K_LEVELS.
K_LEVELS = 24
# Safety net against a pathological friction chatter: after this many trials
# in one side step, pieces are accepted without further bisection.
_MAX_TRIALS = 400

# -- parameter table layout (P) ---------------------------------------------
P_H = 0          # step h (s)
P_BATT = 1       # battery voltage (V)
P_PWM_FULL = 2   # PWM full scale (per mille -> 1000)
P_INV_R = 3      # 1/R (1/ohm)
P_KT_W = 4       # torque constant at the wheel G Kt (N m/A)
P_TF = 5         # Coulomb friction torque at the wheel T_f (N m)
P_B_W = 6        # viscous friction at the wheel B_eff (N m s/rad)
P_RT = 7         # drive wheel radius R_t (m)
P_TR = 8         # distance between the drive wheels T_r (m)
P_FRONT = 9      # footprint extents in the body frame (m): front, rear (<0),
P_REAR = 10      # left, right (<0)
P_LEFT = 11
P_RIGHT = 12
P_RMAX = 13      # farthest footprint corner from the body origin (m)
P_INV_J = 14     # 1/J_eff (1/(kg m^2))
P_KB_W = 15      # back-emf constant at the wheel Kb G (V s/rad)
P_TAB = 16       # first table level
STRIDE = 16      # floats per table level
# Within a level: Phi rows (i, omega, dphi) x columns (i, omega), Gamma rows x
# inputs (E, external torque), and the stuck-wheel current decay e^{-R tau/L}.
T_PHI = 0
T_GAM = 6
T_DECAY = 12
P_SIDE = P_TAB + STRIDE * (K_LEVELS + 1)  # one side's block: P[0:P_SIDE] left, the same layout
#                                           again at P[P_SIDE:2 P_SIDE] for the right side
# -- reality effects (docs/drivetrain.md "Reality"), after the two side blocks -----------
P_REAL = 2 * P_SIDE          # 1.0 when any effect below is on (else the ideal kinematics)
P_CHI0 = P_REAL + 1          # effective / geometric track width spinning in place
P_RHO_C = P_REAL + 2         # m, turn radius at which chi - 1 is halved
P_CREEP = P_REAL + 3         # longitudinal slip fraction at the traction limit
P_INV_MUG = P_REAL + 4       # 1 / (floor_mu g)  (s^2/m)
P_SCRUB_T = P_REAL + 5       # scrub torque at each wheel (N m) at full scrub
P_SCRUB_WC = P_REAL + 6      # wheel-speed difference (rad/s) over which the scrub saturates
P_RINT = P_REAL + 7          # battery internal resistance (ohm)
P_WALL_MU = P_REAL + 8       # body-to-wall friction; < 0: a blocked move stops dead
P_FAN_I = P_REAL + 9         # battery current of the running fan (A)
P_SIZE = P_REAL + 10

# -- drive part of the state array (S) -----------------------------------------
S_X = 0
S_Y = 1
S_TH = 2
S_LEFT = 3       # i_l, omega_l, phi_l
S_RIGHT = 6      # i_r, omega_r, phi_r
S_DRIVE_SIZE = 9


@dataclass(frozen=True)
class DriveConstants:
    """Per-side constants of the linear model, referred to the wheel shaft (SI)."""

    R: float
    L: float
    Kb_w: float     # back-emf per wheel rad/s: Kb G (V s/rad)
    Kt_w: float     # wheel torque per amp: Kt G (N m/A)
    J_eff: float    # kg m^2
    B_eff: float    # N m s/rad
    T_f: float      # N m
    battery: float  # V
    pwm_full: int
    wheel_radius: float
    track_width: float

    @classmethod
    def from_robot(cls, robot: RobotParams, side: str = "") -> DriveConstants:
        """The nominal constants, or with ``side`` "left"/"right" that side's (robot.sides scales)."""
        m, t, b = robot.motor, robot.track, robot.body
        g = m.gear_ratio
        km = kf = kr = 1.0
        if side:
            km = getattr(robot.sides, f"{side}_motor")
            kf = getattr(robot.sides, f"{side}_friction")
            kr = getattr(robot.sides, f"{side}_wheel_radius")
        rt = t.wheel_radius * kr if kr != 1.0 else t.wheel_radius
        j_eff = (m.J * g * g + t.wheel_inertia) * (2.0 + t.L_2 / rt)
        if t.body_inertia:
            # Body mass reflected to each wheel for straight-line motion.
            j_eff += 0.5 * b.mass * rt ** 2
        n_c = t.k / (2.0 * (t.L_r + t.k)) * b.mass * G_ACCEL
        tf = t.mu * n_c * rt
        kb_w = m.Kb * g
        kt_w = m.Kt * g
        if km != 1.0:
            kb_w *= km
            kt_w *= km
        if kf != 1.0:
            tf *= kf
        return cls(R=m.R, L=m.L, Kb_w=kb_w, Kt_w=kt_w, J_eff=j_eff, B_eff=m.B * g * g,
                   T_f=tf, battery=m.battery, pwm_full=m.pwm_max,
                   wheel_radius=rt, track_width=t.track_width)

    def system(self) -> tuple[np.ndarray, np.ndarray]:
        """(A, B) of d[i, omega, phi]/dt = A x + B [E, tau_ext]."""
        A = np.array([
            [-self.R / self.L, -self.Kb_w / self.L, 0.0],
            [self.Kt_w / self.J_eff, -self.B_eff / self.J_eff, 0.0],
            [0.0, 1.0, 0.0],
        ])
        B = np.array([[1.0 / self.L, 0.0], [0.0, 1.0 / self.J_eff], [0.0, 0.0]])
        return A, B


def expm(M: np.ndarray) -> np.ndarray:
    """Matrix exponential by scaling and squaring a Taylor series.

    Scaled to 1-norm <= 1/2, 30 terms bound the truncation error far below
    rounding; only run at set-up, so clarity beats speed here.
    """
    M = np.asarray(M, dtype=np.float64)
    n = M.shape[0]
    norm = float(np.abs(M).sum(axis=0).max()) if n else 0.0
    s = max(0, math.ceil(math.log2(norm / 0.5))) if norm > 0.5 else 0
    X = M / (2.0 ** s)
    result = np.eye(n)
    term = np.eye(n)
    for k in range(1, 31):
        term = term @ X / k
        result = result + term
        if np.abs(term).max() <= 1e-18 * np.abs(result).max():
            break
    for _ in range(s):
        result = result @ result
    return result


def discretise(dc: DriveConstants, tau: float) -> tuple[np.ndarray, np.ndarray]:
    """Exact ZOH step of length tau: (Phi (3,3), Gamma (3,2)) from one augmented exponential."""
    A, B = dc.system()
    M = np.zeros((5, 5))
    M[:3, :3] = A
    M[:3, 3:] = B
    E = expm(M * tau)
    return E[:3, :3], E[:3, 3:]


@lru_cache(maxsize=64)
def _step_tables(dc: DriveConstants, h: float) -> np.ndarray:
    """The Phi, Gamma tables of every dyadic sub-step: 25 matrix exponentials (~2.5 ms),
    so cached per (constants, h): a sweep builds thousands of plants of a few robots."""
    T = np.zeros(P_SIDE - P_TAB)
    for k in range(K_LEVELS + 1):
        tau = h / 2.0 ** k
        Phi, Gam = discretise(dc, tau)
        o = k * STRIDE
        # The phi column of Phi is exactly (0, 0, 1): store only what multiplies i, omega,
        # and propagate phi as an increment (keeps precision when phi is large).
        T[o + T_PHI:o + T_PHI + 6] = Phi[:, :2].reshape(-1)
        T[o + T_GAM:o + T_GAM + 6] = Gam.reshape(-1)
        T[o + T_DECAY] = math.exp(-dc.R / dc.L * tau)
    T.flags.writeable = False
    return T


def build_params(robot: RobotParams, h: float) -> np.ndarray:
    """The flat parameter table P the kernels read, for plant step h (s)."""
    P = np.zeros(P_SIZE)
    for q, side in ((0, "left"), (P_SIDE, "right")):
        _side_block(P[q:q + P_SIDE], robot, DriveConstants.from_robot(robot, side), h)
    sl = robot.slip
    if not robot.ideal_drive:
        P[P_REAL] = 1.0
    P[P_CHI0] = sl.track_factor
    P[P_RHO_C] = sl.turn_radius
    P[P_CREEP] = sl.creep
    P[P_INV_MUG] = 1.0 / (sl.floor_mu * G_ACCEL)
    # Scrub: lateral friction of both tracks about the turning centre, mu m g l / 4 (uniform
    # pressure along a contact length l), held by the two track forces F over the track width
    # (F B = M): at each wheel F R_t.
    m_scrub = sl.scrub_mu * robot.body.mass * G_ACCEL * sl.contact_length / 4.0
    t_scrub = m_scrub / robot.track.track_width * robot.track.wheel_radius
    P[P_SCRUB_T] = t_scrub
    if t_scrub > 0.0:
        # regularised Coulomb law: saturates over a wheel-speed difference wide enough that the
        # explicit step stays stable (rate 2 T / (wc J) <= 1 / (2 h)), at least 0.5 rad/s (chosen)
        j_min = min(DriveConstants.from_robot(robot, s).J_eff for s in ("left", "right"))
        P[P_SCRUB_WC] = max(0.5, 4.0 * t_scrub * h / j_min)
    else:
        P[P_SCRUB_WC] = 1.0
    P[P_RINT] = robot.battery.internal_resistance
    P[P_WALL_MU] = sl.wall_mu
    P[P_FAN_I] = robot.battery.fan_current
    return P


def _side_block(P: np.ndarray, robot: RobotParams, dc: DriveConstants, h: float) -> None:
    P[P_H] = h
    P[P_BATT] = dc.battery
    P[P_PWM_FULL] = dc.pwm_full
    P[P_INV_R] = 1.0 / dc.R
    P[P_KT_W] = dc.Kt_w
    P[P_TF] = dc.T_f
    P[P_B_W] = dc.B_eff
    P[P_RT] = dc.wheel_radius
    P[P_TR] = dc.track_width
    front, rear, left, right = robot.footprint()
    P[P_FRONT], P[P_REAR], P[P_LEFT], P[P_RIGHT] = front, rear, left, right
    P[P_RMAX] = math.hypot(max(front, -rear), max(left, -right))
    P[P_INV_J] = 1.0 / dc.J_eff
    P[P_KB_W] = dc.Kb_w
    P[P_TAB:] = _step_tables(dc, h)


@nb.njit(cache=True)
def pwm_to_voltage(pwm: int, P: np.ndarray) -> float:
    """PWM per mille (clipped to +-full scale) -> armature voltage (V)."""
    full = P[P_PWM_FULL]
    p = float(pwm)
    p = min(full, max(-full, p))
    return p / full * P[P_BATT]


# side_step and drive_step are inlined into their callers (numba's inline="always"): ten plant
# steps per tick call them 30 times, and the calls (arrays passed as structs, no inlining by
# LLVM across numba's function boundaries) cost more than their arithmetic: the drive train's
# share of a tick fell from ~490 to ~220 ns (make bench), the very same operations in the
# same order, so the traces are bit for bit the same (tests/harness/test_determinism.py).
@nb.njit(cache=True, inline="always")
def side_step(S: np.ndarray, b: int, E: float, P: np.ndarray, q: int = 0, tsc: float = 0.0) -> float:
    """Advance one side (S[b:b+3] = i, omega, phi) by one step h; returns the phi increment.

    ``q``: that side's parameter block (0 left, P_SIDE right); ``tsc``: an external torque on the
    wheel held over the step (the scrub torque; 0 for the ideal drive train)."""
    tf = P[q + P_TF]
    if tf == 0.0:
        o = q + P_TAB
        i0 = S[b]
        w0 = S[b + 1]
        S[b] = P[o] * i0 + P[o + 1] * w0 + P[o + 6] * E
        S[b + 1] = P[o + 2] * i0 + P[o + 3] * w0 + P[o + 8] * E
        d = P[o + 4] * i0 + P[o + 5] * w0 + P[o + 10] * E
        if tsc != 0.0:
            S[b] += P[o + 7] * tsc
            S[b + 1] += P[o + 9] * tsc
            d += P[o + 11] * tsc
        S[b + 2] += d
        return d
    ktw = P[q + P_KT_W]
    bw = P[q + P_B_W]
    ess = E * P[q + P_INV_R]        # stalled-rotor steady current
    n = 1 << K_LEVELS               # time left, in units of h / 2**K_LEVELS
    c = 0                           # > 0 while bisecting: finest level allowed next
    dphi = 0.0
    trials = 0
    while n > 0:
        lev = c
        while (1 << (K_LEVELS - lev)) > n:
            lev += 1
        o = q + P_TAB + lev * STRIDE
        i0 = S[b]
        w0 = S[b + 1]
        event = 0  # 1: omega reaches zero, 2: stuck wheel breaks away, 3: speed extremum inside
        if w0 == 0.0 and abs(ktw * i0 + tsc) <= tf:
            # Stuck: friction balances the drive torque, only the current moves
            # (monotonically, so the end-of-piece test cannot miss a breakaway).
            i1 = ess + (i0 - ess) * P[o + T_DECAY]
            w1 = 0.0
            d = 0.0
            if abs(ktw * i1 + tsc) > tf:
                event = 2
        else:
            if w0 > 0.0:
                s = 1.0
            elif w0 < 0.0:
                s = -1.0
            else:
                s = 1.0 if ktw * i0 + tsc > 0.0 else -1.0
            tau = -s * tf
            if tsc != 0.0:
                tau += tsc
            i1 = P[o] * i0 + P[o + 1] * w0 + P[o + 6] * E + P[o + 7] * tau
            w1 = P[o + 2] * i0 + P[o + 3] * w0 + P[o + 8] * E + P[o + 9] * tau
            d = P[o + 4] * i0 + P[o + 5] * w0 + P[o + 10] * E + P[o + 11] * tau
            if s * w1 <= 0.0:
                event = 1
            elif (w0 != 0.0 and s * (ktw * i0 - bw * w0 + tau) < 0.0
                  and s * (ktw * i1 - bw * w1 + tau) > 0.0):
                # Decelerating then accelerating: omega may have dipped through
                # zero and back inside the piece. Bisect to look, unless a bound
                # on |domega/dt| over the piece shows the dip cannot reach zero.
                wmax = max(abs(w0), abs(w1))
                imax = max(abs(i0), (abs(E) + P[q + P_KB_W] * wmax) * P[q + P_INV_R])
                amax = (ktw * imax + bw * wmax + tf + abs(tsc)) * P[q + P_INV_J]
                span = P[P_H] / (1 << lev)
                if min(s * w0, s * w1) <= span * amax:
                    event = 3
        trials += 1
        if event != 0 and lev < K_LEVELS and trials < _MAX_TRIALS:
            c = lev + 1
            continue
        S[b] = i1
        S[b + 1] = w1
        S[b + 2] += d
        dphi += d
        if event == 1:
            S[b + 1] = 0.0  # the wheel stops; the next piece decides stick or slip
        n -= 1 << (K_LEVELS - lev)
        if c > 0:
            c = lev + 1
            if c > K_LEVELS:
                c = 0
    return dphi


@nb.njit(cache=True)
def body_motion(dphi_l: float, dphi_r: float, P: np.ndarray) -> tuple[float, float]:
    """Wheel-angle increments -> (distance along the path, heading change), eqs. (1)-(2)."""
    rt = P[P_RT]
    return 0.5 * rt * (dphi_r + dphi_l), rt * (dphi_r - dphi_l) / P[P_TR]


@nb.njit(cache=True)
def track_factor(dl: float, dr: float, P: np.ndarray) -> float:
    """Effective / geometric track width chi for track travels dl, dr (m) over a step.

    chi = 1 + (chi_0 - 1) / (1 + |rho| / rho_c), rho = (B/2)(dl + dr)/(dr - dl) the turn radius:
    chi_0 spinning in place, falling towards 1 on wide arcs (docs/drivetrain.md)."""
    a = abs(dr - dl) * P[P_RHO_C]
    if a == 0.0:
        return 1.0
    return 1.0 + (P[P_CHI0] - 1.0) * a / (a + 0.5 * P[P_TR] * abs(dr + dl))


@nb.njit(cache=True)
def creep_slip(accel: float, P: np.ndarray) -> float:
    """Longitudinal slip fraction of a track whose rim accelerates at ``accel`` (m/s^2): grows
    with the traction demand |a| / (mu g), creep at the traction limit and beyond."""
    return P[P_CREEP] * min(1.0, abs(accel) * P[P_INV_MUG])


@nb.njit(cache=True)
def body_motion_real(dphi_l: float, dphi_r: float, acc_l: float, acc_r: float,
                     P: np.ndarray) -> tuple[float, float]:
    """As ``body_motion`` with per-side wheel radii, longitudinal slip and the effective track
    width: each track's ground travel is its rim travel R phi times (1 - slip)."""
    dl = P[P_RT] * dphi_l * (1.0 - creep_slip(acc_l, P))
    dr = P[P_SIDE + P_RT] * dphi_r * (1.0 - creep_slip(acc_r, P))
    chi = track_factor(dl, dr, P)
    return 0.5 * (dl + dr), (dr - dl) / (chi * P[P_TR])


@nb.njit(cache=True)
def scrub_torque(P: np.ndarray, w_l: float, w_r: float) -> float:
    """Scrub torque on the right wheel (the left gets minus this): opposes the yaw, saturating
    (a regularised Coulomb law) once the wheel speeds differ by P_SCRUB_WC."""
    t = P[P_SCRUB_T]
    if t == 0.0:
        return 0.0
    u = (w_r - w_l) / P[P_SCRUB_WC]
    return -t * max(-1.0, min(1.0, u))


@nb.njit(cache=True)
def battery_voltages(S: np.ndarray, P: np.ndarray, pwm_l: int, pwm_r: int,
                     fan: float = 0.0) -> tuple[float, float]:
    """Armature voltages (left, right) from a battery that sags by R_int times the current it
    delivers: the duty-weighted motor currents at the start of the step (an H-bridge draws d i),
    plus the fan's current while ``fan`` (1.0) runs."""
    el = pwm_to_voltage(pwm_l, P)
    er = pwm_to_voltage(pwm_r, P)
    rint = P[P_RINT]
    if rint == 0.0:
        return el, er
    vb = P[P_BATT]
    i_batt = (el * S[S_LEFT] + er * S[S_RIGHT]) / vb + fan * P[P_FAN_I]
    k = max(0.0, vb - rint * i_batt) / vb
    return el * k, er * k


@nb.njit(cache=True)
def arc_step(x: float, y: float, th: float, ds: float, dth: float) -> tuple[float, float, float]:
    """Pose after moving ds along an arc turning by dth: eq. (3) integrated for constant u, r."""
    half = 0.5 * dth
    # sin(half)/half; its series below 1e-4 (error < 1e-18) avoids 0/0 on straight moves.
    k = 1.0 - half * half / 6.0 if abs(half) < 1e-4 else math.sin(half) / half
    chord = ds * k
    a = th + half
    return x + chord * math.cos(a), y + chord * math.sin(a), th + dth


@nb.njit(cache=True)
def wrap_angle(th: float) -> float:
    """Heading into [-pi, pi)."""
    if -math.pi <= th < math.pi:
        return th
    return (th + math.pi) % (2.0 * math.pi) - math.pi


@nb.njit(cache=True, inline="always")
def drive_step(S: np.ndarray, P: np.ndarray, pwm_l: int, pwm_r: int, el: float,
               er: float, fan: float = 0.0) -> tuple[float, float]:
    """Both sides one step h; returns the body's (path distance, heading change). el, er: the
    armature voltages of an ideal battery (used as they are when every reality effect is off);
    fan: 1.0 while the fan runs (its current sags the battery)."""
    if P[P_REAL] == 0.0:
        dl = side_step(S, S_LEFT, el, P)
        dr = side_step(S, S_RIGHT, er, P)
        return body_motion(dl, dr, P)
    vl, vr = battery_voltages(S, P, pwm_l, pwm_r, fan)
    wl0 = S[S_LEFT + 1]
    wr0 = S[S_RIGHT + 1]
    ts = scrub_torque(P, wl0, wr0)
    dl = side_step(S, S_LEFT, vl, P, 0, -ts)
    dr = side_step(S, S_RIGHT, vr, P, P_SIDE, ts)
    inv_h = 1.0 / P[P_H]
    acc_l = P[P_RT] * (S[S_LEFT + 1] - wl0) * inv_h
    acc_r = P[P_SIDE + P_RT] * (S[S_RIGHT + 1] - wr0) * inv_h
    return body_motion_real(dl, dr, acc_l, acc_r, P)


@nb.njit(cache=True)
def run_free(S: np.ndarray, P: np.ndarray, pwm_l: int, pwm_r: int, n: int) -> None:
    """n plant steps with constant PWM and no walls (drive state S[0:9])."""
    el = pwm_to_voltage(pwm_l, P)
    er = pwm_to_voltage(pwm_r, P)
    for _ in range(n):
        ds, dth = drive_step(S, P, pwm_l, pwm_r, el, er)
        x, y, th = arc_step(S[S_X], S[S_Y], S[S_TH], ds, dth)
        S[S_X] = x
        S[S_Y] = y
        S[S_TH] = wrap_angle(th)
