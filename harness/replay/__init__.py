"""The mission replay: one self-contained HTML file with the arena in 3D, the
robot driving its path, and its sensors and motor commands over time
(docs/replay.md)."""

from harness.replay.data import ReplayData, build_replay
from harness.replay.html import render_html, save_replay

__all__ = ["ReplayData", "build_replay", "render_html", "save_replay"]
