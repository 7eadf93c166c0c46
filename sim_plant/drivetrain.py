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
P_SIZE = P_TAB + STRIDE * (K_LEVELS + 1)

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
    def from_robot(cls, robot: RobotParams) -> DriveConstants:
        m, t, b = robot.motor, robot.track, robot.body
        g = m.gear_ratio
        j_eff = (m.J * g * g + t.wheel_inertia) * (2.0 + t.L_2 / t.wheel_radius)
        if t.body_inertia:
            # Body mass reflected to each wheel for straight-line motion.
            j_eff += 0.5 * b.mass * t.wheel_radius ** 2
        n_c = t.k / (2.0 * (t.L_r + t.k)) * b.mass * G_ACCEL
        return cls(R=m.R, L=m.L, Kb_w=m.Kb * g, Kt_w=m.Kt * g, J_eff=j_eff, B_eff=m.B * g * g,
                   T_f=t.mu * n_c * t.wheel_radius, battery=m.battery, pwm_full=m.pwm_max,
                   wheel_radius=t.wheel_radius, track_width=t.track_width)

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
    T = np.zeros(P_SIZE - P_TAB)
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
    dc = DriveConstants.from_robot(robot)
    P = np.zeros(P_SIZE)
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
    return P


@nb.njit(cache=True)
def pwm_to_voltage(pwm: int, P: np.ndarray) -> float:
    """PWM per mille (clipped to +-full scale) -> armature voltage (V)."""
    full = P[P_PWM_FULL]
    p = float(pwm)
    p = min(full, max(-full, p))
    return p / full * P[P_BATT]


@nb.njit(cache=True)
def side_step(S: np.ndarray, b: int, E: float, P: np.ndarray) -> float:
    """Advance one side (S[b:b+3] = i, omega, phi) by one step h; returns the phi increment."""
    tf = P[P_TF]
    if tf == 0.0:
        o = P_TAB
        i0 = S[b]
        w0 = S[b + 1]
        S[b] = P[o] * i0 + P[o + 1] * w0 + P[o + 6] * E
        S[b + 1] = P[o + 2] * i0 + P[o + 3] * w0 + P[o + 8] * E
        d = P[o + 4] * i0 + P[o + 5] * w0 + P[o + 10] * E
        S[b + 2] += d
        return d
    ktw = P[P_KT_W]
    bw = P[P_B_W]
    ess = E * P[P_INV_R]            # stalled-rotor steady current
    n = 1 << K_LEVELS               # time left, in units of h / 2**K_LEVELS
    c = 0                           # > 0 while bisecting: finest level allowed next
    dphi = 0.0
    trials = 0
    while n > 0:
        lev = c
        while (1 << (K_LEVELS - lev)) > n:
            lev += 1
        o = P_TAB + lev * STRIDE
        i0 = S[b]
        w0 = S[b + 1]
        event = 0  # 1: omega reaches zero, 2: stuck wheel breaks away, 3: speed extremum inside
        if w0 == 0.0 and abs(ktw * i0) <= tf:
            # Stuck: friction balances the drive torque, only the current moves
            # (monotonically, so the end-of-piece test cannot miss a breakaway).
            i1 = ess + (i0 - ess) * P[o + T_DECAY]
            w1 = 0.0
            d = 0.0
            if abs(ktw * i1) > tf:
                event = 2
        else:
            if w0 > 0.0:
                s = 1.0
            elif w0 < 0.0:
                s = -1.0
            else:
                s = 1.0 if ktw * i0 > 0.0 else -1.0
            tau = -s * tf
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
                imax = max(abs(i0), (abs(E) + P[P_KB_W] * wmax) * P[P_INV_R])
                amax = (ktw * imax + bw * wmax + tf) * P[P_INV_J]
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


@nb.njit(cache=True)
def run_free(S: np.ndarray, P: np.ndarray, pwm_l: int, pwm_r: int, n: int) -> None:
    """n plant steps with constant PWM and no walls (drive state S[0:9])."""
    el = pwm_to_voltage(pwm_l, P)
    er = pwm_to_voltage(pwm_r, P)
    for _ in range(n):
        dl = side_step(S, S_LEFT, el, P)
        dr = side_step(S, S_RIGHT, er, P)
        ds, dth = body_motion(dl, dr, P)
        x, y, th = arc_step(S[S_X], S[S_Y], S[S_TH], ds, dth)
        S[S_X] = x
        S[S_Y] = y
        S[S_TH] = wrap_angle(th)
