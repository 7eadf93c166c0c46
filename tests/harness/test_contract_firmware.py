"""Any firmware that meets the contract (docs/contract.md) runs in the harness: a tiny test
firmware with a configuration layout unlike ours (tests/firmware/fixtures/tiny_fw/), compiled here
with cc, is loaded, described, configured by field name and run; its names come from its library."""

from __future__ import annotations

import os
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest
from ffr_firmware.build import CSTD

from ffr_link.abi import contract_hash
from ffr_link.ctypes_link import default_config, firmware_info
from harness.cli import main
from harness.firmware_config import build_config, tunable_fields
from harness.loop import run_mission
from harness.scenario import make_scenario
from sim_plant.errors import FfrInputError
from sim_plant.robot import load_robot

REPO = Path(__file__).resolve().parents[2]
FIXTURE = REPO / "tests" / "firmware" / "fixtures" / "tiny_fw"
CC = shutil.which("cc")
pytestmark = pytest.mark.skipif(CC is None and not os.environ.get("CI"),  # CI has cc: missing fails there
                                reason="needs a C compiler (cc)")


def _build(out: Path, *defines: str) -> str:
    flags = [f for f in CSTD if not f.startswith("-I")]
    subprocess.run([CC, *flags, *defines, f"-I{REPO / 'firmware' / 'include'}", f"-I{FIXTURE}", "-O2", "-fPIC",
                    "-shared", "-o", str(out), str(FIXTURE / "tiny_fw.c")], check=True, timeout=120)
    return str(out)


@pytest.fixture(scope="module")
def tiny(tmp_path_factory: pytest.TempPathFactory) -> str:
    return _build(tmp_path_factory.mktemp("tiny") / "libtiny.so")


def test_a_library_with_its_own_config_layout_loads_and_describes_itself(tiny: str) -> None:
    fw = firmware_info(tiny)
    assert fw.firmware_name == "tiny 0.1" and not fw.is_reference
    assert fw.state_names == ("WAIT", "GO", "STOP", "GAVE_UP") and fw.fail_names == ("", "told to fail")
    dt = fw.config_dtype
    assert dt.names == ("mode", "fail_on", "run_ms", "speed_permille", "reserved", "wheel_radius_mm", "ir_x_mm",
                        "ticks_seen_limit", "legs")
    assert dt.itemsize == fw.sizes[2] == 48
    legs = dt.fields["legs"][0]  # type: ignore[index]
    assert legs.shape == (3,) and legs.base.names == ("pwm", "ms") and legs.base.itemsize == 4
    assert fw.layout_hash == contract_hash(fw)  # the documented recipe (ffr_contract_hash.h)
    cfg = default_config(tiny)
    assert (int(cfg["run_ms"]), int(cfg["speed_permille"]), int(cfg["legs"][0]["ms"])) == (500, 150, 200)
    ours = firmware_info()
    assert ours.is_reference and ours.config_dtype != dt and ours.layout_hash != fw.layout_hash


def test_its_fields_are_set_by_name_and_the_calibration_by_the_contract_s_names(tiny: str) -> None:
    fw = firmware_info(tiny)
    robot = load_robot(None)
    cfg = build_config(robot, {"run_ms": 1234, "speed_permille": -40, "ir_x_mm": [1, 2, 3, 4, 5.5]},
                       "test.toml", firmware=fw)
    assert cfg.dtype == fw.config_dtype
    assert (int(cfg["run_ms"]), int(cfg["speed_permille"])) == (1234, -40)
    assert list(cfg["ir_x_mm"]) == [1, 2, 3, 4, 5.5]  # set after the calibration: the override wins
    wheel, *_ = robot.calibrated()
    assert cfg["wheel_radius_mm"] == np.float32(wheel * 1000.0)  # a well-known name it has
    assert "legs" not in tunable_fields(fw) and "reserved" not in tunable_fields(fw)
    with pytest.raises(FfrInputError, match=r"firmware.run_ms = 70000: must be an integer in \[0, 65535\]"):
        build_config(robot, {"run_ms": 70000}, "test.toml", firmware=fw)
    with pytest.raises(FfrInputError, match=r"did you mean 'run_ms'\?"):
        build_config(robot, {"run_mss": 1}, "test.toml", firmware=fw)
    with pytest.raises(FfrInputError, match="no such setting in the firmware 'tiny 0.1'"):
        build_config(robot, {"cruise_speed_mm_s": 250.0}, "test.toml", firmware=fw)  # ours, not its


@pytest.mark.parametrize("compiled", [True, False])
def test_a_mission_ends_on_its_done_flag_and_traces_carry_its_state_names(tiny: str, compiled: bool) -> None:
    scn = make_scenario(room=1, firmware={"run_ms": 300, "speed_permille": 200})
    res, trace = run_mission(scn, f"ctypes:{tiny}", compiled=compiled)
    assert trace.state_names == ("WAIT", "GO", "STOP", "GAVE_UP")
    assert int(trace.state[-1]) == 2 and int(trace.i[-1, 4]) & 8  # STOP with DONE in flags: the end
    assert np.count_nonzero(trace.state == 1) == 30  # 300 ms of GO at 10 ms a tick
    assert res.outcome != "timeout"


def test_compiled_and_python_loops_agree_bit_for_bit_on_another_firmware(tiny: str) -> None:
    scn = make_scenario(room=2, firmware={"run_ms": 800, "speed_permille": 300})
    _, a = run_mission(scn, f"ctypes:{tiny}", compiled=True)
    _, b = run_mission(scn, f"ctypes:{tiny}", compiled=False)
    assert a.f.tobytes() == b.f.tobytes() and a.i.tobytes() == b.i.tobytes()


def test_its_failed_flag_ends_the_mission_with_its_failure_name(tiny: str) -> None:
    scn = make_scenario(room=1, firmware={"run_ms": 100, "fail_on": 1})
    res, trace = run_mission(scn, f"ctypes:{tiny}")
    assert res.outcome == "error" and res.detail == "firmware: told to fail"  # failed, flame burning
    assert trace.state_names[int(trace.state[-1])] == "GAVE_UP"


def test_unknown_config_name_is_one_line_and_exit_2(tiny: str, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["run", "--firmware", tiny, "--room", "1", "--set", "firmware.speed_permile=100"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "firmware.speed_permile = 100" in err
    assert "did you mean 'speed_permille'?" in err and "'tiny 0.1'" in err
    assert main(["sweep", "-n", "1", "--firmware", tiny, "--param", "firmware.run_mss=1,2", "--no-progress"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "did you mean 'run_ms'?" in err


def test_list_firmware_config_lists_its_fields(tiny: str, capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["run", "--firmware", tiny, "--list-firmware-config"]) == 0
    out = capsys.readouterr().out.splitlines()
    assert out[0].startswith("# tiny 0.1 (contract 2.0): inputs 32 bytes, outputs 24, config 48, state ")
    assert out[0].endswith(f"layout hash 0x{firmware_info(tiny).layout_hash:08x}")
    rows = {ln.split()[0]: ln.split()[1:] for ln in out[2:]}
    assert rows["run_ms"] == ["u2", "unsigned", "500"] and rows["speed_permille"] == ["i2", "integer", "150"]
    assert rows["ir_x_mm"][0] == "f4[5]" and "legs" not in rows


def test_the_layout_hash_changes_when_a_name_changes(tiny: str, tmp_path: Path) -> None:
    other = _build(tmp_path / "libtiny_halt.so", '-DTINY_STATE_STOP_NAME="HALT"')
    a, b = firmware_info(tiny), firmware_info(other)
    assert b.state_names[2] == "HALT" and a.rows == b.rows and a.sizes == b.sizes
    assert a.layout_hash != b.layout_hash and b.layout_hash == contract_hash(b)


@pytest.fixture(scope="module")
def tiny_board(tmp_path_factory: pytest.TempPathFactory) -> str:
    """The tiny firmware as a host board: our codec, board link and host board around it."""
    out = tmp_path_factory.mktemp("tiny_board") / "tiny-board"
    fw = REPO / "firmware"
    srcs = [FIXTURE / "tiny_fw.c", *sorted((fw / "codec").glob("*.c")), *sorted((fw / "link").glob("*.c")),
            *sorted((fw / "boards" / "host").glob("*.c"))]
    flags = [f for f in CSTD if not f.startswith("-I")]
    subprocess.run([CC, *flags, f"-I{fw / 'include'}", f"-I{FIXTURE}", f"-I{fw / 'boards' / 'host'}", "-O2",
                    "-o", str(out), *map(str, srcs)], check=True, timeout=300)
    return str(out)


def test_the_wire_and_the_host_board_carry_another_firmware(tiny: str, tiny_board: str,
                                                             monkeypatch: pytest.MonkeyPatch) -> None:
    """Its config (48 bytes, a sub-struct array) crosses the wire in RESET, the handshake compares
    the board's hash with the host library's, and the traces are the in-process ones bit for bit."""
    scn = make_scenario(room=3, firmware={"run_ms": 400, "speed_permille": 250, "ir_x_mm": [5, 4, 3, 2, 1]})
    _, ref = run_mission(scn, f"ctypes:{tiny}", compiled=False)
    monkeypatch.setenv("FFR_FIRMWARE_LIB", tiny)
    monkeypatch.setenv("FFR_HOST_BOARD", tiny_board)
    res, got = run_mission(scn, "host-board:serial")
    assert res.link == "host-board:serial" and res.link_counters["crc_errors"] == 0
    assert got.state_names == ("WAIT", "GO", "STOP", "GAVE_UP")
    assert got.f.tobytes() == ref.f.tobytes() and got.i.tobytes() == ref.i.tobytes()
