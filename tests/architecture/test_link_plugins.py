"""A team's own link is a pip package: a scheme registered only through an entry point of the
group ``ffr.links`` (no patch to ffr) is found by ``--link``, runs a whole mission, and a
plug-in that does not load is one line and exit 2."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]

# The plug-in: a link that counts its steps around the in-process library.
PLUGIN = '''
from ffr_link.ctypes_link import CtypesLink


class TeeLink(CtypesLink):
    """The host library, with every step also counted in a file (a stand-in for a team's transport)."""

    def __init__(self, url):
        super().__init__(None)
        self.log = url.partition(":")[2]

    def close(self):
        with open(self.log, "w") as fh:
            fh.write(str(self.steps))
        super().close()


def open_tee(url):
    return TeeLink(url)
'''


def _install(site: Path, scheme: str, target: str) -> None:
    """What ``pip install`` of a package with that entry point leaves on the path."""
    (site / "team_link").mkdir(parents=True)
    (site / "team_link" / "__init__.py").write_text(PLUGIN)
    info = site / "team_link-0.1.dist-info"
    info.mkdir()
    (info / "METADATA").write_text("Metadata-Version: 2.1\nName: team-link\nVersion: 0.1\n")
    (info / "entry_points.txt").write_text(f"[ffr.links]\n{scheme} = {target}\n")


def _ffr(site: Path, *args: str) -> subprocess.CompletedProcess[str]:
    env = os.environ | {"PYTHONPATH": os.pathsep.join([str(site), str(REPO)])}
    return subprocess.run([sys.executable, "-m", "harness", *args], cwd=REPO, env=env,
                          capture_output=True, text=True, timeout=120)


def test_a_scheme_installed_only_as_an_entry_point_runs_a_mission(tmp_path) -> None:
    _install(tmp_path / "site", "tee", "team_link:open_tee")
    log = tmp_path / "steps.txt"
    p = _ffr(tmp_path / "site", "run", "--room", "1", "--link", f"tee:{log}", "--json", "-")
    assert p.returncode == 0, p.stderr
    res = json.loads(p.stdout)
    assert res["outcome"] == "home" and res["link"] == f"tee:{log}"
    # the Python loop ran through the plug-in (a subclass never takes the compiled loop)
    assert int(log.read_text()) == res["link_counters"]["sent"] > 1000


def test_the_known_schemes_name_an_installed_plug_in(tmp_path) -> None:
    _install(tmp_path / "site", "tee", "team_link:open_tee")
    p = _ffr(tmp_path / "site", "run", "--room", "1", "--link", "teee:")
    assert p.returncode == 2 and p.stdout == ""
    assert p.stderr.count("\n") == 1 and "unknown scheme 'teee'" in p.stderr and "'tee'" in p.stderr


def test_a_plug_in_that_does_not_load_is_one_line_and_exit_2(tmp_path) -> None:
    _install(tmp_path / "site", "broken", "team_link:no_such_factory")
    p = _ffr(tmp_path / "site", "run", "--room", "1", "--link", "broken:")
    assert p.returncode == 2 and p.stdout == ""
    assert p.stderr.count("\n") == 1 and "team_link:no_such_factory" in p.stderr and "Traceback" not in p.stderr


def test_the_shipped_schemes_are_entry_points_too() -> None:
    from importlib.metadata import entry_points

    names = {ep.name for ep in entry_points(group="ffr.links")}
    assert {"ctypes", "serial", "can", "host-board", "qemu"} <= names
