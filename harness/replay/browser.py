"""Open a replay in headless Chromium (Debian's ``chromium``, driven by Playwright).

Used by the browser tests and to take the README's picture:

    python -m harness.replay.browser out/replay_room1.html docs/img/replay.png --t 15 --view orbit

Playwright's own browser download does not work offline, so this drives the
system's Chromium (``FFR_CHROMIUM`` or ``/usr/bin/chromium``).
"""

from __future__ import annotations

import argparse
import os
import shutil
import sys
from collections.abc import Callable, Iterator, Sequence
from contextlib import contextmanager
from pathlib import Path
from typing import Any

CHROMIUM_FLAGS = (
    "--no-sandbox",  # root in CI
    "--disable-gpu",
    "--enable-unsafe-swiftshader",  # software WebGL for Plotly's 3D scene, no GPU here
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",  # no network: don't flood refused connections
    "--disable-component-update",
    "--disable-sync",
)
VIEWPORT = {"width": 1400, "height": 820}


def chromium_path() -> str | None:
    """The Chromium to drive, or None when there is none."""
    env = os.environ.get("FFR_CHROMIUM")
    if env:
        return env if os.path.exists(env) else None
    for name in ("chromium", "chromium-browser"):
        found = shutil.which(name)
        if found:
            return found
    return None


def missing_reason() -> str | None:
    """Why a browser cannot be driven here, or None when it can."""
    try:
        import playwright.sync_api  # noqa: F401
    except ImportError:
        return "the Python package 'playwright' is not installed (pip install -e '.[test]')"
    if chromium_path() is None:
        return "no Chromium found (apt-get install chromium, or set FFR_CHROMIUM)"
    return None


@contextmanager
def replay_page(html: str | Path, viewport: dict[str, int] | None = None,
                before_load: Callable[[Any], None] | None = None) -> Iterator[Any]:
    """A Playwright page with the replay loaded from its file:// URL and the player ready.
    ``before_load(page)`` runs before the page is opened (to listen to its requests, say)."""
    from playwright.sync_api import sync_playwright

    exe = chromium_path()
    if exe is None:
        raise RuntimeError(missing_reason() or "no Chromium")
    url = Path(html).resolve().as_uri()
    # Playwright gives the browser a fresh temporary profile (user-data-dir) of its own.
    with sync_playwright() as pw:
        browser = pw.chromium.launch(executable_path=exe, headless=True, args=list(CHROMIUM_FLAGS))
        try:
            page = browser.new_page(viewport=viewport or VIEWPORT)
            if before_load is not None:
                before_load(page)
            page.goto(url)
            page.wait_for_function("window.ffrReplay && window.ffrReplay.ready === true", timeout=60_000)
            yield page
        finally:
            browser.close()


def show_time(page: Any, t: float) -> None:
    """Move the time slider to t (s), as a user would, and wait until the scene is drawn there."""
    ms = int(round(t * 1000))
    page.locator("#slider").fill(str(ms))
    page.wait_for_function(f"Math.abs(window.ffrReplay.renderedT - {ms / 1000}) < 1e-9", timeout=30_000)


def screenshot(html: str | Path, png: str | Path, t: float | None = None, view: str = "orbit") -> None:
    """Save a PNG of the whole page at time t."""
    with replay_page(html) as page:
        if view != "orbit":
            page.locator(f"[data-view={view}]").click()
        show_time(page, 0.0 if t is None else t)
        page.wait_for_timeout(300)  # let the WebGL canvas settle after the last draw
        out = Path(png)
        out.parent.mkdir(parents=True, exist_ok=True)
        page.screenshot(path=str(out))


def main(argv: Sequence[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m harness.replay.browser", description=__doc__.splitlines()[0])
    ap.add_argument("html")
    ap.add_argument("png")
    ap.add_argument("--t", type=float, default=None, help="simulated time to show (s)")
    ap.add_argument("--view", choices=("orbit", "top", "follow"), default="orbit")
    args = ap.parse_args(argv)
    reason = missing_reason()
    if reason:
        print(f"error: {reason}", file=sys.stderr)
        return 2
    screenshot(args.html, args.png, args.t, args.view)
    return 0


if __name__ == "__main__":
    sys.exit(main())
