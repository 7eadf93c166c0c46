"""The robot's sensors, one module each, and the suite that samples them per tick.

Where things are: ``gp2d12.py`` (IR rangers), ``flame_sensor.py``,
``line_sensor.py``, ``encoders.py``, ``noise.py`` (noise and fault profiles),
``suite.py`` (``SensorSuite``), ``channels.py`` (output array layout).
"""

from sim_plant.sensors.channels import (
    CH_ENC_L,
    CH_ENC_R,
    CH_FLAME_L,
    CH_FLAME_R,
    CH_IR,
    CH_LINE,
    N_CHANNELS,
    new_output,
)
from sim_plant.sensors.flame_sensor import FlameModel
from sim_plant.sensors.gp2d12 import Gp2d12Model, distance_to_mv
from sim_plant.sensors.noise import NoiseProfile, load_noise_profile
from sim_plant.sensors.suite import SensorSuite

__all__ = [
    "CH_ENC_L",
    "CH_ENC_R",
    "CH_FLAME_L",
    "CH_FLAME_R",
    "CH_IR",
    "CH_LINE",
    "N_CHANNELS",
    "FlameModel",
    "Gp2d12Model",
    "NoiseProfile",
    "SensorSuite",
    "distance_to_mv",
    "load_noise_profile",
    "new_output",
]
