"""Every kind of malformed input ffr reads (command line, scenario, arena, robot, noise and events
files, link URL, output path) ends the same way: one line on stderr that names the file or option,
the field and the value, exit status 2, no traceback, nothing on stdout and nothing written.

Each case is a command line (``{d}`` is a scratch directory holding the files of ``FILES``) and a
piece of text the line must contain."""

from __future__ import annotations

from pathlib import Path

import pytest

from harness.cli import main

ARENA = Path(__file__).resolve().parents[2] / "sim_plant" / "data" / "arena_2004.toml"
ROBOT = Path(__file__).resolve().parents[2] / "sim_plant" / "data" / "robot_default.toml"


def _arena(old: str, new: str) -> str:
    text = ARENA.read_text()
    assert old in text
    return text.replace(old, new, 1)


def _robot(old: str, new: str) -> str:
    text = ROBOT.read_text()
    assert old in text
    return text.replace(old, new, 1)


FILES: dict[str, str | bytes] = {
    # scenarios
    "top_typo.toml": "nosie = 'typical'\n",
    "candle_typo.toml": "[candle]\npositon = [0.55, 1.20]\n",
    "start_typo.toml": "[start]\nx = 2.11\ny = 1.17\nheading = 90\n",
    "timing_typo.toml": "[timing]\nfirmware_period = 10\n",
    "seed_type.toml": "seed = 'one'\n",
    "seed_negative.toml": "seed = -1\n",
    "period_zero.toml": "[timing]\nfirmware_period_ms = 0\n",
    "plant_dt.toml": "[timing]\nplant_dt_ms = 3.0\n",
    "find_limit.toml": "[timing]\nfind_limit_s = -5\n",
    "candle_both.toml": "[candle]\nroom = 2\nposition = [0.55, 1.20]\n",
    "candle_room.toml": "[candle]\nroom = 9\n",
    "candle_hall.toml": "[candle]\nposition = [1.0, 1.0]\n",
    "candle_type.toml": "[candle]\nposition = 'kitchen'\n",
    "start_out.toml": "[start]\nx = 1.0\ny = 1.0\nheading_deg = 0\n",
    "start_both.toml": "[start]\nrandom = true\nx = 2.11\ny = 1.17\n",
    "jitter_big.toml": "arena_jitter = 0.5\n",
    "firmware_field.toml": "[firmware]\nno_such_knob = 1\n",
    "firmware_type.toml": "[firmware]\ncruise_speed_mm_s = 'fast'\n",
    "robot_override.toml": "[robot_overrides]\n'motor.Q' = 1.0\n",
    "noise_name.toml": "noise = 'loud'\n",
    "noise_inline.toml": "[noise.ir]\nsigmaa = 12.0\n",
    "noise_negative.toml": "[noise.ir]\nsigma = -1.0\n",
    "event_sensor.toml": "[[events]]\nat_s = 3\nsensor = 'ir.XX'\nfault = 'dead'\n",
    "event_fault.toml": "[[events]]\nat_s = 3\nsensor = 'ir.RF'\nfault = 'melted'\n",
    "event_time.toml": "[[events]]\nat_s = -3\nsensor = 'ir.RF'\nfault = 'dead'\n",
    "event_key.toml": "[[events]]\nat_s = 3\nsensor = 'ir.RF'\nfault = 'dead'\nwhen = 4\n",
    "syntax.toml": "seed = = 3\n",
    "binary.toml": bytes(range(128, 256)) * 2,
    "arena_missing.toml": "arena = 'no_such_arena.toml'\n",
    "robot_missing.toml": "robot = 'no_such_robot.toml'\n",
    "firmware_nested.toml": "[firmware.sub]\nx = 1\n",
    "start_half.toml": "[start]\nx = 2.11\n",
    "events_type.toml": "events = 5\n",
    "reality_range.toml": "[noise.reality]\ncreep = [0.5, 0.1]\n",
    "furniture_typo.toml": "[[furniture]]\nx = 1.76\ny = 1.85\nwidth = 0.15\ndepht = 0.15\n",
    "override_table.toml": "[robot_overrides]\n'motor.R' = {a = 1}\n",
    "nan.toml": "[candle]\nposition = [0.55, nan]\n",
    # arenas
    "arena_key.toml": _arena('name = "outer_bottom"', 'name = "outer_bottom"\ncolour = "white"'),
    "arena_thick.toml": _arena("t = 0.02", "t = -0.02"),
    "arena_home.toml": _arena("radius = 0.15", "radius = 'wide'"),
    "arena_top.toml": _arena("[home]", "[garden]\nsize = 1\n\n[home]"),
    "arena_room.toml": _arena("default_candle = [2.30, 0.14]", "default_candle = [2.30, 0.14]\nfloor = 'oak'"),
    # robots
    "robot_section.toml": _robot("[body]", "[wings]\nspan = 1.0\n\n[body]"),
    "robot_key.toml": _robot("R = 6.69", "R = 6.69\nRR = 1.0"),
    "robot_value.toml": _robot("R = 6.69", "R = -6.69"),
    "robot_type.toml": _robot("wheel_radius = 0.028", "wheel_radius = 'small'"),
    "robot_calibration.toml": _robot("[body]", "[calibration.ir.LF]\nx = 0.06\ny = 0.05\nangel_deg = 45\n\n[body]"),
    # noise profile files
    "noise_group.toml": "[p]\ndescription = 'x'\n[p.sonar]\nsigma = 1.0\n",
    "noise_field.toml": "[p]\ndescription = 'x'\n[p.ir]\nsigmaa = 1.0\n",
    "noise_mode.toml": "[p]\ndescription = 'x'\n[p.ir]\ndropout_mode = 'vanish'\n",
}

CASES = [
    # the command line
    (["run", "--room", "9"], "room = 9"),
    (["run", "--room", "two"], "--room"),
    (["run", "--candle", "1"], "--candle = '1'"),
    (["run", "--candle", "nan,1"], "--candle = 'nan,1'"),
    (["run", "--seed", "-1"], "--seed = '-1'"),
    (["run", "--set", "speed=3"], "--set = 'speed=3'"),
    (["run", "--set", "firmware.no_such=1"], "firmware.no_such"),
    (["run", "--set", "robot.motor.Q=1"], "robot.motor.Q"),
    (["run", "--start", "1,2"], "--start = '1,2'"),
    (["run", "--start", "1.0,1.0,0"], "start"),
    (["run", "--arena-jitter", "0.2"], "--arena-jitter = '0.2'"),
    (["run", "--noise", "loud"], "loud"),
    (["run", "--arena", "{d}/nothing.toml"], "nothing.toml"),
    (["run", "--robot", "{d}/nothing.toml"], "nothing.toml"),
    (["sweep", "--seeds", "5:2", "--no-progress"], "--seeds = '5:2'"),
    (["sweep", "--param", "firmware.cruise_speed_mm_s=1:2", "--no-progress"], "firmware.cruise_speed_mm_s"),
    (["sweep", "--out", "{d}/rows.txt", "--no-progress"], "rows.txt"),
    (["fly"], "fly"),
    # link URLs
    (["run", "--link", "nope:x"], "unknown scheme 'nope'"),
    (["run", "--link", "ctypes"], "--link = 'ctypes'"),
    (["run", "--link", "host-board:pigeon"], "host-board:pigeon"),
    (["run", "--link", "ctypes:{d}/libnothing.so"], "libnothing.so"),
    # output paths
    (["run", "--json", "/dev/null/x.json"], "/dev/null/x.json"),
    (["run", "--plot", "/dev/null/p.png"], "/dev/null/p.png"),
    (["run", "--replay", "{d}/r.txt"], "r.txt"),
    (["table1", "--replay-dir", "/dev/null/replays"], "--replay-dir"),
    # files
    *[(["run", "--scenario", f"{{d}}/{name}"], name) for name in FILES
      if not name.startswith(("arena_", "robot_", "noise_")) or name in (
          "arena_missing.toml", "robot_missing.toml", "noise_name.toml", "noise_inline.toml", "noise_negative.toml")],
    *[(["run", "--arena", f"{{d}}/{name}"], name) for name in FILES
      if name.startswith("arena_") and name != "arena_missing.toml"],
    *[(["run", "--robot", f"{{d}}/{name}"], name) for name in FILES
      if name.startswith("robot_") and name not in ("robot_missing.toml", "robot_override.toml")],
    *[(["run", "--noise", f"{{d}}/{name}#p"], name) for name in ("noise_group.toml", "noise_field.toml",
                                                                  "noise_mode.toml")],
]


def test_the_catalogue_holds_at_least_40_kinds() -> None:
    assert len(CASES) >= 60 and len({tuple(a) for a, _ in CASES}) == len(CASES)


@pytest.mark.parametrize(("argv", "needle"), CASES, ids=[" ".join(a) for a, _ in CASES])
def test_malformed_input_is_one_line_and_exit_2(tmp_path, capsys, argv, needle) -> None:
    for name, text in FILES.items():
        path = tmp_path / name
        path.write_bytes(text) if isinstance(text, bytes) else path.write_text(text)
    before = {p.name for p in tmp_path.iterdir()}
    argv = [a.replace("{d}", str(tmp_path)) for a in argv]
    if argv[0] in ("run", "table1") and "--json" not in argv:
        argv += ["--json", str(tmp_path / "out.json")]
    code = main(argv)
    out, err = capsys.readouterr()
    assert code == 2, f"exit {code}; stderr: {err!r}"
    assert err.count("\n") == 1 and err.startswith("ffr: error: "), err
    assert "Traceback" not in err and out == ""
    assert needle in err, err
    assert {p.name for p in tmp_path.iterdir()} == before  # nothing written
