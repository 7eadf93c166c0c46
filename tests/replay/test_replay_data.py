"""The replay's data preparation: frames, downsampling, beams, fans, flame-out time."""

from __future__ import annotations

import math

import numpy as np
import pytest

from ffr_link.ctypes_link import firmware_info
from harness.loop import I_FAN, I_SENS, I_STATE, N_F, N_I, Trace
from harness.replay.data import (
    MV_AT_FAR,
    build_replay,
    fan_on_time,
    frame_indices,
    ir_length,
    robot_model,
)
from harness.scenario import make_scenario
from harness.scoring import MissionResult
from sim_plant.sensors.gp2d12 import D_FAR, distance_to_mv


def _trace(n: int, dt: float = 0.01) -> Trace:
    """A synthetic straight drive along +x at 0.2 m/s, n ticks."""
    f = np.zeros((n, N_F))
    f[:, 0] = np.arange(n) * dt
    f[:, 1] = 0.5 + 0.2 * f[:, 0]
    f[:, 2] = 1.0
    i = np.zeros((n, N_I), dtype=np.int32)
    i[:, I_STATE] = firmware_info().state_names.index("FOLLOW")
    i[:, I_SENS:I_SENS + 5] = 1000
    return Trace(f, i)


def _result(ext: float | None) -> MissionResult:
    return MissionResult(outcome="extinguished" if ext is not None else "timeout", room=1, candle=(1.8, 1.5),
                         time_to_extinguish_s=ext, total_time_s=None, wall_contacts=0,
                         min_wall_clearance_m=0.1, path_length_m=1.0, seed=0)


def test_frame_indices_hit_each_period_and_keep_both_ends() -> None:
    t = np.arange(1006) * 0.01  # 0 .. 10.05 s at 100 Hz
    idx = frame_indices(t, 15.0)
    assert idx[0] == 0 and idx[-1] == 1005
    assert len(idx) == math.floor(10.05 * 15) + 1 + 1  # 151 grid frames, plus the last tick (off-grid)
    grid = t[idx[:-1]]
    # each frame is the first tick at or after k/15 s: never early, late by less than one tick
    lag = grid - np.arange(len(grid)) / 15.0
    assert lag.min() >= -1e-9 and lag.max() < 0.01
    assert np.all(np.diff(idx) > 0)


def test_frame_indices_rate_not_above_the_trace_gives_every_tick() -> None:
    t = np.arange(50) * 0.01
    assert np.array_equal(frame_indices(t, 100.0), np.arange(50))
    assert np.array_equal(frame_indices(t, 1000.0), np.arange(50))  # no duplicates
    assert len(frame_indices(np.zeros(0), 10.0)) == 0
    with pytest.raises(ValueError):
        frame_indices(t, 0.0)


def test_fan_on_time_counts_the_seconds_the_fans_ran() -> None:
    t = np.arange(10) * 0.5
    fan = np.array([0, 1, 1, 0, 0, 1, 0, 0, 0, 0])
    # the command at a tick drives the fans until the next tick
    assert np.allclose(fan_on_time(t, fan), [0, 0, 0.5, 1.0, 1.0, 1.0, 1.5, 1.5, 1.5, 1.5])


def test_ir_length_inverts_the_sensor_curve_and_flags_no_wall() -> None:
    d = np.array([0.10, 0.15, 0.3, 0.55, 0.79])
    length, ok = ir_length(np.asarray(distance_to_mv(d)))
    assert np.allclose(length, d, atol=1e-3) and ok.all()
    length, ok = ir_length(np.array([MV_AT_FAR - 30.0, 300.0]))
    assert np.allclose(length, D_FAR) and not ok.any()


def test_frames_are_downsampled_and_follow_the_pose() -> None:
    tr = _trace(2001)  # 20 s
    data = build_replay(make_scenario(room=1), tr, _result(None), fps=10.0, chart_hz=25.0)
    fr = data.frames
    assert data.n_frames == 201  # 0, 0.1, ..., 20.0 s
    assert fr["t"][0] == 0.0 and fr["t"][-1] == 20.0
    assert np.allclose(fr["x"], 0.5 + 0.2 * np.asarray(fr["t"]), atol=1e-4)
    assert len(data.charts["t"]) == 501
    assert all(len(fr[k]) == 201 for k in ("y", "theta", "fan", "state", "lit", "pwm_l", "enc_r"))
    assert all(len(col) == 201 for col in fr["ir_len"])
    assert fr["state"][0] == firmware_info().state_names.index("FOLLOW")


def test_flame_goes_out_at_the_extinguish_time() -> None:
    tr = _trace(1001)
    data = build_replay(make_scenario(room=1), tr, _result(4.567), fps=10.0)
    t = np.asarray(data.frames["t"])
    lit = np.asarray(data.frames["lit"])
    assert lit[t < 4.567].all() and not lit[t >= 4.567].any()
    assert data.meta["time_to_extinguish_s"] == 4.567
    assert data.meta["flame_out_text"] == "4.6"  # the header's figure, as the table prints it
    # a tie: JavaScript's toFixed would give 40.3, every Python output 40.2
    assert build_replay(make_scenario(room=1), tr, _result(40.25), fps=10.0).meta["flame_out_text"] == "40.2"
    never = build_replay(make_scenario(room=1), tr, _result(None), fps=10.0)
    assert all(never.frames["lit"]) and never.meta["time_to_extinguish_s"] is None


def test_fan_angle_advances_only_while_the_fans_run() -> None:
    tr = _trace(501)
    tr.i[100:300, I_FAN] = 1
    fr = build_replay(make_scenario(room=1), tr, _result(None), fps=10.0).frames
    fan_t = np.asarray(fr["fan_t"])
    t = np.asarray(fr["t"])
    assert np.all(fan_t[t <= 1.0] == 0.0)
    assert fan_t[-1] == pytest.approx(2.0)
    assert np.all(np.diff(fan_t) >= 0)
    assert [bool(v) for v in fr["fan"]] == [1.0 <= v < 3.0 - 1e-9 for v in t]


def test_empty_trace_is_refused() -> None:
    with pytest.raises(ValueError, match="no tick"):
        build_replay(make_scenario(room=1), Trace(np.zeros((0, N_F)), np.zeros((0, N_I), np.int32)), _result(None))


def test_real_mission_replay(room1) -> None:
    d, res = room1.data, room1.result
    # 15 frames per simulated second, the last one where the mission ended
    assert d.n_frames == pytest.approx(res.total_time_s * 15 + 1, abs=2)
    assert d.frames["t"][-1] == pytest.approx(room1.trace.t[-1])
    assert d.frames["x"][-1] == pytest.approx(room1.trace.f[-1, 1], abs=1e-4)
    lit = np.asarray(d.frames["lit"])
    t = np.asarray(d.frames["t"])
    assert lit[0] and not lit[-1]
    first_out = t[np.argmin(lit)]
    assert res.time_to_extinguish_s <= first_out < res.time_to_extinguish_s + 1 / 15 + 1e-9
    # the fans ran while the flame was put out: at least the candle's 4 s
    assert d.frames["fan_t"][-1] >= 4.0 - 1e-6
    # the path by state covers states the firmware went through
    assert {"FOLLOW", "EXTINGUISH", "HOMING"} <= set(d.meta["path"])
    # the JSON is plain data (no NaN), the same every time
    import json
    assert json.dumps(d.to_json(), allow_nan=False) == json.dumps(
        build_replay(room1.scn, room1.trace, res).to_json(), allow_nan=False)


def test_robot_model_matches_the_robot_file() -> None:
    scn = make_scenario(room=1)
    m = robot_model(scn.robot)
    xs, ys, zs = (np.asarray(m["mesh"][k]) for k in "xyz")
    b = scn.robot.body
    assert xs.max() == pytest.approx(b.length_front, abs=1e-3) and xs.min() == pytest.approx(-b.length_rear, abs=1e-3)
    assert ys.max() <= b.width / 2 + 1e-6 and zs.max() <= b.height + 1e-6 and zs.min() >= 0
    assert [p["name"] for p in m["ir"]] == ["CF", "LF", "RF", "LR", "RR"]
    assert len(m["fans"]) == 2 and len(m["tracks"]) == 2
    n = len(xs)
    assert max(max(m["mesh"]["i"]), max(m["mesh"]["j"]), max(m["mesh"]["k"])) < n
    assert len(m["mesh"]["facecolor"]) == len(m["mesh"]["i"])


def test_one_state_colour_table_serves_the_2d_picture_and_the_replay() -> None:
    import harness.plot
    import harness.replay.data
    from harness.state_colors import STATE_COLORS, state_colors

    assert harness.plot.state_colors is state_colors is harness.replay.data.state_colors
    assert set(STATE_COLORS) == set(firmware_info().state_names)
    assert len(set(STATE_COLORS.values())) == len(STATE_COLORS)  # every state told apart
    assert state_colors(firmware_info().state_names) == STATE_COLORS


def test_states_of_another_firmware_get_palette_colours_in_code_order() -> None:
    from harness.state_colors import PALETTE, STATE_COLORS, state_colors

    got = state_colors(["IDLE", "SEEK", "WALL_LEFT", "DONE", "SEEK"])
    assert got == {"IDLE": STATE_COLORS["IDLE"], "SEEK": PALETTE[0], "WALL_LEFT": PALETTE[1],
                   "DONE": STATE_COLORS["DONE"]}
    assert not set(PALETTE) & set(STATE_COLORS.values())  # never mistaken for one of ours
    many = state_colors([f"S{k}" for k in range(len(PALETTE) + 2)])
    assert list(many.values())[len(PALETTE)] == PALETTE[0]  # cycles past the palette's end
