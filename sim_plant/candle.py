"""The candle and the robot's fans: when does the flame go out.

The paper assumes the flame goes out after the fans have run for 4 s with the
robot close to the candle. Here the fans count as blowing at the flame when
all of these hold:

* the fans are on;
* the flame is within ``fans.reach`` of the fan outlet (body x = ``fans.x``,
  on the centre line), horizontally;
* the direction from the outlet to the flame is within ``fans.half_angle_deg``
  of the robot's heading (a flame right at the outlet counts as in front);
* no wall stands between outlet and flame.

The timer accumulates while they hold and **resets to 0 as soon as any
breaks** (fans off, robot turned or moved away): the conservative choice, so
a firmware that only brushes the flame with air, or pulses the fans, does
not get credit for the sum of short puffs. The flame goes out at the end of
the step in which the timer reaches ``fans.time_to_extinguish``.

The candle as an obstacle (issue 12): with the arena's ``candle_base_radius``
> 0 the candle stands on a disc of that radius (its wooden base). The rangers
see it (sensors/suite.py), and the robot's footprint rectangle touching the
disc at the end of a step knocks the candle over (``knocked``, whether lit or
already out): the mission loops end the run there (outcome "collision",
detail "knocked the candle over", docs/sensors.md).
"""

from __future__ import annotations

import math

import numba as nb
import numpy as np

from sim_plant.arena import Arena
from sim_plant.geometry import segment_blocked
from sim_plant.robot import RobotParams

_TIME_EPS = 1e-9  # s, so 400 steps of 0.01 s reach 4 s despite rounding

# The compiled twin of ``Candle`` (the lockstep kernel, harness/tick.py): parameters
# and state as flat float64 arrays, the same arithmetic in the same order.
(CP_X, CP_Y, CP_FAN_X, CP_REACH2, CP_COS_HALF, CP_T_EXT, CP_BASE_R, CP_FRONT, CP_REAR,
 CP_LEFT, CP_RIGHT) = range(11)
N_CP = 11
CS_LIT, CS_FAN_TIME, CS_EXT_AT, CS_KNOCKED = range(4)  # CS_EXT_AT is NaN while not extinguished
N_CS = 4


@nb.njit(cache=True)
def footprint_touches(cp: np.ndarray, x: float, y: float, theta: float) -> bool:
    """The robot's body rectangle at (x, y, θ) touches the candle's base disc (radius > 0)."""
    r = cp[CP_BASE_R]
    if r <= 0.0:
        return False
    c = math.cos(theta)
    s = math.sin(theta)
    dx = cp[CP_X] - x
    dy = cp[CP_Y] - y
    bx = c * dx + s * dy  # the candle in the body frame
    by = -s * dx + c * dy
    qx = min(max(bx, cp[CP_REAR]), cp[CP_FRONT])
    qy = min(max(by, cp[CP_RIGHT]), cp[CP_LEFT])
    ex = bx - qx
    ey = by - qy
    return ex * ex + ey * ey <= r * r


@nb.njit(cache=True)
def fans_reach_kernel(cp: np.ndarray, edges: np.ndarray, x: float, y: float, theta: float) -> bool:
    c = math.cos(theta)
    s = math.sin(theta)
    ox = x + c * cp[CP_FAN_X]
    oy = y + s * cp[CP_FAN_X]
    dx = cp[CP_X] - ox
    dy = cp[CP_Y] - oy
    d2 = dx * dx + dy * dy
    if d2 > cp[CP_REACH2]:
        return False
    if d2 > 1e-18 and (dx * c + dy * s) < cp[CP_COS_HALF] * math.sqrt(d2):
        return False
    return not segment_blocked(ox, oy, cp[CP_X], cp[CP_Y], edges)


@nb.njit(cache=True)
def update_kernel(cs: np.ndarray, cp: np.ndarray, edges: np.ndarray, t: float, dt: float,
                  fan_on: bool, x: float, y: float, theta: float) -> None:
    if cs[CS_KNOCKED] == 0.0 and footprint_touches(cp, x, y, theta):
        cs[CS_KNOCKED] = 1.0
    if cs[CS_LIT] == 0.0:
        return
    if fan_on and fans_reach_kernel(cp, edges, x, y, theta):
        cs[CS_FAN_TIME] += dt
        if cs[CS_FAN_TIME] >= cp[CP_T_EXT] - _TIME_EPS:
            cs[CS_LIT] = 0.0
            cs[CS_EXT_AT] = t
    else:
        cs[CS_FAN_TIME] = 0.0


class Candle:
    """A lit candle at (x, y); ``update`` once per step with the fans' state and the robot pose."""

    def __init__(self, x: float, y: float, robot: RobotParams, arena: Arena) -> None:
        self.x = float(x)
        self.y = float(y)
        self.height = arena.flame_height  # m, flame above the floor
        self.lit = True
        self.fan_time = 0.0  # s, fans blowing at the flame without a break
        self.extinguished_at: float | None = None
        self.base_radius = arena.candle_base_radius  # m, 0 = not an obstacle
        self.knocked = False  # the robot knocked it over
        self._footprint = robot.footprint()  # front, rear, left, right
        self._fan_x = robot.fans.x
        self._reach2 = robot.fans.reach ** 2
        self._cos_half = math.cos(math.radians(robot.fans.half_angle_deg))
        self._time_to_extinguish = robot.fans.time_to_extinguish
        self._edges = arena.wall_edges

    def pack(self) -> tuple[np.ndarray, np.ndarray]:
        """(parameters, state) for ``update_kernel``; ``unpack`` reads the state back."""
        cp = np.array([self.x, self.y, self._fan_x, self._reach2, self._cos_half,
                       self._time_to_extinguish, self.base_radius, *self._footprint])
        ext = math.nan if self.extinguished_at is None else self.extinguished_at
        cs = np.array([1.0 if self.lit else 0.0, self.fan_time, ext, 1.0 if self.knocked else 0.0])
        return cp, cs

    def unpack(self, cs: np.ndarray) -> None:
        self.lit = bool(cs[CS_LIT])
        self.fan_time = float(cs[CS_FAN_TIME])
        self.extinguished_at = None if math.isnan(cs[CS_EXT_AT]) else float(cs[CS_EXT_AT])
        self.knocked = bool(cs[CS_KNOCKED])

    def touches(self, x: float, y: float, theta: float) -> bool:
        """True when the robot's footprint at (x, y, θ) touches the candle's base."""
        return bool(footprint_touches(self.pack()[0], x, y, theta))

    def fans_reach(self, x: float, y: float, theta: float) -> bool:
        """True when fans running at robot pose (x, y, θ) would blow at the flame."""
        c = math.cos(theta)
        s = math.sin(theta)
        ox = x + c * self._fan_x
        oy = y + s * self._fan_x
        dx = self.x - ox
        dy = self.y - oy
        d2 = dx * dx + dy * dy
        if d2 > self._reach2:
            return False
        if d2 > 1e-18 and (dx * c + dy * s) < self._cos_half * math.sqrt(d2):
            return False
        return not segment_blocked(ox, oy, self.x, self.y, self._edges)

    def update(self, t: float, dt: float, fan_on: bool, x: float, y: float, theta: float) -> None:
        """Advance the fan timer over the step of length dt that ends at time t; a footprint
        touching the base at the step's end knocks the candle over."""
        if not self.knocked and self.base_radius > 0.0 and self.touches(x, y, theta):
            self.knocked = True
        if not self.lit:
            return
        if fan_on and self.fans_reach(x, y, theta):
            self.fan_time += dt
            if self.fan_time >= self._time_to_extinguish - _TIME_EPS:
                self.lit = False
                self.extinguished_at = t
        else:
            self.fan_time = 0.0
