"""`python -m harness.mission_trace`: a replay line's mission, tick by tick, as text."""

from __future__ import annotations

import pytest

from harness import mission_trace
from harness.loop import run_mission
from harness.scenario import make_scenario


def test_a_line_at_every_state_change_and_the_window_is_kept() -> None:
    _, trace = run_mission(make_scenario(room=1))
    names = trace.names_of_states()
    out = mission_trace.lines(trace, 0.0, 1e9, 10**9, sensors=False)
    states = [ln.split()[4] for ln in out[1:]]
    changes = [names[c] for k, c in enumerate(trace.state) if k == 0 or c != trace.state[k - 1]]
    assert states == changes  # with --every huge: exactly one line per change
    window = mission_trace.lines(trace, 5.0, 6.0, 1, sensors=True)
    times = [float(ln.split()[0]) for ln in window[1:]]
    assert len(times) == 101 and times[0] == pytest.approx(5.0) and times[-1] == pytest.approx(6.0)
    assert len(window[1].split()) == len(mission_trace.HEAD.split()) + 10  # 5 IR, 2 flame, line, 2 enc


def test_the_command_runs_the_replayed_mission(capsys: pytest.CaptureFixture[str]) -> None:
    assert mission_trace.main(["ffr run --room 2 --seed 3", "--from", "1", "--to", "1.2", "--every", "1"]) == 0
    out = capsys.readouterr().out.splitlines()
    assert out[0] == "outcome home" and len(out) == 2 + 21  # 10 ms ticks


@pytest.mark.parametrize("argv, names", [
    (["ffr sweep --room 1"], ["ffr sweep"]),
    (["ffr run --room 1", "--every", "0"], ["--every", "0"]),
    (["ffr run --candle 1"], ["--candle", "'1'"]),
    (["ffr run --arena /no/such.toml"], ["/no/such.toml"]),
    (["ffr run 'unclosed"], ["unclosed"]),
    (["ffr run --room 1 --link ctypes:/no/such/libteam.so"], ["/no/such/libteam.so"]),  # the replay's own link
])
def test_bad_input_gets_one_line_and_exit_2(capsys: pytest.CaptureFixture[str], argv: list[str],
                                           names: list[str]) -> None:
    assert mission_trace.main(argv) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and all(n in err for n in names), err
