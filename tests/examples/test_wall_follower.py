"""The example firmware a team copies (examples/firmware/wall_follower/): its own C unit tests,
its scenario tests through the pytest plugin (``--ffr-firmware``), ``ffr table1 --firmware``
beside ours, and its CI workflow file."""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
import yaml

REPO = Path(__file__).resolve().parents[2]
EXAMPLE = REPO / "examples" / "firmware" / "wall_follower"
# under CI the tools are there (a fresh machine has gcc and make; .ci/run installs the rest): missing fails
pytestmark = pytest.mark.skipif((shutil.which("cc") is None or shutil.which("make") is None)
                                and not os.environ.get("CI"), reason="needs a C compiler (cc) and make")


def _make(build: Path, *targets: str) -> str:
    p = subprocess.run(["make", "-s", "-C", str(EXAMPLE), f"BUILD={build}", *targets], capture_output=True,
                       text=True, timeout=300)
    assert p.returncode == 0, p.stdout + p.stderr
    return p.stdout


@pytest.fixture(scope="module")
def library(tmp_path_factory: pytest.TempPathFactory) -> Path:
    build = tmp_path_factory.mktemp("wf")
    _make(build, "lib")
    return build / "libwall_follower.so"


def test_its_c_unit_tests_pass_by_name(tmp_path: Path) -> None:
    out = _make(tmp_path, "test")
    names = re.findall(r"^ok (test_\w+) \((\d+) checks\)$", out, re.M)
    assert len(names) == 15 and all(int(n) > 0 for _, n in names), out
    assert "15 tests, 0 failed" in out and "FAIL" not in out


def test_it_meets_the_contract_with_its_own_config(library: Path) -> None:
    from ffr_link.abi import contract_hash
    from ffr_link.ctypes_link import default_config, firmware_info

    fw = firmware_info(str(library))
    assert fw.firmware_name == "wall_follower 0.1" and not fw.is_reference
    assert fw.layout_hash == contract_hash(fw)
    assert fw.state_names[0] == "IDLE" and {"FOLLOW", "SCAN", "DONE", "FAILED"} <= set(fw.state_names)
    assert fw.fail_names[:2] == ("", "no flame found")
    names = fw.config_dtype.names
    assert names is not None and "wall_mm" in names and "route" not in names  # its own, not ours
    cfg = default_config(str(library))
    assert float(cfg["wall_mm"]) == 190.0 and float(cfg["wheel_radius_mm"]) == 28.0


def test_its_scenario_tests_pass_through_the_plugin(library: Path, tmp_path: Path) -> None:
    env = {k: v for k, v in os.environ.items() if k != "FFR_FIRMWARE_LIB"}
    p = subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider",
                        str(EXAMPLE / "tests" / "test_missions.py"), "--ffr-firmware", str(library),
                        "--junitxml", str(tmp_path / "junit.xml"), "--ffr-failures", str(tmp_path / "failures")],
                       cwd=REPO, env=env, capture_output=True, text=True, timeout=600)
    assert p.returncode == 0, p.stdout[-3000:] + p.stderr[-2000:]
    assert re.search(r"\b6 passed\b", p.stdout), p.stdout[-2000:]
    junit = (tmp_path / "junit.xml").read_text()
    assert 'name="outcome" value="home"' in junit and f"ctypes:{library}" in junit
    assert "xunit2" not in p.stdout  # the plugin's properties work under pytest's default family


def test_table1_shows_the_example_beside_ours(library: Path) -> None:
    def table1(*args: str, status: int) -> str:
        p = subprocess.run([sys.executable, "-m", "harness", "table1", *args], cwd=REPO, capture_output=True,
                           text=True, timeout=600)
        assert p.returncode == status, p.stderr
        return p.stdout

    ours = table1(status=0)
    both = table1("--firmware", str(library), status=1)  # 1: a mission of the library's failed (room 1)
    first, _, second = both.partition("\n\n")
    assert first.startswith("ffr-reference ") and first.split("\n", 1)[1] == ours.rstrip("\n")
    assert second.startswith(f"wall_follower 0.1 ({library})\n")
    outcome = next(line for line in second.splitlines() if line.startswith("outcome")).split()[1:]
    assert outcome == ["error", "home", "home", "home"]  # room 1, the island room, is out of its reach


def test_the_ci_workflow_is_valid_yaml_and_runs_the_team_s_commands() -> None:
    wf = yaml.safe_load((EXAMPLE / "ci" / "github-workflow.yml").read_text())
    assert set(wf[True]) == {"push", "pull_request"}  # YAML 1.1 reads the key `on` as True
    steps = wf["jobs"]["missions"]["steps"]
    runs = [s.get("run", "") for s in steps]
    uses = [s.get("uses", "") for s in steps]
    assert any(r.startswith("python -m pip install") for r in runs)
    assert "make test" in runs and "ffr build --src . --out build" in runs
    tests = next(r for r in runs if "pytest tests/" in r)
    assert "--ffr-firmware build/libwall_follower.so" in tests and "--junitxml=out/junit.xml" in tests
    assert "--ffr-failures out/ffr-failures" in tests
    assert any("ffr run --scenario" in r and "--replay" in r for r in runs)
    artefacts = [s["with"]["path"] for s in steps if s.get("uses", "").startswith("actions/upload-artifact")]
    assert artefacts == ["out/junit.xml", "out/ffr-failures"]
    assert uses[0].startswith("actions/checkout") and any(u.startswith("actions/setup-python") for u in uses)


def test_readme_success_rates_are_what_the_sweep_prints(library: Path) -> None:
    """The example's README quotes its success rates; they are what its `ffr sweep` prints now."""
    readme = (EXAMPLE / "README.md").read_text(encoding="utf-8")
    rows = re.findall(r"^\| (\w+) \| (\d+) of (\d+) \(([\d.]+) %\) \|$", readme, re.M)
    assert [r[0] for r in rows] == ["none", "typical", "datasheet", "realistic", "harsh"]
    quoted = {noise: f"{n} missions: {ok} succeeded ({pct} %)" for noise, ok, n, pct in rows}
    both = re.search(r"\(`--rooms 1,2,3,4`, typical\): (\d+) of (\d+) \(([\d.]+) %\)", readme)
    assert both is not None
    # the fast ones here (a failing mission runs to its time limit: realistic and harsh take minutes)
    for noise, rooms, want in [*[(k, "2,3,4", quoted[k]) for k in ("none", "typical", "datasheet")],
                               ("typical", "1,2,3,4", f"{both[2]} missions: {both[1]} succeeded ({both[3]} %)")]:
        p = subprocess.run([sys.executable, "-m", "harness", "sweep", "--firmware", str(library), "--rooms", rooms,
                            "--candles", "random", "-n", "30", "--noise", noise, "--workers", "1", "--no-progress"],
                           cwd=REPO, capture_output=True, text=True, timeout=600)
        assert want in p.stdout, (noise, rooms, p.stdout[:400], p.stderr[-400:])


def _b2b(link: str, library: Path, env: dict[str, str]) -> str:
    p = subprocess.run([sys.executable, "-m", "harness", "b2b", "--room", "4", "--link", link, "--firmware",
                        str(library)], cwd=REPO, env=os.environ | env, capture_output=True, text=True, timeout=600)
    assert p.returncode == 0, p.stdout + p.stderr
    return p.stdout


def test_it_runs_unchanged_on_the_host_board(library: Path) -> None:
    """The same sources behind ffr's wire (codec, board link, host board): tick for tick the
    in-process library's mission."""
    board = library.parent / "ffr-host-board"
    _make(library.parent, "board")
    out = _b2b("host-board:serial", library, {"FFR_HOST_BOARD": str(board), "FFR_FIRMWARE_LIB": str(library)})
    assert "vs host-board:serial: identical" in out and "outcomes: home / home" in out


@pytest.mark.skipif((shutil.which("qemu-system-arm") is None or shutil.which("arm-none-eabi-gcc") is None)
                    and not os.environ.get("CI"),
                    reason="needs qemu-system-arm and arm-none-eabi-gcc (.ci/run installs them)")
def test_it_runs_unchanged_on_the_emulated_cortex_m4(library: Path) -> None:
    image = library.parent / "mps2-an386-board.elf"
    _make(library.parent, "qemu")
    out = _b2b("qemu:mps2-an386", library, {"FFR_QEMU_IMAGE": str(image), "FFR_FIRMWARE_LIB": str(library)})
    assert "vs qemu:mps2-an386: identical" in out and "outcomes: home / home" in out


def test_the_compiled_loop_and_the_python_loop_agree_on_it(library: Path) -> None:
    import numpy as np

    from harness.loop import run_mission
    from harness.scenario import make_scenario

    runs = [run_mission(make_scenario(room=3, seed=5, noise="typical"), f"ctypes:{library}", compiled=c)
            for c in (True, False)]
    (fast, tf), (slow, ts) = runs
    assert fast.outcome == slow.outcome == "home"
    assert np.array_equal(tf.f, ts.f) and np.array_equal(tf.i, ts.i)  # bit-identical traces
