"""ffr as a tool installed from a wheel: built from this tree, installed in a new virtual
environment in a temporary directory, run from outside the source tree. It carries its arena,
robot and noise data and the firmware's sources, and compiles its host library and host board on
first use into the user's cache (firmware/build.py): the same missions as the checkout's build."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import sysconfig
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
EXAMPLE = REPO / "examples" / "firmware" / "wall_follower"


@pytest.fixture(scope="module")
def installed(tmp_path_factory) -> tuple[Path, dict[str, str]]:
    tmp = tmp_path_factory.mktemp("wheel")
    subprocess.run([sys.executable, "-m", "pip", "wheel", str(REPO), "--no-deps", "-q", "-w", str(tmp / "dist")],
                   check=True, capture_output=True, timeout=600)
    wheel = next((tmp / "dist").glob("ffr-*.whl"))
    venv = tmp / "venv"
    subprocess.run([sys.executable, "-m", "venv", str(venv)], check=True, timeout=120)
    subprocess.run([str(venv / "bin" / "python"), "-m", "pip", "install", "-q", "--no-deps", str(wheel)],
                   check=True, capture_output=True, timeout=300)
    # the pinned dependencies are borrowed from this environment (a path, not its .pth files, so
    # the checkout's editable ffr stays out); ffr itself comes only from the wheel
    site = next((venv / "lib").glob("python3*/site-packages"))
    (site / "borrowed_deps.pth").write_text(sysconfig.get_paths()["purelib"] + "\n")
    env = {k: v for k, v in os.environ.items() if not k.startswith(("FFR_", "PYTHON"))}
    env |= {"FFR_CACHE": str(tmp / "cache"), "HOME": str(tmp)}
    work = tmp / "team"
    work.mkdir()
    return venv, env | {"_CWD": str(work)}


def _run(installed: tuple[Path, dict[str, str]], exe: str, *args: str,
         cwd: Path | None = None) -> subprocess.CompletedProcess[str]:
    venv, env = installed
    where = cwd or env["_CWD"]
    env = {k: v for k, v in env.items() if k != "_CWD"}
    return subprocess.run([str(venv / "bin" / exe), *args], cwd=where, env=env, capture_output=True, text=True,
                          timeout=600)


def _ffr(installed: tuple[Path, dict[str, str]], *args: str, cwd: Path | None = None
         ) -> subprocess.CompletedProcess[str]:
    return _run(installed, "ffr", *args, cwd=cwd)


def test_the_installed_ffr_comes_from_the_wheel_not_the_checkout(installed) -> None:
    venv, env = installed
    p = subprocess.run([str(venv / "bin" / "python"), "-c",
                        "import harness, ffr_firmware, sim_plant; print(harness.__file__, ffr_firmware.__file__)"],
                       cwd=env["_CWD"], env={k: v for k, v in env.items() if k != "_CWD"},
                       capture_output=True, text=True, timeout=120)
    assert p.returncode == 0, p.stderr
    assert str(REPO) not in p.stdout and "site-packages" in p.stdout


def test_the_installed_ffr_runs_the_checkouts_missions(installed) -> None:
    p = _ffr(installed, "table1", "--json", "t1.json")
    assert p.returncode == 0, p.stderr
    got = json.loads((Path(installed[1]["_CWD"]) / "t1.json").read_text())
    mine = Path(installed[1]["_CWD"]) / "here.json"
    here = subprocess.run([sys.executable, "-m", "harness", "table1", "--json", str(mine)], cwd=REPO,
                          capture_output=True, text=True, timeout=600)
    assert here.returncode == 0, here.stderr
    assert [r["outcome"] for r in got] == ["home"] * 4
    assert got == json.loads(mine.read_text())  # same firmware, same flags, same bits
    cache = Path(installed[1]["FFR_CACHE"])
    assert len(list(cache.glob("*/libffr.so"))) == 1  # built once, on first use


def test_the_installed_ffr_runs_its_host_board_and_builds_a_firmware(installed) -> None:
    p = _ffr(installed, "run", "--room", "1", "--link", "host-board:serial", "--json", "-")
    assert p.returncode == 0, p.stderr
    res = json.loads(p.stdout)
    assert res["outcome"] == "home" and res["link_counters"]["retries"] == 0
    p = _ffr(installed, "build", "--out", "fw")
    assert p.returncode == 0, p.stderr
    lib = Path(installed[1]["_CWD"]) / "fw" / "libffr.so"
    assert "library: fw/libffr.so" in p.stdout and lib.exists()
    p = _ffr(installed, "run", "--room", "1", "--firmware", str(lib), "--json", "-")
    assert p.returncode == 0 and json.loads(p.stdout)["outcome"] == "home", p.stderr


def test_a_team_builds_and_tests_the_example_firmware_with_the_installed_ffr(installed) -> None:
    """Issue 16's end to end: the example firmware copied out of the tree, as a team's repository
    holds it; the installed ffr builds it (`ffr build --src`), its C tests run against the header
    the wheel ships, and its scenario tests pass through the installed pytest plugin."""
    team = Path(installed[1]["_CWD"]) / "wall_follower"
    shutil.copytree(EXAMPLE, team, ignore=shutil.ignore_patterns("build", "out", "__pycache__"))
    p = _ffr(installed, "build", "--src", ".", "--out", "build", cwd=team)
    assert p.returncode == 0, p.stderr
    assert "library: build/libwall_follower.so" in p.stdout and (team / "build" / "libwall_follower.so").exists()
    venv = installed[0]
    make = subprocess.run(["make", "-s", "test", f"PYTHON={venv / 'bin' / 'python'}"], cwd=team,
                          env={k: v for k, v in installed[1].items() if k != "_CWD"}, capture_output=True,
                          text=True, timeout=300)
    assert make.returncode == 0 and "15 tests, 0 failed" in make.stdout, make.stdout + make.stderr
    p = _run(installed, "python", "-m", "pytest", "-q", "-p", "no:cacheprovider", "tests/test_missions.py",
             "--ffr-firmware", "build/libwall_follower.so", "--junitxml", "out/junit.xml", cwd=team)
    assert p.returncode == 0, p.stdout[-3000:] + p.stderr[-2000:]
    assert "6 passed" in p.stdout and "warning" not in p.stdout.lower(), p.stdout[-2000:]
    assert 'name="outcome" value="home"' in (team / "out" / "junit.xml").read_text()
