"""pytest option ``--link URL``: run every mission of the test suite over that
firmware link instead of the in-process ``ctypes:`` (e.g. ``pytest
tests/scenario --link host-board:serial``). Enabled in pyproject.toml.

A test that opens the default link (``run_mission(scn)``) gets the chosen one;
tests that name a link themselves keep it.
"""

from __future__ import annotations

from collections.abc import Iterator

import pytest


def pytest_addoption(parser: pytest.Parser) -> None:
    parser.addoption("--link", default=None, metavar="URL",
                     help="firmware link for every mission (default ctypes:), e.g. host-board:serial, "
                          "host-board:can, serial:/dev/ttyACM0, can:socketcan:can0")


def pytest_report_header(config: pytest.Config) -> str | None:
    url = config.getoption("--link")
    return f"ffr firmware link: {url}" if url else None


@pytest.fixture(autouse=True)
def _ffr_link(request: pytest.FixtureRequest, monkeypatch: pytest.MonkeyPatch) -> Iterator[None]:
    url = request.config.getoption("--link")
    if url:
        import harness.loop
        from harness.links.base import open_link

        def chosen(u: str):  # noqa: ANN202 - the harness's own signature
            return open_link(url if u == "ctypes:" else u)

        monkeypatch.setattr(harness.loop, "open_link", chosen)
    yield
