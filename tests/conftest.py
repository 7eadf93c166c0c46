"""The whole suite runs each ``ffr`` command in its own process, as a user without a warm server
does: a developer's running ``ffr server`` must not carry the suite's commands (its forks would
change the process trees the sweep tests look at). tests/harness/test_server.py turns it back on
for the commands it sends to its own server."""

import os

os.environ["FFR_NO_SERVER"] = "1"
