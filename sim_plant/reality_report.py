"""What the ``realistic`` profile's reality draws, seed by seed:
``python -m sim_plant.reality_report [PROFILE] SEEDS`` (apart from reality.py, which the noise
profiles build on)."""

from __future__ import annotations

import numpy as np

from sim_plant.broken_pipe import exit_with
from sim_plant.errors import FfrInputError
from sim_plant.robot import RobotParams, load_robot
from sim_plant.sensors import load_noise_profile


def describe(robot: RobotParams, truth: RobotParams) -> str:
    """One line: the drawn floor and the team's calibration errors against that truth."""
    sl, s, cal = truth.slip, truth.sides, truth.calibration
    rolling = robot.track.wheel_radius * 0.5 * (s.left_wheel_radius + s.right_wheel_radius)
    spun = sl.track_factor * robot.track.track_width
    assert cal.wheel_radius is not None and cal.track_width is not None
    e_r = cal.wheel_radius / rolling - 1.0
    e_t = cal.track_width / spun - 1.0
    turn = (1.0 + e_r) / (1.0 + e_t) - 1.0  # the firmware's turn odometry scale error
    return (f"chi0 {sl.track_factor:.3f}  creep {sl.creep:.3f}  scrub_mu {sl.scrub_mu:.2f}  "
            f"R_int {truth.battery.internal_resistance:.2f}  motors L/R {s.left_motor:.3f}/{s.right_motor:.3f}  "
            f"cal wheel {100 * e_r:+.2f} %  cal turn scale {100 * e_t:+.2f} %  turn odometry {100 * turn:+.2f} %")


def main(argv: list[str] | None = None) -> int:
    """``python -m sim_plant.reality_report [PROFILE] SEEDS``: what each seed draws (SEEDS: A:B or N,N,...)."""
    import sys

    args = sys.argv[1:] if argv is None else argv
    if not args or len(args) > 2:
        print("usage: python -m sim_plant.reality_report [PROFILE] SEEDS (A:B or N,N,...)", file=sys.stderr)
        return 2
    name, spec = (args[0], args[1]) if len(args) == 2 else ("realistic", args[0])
    try:
        if ":" in spec:
            a, b = spec.split(":")
            seeds = list(range(int(a), int(b)))
        else:
            seeds = [int(v) for v in spec.split(",")]
        prof = load_noise_profile(name)
    except ValueError:
        print(f"SEEDS: {spec!r}: expected A:B or N,N,...", file=sys.stderr)
        return 2
    except FfrInputError as exc:
        print(exc, file=sys.stderr)
        return 2
    if not prof.reality.enabled:
        print(f"{name}: profile has no reality group: the plant is the robot file's", file=sys.stderr)
        return 2
    robot = load_robot()
    for seed in seeds:
        print(f"seed {seed:5d}  {describe(robot, prof.reality.draw(robot, np.random.default_rng(seed)))}")
    return 0


if __name__ == "__main__":
    exit_with(main)
