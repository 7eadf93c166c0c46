"""The whole suite runs each ``ffr`` command in its own process, as a user without a warm server
does: a developer's running ``ffr server`` must not carry the suite's commands (its forks would
change the process trees the sweep tests look at). tests/harness/test_server.py turns it back on
for the commands it sends to its own server.

A CI runner may start the suite with SIGINT ignored (a background job of a non-interactive
shell, ``nohup``): Python then installs no KeyboardInterrupt handler, and every command the
tests start inherits the ignored signal, so the tests of Ctrl-C would press it on processes
deaf to it (8 of them failed so on 30 Nov). What those tests are about is a terminal's Ctrl-C:
the suite runs with Python's own handler, and the commands it starts with the default
disposition (an exec resets a handled signal, not an ignored one)."""

import os
import signal

os.environ["FFR_NO_SERVER"] = "1"
if signal.getsignal(signal.SIGINT) is signal.SIG_IGN:
    signal.signal(signal.SIGINT, signal.default_int_handler)
