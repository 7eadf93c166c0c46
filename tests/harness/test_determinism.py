"""Same scenario and seed: a bit-identical trace; another seed (with noise): a different one."""

from __future__ import annotations

import numpy as np

from harness.loop import run_mission
from harness.scenario import make_scenario


def _trace(seed: int, noise: str):
    scn = make_scenario(room=1, seed=seed, noise=noise)
    scn.timing.find_limit_s = 15.0  # a part of the mission is enough
    scn.timing.return_limit_s = 1.0
    return run_mission(scn)[1]


def test_same_seed_bit_identical_without_noise() -> None:
    a, b = _trace(1, "none"), _trace(1, "none")
    assert a.f.tobytes() == b.f.tobytes() and a.i.tobytes() == b.i.tobytes()


def test_same_seed_bit_identical_with_noise_other_seed_differs() -> None:
    a, b, c = _trace(5, "typical"), _trace(5, "typical"), _trace(6, "typical")
    assert a.f.tobytes() == b.f.tobytes() and a.i.tobytes() == b.i.tobytes()
    n = min(len(a.f), len(c.f))
    assert not np.array_equal(a.i[:n], c.i[:n])
