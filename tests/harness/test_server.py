"""``ffr server``: a warm process runs ``ffr`` commands by forking (harness/server.py, harness/launch.py).

A served command must be indistinguishable from the same command run in its own process: the same
bytes out, the same exit status, the caller's directory and environment, Ctrl-C reaching it, and
never code older than the files on disk."""

from __future__ import annotations

import json
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from collections.abc import Iterator
from pathlib import Path

import pytest

from harness.server_wire import fingerprint

REPO = Path(__file__).resolve().parents[2]
PY = sys.executable


def _env(server_dir: str, **extra: str) -> dict[str, str]:
    env = {k: v for k, v in os.environ.items() if k != "FFR_NO_SERVER"}
    env["FFR_SERVER_DIR"] = server_dir
    env.update(extra)
    return env


def _ffr(env: dict[str, str], *args: str, cwd: Path = REPO, timeout: float = 300) -> subprocess.CompletedProcess:
    return subprocess.run([PY, "-m", "harness", *args], cwd=cwd, env=env, capture_output=True, text=True,
                          timeout=timeout)


def _status(env: dict[str, str]) -> dict:
    """What the one server in the test's directory says of itself (asked directly: this pytest
    process's import path differs from the commands', so its fingerprint would too)."""
    from harness.server import _request

    (sock,) = Path(env["FFR_SERVER_DIR"]).glob("*.sock")
    info = _request(sock, {"op": "status"})
    assert info is not None
    return info


@pytest.fixture(scope="module")
def served() -> Iterator[dict[str, str]]:
    d = tempfile.mkdtemp(prefix="ffrs", dir="/tmp")  # short: a socket's path has at most 107 bytes
    env = _env(d)
    r = _ffr(env, "server", "start")
    assert r.returncode == 0, r.stderr
    assert "ready" in r.stdout
    try:
        yield env
    finally:
        _ffr(env, "server", "stop")
        shutil.rmtree(d, ignore_errors=True)


def _cold(env: dict[str, str]) -> dict[str, str]:
    return {**env, "FFR_NO_SERVER": "1"}


def test_a_served_mission_prints_the_bytes_of_one_run_in_its_own_process(served: dict[str, str]) -> None:
    before = _status(served)["served"]
    warm = _ffr(served, "run", "--room", "2", "--noise", "typical", "--seed", "3", "--json", "-")
    cold = _ffr(_cold(served), "run", "--room", "2", "--noise", "typical", "--seed", "3", "--json", "-")
    assert (warm.returncode, warm.stdout, warm.stderr) == (cold.returncode, cold.stdout, cold.stderr)
    assert warm.returncode == 0 and json.loads(warm.stdout)["outcome"] == "home"
    assert _status(served)["served"] == before + 1  # it went through the server; the cold one did not


def test_a_served_table1_is_the_table_of_its_own_process(served: dict[str, str]) -> None:
    warm = _ffr(served, "table1", "--json", "-")
    cold = _ffr(_cold(served), "table1", "--json", "-")
    assert warm.returncode == cold.returncode == 0
    assert warm.stdout == cold.stdout


def test_bad_input_through_the_server_is_the_same_one_line_and_exit_2(served: dict[str, str]) -> None:
    warm = _ffr(served, "run", "--room", "9")
    cold = _ffr(_cold(served), "run", "--room", "9")
    assert warm.returncode == cold.returncode == 2
    assert warm.stderr == cold.stderr and warm.stderr.count("\n") == 1 and "room = 9" in warm.stderr


def test_a_served_command_works_in_the_callers_directory_with_its_environment(
        served: dict[str, str], tmp_path: Path) -> None:
    before = _status(served)["served"]
    r = _ffr(served, "run", "--room", "1", "--json", "out.json", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    assert _status(served)["served"] == before + 1  # served, though `python -m` put another directory first
    assert json.loads((tmp_path / "out.json").read_text())["outcome"] == "home"
    missing = tmp_path / "nowhere" / "libffr.so"
    r = _ffr({**served, "FFR_FIRMWARE_LIB": str(missing)}, "run", "--room", "1")
    assert r.returncode == 2 and str(missing) in r.stderr  # the caller's variable, not the server's
    assert _status(served)["served"] == before + 2


def _long_sweep(env: dict[str, str], out: Path) -> subprocess.Popen:
    return subprocess.Popen([PY, "-m", "harness", "sweep", "-n", "200", "--seeds", "0:20", "--workers", "1",
                             "--no-progress", "--out", str(out)], cwd=REPO, env=env, text=True,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE)


def _wait_rows(out: Path, proc: subprocess.Popen) -> None:
    for _ in range(600):
        if out.exists() and out.read_text().count("\n") >= 3:
            return
        assert proc.poll() is None, proc.communicate()
        time.sleep(0.1)
    raise AssertionError("the sweep wrote no rows in 60 s")


def test_ctrl_c_reaches_a_served_sweep_which_keeps_its_finished_rows(served: dict[str, str], tmp_path: Path) -> None:
    out = tmp_path / "s.csv"
    proc = _long_sweep(served, out)
    _wait_rows(out, proc)
    proc.send_signal(signal.SIGINT)
    _, err = proc.communicate(timeout=120)
    assert proc.returncode == 130, err
    assert "ffr: interrupted:" in err and "kept in" in err


def test_a_caller_killed_takes_its_command_with_it(served: dict[str, str], tmp_path: Path) -> None:
    out = tmp_path / "s.csv"
    proc = _long_sweep(served, out)
    _wait_rows(out, proc)
    children = _status(served)["children"]
    assert len(children) == 1
    proc.kill()
    proc.communicate()
    for _ in range(300):
        if children[0] not in _status(served)["children"]:
            break
        time.sleep(0.1)
    assert _status(served)["children"] == []
    with pytest.raises(ProcessLookupError):
        os.kill(children[0], 0)


def test_a_command_killed_by_a_signal_kills_its_caller_with_it(served: dict[str, str], tmp_path: Path) -> None:
    out = tmp_path / "s.csv"
    proc = _long_sweep(served, out)
    _wait_rows(out, proc)
    (child,) = _status(served)["children"]
    os.kill(child, signal.SIGKILL)
    proc.communicate(timeout=60)
    assert proc.returncode == -signal.SIGKILL  # as the shell would have seen of the command itself


def test_other_code_or_settings_are_never_served_by_a_server_of_the_old_ones(served: dict[str, str]) -> None:
    before = _status(served)["served"]
    r = _ffr({**served, "NUMBA_OPT": "2"}, "run", "--room", "1")  # numba's settings: another fingerprint
    assert r.returncode == 0, r.stderr
    assert _status(served)["served"] == before


def test_the_fingerprint_follows_every_python_file_and_numbas_settings(tmp_path: Path) -> None:
    pkg = tmp_path / "pkg"
    (pkg / "sub").mkdir(parents=True)
    (pkg / "a.py").write_text("x = 1\n")
    (pkg / "sub" / "b.py").write_text("y = 1\n")
    fp = fingerprint([pkg], {})
    assert fingerprint([pkg], {}) == fp
    os.utime(pkg / "sub" / "b.py", ns=(1, 1))  # an edit: its mtime changes
    fp2 = fingerprint([pkg], {})
    assert fp2 != fp
    (pkg / "c.py").write_text("")  # a new module
    fp3 = fingerprint([pkg], {})
    assert fp3 != fp2
    assert fingerprint([pkg], {"NUMBA_OPT": "0"}) != fp3
    assert fingerprint([pkg], {"UNRELATED": "1"}) == fp3


def test_an_idle_server_ends_by_itself_and_status_says_so() -> None:
    d = tempfile.mkdtemp(prefix="ffri", dir="/tmp")
    env = _env(d)
    try:
        r = _ffr(env, "server", "start", "--idle", "1")
        assert r.returncode == 0, r.stderr
        # start says ready only once the server answered a status request (harness/server.py); a
        # separate `ffr server status` here raced the 1 s idle on a loaded CPU (its own Python start
        # took longer, and it found the server already gone)
        assert r.stdout.startswith("ffr server: ready (pid "), r.stdout
        deadline = time.monotonic() + 60.0  # a bound for a hang, not a speed goal
        while list(Path(d).glob("*.sock")) and time.monotonic() < deadline:
            time.sleep(0.1)
        assert not list(Path(d).glob("*.sock"))
        assert _ffr(env, "server", "status").stdout.startswith("no server")
        r = _ffr(env, "run", "--room", "1")  # no server: the command runs in its own process
        assert r.returncode == 0, r.stderr
    finally:
        _ffr(env, "server", "stop")
        shutil.rmtree(d, ignore_errors=True)


def test_stop_ends_the_server_and_commands_run_in_their_own_process_again() -> None:
    d = tempfile.mkdtemp(prefix="ffrt", dir="/tmp")
    env = _env(d)
    try:
        assert _ffr(env, "server", "start").returncode == 0
        assert _ffr(env, "server", "start").stdout.startswith("ffr server: already running")
        r = _ffr(env, "server", "stop")
        assert r.stdout.strip() == "ffr server: stopped 1 server"
        deadline = time.monotonic() + 60.0  # a bound for a hang on a loaded CPU, not a speed goal
        while list(Path(d).glob("*.sock")) and time.monotonic() < deadline:
            time.sleep(0.1)
        assert not list(Path(d).glob("*.sock"))
        assert _ffr(env, "run", "--room", "1").returncode == 0
    finally:
        _ffr(env, "server", "stop")
        shutil.rmtree(d, ignore_errors=True)


@pytest.mark.parametrize("value", ["-1", "0", "soon", "inf"])
def test_a_bad_idle_time_is_one_line_and_exit_2(value: str) -> None:
    r = _ffr(_env("/tmp/ffr-unused-server-dir"), "server", "start", "--idle", value)
    assert r.returncode == 2
    assert r.stderr.count("\n") == 1 and "--idle" in r.stderr and value in r.stderr
    assert not Path("/tmp/ffr-unused-server-dir").exists()


def test_a_server_dir_too_long_for_a_socket_is_one_line_and_exit_2(tmp_path: Path) -> None:
    long_dir = tmp_path / ("d" * 120)
    r = _ffr(_env(str(long_dir)), "server", "start")
    assert r.returncode == 2
    assert r.stderr.count("\n") == 1 and "FFR_SERVER_DIR" in r.stderr
