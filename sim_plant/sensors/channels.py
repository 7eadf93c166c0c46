"""Channel layout of the hardware-units array the sensors write and the firmware reads.

One int32 array of ``N_CHANNELS`` values per tick: IR rangers in mV, flame
sensors in ADC counts, the line sensor as 0/1, the wheel encoders as
cumulative counts.
"""

from __future__ import annotations

import numpy as np

CH_IR = (0, 1, 2, 3, 4)  # GP2D12 rangers CF, LF, RF, LR, RR (robot.IR_NAMES order), mV
CH_FLAME_L = 5  # left flame sensor, ADC counts
CH_FLAME_R = 6  # right flame sensor, ADC counts
CH_LINE = 7  # 1 over a white line, else 0
CH_ENC_L = 8  # left wheel encoder, cumulative counts
CH_ENC_R = 9  # right wheel encoder, cumulative counts
N_CHANNELS = 10


def new_output() -> np.ndarray:
    """A zeroed output array of the right dtype and length for ``SensorSuite.sample``."""
    return np.zeros(N_CHANNELS, dtype=np.int32)
