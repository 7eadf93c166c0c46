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


def _whole(room: int, noise: str = "typical", seed: int = 2, compiled: bool | None = None):
    return run_mission(make_scenario(room=room, seed=seed, noise=noise), compiled=compiled)


def test_a_mission_after_a_longer_one_has_the_trace_it_has_alone() -> None:
    # the trace's work arrays are reused per thread (harness/loop.py): nothing of room 4's
    # longer trace may show in room 1's, in either loop
    for compiled in (True, False):
        first_res, first = _whole(1, compiled=compiled)
        _whole(4, compiled=compiled)
        again_res, again = _whole(1, compiled=compiled)
        assert again_res.outcome == first_res.outcome == "home"
        assert len(again.f) == len(first.f) and len(again.i) == len(first.i)
        assert again.f.tobytes() == first.f.tobytes() and again.i.tobytes() == first.i.tobytes()
        assert not np.shares_memory(again.f, first.f)  # each result owns its trace


def test_missions_in_two_threads_at_once_have_the_traces_they_have_alone() -> None:
    from concurrent.futures import ThreadPoolExecutor

    alone = {room: _whole(room)[1] for room in (2, 3)}
    with ThreadPoolExecutor(2) as pool:
        together = dict(zip((2, 3), pool.map(lambda r: _whole(r)[1], (2, 3)), strict=True))
    for room in (2, 3):
        assert together[room].f.tobytes() == alone[room].f.tobytes()
        assert together[room].i.tobytes() == alone[room].i.tobytes()
