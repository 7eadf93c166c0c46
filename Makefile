# ffr - firmware-in-the-loop test harness for a fire-fighting robot.
#   make run    set up, build, run the four-room missions (table + pictures)
#   make test   set up, build, run every test
#   make bench  per-tick costs, real-time factor, sweep missions/min, start-up: each beside its goal
#   make test-thorough  the property tests with the thorough hypothesis profile
#   make stress  the wire and PIL missions again with every core busy: same traces, silent links
#   make envelope  success rate per kind and level of sensor noise (docs/robustness.md)
#   make firmware  host library + board builds: mps2-an386, netduinoplus2, microbit (flash/RAM printed)
#   make statechart  the route program's state diagrams in docs/firmware.md, generated from firmware/src

PYTHON ?= python3
VENV   := .venv
PY     := $(VENV)/bin/python
BUILD  := build
OUT    := out

CC      ?= gcc
ARM_CC  ?= arm-none-eabi-gcc
ARM_SIZE ?= arm-none-eabi-size

FW_SRCS := $(sort $(wildcard firmware/src/*.c))
FW_HDRS := $(wildcard firmware/include/*.h firmware/src/*.h)
FW_TESTS := $(sort $(wildcard firmware/tests/*.c))
# The wire (docs/protocol.md): codec and board link, shared by every board.
WIRE_SRCS := $(sort $(wildcard firmware/codec/*.c firmware/link/*.c))
WIRE_TESTS := $(sort $(wildcard firmware/tests/wire/*.c))
HOST_BOARD_SRCS := $(sort $(wildcard firmware/boards/host/*.c))
WIRE_VECTORS := tests/bridge/vectors/wire_vectors.txt
FUZZ_SECONDS ?= 60
CLANG ?= clang
CSTD    := -std=c99 -Wall -Wextra -Werror -pedantic -Wshadow -Wconversion -Wdouble-promotion \
           -ffp-contract=off -fno-common -Ifirmware/include -Ifirmware/src
HOST_CFLAGS := $(CSTD) -O2 -fPIC
# -Os on the target, by choice: ffr_step's cost was cut in the sources (work
# done once a tick, tiny helpers inline), where it holds for every compiler.
# Measured on top of that (QEMU -icount, rooms 1 and 4, both bit-identical to
# the host): -O2 ~1-2 % fewer instructions for +3 KB of flash; -flto ~2 % fewer
# and ~1 KB smaller. Small gains, so the target stays a plain per-file build
# like the host's (and like the C tests'), whose numbers docs/pil.md gives.
ARM_CFLAGS  := $(CSTD) -Os -mcpu=cortex-m4 -mthumb -mfloat-abi=hard -mfpu=fpv4-sp-d16 \
               -ffunction-sections -fdata-sections

.PHONY: all setup run test statechart stress test-thorough envelope acceptance bench firmware firmware-host firmware-arm firmware-boards firmware-test selftest lint clean wire-test fuzz

all: firmware-host

$(VENV)/.stamp: pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(VENV)/bin/pip install -q --disable-pip-version-check -e '.[test]'
	touch $@

setup: $(VENV)/.stamp

# ---- firmware --------------------------------------------------------------
$(BUILD)/host/libffr.so: $(FW_SRCS) $(WIRE_SRCS) $(FW_HDRS) Makefile
	@mkdir -p $(dir $@)
	$(CC) $(HOST_CFLAGS) -shared -o $@ $(FW_SRCS) $(WIRE_SRCS)

UNIT_TEST_DEPS := $(FW_SRCS) $(FW_TESTS) $(FW_HDRS) firmware/tests/unit.h firmware/tests/rig.h Makefile
UNIT_TEST_CC = $(CC) $(CSTD) -O1 -g -fsanitize=address,undefined -fno-sanitize-recover=all -Ifirmware/tests

$(BUILD)/host/ffr_unit_tests: $(UNIT_TEST_DEPS)
	@mkdir -p $(dir $@)
	$(UNIT_TEST_CC) -o $@ $(FW_SRCS) $(FW_TESTS) -lm

# The same tests with the orientation's fold-back rules built in (FFR_HOME_FOLD_MM, off in
# the firmware as shipped: ffr_internal.h): the code those rules reach is tested too.
$(BUILD)/host/ffr_unit_tests_homefold: $(UNIT_TEST_DEPS)
	@mkdir -p $(dir $@)
	$(UNIT_TEST_CC) -DFFR_HOME_FOLD_MM=160.0f -o $@ $(FW_SRCS) $(FW_TESTS) -lm

firmware-host: $(BUILD)/host/libffr.so $(BUILD)/host/ffr-host-board

# The host board: the firmware, the codec and a POSIX transport (pty, TCP, stdio).
$(BUILD)/host/ffr-host-board: $(FW_SRCS) $(WIRE_SRCS) $(HOST_BOARD_SRCS) $(FW_HDRS) firmware/boards/host/transport.h Makefile
	@mkdir -p $(dir $@)
	$(CC) $(CSTD) -O2 -Ifirmware/boards/host -o $@ $(FW_SRCS) $(WIRE_SRCS) $(HOST_BOARD_SRCS)

# the wire tests share the unit tests' runner (firmware/tests/unit_runner.c)
$(BUILD)/host/ffr_wire_tests: $(FW_SRCS) $(WIRE_SRCS) $(WIRE_TESTS) $(FW_HDRS) firmware/tests/unit.h firmware/tests/unit_runner.c firmware/tests/wire/wire_tests.h Makefile
	@mkdir -p $(dir $@)
	$(UNIT_TEST_CC) -Ifirmware/tests/wire -o $@ $(FW_SRCS) $(WIRE_SRCS) $(WIRE_TESTS) firmware/tests/unit_runner.c -lm

wire-test: $(BUILD)/host/ffr_wire_tests
	$(BUILD)/host/ffr_wire_tests --vectors $(WIRE_VECTORS)

# libFuzzer with ASan+UBSan on the board's whole receive path; FUZZ_SECONDS bounds it.
$(BUILD)/fuzz/ffr_fuzz_rx: $(FW_SRCS) $(WIRE_SRCS) firmware/tests/fuzz/fuzz_rx.c $(FW_HDRS) Makefile
	@mkdir -p $(dir $@)
	$(CLANG) -std=c99 -g -O1 -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=all \
		-Ifirmware/include -Ifirmware/src -o $@ $(FW_SRCS) $(WIRE_SRCS) firmware/tests/fuzz/fuzz_rx.c

fuzz: $(BUILD)/fuzz/ffr_fuzz_rx
	@mkdir -p $(BUILD)/fuzz/corpus
	$(BUILD)/fuzz/ffr_fuzz_rx -max_total_time=$(FUZZ_SECONDS) -max_len=2048 -print_final_stats=1 \
		$(BUILD)/fuzz/corpus firmware/tests/fuzz/seeds

firmware-test: $(BUILD)/host/ffr_unit_tests $(BUILD)/host/ffr_unit_tests_homefold
	$(BUILD)/host/ffr_unit_tests
	$(BUILD)/host/ffr_unit_tests_homefold

# The Cortex-M4 build: every source compiled for the target, linked into a
# size probe (the firmware plus a minimal main and newlib-nano), sizes printed.
$(BUILD)/arm/ffr_size_probe.elf: $(FW_SRCS) $(FW_HDRS) firmware/boards/size_probe/main.c Makefile
	@mkdir -p $(dir $@)
	$(ARM_CC) $(ARM_CFLAGS) -Wl,--gc-sections --specs=nano.specs --specs=nosys.specs \
		-o $@ $(FW_SRCS) firmware/boards/size_probe/main.c

# The same with the wire: the board link and codec behind a byte-stream UART.
$(BUILD)/arm/ffr_wire_probe.elf: $(FW_SRCS) $(WIRE_SRCS) $(FW_HDRS) firmware/boards/size_probe_wire/main.c Makefile
	@mkdir -p $(dir $@)
	$(ARM_CC) $(ARM_CFLAGS) -Wl,--gc-sections --specs=nano.specs --specs=nosys.specs \
		-o $@ $(FW_SRCS) $(WIRE_SRCS) firmware/boards/size_probe_wire/main.c

firmware-arm: $(BUILD)/arm/ffr_size_probe.elf $(BUILD)/arm/ffr_wire_probe.elf
	@$(ARM_SIZE) $< | awk 'NR==2 { printf "cortex-m4: flash %d bytes (text %d + data %d), RAM %d bytes (data %d + bss %d)\n", $$1+$$2, $$1, $$2, $$2+$$3, $$2, $$3 }'
	@$(ARM_SIZE) $(BUILD)/arm/ffr_wire_probe.elf | awk 'NR==2 { printf "cortex-m4 with the wire board link: flash %d bytes, RAM %d bytes\n", $$1+$$2, $$2+$$3 }'

firmware: firmware-host firmware-arm firmware-boards

# ---- boards ----------------------------------------------------------------
BOARD_COMMON := firmware/boards/common/selftest.c
MPS2_DIR := firmware/boards/mps2-an386
# every microcontroller board's main loop (board link behind the UART)
BOARD_LOOP := firmware/boards/common/board_loop.c
MPS2_SRCS := $(MPS2_DIR)/startup.c $(MPS2_DIR)/uart_cmsdk.c $(MPS2_DIR)/eth_lan9118.c
MPS2_LDFLAGS := -T $(MPS2_DIR)/mps2_an386.ld -nostartfiles -Wl,--gc-sections --specs=nano.specs --specs=nosys.specs

$(BUILD)/arm/mps2-an386-selftest.elf: $(FW_SRCS) $(FW_HDRS) $(BOARD_COMMON) $(MPS2_SRCS) $(MPS2_DIR)/selftest_main.c $(MPS2_DIR)/*.h $(MPS2_DIR)/*.ld Makefile
	@mkdir -p $(dir $@)
	$(ARM_CC) $(ARM_CFLAGS) -I$(MPS2_DIR) -Ifirmware/boards/common $(MPS2_LDFLAGS) -o $@ \
		$(FW_SRCS) $(BOARD_COMMON) $(MPS2_SRCS) $(MPS2_DIR)/selftest_main.c

# The board itself: firmware + codec + board link behind its Ethernet or UART0 (--link qemu:mps2-an386).
$(BUILD)/arm/mps2-an386-board.elf: $(FW_SRCS) $(WIRE_SRCS) $(FW_HDRS) $(BOARD_LOOP) $(MPS2_SRCS) $(MPS2_DIR)/main.c $(MPS2_DIR)/*.h $(MPS2_DIR)/*.ld Makefile
	@mkdir -p $(dir $@)
	$(ARM_CC) $(ARM_CFLAGS) -I$(MPS2_DIR) -Ifirmware/boards/common $(MPS2_LDFLAGS) -o $@ $(FW_SRCS) $(WIRE_SRCS) \
		$(BOARD_LOOP) $(MPS2_SRCS) $(MPS2_DIR)/main.c
	@$(ARM_SIZE) $@ | awk 'NR==2 { printf "mps2-an386 board: flash %d bytes, RAM %d bytes\n", $$1+$$2, $$2+$$3 }'

# STM32F405 (Cortex-M4F) on QEMU's netduinoplus2 (--link qemu:netduinoplus2).
F405_DIR := firmware/boards/netduinoplus2
F405_SRCS := $(F405_DIR)/startup.c $(F405_DIR)/uart_stm32.c $(F405_DIR)/main.c
F405_LDFLAGS := -T $(F405_DIR)/stm32f405.ld -nostartfiles -Wl,--gc-sections --specs=nano.specs --specs=nosys.specs

$(BUILD)/arm/netduinoplus2-board.elf: $(FW_SRCS) $(WIRE_SRCS) $(FW_HDRS) $(BOARD_LOOP) $(F405_SRCS) $(F405_DIR)/*.h $(F405_DIR)/*.ld Makefile
	@mkdir -p $(dir $@)
	$(ARM_CC) $(ARM_CFLAGS) -I$(F405_DIR) -Ifirmware/boards/common $(F405_LDFLAGS) -o $@ $(FW_SRCS) $(WIRE_SRCS) \
		$(BOARD_LOOP) $(F405_SRCS)
	@$(ARM_SIZE) $@ | awk 'NR==2 { printf "netduinoplus2 board: flash %d bytes, RAM %d bytes\n", $$1+$$2, $$2+$$3 }'

# nRF51822 (Cortex-M0, no FPU: soft float from libgcc) on QEMU's microbit (--link qemu:microbit).
MICROBIT_DIR := firmware/boards/microbit
MICROBIT_SRCS := $(MICROBIT_DIR)/startup.c $(MICROBIT_DIR)/uart_nrf51.c $(MICROBIT_DIR)/main.c
M0_CFLAGS := $(CSTD) -Os -mcpu=cortex-m0 -mthumb -mfloat-abi=soft -ffunction-sections -fdata-sections
MICROBIT_LDFLAGS := -T $(MICROBIT_DIR)/nrf51822.ld -nostartfiles -Wl,--gc-sections --specs=nano.specs --specs=nosys.specs

$(BUILD)/arm/microbit-board.elf: $(FW_SRCS) $(WIRE_SRCS) $(FW_HDRS) $(BOARD_LOOP) $(MICROBIT_SRCS) $(MICROBIT_DIR)/*.h $(MICROBIT_DIR)/*.ld Makefile
	@mkdir -p $(dir $@)
	$(ARM_CC) $(M0_CFLAGS) -I$(MICROBIT_DIR) -Ifirmware/boards/common $(MICROBIT_LDFLAGS) -o $@ $(FW_SRCS) $(WIRE_SRCS) \
		$(BOARD_LOOP) $(MICROBIT_SRCS)
	@$(ARM_SIZE) $@ | awk 'NR==2 { printf "microbit board: flash %d bytes, RAM %d bytes\n", $$1+$$2, $$2+$$3 }'

$(BUILD)/arm/microbit-selftest.elf: $(FW_SRCS) $(FW_HDRS) $(BOARD_COMMON) $(MICROBIT_DIR)/startup.c $(MICROBIT_DIR)/uart_nrf51.c $(MICROBIT_DIR)/selftest_main.c $(MICROBIT_DIR)/*.h $(MICROBIT_DIR)/*.ld Makefile
	@mkdir -p $(dir $@)
	$(ARM_CC) $(M0_CFLAGS) -I$(MICROBIT_DIR) -Ifirmware/boards/common $(MICROBIT_LDFLAGS) -o $@ \
		$(FW_SRCS) $(BOARD_COMMON) $(MICROBIT_DIR)/startup.c $(MICROBIT_DIR)/uart_nrf51.c $(MICROBIT_DIR)/selftest_main.c

# The same for a micro:bit without a debugger: no semihosting (it would fault), so no profile line.
$(BUILD)/arm/microbit-hw.elf: $(FW_SRCS) $(WIRE_SRCS) $(FW_HDRS) $(BOARD_LOOP) $(MICROBIT_SRCS) $(MICROBIT_DIR)/*.h $(MICROBIT_DIR)/*.ld Makefile
	@mkdir -p $(dir $@)
	$(ARM_CC) $(M0_CFLAGS) -DBOARD_PROFILE_LOG=0 -I$(MICROBIT_DIR) -Ifirmware/boards/common $(MICROBIT_LDFLAGS) -o $@ \
		$(FW_SRCS) $(WIRE_SRCS) $(BOARD_LOOP) $(MICROBIT_SRCS)

$(BUILD)/host/ffr_selftest: $(FW_SRCS) $(FW_HDRS) $(BOARD_COMMON) firmware/boards/host_selftest/main.c Makefile
	@mkdir -p $(dir $@)
	$(CC) $(CSTD) -O2 -Ifirmware/boards/common -o $@ $(FW_SRCS) $(BOARD_COMMON) firmware/boards/host_selftest/main.c

firmware-boards: $(BUILD)/arm/mps2-an386-selftest.elf $(BUILD)/arm/mps2-an386-board.elf $(BUILD)/host/ffr_selftest \
	$(BUILD)/arm/netduinoplus2-board.elf $(BUILD)/arm/microbit-board.elf $(BUILD)/arm/microbit-selftest.elf

# Host, Cortex-M4F (mps2-an386) and Cortex-M0 soft float (microbit), both on QEMU, step the same
# synthetic mission: same checksum?
QEMU ?= qemu-system-arm
selftest: firmware-boards
	@$(BUILD)/host/ffr_selftest
	@timeout 60 $(QEMU) -M mps2-an386 -nographic -monitor none -serial stdio -semihosting \
		-icount shift=0 -kernel $(BUILD)/arm/mps2-an386-selftest.elf | grep ffr-
	@timeout 300 $(QEMU) -M microbit -nographic -monitor none -serial none -icount shift=0 \
		-chardev stdio,id=out -semihosting-config enable=on,target=native,chardev=out \
		-kernel $(BUILD)/arm/microbit-selftest.elf | grep ffr-

# ---- Python ----------------------------------------------------------------
# The state diagrams in docs/firmware.md, read from firmware/src and the library's names
# (harness/statechart.py; tests/docs/test_statechart.py fails when they are stale).
statechart: firmware-host
	FFR_FIRMWARE_LIB=$(BUILD)/host/libffr.so $(PY) -m harness.statechart --write docs/firmware.md

lint: setup
	$(VENV)/bin/ruff check .

test: setup firmware-host $(BUILD)/host/ffr_unit_tests $(BUILD)/host/ffr_unit_tests_homefold $(BUILD)/host/ffr_wire_tests
	$(VENV)/bin/ruff check .
	$(BUILD)/host/ffr_unit_tests
	$(BUILD)/host/ffr_unit_tests_homefold
	$(BUILD)/host/ffr_wire_tests --vectors $(WIRE_VECTORS)
	$(VENV)/bin/pytest -q

# The fresh machine is busy and slow: the missions over every link again, with one busy
# process per core competing for the CPU. Traces stay bit-identical and every clean link
# silent (zero retries, CRC errors, board errors, stale answers: asserted by the tests).
STRESS_TESTS := tests/bridge/test_missions_wire.py tests/pil/test_qemu_board.py::test_mission_on_the_emulated_board_equals_the_host_build
stress: setup firmware-host firmware-boards
	@pids=""; for i in $$(seq $$(nproc)); do yes > /dev/null & pids="$$pids $$!"; done; \
	trap 'kill $$pids 2>/dev/null' EXIT INT TERM; \
	echo "stress: $$(nproc) busy processes ($$pids) while the wire and PIL missions run"; \
	$(VENV)/bin/pytest -q -p no:cacheprovider $(STRESS_TESTS)

test-thorough: setup firmware-host
	$(VENV)/bin/pytest -q tests/property --ffr-profile thorough
	$(VENV)/bin/ffr sweep -n 10 --seeds 0:25 --noise envelope --no-progress --min-success 99

envelope: setup firmware-host
	$(PY) -m harness.envelope

# The robustness goals of issues 12 and 13, each row its own ffr command (harness/acceptance.py);
# ACCEPT_ARGS e.g. --rows realistic,table1, --rows held-out (the same commands on other seeds) or --firmware before=OLD/libffr.so --firmware now=build/host/libffr.so
acceptance: setup firmware-host
	$(PY) -m harness.acceptance $(ACCEPT_ARGS)

run: setup firmware-host
	@mkdir -p $(OUT)
	$(VENV)/bin/ffr table1 --plot $(OUT)/missions.png --json $(OUT)/table1.json --replay-dir $(OUT)

# Budget for ffr_step on the target: 20,000 instructions (an 84 MHz Cortex-M4 at
# ~1.5 cycles per instruction spends 0.36 ms of its 10 ms tick on navigation).
# The firmware's own bound on its worst tick: 5,000 instructions (docs/pil.md).
# Then every board on QEMU (harness/board_bench.py): rooms 1 and 4, identical with the host
# build?, ffr_step mean and worst instructions, and the load at the chip's clock (168 MHz F405 and
# 25 MHz mps2 at an assumed 1.25 cycles/instruction, 16 MHz nRF51 at 1.5; docs/boards.md).
bench: setup firmware-host
	@if command -v $(ARM_CC) >/dev/null && command -v $(QEMU) >/dev/null; then $(MAKE) -s firmware-boards >/dev/null; fi
	$(PY) -m harness.bench
	@if command -v $(ARM_CC) >/dev/null && command -v $(QEMU) >/dev/null; then \
		echo "self-test ffr_step instructions (QEMU -icount): mps2-an386 Cortex-M4F (goal: worst <= 5000, budget 20000), then microbit Cortex-M0:"; \
		$(MAKE) -s selftest | grep ffr-profile; \
		echo "mps2-an386, the four rooms (goal: worst <= 5000):"; \
		for r in 1 2 3 4; do $(VENV)/bin/ffr b2b --room $$r | sed -n "1s/^/  /p;3p"; done; \
		$(PY) -m harness.board_bench; \
	else echo "Cortex-M4 profile skipped: needs $(ARM_CC) and $(QEMU)"; fi

clean:
	rm -rf $(BUILD) $(OUT)
