"""The replay in a real browser: headless Chromium opens the file, the 3D scene renders, the
controls move the robot, the cursor and the flame.

Needs Debian's ``chromium`` and the ``playwright`` package; skipped with the reason where they
are missing, except under CI (which installs them), where a missing browser is a failure.
"""

from __future__ import annotations

import io
import os
import time
from collections.abc import Iterator
from typing import Any

import numpy as np
import pytest

from ffr_link.ctypes_link import firmware_info
from harness.replay.browser import missing_reason, replay_page, show_time

BACKGROUND = np.array([0x15, 0x17, 0x1A])  # the page's and the scene's background


@pytest.fixture(scope="module")
def browser_page(room1) -> Iterator[tuple[Any, dict[str, list[str]]]]:
    reason = missing_reason()
    if reason:
        if os.environ.get("CI"):
            pytest.fail(f"CI must run the browser tests: {reason}")
        pytest.skip(reason)
    seen: dict[str, list[str]] = {"requests": [], "errors": []}

    def listen(page: Any) -> None:
        page.on("request", lambda req: seen["requests"].append(req.url))
        page.on("pageerror", lambda exc: seen["errors"].append(str(exc)))
        page.on("console", lambda msg: seen["errors"].append(msg.text) if msg.type == "error" else None)

    with replay_page(room1.html, before_load=listen) as page:
        yield page, seen


def _pixels(page: Any, selector: str) -> np.ndarray:
    from PIL import Image

    png = page.locator(selector).screenshot()
    return np.asarray(Image.open(io.BytesIO(png)).convert("RGB")).astype(np.int16)


def _js(page: Any, expr: str) -> Any:
    return page.evaluate(expr)


def _trace_by_uid(uid: str) -> str:
    return f"document.getElementById('view3d').data.find(d => d.uid === '{uid}')"


def test_opens_offline_without_errors(browser_page, room1) -> None:
    page, seen = browser_page
    assert _js(page, "window.ffrReplay.frames") == room1.data.n_frames
    # nothing but the file itself (and inline data: URLs) was requested
    assert seen["requests"], "the page's own load is a request"
    assert all(u.startswith(("file:", "data:", "blob:")) for u in seen["requests"]), seen["requests"]
    assert seen["errors"] == []


def test_the_3d_scene_renders(browser_page) -> None:
    page, _ = browser_page
    show_time(page, 5.0)
    assert _js(page, "document.querySelectorAll('#view3d canvas').length") > 0
    img = _pixels(page, "#view3d")
    h, w, _ = img.shape
    assert w > 400 and h > 300
    off_background = np.abs(img - BACKGROUND).sum(axis=2) > 40
    light = (img > 120).all(axis=2)  # the white walls and lines, lit and shaded
    assert off_background.mean() > 0.25, f"only {off_background.mean():.1%} of the scene differs from the background"
    assert light.mean() > 0.15, f"only {light.mean():.1%} of the scene is wall-white"
    assert img.std() > 25


def test_moving_the_slider_moves_the_robot(browser_page, room1) -> None:
    page, _ = browser_page
    fr = room1.data.frames
    positions = {}
    shots = {}
    for t in (2.0, 25.0):
        show_time(page, t)
        drawn = _js(page, "window.ffrReplay.robotXY()")
        hud = (float(page.inner_text("#ro-x")), float(page.inner_text("#ro-y")))
        want = (np.interp(t, fr["t"], fr["x"]), np.interp(t, fr["t"], fr["y"]))
        assert hud == pytest.approx(want, abs=1.5e-3)  # the readout shows the trace's pose
        assert np.hypot(drawn[0] - want[0], drawn[1] - want[1]) < 0.1  # and the robot is drawn there
        positions[t] = np.array(drawn)
        shots[t] = _pixels(page, "#view3d")
    assert np.hypot(*(positions[25.0] - positions[2.0])) > 0.3
    changed = (np.abs(shots[25.0] - shots[2.0]).sum(axis=2) > 40).mean()
    assert changed > 0.001, "the picture did not change"
    assert float(page.inner_text("#ro-t")) == pytest.approx(25.0)


def test_cursor_follows_time(browser_page) -> None:
    page, _ = browser_page
    xs = []
    for t in (1.0, 10.0, 30.0):
        show_time(page, t)
        box = page.locator("#cursor").bounding_box()
        assert box is not None
        xs.append(box["x"])
    assert xs[0] < xs[1] < xs[2]


def test_flame_goes_out(browser_page, room1) -> None:
    from harness.scoring import seconds_text

    page, _ = browser_page
    ext = room1.result.time_to_extinguish_s
    # the header prints the time as the table and the acceptance do
    assert f"flame out {seconds_text(ext)} s" in page.inner_text("#summary")
    show_time(page, ext - 1.0)
    assert _js(page, _trace_by_uid("flame") + ".visible") is True
    assert page.inner_text("#ro-flame") == "burning"
    assert page.inner_text("#ro-fan") == "on"  # the fans blow while it burns down
    blades_before = _js(page, _trace_by_uid("robot") + ".y.slice(-4)")
    show_time(page, ext - 0.5)
    blades_after = _js(page, _trace_by_uid("robot") + ".y.slice(-4)")
    assert blades_before != blades_after  # the fans turned (the robot stands still here)
    show_time(page, ext + 0.5)
    assert _js(page, _trace_by_uid("flame") + ".visible") is False
    assert page.inner_text("#ro-flame").startswith("out")


def test_play_speed_and_pause(browser_page) -> None:
    page, _ = browser_page
    show_time(page, 0.0)
    page.select_option("#speed", "4")
    start = time.monotonic()
    page.locator("#play").click()
    page.wait_for_timeout(1000)
    page.locator("#play").click()  # pause
    wall = time.monotonic() - start
    t = _js(page, "window.ffrReplay.t")
    # 4 simulated seconds per second of wall time, however few frames the renderer managed
    assert 4 * 0.5 < t < 4 * wall + 0.5, (t, wall)
    page.wait_for_timeout(400)
    assert _js(page, "window.ffrReplay.t") == t  # paused: time stands
    page.wait_for_function(f"window.ffrReplay.renderedT === {t}")
    assert page.inner_text("#ro-state") in firmware_info().state_names
    page.select_option("#speed", "1")


def test_views(browser_page) -> None:
    page, _ = browser_page
    show_time(page, 20.0)
    orbit = _pixels(page, "#view3d")
    page.locator("[data-view=top]").click()
    page.wait_for_function("document.getElementById('view3d').layout.scene.camera.projection.type === 'orthographic'")
    page.wait_for_timeout(500)
    top = _pixels(page, "#view3d")
    assert (np.abs(top - orbit).sum(axis=2) > 40).mean() > 0.05
    page.locator("[data-view=follow]").click()
    show_time(page, 22.0)
    c1 = _js(page, "document.getElementById('view3d').layout.scene.camera.center")
    show_time(page, 30.0)
    c2 = _js(page, "document.getElementById('view3d').layout.scene.camera.center")
    assert c1 != c2  # the camera follows the robot
    page.locator("[data-view=orbit]").click()
    page.wait_for_function("document.getElementById('view3d').layout.scene.camera.projection.type === 'perspective'")
