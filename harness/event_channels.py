"""What a scenario event may act on: the sensor channels, the wheels and the faults (harness/events.py),
and each channel's range of readings. Shared by the events and their schema (harness/scenario_schema.py)."""

from __future__ import annotations

from sim_plant.robot import IR_NAMES
from sim_plant.sensors.channels import CH_ENC_L, CH_ENC_R, CH_FLAME_L, CH_FLAME_R, CH_IR, CH_LINE

CHANNELS: dict[str, int] = {f"ir.{n}": CH_IR[i] for i, n in enumerate(IR_NAMES)}
CHANNELS |= {"flame.L": CH_FLAME_L, "flame.R": CH_FLAME_R, "line": CH_LINE,
             "encoder.L": CH_ENC_L, "encoder.R": CH_ENC_R}
WHEELS = {"wheel.L": CH_ENC_L, "wheel.R": CH_ENC_R}
FAULTS = ("dead", "stuck", "noisy", "slip")
LIMITS = {CH_LINE: (0, 1)} | {c: (0, 5000) for c in CH_IR} | {CH_FLAME_L: (0, 65535), CH_FLAME_R: (0, 65535)}
