"""The Plant: drive train + pose + wall contacts, stepped by the harness.

The harness calls ``apply(pwm_l, pwm_r)`` once per firmware tick and then
``integrate(dt)``; the PWM is held over dt (zero-order hold) and dt is split
into plant steps of ``plant_dt``. Because the drive train is discretised
exactly (see ``drivetrain``), ``plant_dt`` equal to the tick is as accurate as
1 ms steps (docs/drivetrain.md gives the numbers) and about twice as cheap.

One ``integrate`` is one compiled call: all plant steps, the collision
response, contact counting, path length and the clearance update run inside
``_advance`` on a small float64 state array, so the per-tick cost is a few
microseconds.
"""

from __future__ import annotations

import math

import numba as nb
import numpy as np

from sim_plant.arena import Arena
from sim_plant.collision import (
    first_wall_hit,
    footprint_into,
    footprint_polygon,
    limit_move,
    released,
    slide_along,
)
from sim_plant.drivetrain import (
    P_RMAX,
    P_WALL_MU,
    S_DRIVE_SIZE,
    S_LEFT,
    S_RIGHT,
    S_TH,
    S_X,
    S_Y,
    arc_step,
    build_params,
    drive_step,
    pwm_to_voltage,
    wrap_angle,
)
from sim_plant.errors import FfrInputError
from sim_plant.geometry import clearance
from sim_plant.robot import RobotParams

# State array beyond the drive part.
S_STEPS = S_DRIVE_SIZE       # plant steps taken (exact integer in a float64)
S_CONTACTS = S_DRIVE_SIZE + 1
S_IN_CONTACT = S_DRIVE_SIZE + 2
S_MIN_CLEAR = S_DRIVE_SIZE + 3
S_PATH = S_DRIVE_SIZE + 4
S_FAN = S_DRIVE_SIZE + 5     # 1.0 while the fan runs (held like the PWM; its battery current)
S_SIZE = S_DRIVE_SIZE + 6

_CLEARANCE_CUTOFF = 1e3  # m, larger than any arena


_FREE_MARGIN = 1e-6  # m, beyond rounding of the footprint corners


@nb.njit(cache=True)
def _free_distance(x: float, y: float, wall_bbox: np.ndarray) -> float:
    """Chebyshev distance from (x, y) to the nearest wall bounding box."""
    best = 1e300
    for w in range(wall_bbox.shape[0]):
        dx = max(wall_bbox[w, 0] - x, 0.0, x - wall_bbox[w, 2])
        dy = max(wall_bbox[w, 1] - y, 0.0, y - wall_bbox[w, 3])
        best = min(best, max(dx, dy))
    return best


@nb.njit(cache=True)
def _advance(S: np.ndarray, P: np.ndarray, poly: np.ndarray, wall_polys: np.ndarray,
             wall_bbox: np.ndarray, pwm_l: int, pwm_r: int, n: int) -> None:
    el = pwm_to_voltage(pwm_l, P)
    er = pwm_to_voltage(pwm_r, P)
    # Far from every wall the collision test cannot fire: the footprint lies within
    # P_RMAX of the origin, which has moved at most ``moved`` (a chord is no longer
    # than its arc) since the tick began, and no wall box is within ``free`` of it.
    # Such steps skip the footprint test; what they compute is unchanged (limit_move
    # would return the free arc step with fraction 1).
    free = -1.0
    if S[S_IN_CONTACT] == 0.0:
        free = _free_distance(S[S_X], S[S_Y], wall_bbox) - P[P_RMAX] - _FREE_MARGIN
    free0 = free
    moved = 0.0
    for _ in range(n):
        ds, dth = drive_step(S, P, pwm_l, pwm_r, el, er, S[S_FAN])
        x = S[S_X]
        y = S[S_Y]
        th = S[S_TH]
        S[S_STEPS] += 1.0
        moved += abs(ds)
        if ds == 0.0 and dth == 0.0:
            blocked = False
        elif moved < free:
            nx, ny, nth = arc_step(x, y, th, ds, dth)
            blocked = False
            S[S_X] = nx
            S[S_Y] = ny
            S[S_TH] = wrap_angle(nth)
            S[S_PATH] += abs(ds)
        else:
            free = -1.0  # once near a wall, test every remaining step
            nx, ny, nth, frac = limit_move(poly, x, y, th, ds, dth, P, wall_polys, wall_bbox)
            blocked = frac < 1.0
            S[S_PATH] += abs(ds) * frac
            if blocked and P[P_WALL_MU] >= 0.0:
                # friction contact: the rest of the move slides along the wall (collision.py)
                nx, ny, nth, slid = slide_along(poly, nx, ny, nth, x, y, th, ds, dth, P,
                                                wall_polys, wall_bbox)
                S[S_PATH] += slid
            S[S_X] = nx
            S[S_Y] = ny
            S[S_TH] = wrap_angle(nth)
        if blocked:
            if S[S_IN_CONTACT] == 0.0:
                S[S_CONTACTS] += 1.0
                S[S_IN_CONTACT] = 1.0
            S[S_MIN_CLEAR] = 0.0
        elif S[S_IN_CONTACT] != 0.0 and released(poly, S[S_X], S[S_Y], S[S_TH], P,
                                                  wall_polys, wall_bbox):
            S[S_IN_CONTACT] = 0.0
    # Only walls nearer than the best so far can lower the minimum: use it as cut-off.
    # When even the nearest wall box is farther than that (free0 - moved bounds the
    # footprint's distance to every box from below), clearance() would skip every
    # wall and return the cut-off unchanged: skip it.
    if S[S_MIN_CLEAR] > 0.0 and free0 - moved <= S[S_MIN_CLEAR]:
        footprint_into(poly, S[S_X], S[S_Y], S[S_TH], P, 0.0)
        S[S_MIN_CLEAR] = clearance(poly, wall_polys, wall_bbox, S[S_MIN_CLEAR])


class Plant:
    """Robot in the arena: state in SI units, advanced by ``integrate``.

    Readable state: x, y, theta (m, m, rad in [-pi, pi)), phi_l, phi_r (rad,
    cumulative wheel angles), omega_l, omega_r (rad/s), i_l, i_r (A), t (s),
    contacts, in_contact, min_clearance (m, lowest footprint-to-wall distance
    seen at the ends of integrate calls, 0 once a wall was touched),
    path_length (m, distance travelled by the body origin).
    """

    def __init__(self, arena: Arena, robot: RobotParams, x: float, y: float, theta: float,
                 plant_dt: float = 0.001, *, source: str = "plant") -> None:
        if not (isinstance(plant_dt, int | float) and math.isfinite(plant_dt) and plant_dt > 0):
            raise FfrInputError(source, "plant_dt", plant_dt,
                                "must be a positive number of seconds")
        pose = [x, y, theta]
        if not all(isinstance(v, int | float) and math.isfinite(v) for v in pose):
            raise FfrInputError(source, "start", pose, "pose must be three finite numbers")
        self.arena = arena
        self.robot = robot
        self.plant_dt = float(plant_dt)
        self._P = build_params(robot, self.plant_dt)
        self._S = np.zeros(S_SIZE)
        self._S[S_X] = x
        self._S[S_Y] = y
        self._S[S_TH] = wrap_angle(float(theta))
        self._poly = np.empty((4, 2))
        self._walls = np.ascontiguousarray(arena.wall_polys, dtype=np.float64)
        self._bbox = np.ascontiguousarray(arena.wall_bbox, dtype=np.float64)
        self._pwm_l = 0
        self._pwm_r = 0
        self._check_start(source)
        footprint_into(self._poly, self._S[S_X], self._S[S_Y], self._S[S_TH], self._P, 0.0)
        self._S[S_MIN_CLEAR] = clearance(self._poly, self._walls, self._bbox, _CLEARANCE_CUTOFF)

    def _check_start(self, source: str) -> None:
        poly = self.footprint_polygon()
        value = [round(self.x, 4), round(self.y, 4), round(self.theta, 4)]
        w = first_wall_hit(poly, self._walls, self._bbox)
        if w >= 0:
            raise FfrInputError(source, "start", value,
                                f"robot footprint overlaps wall '{self.arena.walls[w].name}'")
        sx, sy = self.arena.size
        lo, hi = poly.min(axis=0), poly.max(axis=0)
        if lo[0] < 0 or lo[1] < 0 or hi[0] > sx or hi[1] > sy:
            raise FfrInputError(source, "start", value, "robot footprint is outside the arena")

    # -- stepping --------------------------------------------------------------
    def apply(self, pwm_l: int, pwm_r: int, fan: bool = False) -> None:
        """Set the PWM (per mille, clipped to +-full scale) and the fan, held until the next apply."""
        self._pwm_l = int(pwm_l)
        self._pwm_r = int(pwm_r)
        self._S[S_FAN] = 1.0 if fan else 0.0

    def steps_for(self, dt: float) -> int:
        """Plant steps in dt seconds; dt must be a whole number of them."""
        n = round(dt / self.plant_dt)
        if n < 0 or abs(n * self.plant_dt - dt) > 1e-6 * self.plant_dt:
            raise ValueError(f"integrate({dt!r}): not a non-negative multiple of "
                             f"plant_dt = {self.plant_dt!r}")
        return int(n)

    def kernel_args(self) -> tuple[np.ndarray, ...]:
        """(state, parameters, footprint scratch, walls, wall boxes) for ``_advance``,
        which a compiled caller (harness/tick.py) runs on this plant's own state."""
        return self._S, self._P, self._poly, self._walls, self._bbox

    def integrate(self, dt: float) -> None:
        """Advance dt seconds, a whole number of plant steps."""
        n = self.steps_for(dt)
        if n:
            _advance(self._S, self._P, self._poly, self._walls, self._bbox,
                     self._pwm_l, self._pwm_r, n)

    def footprint_polygon(self) -> np.ndarray:
        """Footprint corners (4, 2) in world coordinates, counter-clockwise."""
        S = self._S
        return footprint_polygon(S[S_X], S[S_Y], S[S_TH], self._P)

    def clearance_now(self) -> float:
        """Current footprint-to-wall distance (m); computed on demand."""
        return float(clearance(self.footprint_polygon(), self._walls, self._bbox,
                               _CLEARANCE_CUTOFF))

    # -- readable state ------------------------------------------------------------
    @property
    def x(self) -> float:
        return float(self._S[S_X])

    @property
    def y(self) -> float:
        return float(self._S[S_Y])

    @property
    def theta(self) -> float:
        return float(self._S[S_TH])

    @property
    def i_l(self) -> float:
        return float(self._S[S_LEFT])

    @property
    def omega_l(self) -> float:
        return float(self._S[S_LEFT + 1])

    @property
    def phi_l(self) -> float:
        return float(self._S[S_LEFT + 2])

    @property
    def i_r(self) -> float:
        return float(self._S[S_RIGHT])

    @property
    def omega_r(self) -> float:
        return float(self._S[S_RIGHT + 1])

    @property
    def phi_r(self) -> float:
        return float(self._S[S_RIGHT + 2])

    @property
    def t(self) -> float:
        return float(self._S[S_STEPS]) * self.plant_dt

    @property
    def contacts(self) -> int:
        return int(self._S[S_CONTACTS])

    @property
    def in_contact(self) -> bool:
        return bool(self._S[S_IN_CONTACT])

    @property
    def min_clearance(self) -> float:
        return float(self._S[S_MIN_CLEAR])

    @property
    def path_length(self) -> float:
        return float(self._S[S_PATH])

    @property
    def pwm(self) -> tuple[int, int]:
        """The PWM pair currently applied."""
        return self._pwm_l, self._pwm_r
