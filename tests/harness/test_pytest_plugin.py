"""The ffr pytest plugin: options, fixtures, markers, JUnit properties, the replay line on failure."""

from __future__ import annotations

import xml.etree.ElementTree as ET

import pytest

pytest_plugins = ["pytester"]

TEST_FILE = '''
import pytest
from harness.scenario import make_scenario

def test_home(ffr_mission, ffr_plant):
    scn = make_scenario(room=1)
    assert ffr_plant(scn).x == scn.start[0]
    res, _ = ffr_mission(scn, record=False)
    assert res.outcome == "home"

def test_breaks(ffr_mission):
    scn = make_scenario(room=2)
    scn.firmware["front_stop_mm"] = 60
    res, _ = ffr_mission(scn, record=False)
    assert res.outcome == "home"

@pytest.mark.hil
def test_needs_a_wire(ffr_link):
    assert not ffr_link.url.startswith("ctypes")
'''


def test_plugin_is_registered_by_entry_point(pytestconfig) -> None:
    assert pytestconfig.pluginmanager.has_plugin("ffr")
    names = {line.split(":")[0] for line in pytestconfig.getini("markers")}
    assert {"slow", "hil", "property"} <= names


def test_fixtures_properties_and_replay(pytester: pytest.Pytester) -> None:
    pytester.makepyfile(test_it=TEST_FILE)
    xml = pytester.path / "j.xml"
    # pytest's defaults (junit_family xunit2, as in a team's repository), warnings as errors
    res = pytester.runpytest_subprocess("-p", "no:cacheprovider", f"--junitxml={xml}", "-W", "error")
    res.assert_outcomes(passed=1, failed=1, deselected=1)  # hil: deselected on the ctypes: link
    out = res.stdout.str()
    assert "warning" not in out.lower(), out
    assert "ffr replay: ffr run --candle 0.62,2.32 --seed 0 --set firmware.front_stop_mm=60" in out
    cases = {c.get("name"): c for c in ET.parse(xml).getroot().iter("testcase")}
    props = {p.get("name"): p.get("value") for p in cases["test_home"].iter("property")}
    assert props["outcome"] == "home" and float(props["total_time_s"]) > 10
    assert props["wall_contacts"] == "0" and props["replay"].startswith("ffr run --candle 1.83,1.53")


def test_run_options_reach_the_missions(pytester: pytest.Pytester) -> None:
    pytester.makepyfile(test_opts='''
from harness.scenario import make_scenario

def test_opts(ffr_mission, record_property):
    scn = make_scenario(room=1)
    scn.timing.find_limit_s = 2.0
    res, _ = ffr_mission(scn, record=False)
    assert scn.seed == 7 and scn.noise.name == "typical"
    assert scn.firmware == {"cruise_speed_mm_s": 250} and scn.robot.motor.R == 7.0
''')
    res = pytester.runpytest_subprocess("-p", "no:cacheprovider", "--ffr-seed", "7", "--ffr-noise", "typical",
                                        "--ffr-set", "firmware.cruise_speed_mm_s=250",
                                        "--ffr-set", "robot.motor.R=7.0")
    res.assert_outcomes(passed=1)


def test_bad_link_is_a_usage_error(pytester: pytest.Pytester) -> None:
    pytester.makepyfile(test_l="def test_l(ffr_link):\n    pass\n")
    res = pytester.runpytest_subprocess("-p", "no:cacheprovider", "--ffr-link", "nonsense:x")
    assert res.ret != 0 and "nonsense" in res.stderr.str() + res.stdout.str()
