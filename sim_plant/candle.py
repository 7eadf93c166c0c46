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
CP_X, CP_Y, CP_FAN_X, CP_REACH2, CP_COS_HALF, CP_T_EXT = range(6)
N_CP = 6
CS_LIT, CS_FAN_TIME, CS_EXT_AT = range(3)  # CS_EXT_AT is NaN while not extinguished
N_CS = 3


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
        self._fan_x = robot.fans.x
        self._reach2 = robot.fans.reach ** 2
        self._cos_half = math.cos(math.radians(robot.fans.half_angle_deg))
        self._time_to_extinguish = robot.fans.time_to_extinguish
        self._edges = arena.wall_edges

    def pack(self) -> tuple[np.ndarray, np.ndarray]:
        """(parameters, state) for ``update_kernel``; ``unpack`` reads the state back."""
        cp = np.array([self.x, self.y, self._fan_x, self._reach2, self._cos_half,
                       self._time_to_extinguish])
        ext = math.nan if self.extinguished_at is None else self.extinguished_at
        cs = np.array([1.0 if self.lit else 0.0, self.fan_time, ext])
        return cp, cs

    def unpack(self, cs: np.ndarray) -> None:
        self.lit = bool(cs[CS_LIT])
        self.fan_time = float(cs[CS_FAN_TIME])
        self.extinguished_at = None if math.isnan(cs[CS_EXT_AT]) else float(cs[CS_EXT_AT])

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
        """Advance the fan timer over the step of length dt that ends at time t."""
        if not self.lit:
            return
        if fan_on and self.fans_reach(x, y, theta):
            self.fan_time += dt
            if self.fan_time >= self._time_to_extinguish - _TIME_EPS:
                self.lit = False
                self.extinguished_at = t
        else:
            self.fan_time = 0.0
