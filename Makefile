# ffr - firmware-in-the-loop test harness for a fire-fighting robot.
#   make run    set up, build, run the four-room missions (table + pictures)
#   make test   set up, build, run every test
#   make bench  real-time factor and per-tick costs, sweep throughput (missions/s)
#   make test-thorough  the property tests with the thorough hypothesis profile
#   make envelope  success rate per kind and level of sensor noise (docs/robustness.md)
#   make firmware  host library + Cortex-M4 build (flash/RAM printed)

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
CSTD    := -std=c99 -Wall -Wextra -Werror -pedantic -Wshadow -Wconversion -Wdouble-promotion \
           -ffp-contract=off -fno-common -Ifirmware/include -Ifirmware/src
HOST_CFLAGS := $(CSTD) -O2 -fPIC
ARM_CFLAGS  := $(CSTD) -Os -mcpu=cortex-m4 -mthumb -mfloat-abi=hard -mfpu=fpv4-sp-d16 \
               -ffunction-sections -fdata-sections

.PHONY: all setup run test test-thorough envelope bench firmware firmware-host firmware-arm firmware-test lint clean

all: firmware-host

$(VENV)/.stamp: pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(VENV)/bin/pip install -q --disable-pip-version-check -e '.[test]'
	touch $@

setup: $(VENV)/.stamp

# ---- firmware --------------------------------------------------------------
$(BUILD)/host/libffr.so: $(FW_SRCS) $(FW_HDRS) Makefile
	@mkdir -p $(dir $@)
	$(CC) $(HOST_CFLAGS) -shared -o $@ $(FW_SRCS)

$(BUILD)/host/ffr_unit_tests: $(FW_SRCS) $(FW_TESTS) $(FW_HDRS) firmware/tests/unit.h Makefile
	@mkdir -p $(dir $@)
	$(CC) $(CSTD) -O1 -g -fsanitize=address,undefined -fno-sanitize-recover=all -Ifirmware/tests \
		-o $@ $(FW_SRCS) $(FW_TESTS) -lm

firmware-host: $(BUILD)/host/libffr.so

firmware-test: $(BUILD)/host/ffr_unit_tests
	$(BUILD)/host/ffr_unit_tests

# The Cortex-M4 build: every source compiled for the target, linked into a
# size probe (the firmware plus a minimal main and newlib-nano), sizes printed.
$(BUILD)/arm/ffr_size_probe.elf: $(FW_SRCS) $(FW_HDRS) firmware/boards/size_probe/main.c Makefile
	@mkdir -p $(dir $@)
	$(ARM_CC) $(ARM_CFLAGS) -Wl,--gc-sections --specs=nano.specs --specs=nosys.specs \
		-o $@ $(FW_SRCS) firmware/boards/size_probe/main.c

firmware-arm: $(BUILD)/arm/ffr_size_probe.elf
	@$(ARM_SIZE) $< | awk 'NR==2 { printf "cortex-m4: flash %d bytes (text %d + data %d), RAM %d bytes (data %d + bss %d)\n", $$1+$$2, $$1, $$2, $$2+$$3, $$2, $$3 }'

firmware: firmware-host firmware-arm

# ---- Python ----------------------------------------------------------------
lint: setup
	$(VENV)/bin/ruff check .

test: setup firmware-host $(BUILD)/host/ffr_unit_tests
	$(VENV)/bin/ruff check .
	$(BUILD)/host/ffr_unit_tests
	$(VENV)/bin/pytest -q

test-thorough: setup firmware-host
	$(VENV)/bin/pytest -q tests/property --ffr-profile thorough
	$(VENV)/bin/ffr sweep -n 10 --seeds 0:25 --noise envelope --no-progress --min-success 98

envelope: setup firmware-host
	$(PY) -m harness.envelope

run: setup firmware-host
	@mkdir -p $(OUT)
	$(VENV)/bin/ffr table1 --plot $(OUT)/missions.png --json $(OUT)/table1.json

bench: setup firmware-host
	$(PY) -m harness.bench

clean:
	rm -rf $(BUILD) $(OUT)
