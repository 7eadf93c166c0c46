"""The firmware's C sources as a Python package (``ffr_firmware``), so that an installed ffr (a
wheel, no checkout) carries them and builds its host library and host board on first use
(``build.py``). The C tree is the firmware; this file and build.py are only its shipping."""
