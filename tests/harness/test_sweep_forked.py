"""The forked-process engine (``harness.sweep.run_forked``) and Ctrl-C.

A Ctrl-C raised as an exception inside ``multiprocessing.Pool``'s own code can land between a lock's
acquire and its ``with``, leaving the lock held; ``Pool.terminate()`` then waits on it for ever (a sweep
that never exits after Ctrl-C, seen once in a fresh-clone CI run). So while the pool runs, a Ctrl-C is
only noted: the engine stops its loop, stops the pool, and raises ``KeyboardInterrupt`` after.

The rig runs in a child process (forking pytest itself would copy its threads): it stands a fake in
for the missions, and sends the Ctrl-C from inside the pool's result iterator, the spot the old code
was interrupted in.
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]

RIG = r"""
import json, multiprocessing, multiprocessing.pool, os, signal, time
from harness import sweep

def fake_chunk(jobs):
    time.sleep(0.05)
    return [{"id": j["id"]} for j in jobs]

sweep.run_chunk = fake_chunk
seen = {"calls": 0, "raised_inside_pool": False}
original = multiprocessing.pool.IMapIterator.next

def next_with_ctrl_c(self, timeout=None):
    seen["calls"] += 1
    try:
        if seen["calls"] == 2:
            os.kill(os.getpid(), signal.SIGINT)
        return original(self, timeout)
    except KeyboardInterrupt:
        seen["raised_inside_pool"] = True
        raise

multiprocessing.pool.IMapIterator.next = next_with_ctrl_c
sunk = []
outcome = "returned"
try:
    sweep.run_forked([{"id": i} for i in range(40)], 2, sink=sunk.extend)
except KeyboardInterrupt:
    outcome = "KeyboardInterrupt"
print(json.dumps(seen | {"outcome": outcome, "children_left": len(multiprocessing.active_children()),
                         "sunk": sorted(r["id"] for r in sunk)}))
"""


def test_a_ctrl_c_while_the_pool_runs_is_raised_after_it_stops_never_inside_its_code() -> None:
    r = subprocess.run([sys.executable, "-c", RIG], cwd=REPO, capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    got = json.loads(r.stdout)
    assert got["calls"] >= 2  # the Ctrl-C was sent from inside the pool's iterator
    assert got["raised_inside_pool"] is False
    assert got["outcome"] == "KeyboardInterrupt"  # not lost: raised once the pool has stopped
    assert got["children_left"] == 0
    # the rows that reached the sink are whole chunks, the warm-up's mission 0 first among them
    assert got["sunk"][0] == 0 and len(got["sunk"]) == len(set(got["sunk"])) < 40
