"""Plant truth apart from the team's calibration: the ``reality`` group of a noise profile.

A profile's ``[NAME.reality]`` table gives ranges; ``Reality.draw`` draws, from the mission's
one ``numpy.random.Generator``, two things SEPARATELY:

* the plant's truth: the floor (effective track width factor chi_0 and its turn-radius scale,
  creep slip, traction, scrub and wall friction), the battery's internal resistance, the motor
  part spread, the per-side mismatch of motor, track friction and wheel radius, and where each
  ranger was actually mounted;
* the team's calibration: what it measured and configures the firmware with. The wheel radius
  by driving against marks (the true mean rolling radius times 1 + e_r), the turn scale by
  spinning in place against marks (the true effective track width chi_0 B times 1 + e_t), the
  encoder resolution exactly, and the rangers at their design poses (the drawing).

The firmware is configured from the calibration only (``RobotParams.calibrated``,
``harness/firmware_config.py``), never from the truth. Every draw is uniform in its range, all
in one block of ``N_DRAWS`` uniforms so the consumption does not depend on the values; a profile
without a reality group draws nothing (missions without it are unchanged). Ranges and their
sources: docs/drivetrain.md "Reality" and docs/robustness.md.
"""

from __future__ import annotations

import copy
import dataclasses
from dataclasses import dataclass
from typing import Any

import numpy as np

from sim_plant.file_schemas import RealityTable
from sim_plant.robot import IR_NAMES, Calibration, IrPose, RobotParams
from sim_plant.schema import check

Range = tuple[float, float]

# ranges and bounds of each field: sim_plant/file_schemas.py RealityTable
# uniforms drawn per mission when a reality group is on: 8 ranges, 2 + 6 spreads, 3 x 5 mounts, 2 calibration
N_DRAWS = 33


@dataclass(frozen=True)
class Reality:
    track_factor: Range = (1.0, 1.0)      # chi_0, effective / geometric track width spinning
    turn_radius: Range = (0.10, 0.10)     # m, where chi - 1 has halved
    creep: Range = (0.0, 0.0)             # longitudinal slip at the traction limit
    floor_mu: Range = (0.6, 0.6)          # traction coefficient
    scrub_mu: Range = (0.0, 0.0)          # lateral friction of the scrub torque
    wall_mu: Range = (-1.0, -1.0)         # body-to-wall friction (< 0: no slide)
    internal_resistance: Range = (0.0, 0.0)  # ohm
    fan_current: Range = (0.0, 0.0)       # A while the fan runs
    motor_spread: float = 0.0       # ± fraction on R and the motor constant (both sides alike)
    side_motor: float = 0.0         # ± fraction per side on the motor constant
    side_friction: float = 0.0      # ± fraction per side on the track friction
    side_wheel_radius: float = 0.0  # ± fraction per side on the wheel radius
    ir_mount_mm: float = 0.0        # ± mm each ranger's x, y off its design position
    ir_mount_deg: float = 0.0       # ± degrees each ranger's aim off its design angle
    cal_wheel_radius: float = 0.0   # ± fraction: the team's wheel-radius error
    cal_track_width: float = 0.0    # ± fraction: the team's turn-scale (track width) error

    @property
    def enabled(self) -> bool:
        return self != Reality()

    def draw(self, robot: RobotParams, rng: np.random.Generator) -> RobotParams:
        """The plant's truth for this mission, carrying the team's calibration of it."""
        u = rng.random(N_DRAWS)
        k = iter(range(N_DRAWS))

        def rng_in(r: Range) -> float:
            return r[0] + (r[1] - r[0]) * float(u[next(k)])

        def pm(half: float) -> float:
            return half * (2.0 * float(u[next(k)]) - 1.0)

        t = copy.deepcopy(robot)
        sl = t.slip
        sl.track_factor = rng_in(self.track_factor)
        sl.turn_radius = rng_in(self.turn_radius)
        sl.creep = rng_in(self.creep)
        sl.floor_mu = rng_in(self.floor_mu)
        sl.scrub_mu = rng_in(self.scrub_mu)
        sl.wall_mu = rng_in(self.wall_mu)
        t.battery.internal_resistance = rng_in(self.internal_resistance)
        t.battery.fan_current = rng_in(self.fan_current)
        km = 1.0 + pm(self.motor_spread)
        t.motor.Kt *= km
        t.motor.Kb *= km
        t.motor.R *= 1.0 + pm(self.motor_spread)
        s = t.sides
        s.left_motor = 1.0 + pm(self.side_motor)
        s.right_motor = 1.0 + pm(self.side_motor)
        s.left_friction = 1.0 + pm(self.side_friction)
        s.right_friction = 1.0 + pm(self.side_friction)
        s.left_wheel_radius = 1.0 + pm(self.side_wheel_radius)
        s.right_wheel_radius = 1.0 + pm(self.side_wheel_radius)
        for n in IR_NAMES:
            p = t.ir[n]
            t.ir[n] = IrPose(p.x + pm(self.ir_mount_mm) / 1000.0, p.y + pm(self.ir_mount_mm) / 1000.0,
                             p.angle_deg + pm(self.ir_mount_deg))
        # The team's calibration, measured on this truth with its own error.
        rolling = t.track.wheel_radius * 0.5 * (s.left_wheel_radius + s.right_wheel_radius)
        spun = sl.track_factor * t.track.track_width  # chi at spin in place is chi_0
        t.calibration = Calibration(
            wheel_radius=rolling * (1.0 + pm(self.cal_wheel_radius)),
            track_width=spun * (1.0 + pm(self.cal_track_width)),
            ticks_per_rev=robot.encoder.ticks_per_rev,
            ir={n: dataclasses.replace(robot.ir[n]) for n in IR_NAMES},
        )
        t.source = f"{robot.source} (realistic draw)"
        return t


def reality_from_table(src: str, prefix: str, table: Any) -> Reality:
    """A reality group from its table (checked against ``sim_plant/file_schemas.RealityTable``)."""
    t = check(table, RealityTable, src, prefix)
    return Reality(**{f.name: getattr(t, f.name) for f in dataclasses.fields(Reality)})


def reality_to_table(r: Reality) -> dict[str, Any]:
    """Only the fields that differ from the ideal default; ranges as [lo, hi] lists."""
    out: dict[str, Any] = {}
    for f in dataclasses.fields(r):
        v = getattr(r, f.name)
        if v != f.default:
            out[f.name] = list(v) if isinstance(v, tuple) else v
    return out
