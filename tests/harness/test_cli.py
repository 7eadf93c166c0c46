"""The ffr command line: contracts, exit codes, one-line errors, nothing half-written."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from harness.cli import main

REPO = Path(__file__).resolve().parents[2]
CONTRACT_KEYS = {"outcome", "room", "candle", "time_to_extinguish_s", "total_time_s", "wall_contacts",
                 "min_wall_clearance_m", "path_length_m", "seed"}


def test_run_json_and_plot(tmp_path, capsys) -> None:
    out, png = tmp_path / "r.json", tmp_path / "p.png"
    assert main(["run", "--room", "2", "--json", str(out), "--plot", str(png)]) == 0
    data = json.loads(out.read_text())
    assert set(data) >= CONTRACT_KEYS
    assert data["outcome"] == "home" and data["room"] == 2 and data["seed"] == 0
    assert isinstance(data["time_to_extinguish_s"], float)
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and png.stat().st_size > 20_000
    assert "room2: home" in capsys.readouterr().out


def test_run_json_to_stdout_is_pure_json(capsys) -> None:
    assert main(["run", "--candle", "2.30,0.80", "--json", "-"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["candle"] == [2.3, 0.8] and data["room"] == 4


def test_table1_prints_ours_beside_the_paper(tmp_path, capsys) -> None:
    out = tmp_path / "t.json"
    assert main(["table1", "--json", str(out)]) == 0
    text = capsys.readouterr().out
    assert "paper" in text and "40.8" in text and "196.3" in text
    rows = json.loads(out.read_text())
    assert [r["room"] for r in rows] == [1, 2, 3, 4]
    assert all(r["outcome"] == "home" for r in rows)
    assert rows[3]["paper_total_time_s"] == 196.3
    # each time as its JSON value prints it, as the acceptance (which reads the JSON) does
    line = next(t for t in text.splitlines() if t.startswith("time to put flame out"))
    assert line.split()[-4:] == [f"{r['time_to_extinguish_s']:.1f}" for r in rows]


def test_a_time_on_the_half_prints_as_its_json_value_does() -> None:
    from harness.cli import _fmt

    # 73.85 s (7,385 ticks of 10 ms) computed lies a hair above 73.85, its JSON value (3 decimals) a
    # hair below
    assert 7385 * 0.01 > 73.85 and f"{7385 * 0.01:.1f}" == "73.9"
    assert _fmt(7385 * 0.01) == _fmt(round(7385 * 0.01, 3)) == f"{73.85:.1f}" == "73.8"
    assert _fmt(None) == "-"


@pytest.mark.parametrize(
    ("argv", "needle"),
    [
        (["run", "--room", "7"], "room = 7"),
        (["run", "--candle", "1.0,1.0"], "in-hallway"),
        (["run", "--candle", "abc"], "--candle"),
        (["run", "--seed", "-3"], "--seed"),
        (["run", "--set", "firmware.no_such=1"], "firmware.no_such"),
        (["run", "--set", "robot.body.width=0.5"], "robot.body.width"),
        (["run", "--noise", "loud"], "loud"),
        (["run", "--link", "nonsense"], "nonsense"),
        (["run", "--scenario", "/nonexistent/s.toml"], "/nonexistent/s.toml"),
        (["fly"], "fly"),
    ],
)
def test_bad_input_one_line_exit_2_nothing_written(tmp_path, capsys, argv, needle: str) -> None:
    out = tmp_path / "never.json"
    assert main([*argv, "--json", str(out)] if argv[0] == "run" else argv) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith("ffr: error:") and needle in err
    assert "Traceback" not in err
    assert not out.exists()
    assert list(tmp_path.iterdir()) == []


def test_bad_scenario_file_names_file_field_value(tmp_path, capsys) -> None:
    s = tmp_path / "bad.toml"
    s.write_text('[candle]\nroom = 2\n[timing]\nfirmware_period_ms = "fast"\n')
    assert main(["run", "--scenario", str(s)]) == 2
    err = capsys.readouterr().err
    assert str(s) in err and "timing.firmware_period_ms" in err and "'fast'" in err


@pytest.mark.parametrize(("text", "needle"), [
    ("[candle]\npositon = [0.55, 1.20]\n", "candle.positon = [0.55, 1.2]: unknown field (did you mean 'position'?"),
    ("[candle]\nroom = 1\n[start]\nx = 2.1\ny = 1.17\nheadng_deg = 0\n",
     "start.headng_deg = 0: unknown field (did you mean 'heading_deg'?"),
])
def test_a_misspelt_key_in_a_table_is_refused(tmp_path, capsys, text: str, needle: str) -> None:
    """A typo must never quietly change the experiment: the default would run and exit 0."""
    s = tmp_path / "typo.toml"
    s.write_text(text)
    out = tmp_path / "r.json"
    assert main(["run", "--scenario", str(s), "--json", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and str(s) in err and needle in err
    assert not out.exists()


@pytest.mark.parametrize("argv", [
    ["run", "--room", "1", "--json", "/dev/null/x.json"],
    ["run", "--room", "1", "--plot", "/dev/null/x.png"],
    ["table1", "--json", "/dev/null/t.json"],
    ["b2b", "--room", "1", "--link", "ctypes:", "--json", "/dev/null/b.json"],
    ["sweep", "-n", "1", "--seeds", "0:1", "--out", "/dev/null/s.csv"],
    ["sweep", "-n", "1", "--seeds", "0:1", "--plot", "/dev/null/s.png"],
])
def test_an_output_path_inside_a_file_is_one_line_before_any_mission(capsys, argv: list[str]) -> None:
    assert main(argv) == 2
    captured = capsys.readouterr()
    assert captured.err.count("\n") == 1 and "/dev/null is not a directory" in captured.err
    assert captured.out == ""  # refused before any mission ran


def test_a_scenario_that_is_not_utf8_is_refused(tmp_path, capsys) -> None:
    s = tmp_path / "noise.toml"
    s.write_bytes(bytes(np.random.default_rng(1).integers(128, 256, 300, dtype=np.uint8)))
    assert main(["run", "--scenario", str(s)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and str(s) in err and "not UTF-8" in err


def test_example_scenario_runs(capsys) -> None:
    assert main(["run", "--scenario", str(REPO / "scenarios" / "example.toml")]) == 0
    assert "room3-near-door-wall: home" in capsys.readouterr().out


def test_python_dash_m_and_console_script_agree() -> None:
    res = subprocess.run([sys.executable, "-m", "harness", "run", "--room", "1", "--json", "-"],
                         capture_output=True, text=True, cwd=REPO, timeout=120)
    assert res.returncode == 0, res.stderr
    assert json.loads(res.stdout)["outcome"] == "home"
    bad = subprocess.run([sys.executable, "-m", "harness", "run", "--room", "x"],
                         capture_output=True, text=True, cwd=REPO, timeout=120)
    assert bad.returncode == 2 and "Traceback" not in bad.stderr and bad.stderr.count("\n") == 1


def test_a_reader_that_leaves_early_gets_no_traceback() -> None:
    # `ffr table1 | head -1`: the pipe closes before ffr prints
    p = subprocess.Popen([sys.executable, "-m", "harness", "run", "--room", "1"], cwd=REPO,
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    assert p.stdout is not None and p.stderr is not None
    p.stdout.close()
    err = p.stderr.read().decode()
    assert p.wait(timeout=120) == 141 and err == ""
