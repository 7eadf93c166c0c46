"""``qemu:<machine>``: a board build of the firmware on an emulated board.

``qemu:mps2-an386`` (Cortex-M4F), ``qemu:netduinoplus2`` (STM32F405,
Cortex-M4F) and ``qemu:microbit`` (nRF51822, Cortex-M0, soft float) start
``qemu-system-arm -M <machine>`` with the board image
(``build/arm/<machine>-board.elf``: firmware, codec and board link behind
the board's UART), connect the serial link to that UART through a loopback
socket, and run the mission exactly as over a real serial port. The
mps2-an386 also has an Ethernet controller, its default transport
(``#transport=eth``; ``#transport=uart`` for the UART): one link frame per
Ethernet frame, carried by QEMU's ``-netdev dgram`` as one datagram on a
local socket (``hil_bridge/datagram_link.py``): several times faster a
tick than the UART, whose model hands over one byte at a time (make bench
prints both; docs/pil.md, "Speed").

QEMU runs with ``-icount shift=0``: every guest instruction is one
nanosecond of virtual time, so the board's free-running timer readings
around each ``ffr_step`` count instructions (``Machine.insn_per_count``:
40 for the mps2's 25 MHz timer, 1 for the STM32's TIM2 which QEMU clocks at
1 GHz, 62.5 for the nRF51's 16 MHz TIMER0). The board writes that profile to
its second UART (or, on the one-UART nRF51, semihosting), which goes to a
file the link reads when it closes (``QemuLink.profile``). QEMU never
outlives the link: ``close()`` ends it (terminate, then kill), it is killed
with its parent (PR_SET_PDEATHSIG), and Ctrl-C reaches the CLI's ``finally``
that closes the link.
"""

from __future__ import annotations

import ctypes
import os
import re
import shutil
import signal
import socket
import subprocess
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

from ffr_link.base import LinkError
from hil_bridge.child_process import describe_exit, stop_process
from hil_bridge.datagram_link import DatagramLink
from hil_bridge.options import WireOptions, parse_url, simulated_board
from hil_bridge.owned_board import OwnsItsBoard
from hil_bridge.serial_link import SerialLink

REPO = Path(__file__).resolve().parents[1]
_PR_SET_PDEATHSIG = 1


@dataclass(frozen=True)
class Machine:
    """One emulated board: its image, where its profile goes, what a timer count is."""

    elf: Path
    insn_per_count: float  # -icount shift=0: one instruction per ns of virtual time
    profile_on: str  # "serial1": the board's second UART; "semihosting": SYS_WRITE0
    cpu_hz: int  # the real chip's clock (make bench: the load at that clock)
    cycles_per_insn: float  # assumed for the load estimate
    # the link's transports, the default first: "uart" (the board's UART on a loopback TCP
    # socket), "eth" (its Ethernet controller, one frame a datagram: hil_bridge/datagram_link.py)
    transports: tuple[str, ...] = ("uart",)


def _elf(name: str) -> Path:
    return REPO / "build" / "arm" / f"{name}-board.elf"


def board_image(machine: str, default: Path) -> Path:
    """The image to boot: ``$FFR_QEMU_IMAGE``; else the one built beside the host build the other
    links run (``$FFR_FIRMWARE_LIB``/``$FFR_HOST_BOARD``: the same directory, or ``../arm/`` of a
    ``build/host/``), so a second checkout sharing this install compares its own build with itself;
    else this checkout's ``build/arm/``."""
    env = os.environ.get("FFR_QEMU_IMAGE")
    if env:
        return Path(env)
    name = f"{machine}-board.elf"
    for var in ("FFR_FIRMWARE_LIB", "FFR_HOST_BOARD"):
        host = os.environ.get(var)
        if not host:
            continue
        where = Path(host).resolve().parent
        for image in (where / name, where.parent / "arm" / name):
            if image.exists() and image.resolve() != default.resolve():
                return image
    return default


MACHINES = {
    # CMSDK timer 0 on the 25 MHz clock: 40 ns, 40 instructions a count
    # its LAN9118 Ethernet is the default link (docs/pil.md, "Speed"), #transport=uart the UART
    "mps2-an386": Machine(_elf("mps2-an386"), 40.0, "serial1", 25_000_000, 1.25, ("eth", "uart")),
    # TIM2, PSC 0: QEMU clocks the STM32F2xx/F4xx timers at 1 GHz, one instruction a count
    "netduinoplus2": Machine(_elf("netduinoplus2"), 1.0, "serial1", 168_000_000, 1.25),
    # TIMER0 at 16 MHz: 62.5 ns, 62.5 instructions a count; one UART, so the profile goes by semihosting
    "microbit": Machine(_elf("microbit"), 62.5, "semihosting", 16_000_000, 1.5),
}


@dataclass(frozen=True)
class StepProfile:
    steps: int
    mean_insn: float
    max_insn: int
    rx_overruns: int  # bytes the board's UART lost before its driver read them: 0 on a sound board


def _die_with_parent() -> None:  # runs in the child between fork and exec
    libc = ctypes.CDLL(None, use_errno=True)
    libc.prctl(_PR_SET_PDEATHSIG, signal.SIGKILL, 0, 0, 0)


def _free_port() -> int:
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


class QemuBoard:
    """qemu-system-arm running a board image, the link on its UART0 (a loopback TCP socket) or
    its Ethernet (datagrams on a local socket: ``eth_sock`` is QEMU's end, ``host_sock`` ours)."""

    def __init__(self, machine: str, spec: Machine, log: str = "", transport: str = "uart") -> None:
        elf = board_image(machine, spec.elf)  # a team's image, or another checkout's (docs/teams.md)
        qemu = shutil.which("qemu-system-arm")
        if qemu is None:
            raise LinkError(f"qemu:{machine}: qemu-system-arm not found (apt-get install qemu-system-arm)")
        if not elf.exists():
            raise LinkError(f"qemu:{machine}: board image {elf} not found: build it with `make firmware-boards`")
        self.machine = machine
        self.spec = spec
        self.transport = transport
        self.tmp = Path(tempfile.mkdtemp(prefix="ffr-qemu-"))
        self.profile_path = self.tmp / "profile.log"
        self.eth_sock, self.host_sock = self.tmp / "board.sock", self.tmp / "host.sock"
        self._log = open(log, "ab") if log else None  # noqa: SIM115 - closed in stop()
        cmd = [qemu, "-M", machine, "-nographic", "-monitor", "none", "-icount", "shift=0",
               "-kernel", str(elf)]
        if transport == "eth":
            # every Ethernet frame the board sends is one datagram to host_sock, and back
            self.port = 0
            cmd += ["-netdev", f"dgram,id=eth,local.type=unix,local.path={self.eth_sock},"
                               f"remote.type=unix,remote.path={self.host_sock}",
                    "-net", "nic,netdev=eth,model=lan9118", "-serial", "null"]
        else:
            self.port = _free_port()
            cmd += ["-nic", "none",
                    "-chardev", f"socket,id=link,host=127.0.0.1,port={self.port},server=on,wait=on,nodelay=on",
                    "-serial", "chardev:link"]
        if spec.profile_on == "semihosting":
            cmd += ["-chardev", f"file,id=prof,path={self.profile_path}",
                    "-semihosting-config", "enable=on,target=native,chardev=prof"]
        else:
            cmd += ["-serial", f"file:{self.profile_path}"]
        self.proc = subprocess.Popen(cmd, stdin=subprocess.DEVNULL, stdout=self._log or subprocess.DEVNULL,
                                     stderr=self._log or subprocess.DEVNULL, close_fds=True,
                                     preexec_fn=_die_with_parent)  # noqa: PLW1509 - prctl only

    def gone(self, wait_s: float = 0.0) -> str | None:
        return describe_exit(self.proc, f"qemu-system-arm ({self.machine}, pid {self.proc.pid})", wait_s)

    def ready(self) -> bool:
        """The board has started and its link UART listens (its "ffr-board ready" log line)."""
        try:
            return b"ffr-board ready" in self.profile_path.read_bytes()
        except OSError:
            return False

    def profile(self) -> StepProfile | None:
        try:
            text = self.profile_path.read_text(errors="replace")
        except OSError:
            return None
        found = re.findall(r"ffr-profile steps=(\d+) sum=(\d+) max=(\d+) overruns=(\d+)", text)
        if not found:
            return None
        steps, total, worst, overruns = (int(v) for v in found[-1])
        per = self.spec.insn_per_count
        return StepProfile(steps, total * per / steps, round(worst * per), overruns)

    def stop(self) -> None:
        stop_process(self.proc, (self.proc.terminate, self.proc.kill), wait_s=2.0)
        if self._log is not None:
            self._log.close()
            self._log = None

    def cleanup(self) -> None:
        shutil.rmtree(self.tmp, ignore_errors=True)


class _OwnsQemu(OwnsItsBoard):
    """Closing also reads the board's step profile (its log outlives QEMU) and removes its files."""

    board: QemuBoard
    profile: StepProfile | None

    def _release_board(self) -> None:
        super()._release_board()
        self.profile = self.board.profile()
        self.board.cleanup()


def _wait_ready(link: QemuLink | QemuEthLink, board: QemuBoard, opts: WireOptions) -> None:
    """QEMU starts the guest (over the UART: once the socket is connected); the first frame waits
    until the board says its link listens (the STM32 USART model drops bytes that arrive before)."""
    deadline = time.monotonic() + opts.handshake_timeout_s
    while not board.ready():
        gone = board.gone()
        if gone or time.monotonic() > deadline:
            link.close()
            why = gone or f"no ready line within {opts.handshake_timeout_s:g} s"
            raise LinkError(f"qemu:{board.machine}: {why}")
        time.sleep(0.005)


class QemuLink(_OwnsQemu, SerialLink):
    """The serial link to the firmware on an emulated board it started and will stop."""

    def __init__(self, board: QemuBoard, opts: WireOptions) -> None:
        self.board = board
        self.profile: StepProfile | None = None
        deadline = time.monotonic() + 10.0
        while True:  # QEMU listens a moment after it starts
            try:
                super().__init__(f"socket://127.0.0.1:{board.port}", opts)
                break
            except LinkError:
                gone = board.gone()
                if gone or time.monotonic() > deadline:
                    raise LinkError(f"qemu:{board.machine}: {gone or 'no UART socket within 10 s'}") from None
                time.sleep(0.02)
        _wait_ready(self, board, opts)


class QemuEthLink(_OwnsQemu, DatagramLink):
    """The datagram link to the firmware on an emulated board's Ethernet, which it started and will stop."""

    def __init__(self, board: QemuBoard, opts: WireOptions) -> None:
        self.board = board
        self.profile: StepProfile | None = None
        super().__init__(board.host_sock, board.eth_sock, opts)
        _wait_ready(self, board, opts)


def open_qemu(url: str) -> QemuLink | QemuEthLink:
    machine, opts = parse_url(url)
    simulated_board(opts)
    # an emulated board translates its code on first use: give the start-up more time
    if "handshake_timeout_s" not in opts.given:
        opts.handshake_timeout_s = max(opts.handshake_timeout_s, 10.0)
    spec = MACHINES.get(machine)
    if spec is None:
        raise LinkError(f"--link = {url!r}: unknown emulated board '{machine}', known: {sorted(MACHINES)}")
    # the transport: the machine's fastest unless the URL names one it has
    transport = opts.transport if "transport" in opts.given else spec.transports[0]
    if transport not in spec.transports:
        raise LinkError(f"--link = {url!r}: option transport = {transport!r}: qemu:{machine} has "
                        f"{', '.join(spec.transports)}")
    board = QemuBoard(machine, spec, opts.log, transport)
    try:
        link: QemuLink | QemuEthLink = QemuEthLink(board, opts) if transport == "eth" else QemuLink(board, opts)
    except BaseException:
        board.stop()
        board.cleanup()
        raise
    link.url = url
    return link
