"""The ffr pytest plugin (registered through the ``pytest11`` entry point).

Fixtures:

* ``ffr_link``: the firmware link of the session, from ``--ffr-link URL``
  (default ``ctypes:``, the in-process host build; ``serial:...``,
  ``can:...``, ``host-board:...`` where those transports are installed).
* ``ffr_plant``: a factory, ``ffr_plant(scenario)`` -> a fresh ``Plant`` at the
  scenario's start pose.
* ``ffr_mission``: the mission runner, ``ffr_mission(scenario)`` ->
  ``(MissionResult, Trace)`` over ``ffr_link``, with the run options applied
  (``--ffr-seed``, ``--ffr-noise``, ``--ffr-set``), every mission's metrics
  recorded as JUnit properties, and, when the test fails, the one-line
  ``ffr run ...`` command that replays each of its missions.

Options: ``--ffr-link``, ``--ffr-firmware LIB.so`` (= ``--ffr-link ctypes:LIB.so``), ``--ffr-seed``,
``--ffr-noise``, ``--ffr-set KEY=VALUE``
(repeatable), ``--ffr-profile quick|thorough`` (the hypothesis profile of the
property tests), ``--ffr-failures DIR`` (where replay scenarios are written).

Markers: ``slow`` (whole missions), ``property`` (hypothesis over missions),
``hil`` (needs a wire link: deselected unless ``--ffr-link`` is one).
"""

from __future__ import annotations

import json
import os
import re
import shlex
from pathlib import Path
from typing import Any

import pytest

MARKERS = {
    "slow": "whole-mission tests (seconds each)",
    "property": "hypothesis property tests over whole missions",
    "hil": "needs a firmware link over a wire (serial:, can:, host-board:, qemu:); runs only with --ffr-link",
}

MAX_RECORDED = 20  # missions per test whose metrics go into the JUnit report
_REPLAYS = pytest.StashKey[list[tuple[Any, str, str]]]()


def pytest_addoption(parser: pytest.Parser) -> None:
    g = parser.getgroup("ffr", "ffr firmware-in-the-loop missions")
    g.addoption("--ffr-link", "--link", dest="ffr_link", default="ctypes:", metavar="URL",
                help="firmware link URL for every mission (default ctypes:), e.g. host-board:serial, "
                     "host-board:can, qemu:mps2-an386, qemu:netduinoplus2, qemu:microbit, serial:/dev/ttyACM0, "
                     "can:socketcan:can0")
    g.addoption("--ffr-firmware", dest="ffr_firmware", default=None, metavar="LIB.so",
                help="a firmware library to run in-process (the same as --ffr-link ctypes:LIB.so), e.g. a "
                     "team's build from `ffr build --src DIR`")
    g.addoption("--ffr-seed", type=int, default=None, metavar="N", help="seed for every mission (default: the test's)")
    g.addoption("--ffr-noise", default=None, metavar="PROFILE",
                help="noise profile for every mission (none, typical, datasheet, envelope, harsh, realistic, "
                     "FILE.toml)")
    g.addoption("--ffr-set", action="append", default=[], metavar="KEY=VALUE",
                help="firmware.NAME=V or robot.PATH=V for every mission (repeatable)")
    g.addoption("--ffr-profile", default=None, choices=("quick", "thorough"),
                help="hypothesis profile of the property tests (default quick, or $FFR_PROFILE)")
    g.addoption("--ffr-failures", default="out/ffr-failures", metavar="DIR",
                help="where the scenarios of failed missions are written (default out/ffr-failures)")


# The property tests' budgets. "quick" keeps `make test` short; "thorough" is
# `make test-thorough`. Derandomized: CI runs the same examples every time.
PROFILES: dict[str, dict[str, Any]] = {
    "quick": {"max_examples": 12, "derandomize": True},
    "thorough": {"max_examples": 150, "derandomize": True},
}
active_profile = "quick"


def pytest_configure(config: pytest.Config) -> None:
    global active_profile
    for name, text in MARKERS.items():
        config.addinivalue_line("markers", f"{name}: {text}")
    active_profile = config.getoption("--ffr-profile") or os.environ.get("FFR_PROFILE") or "quick"
    firmware = config.getoption("ffr_firmware", None)
    if firmware:  # --ffr-firmware LIB.so is --ffr-link ctypes:LIB.so (ffr's --firmware rule)
        link = config.getoption("ffr_link")
        if link not in ("ctypes:", f"ctypes:{firmware}"):
            raise pytest.UsageError(f"--ffr-firmware = {firmware!r}: runs in-process; leave --ffr-link {link} out")
        config.option.ffr_link = f"ctypes:{firmware}"
    if active_profile not in PROFILES:
        raise pytest.UsageError(f"FFR_PROFILE = {active_profile!r}: expected one of {', '.join(PROFILES)}")


def pytest_collection_modifyitems(config: pytest.Config, items: list[pytest.Item]) -> None:
    url = config.getoption("--ffr-link")
    if url.startswith("ctypes:"):
        keep, drop = [], []
        for it in items:
            (drop if it.get_closest_marker("hil") else keep).append(it)
        if drop:
            config.hook.pytest_deselected(items=drop)
            items[:] = keep


def _settings(config: pytest.Config) -> list[tuple[str, str, Any]]:
    from harness.cli_args import parse_setting  # the same parser as ffr's --set

    try:
        return [parse_setting(text, "--ffr-set") for text in config.getoption("--ffr-set")]
    except ValueError as exc:
        raise pytest.UsageError(str(exc)) from None


def pytest_report_header(config: pytest.Config) -> str | None:
    url = config.getoption("ffr_link")
    return None if url == "ctypes:" else f"ffr firmware link: {url}"


@pytest.fixture(autouse=True)
def _ffr_default_link(request: pytest.FixtureRequest, monkeypatch: pytest.MonkeyPatch):
    """With ``--ffr-link URL``, a test that runs a mission on the default link
    (``run_mission(scn)``) gets that URL instead; tests naming a link keep it."""
    url = request.config.getoption("ffr_link")
    if url != "ctypes:":
        import harness.loop
        from ffr_link import open_link

        opened: list[Any] = []

        def chosen(u: str):  # noqa: ANN202 - open_link's own signature
            link = open_link(url if u == "ctypes:" else u)
            opened.append((link, link.link_counters()))
            return link

        monkeypatch.setattr(harness.loop, "open_link", chosen)
        yield
        for link, before in opened:
            check_clean_link(link, link.link_counters() - before)
        return
    yield


def check_clean_link(link: Any, counters: Any) -> None:
    """A clean link is silent: without injected faults, any retry, CRC error, board error report
    or stale answer fails the test (recovery must never hide a defect)."""
    if not link.faults_injected and counters.errors:
        pytest.fail(f"{link.url}: a link without injected faults is not silent: {counters.errors} "
                    f"({counters.as_dict()})", pytrace=False)


@pytest.fixture(scope="session")
def ffr_link(pytestconfig: pytest.Config):
    """The session's firmware link (``--ffr-link``), opened once."""
    from ffr_link import LinkError, open_link
    url = pytestconfig.getoption("--ffr-link")
    try:
        link = open_link(url)
    except LinkError as exc:
        raise pytest.UsageError(str(exc)) from None
    yield link
    link.close()


@pytest.fixture
def ffr_plant():
    """``ffr_plant(scenario)``: a fresh plant at the scenario's start pose."""
    from sim_plant.plant import Plant

    def make(scn: Any) -> Any:
        return Plant(scn.arena, scn.robot, *scn.start, plant_dt=scn.timing.plant_dt_ms / 1000.0, source=scn.source)

    return make


def replay_command(scn: Any, link_url: str, failures_dir: str | Path | None) -> str | None:
    """One line of ``ffr run`` that replays the scenario: flags when they can say it all, else a
    scenario file written to ``failures_dir`` (None: don't write, return None)."""
    from harness.scenario import default_start, scenario_to_toml
    from sim_plant.arena import DEFAULT_ARENA
    from sim_plant.sensors import load_noise_profile

    noise_name = scn.noise.name
    named = False
    try:
        named = load_noise_profile(noise_name) == scn.noise if not noise_name.endswith(".toml") else False
    except Exception:  # noqa: BLE001 - an inline or file profile: not nameable
        named = False
    simple = (not scn.events and scn.start == default_start(scn.arena) and named and not scn.robot_file
              and not scn.arena_jitter
              and scn.arena.source == str(DEFAULT_ARENA) and not scn.stop_on_contact
              and scn.timing == type(scn.timing)())
    link = [] if link_url == "ctypes:" else ["--link", link_url]
    if simple:
        argv = ["ffr", "run", "--candle", f"{scn.candle[0]!r},{scn.candle[1]!r}", "--seed", str(scn.seed)]
        if scn.noise.enabled or scn.noise.reality.enabled:
            argv += ["--noise", noise_name]
        for group, d in (("firmware", scn.firmware), ("robot", scn.robot_overrides)):
            argv += [a for k, v in d.items() for a in ("--set", f"{group}.{k}={json.dumps(v)}")]
        return shlex.join(argv + link)
    if failures_dir is None:
        return None
    d = Path(failures_dir)
    d.mkdir(parents=True, exist_ok=True)
    path = d / (re.sub(r"[^A-Za-z0-9_.-]+", "_", scn.name) + ".replay.toml")
    path.write_text(scenario_to_toml(scn, comment="written by the ffr pytest plugin: a mission that failed"),
                    encoding="utf-8")
    return shlex.join(["ffr", "run", "--scenario", str(path), *link])


@pytest.fixture
def ffr_mission(request: pytest.FixtureRequest, ffr_link: Any):
    """``ffr_mission(scenario, record=True)`` -> (result, trace), with the run options applied."""
    from harness.loop import run_mission
    from sim_plant.robot import override
    from sim_plant.sensors import load_noise_profile

    config = request.config
    seed = config.getoption("--ffr-seed")
    noise = config.getoption("--ffr-noise")
    settings = _settings(config)
    replays: list[tuple[Any, str, str]] = []
    request.node.stash[_REPLAYS] = replays
    count = 0

    def record_property(name: str, value: object) -> None:
        # the test's user properties, which every reporter gets (JUnit XML writes them as
        # <property>); the record_property fixture would warn under pytest's default xunit2
        request.node.user_properties.append((name, value))

    def run(scn: Any, record: bool = True) -> tuple[Any, Any]:
        nonlocal count
        if seed is not None:
            scn.seed = seed
        if noise is not None:
            scn.noise = load_noise_profile(noise)
        for group, k, v in settings:
            if group == "firmware":
                scn.firmware[k] = v
            else:
                scn.robot = override(scn.robot, k, v, "--ffr-set")
                scn.robot_overrides[k] = v
        before = ffr_link.link_counters()
        res, trace = run_mission(scn, ffr_link, record=record)
        check_clean_link(ffr_link, ffr_link.link_counters() - before)
        count += 1
        prefix = "" if count == 1 else f"{count}."
        if count <= MAX_RECORDED:  # a property test runs hundreds: the report keeps the first ones
            for key, value in res.to_json().items():
                if key in ("final_pose", "candle"):
                    value = " ".join(str(v) for v in value)
                elif key == "link_counters":
                    value = " ".join(f"{k}={v}" for k, v in value.items())
                record_property(f"{prefix}{key}", value)
            cmd = replay_command(scn, ffr_link.url, None)  # a file only if the test fails
            if cmd:
                record_property(f"{prefix}replay", cmd)
        replays.append((scn, ffr_link.url, f"{scn.name}: {res.outcome}{' (' + res.detail + ')' if res.detail else ''}"))
        return res, trace

    def total() -> None:
        if count > 1:
            record_property("missions", count)

    request.addfinalizer(total)
    return run


@pytest.hookimpl(wrapper=True)
def pytest_runtest_makereport(item: pytest.Item, call: pytest.CallInfo[None]):
    report = yield
    if report.when == "call" and report.failed:
        missions = item.stash.get(_REPLAYS, [])
        if missions:
            where = item.config.getoption("--ffr-failures")
            # a property test runs many missions: the last ones are the (shrunk) failure
            shown = missions[-5:]
            lines = [f"{what} -> {replay_command(scn, url, where)}" for scn, url, what in shown]
            if len(missions) > len(shown):
                lines.insert(0, f"({len(missions)} missions in this test; the last {len(shown)}:)")
            report.sections.append(("ffr replay", "\n".join(lines)))
            # the last line of a failure is what a reader sees first: the command
            report.longrepr = f"{report.longrepr}\nffr replay: {lines[-1].rsplit(' -> ', 1)[-1]}"
    return report
