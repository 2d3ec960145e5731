# canalpath - one non-recursive Makefile. `make help` lists the targets.
# SPDX-License-Identifier: MIT
#
# Build trees (out of tree, under $(BUILD)):
#   host/   native float build: unit tests, native firmware (pty), host_sim
#   hostd/  native double build (CP_REAL_DOUBLE=1): unit tests
#   m4f/    Cortex-M4F (QEMU mps2-an386): firmware image fw.elf, unit tests unit.elf
# Fragments: mk/m4f.mk (cross build, QEMU, size/stack/bench), mk/sim.mk (posix
# port, host_sim, pty sessions).

BUILD   ?= build
CC      ?= cc
CLANG   ?= clang
CROSS   ?= arm-none-eabi-
PYTHON  ?= /usr/bin/python3
V       ?= 0
Q       := $(if $(filter 1,$(V)),,@)

# Warnings that every compiler (gcc, clang, arm-none-eabi-gcc) must pass clean.
WARN := -std=c99 -pedantic -Werror -Wall -Wextra -Wvla -Wdouble-promotion -Wshadow \
        -Wstrict-prototypes -Wmissing-prototypes -Wundef -Wcast-align
# Determinism: no FMA contraction (native and M4F streams are byte-identical),
# no errno from sqrt (inlined as one instruction).
FPFLAGS := -ffp-contract=off -fno-math-errno
# The firmware's layers are the folders of firmware/ (docs/ARCHITECTURE.md); sources include
# each other by file name, so every layer folder is on the include path.
FW_DIRS := $(sort $(patsubst %/,%,$(dir $(wildcard firmware/*/*.h firmware/*/*.c firmware/*/*.def))))
FW_INC  := $(addprefix -I,$(FW_DIRS))
# CP_DEFS: compile-time knobs for a test build (e.g. -DCP_WITH_PLANE=1, make example-model)
CP_DEFS ?=
INC := $(FW_INC) -Itests $(CP_DEFS)

FW_SRC   := $(wildcard firmware/*/*.c)
# (tests/test_sim_machine.c is a program of its own: make sim-machine, mk/sim.mk)
TEST_SRC := $(filter-out tests/fuzz_%.c tests/fw_fake.c tests/test_sim_machine.c,$(wildcard tests/*.c))

HOST_CFLAGS := $(WARN) $(FPFLAGS) -O2 -g $(INC)
# Firmware objects also prove the stack bound per function.
# (the same limit as the M4F build's: linker/budget.txt `stack_fn`, the one place it is set)
STACK_FN_MAX ?= $(shell sed -n 's/^stack_fn  *\([0-9][0-9]*\).*/\1/p' linker/budget.txt)

.PHONY: all help check demo bench size stack clean unit unit-double guards
all: unit unit-double

## help: list the targets
help:
	@awk '/^## /{sub(/^## /,""); print}' $(MAKEFILE_LIST)

##
## unit: host unit tests, float build (runner word "unit")
unit: $(BUILD)/host/unit
	$(Q)$(BUILD)/host/unit

## unit-double: host unit tests, double build (runner word "unit-double")
unit-double: $(BUILD)/hostd/unit
	$(Q)$(BUILD)/hostd/unit

$(BUILD)/host/fw/%.o: firmware/%.c
	@mkdir -p $(@D)
	$(Q)$(CC) $(HOST_CFLAGS) -fstack-usage -Wstack-usage=$(STACK_FN_MAX) -MMD -MP -c $< -o $@

$(BUILD)/host/tests/%.o: tests/%.c
	@mkdir -p $(@D)
	$(Q)$(CC) $(HOST_CFLAGS) -Wno-double-promotion -MMD -MP -c $< -o $@

$(BUILD)/hostd/fw/%.o: firmware/%.c
	@mkdir -p $(@D)
	$(Q)$(CC) $(HOST_CFLAGS) -DCP_REAL_DOUBLE=1 -MMD -MP -c $< -o $@

$(BUILD)/hostd/tests/%.o: tests/%.c
	@mkdir -p $(@D)
	$(Q)$(CC) $(HOST_CFLAGS) -Wno-double-promotion -DCP_REAL_DOUBLE=1 -DTEST_WORD='"unit-double"' -MMD -MP -c $< -o $@

HOST_FW_OBJ  := $(patsubst firmware/%.c,$(BUILD)/host/fw/%.o,$(FW_SRC))
HOSTD_FW_OBJ := $(patsubst firmware/%.c,$(BUILD)/hostd/fw/%.o,$(FW_SRC))

$(BUILD)/host/unit: $(HOST_FW_OBJ) $(patsubst tests/%.c,$(BUILD)/host/tests/%.o,$(TEST_SRC))
	$(Q)$(CC) -o $@ $^ -lm

$(BUILD)/hostd/unit: $(HOSTD_FW_OBJ) $(patsubst tests/%.c,$(BUILD)/hostd/tests/%.o,$(TEST_SRC))
	$(Q)$(CC) -o $@ $^ -lm

-include mk/m4f.mk
-include mk/sim.mk
-include mk/canal.mk
-include mk/stream.mk
-include mk/fuzz.mk
-include mk/hardening.mk
-include mk/py.mk

## stream-diff: BASE=<git ref>: firmware replies and streams byte-identical to BASE's (tools/stream_diff.sh; word "stream-diff")
.PHONY: stream-diff
stream-diff:
	$(Q)test -n "$(BASE)" || { echo "stream-diff: BASE=<git ref> is required"; echo "stream-diff: 0 passed, 1 failed"; exit 1; }
	$(Q)rm -rf $(BUILD)/stream_diff_base && mkdir -p $(BUILD)/stream_diff_base && \
	    git archive "$(BASE)" | tar -x -C $(BUILD)/stream_diff_base
	$(Q)sh tools/stream_diff.sh $(BUILD)/stream_diff_base .

## check: every test and guard; ends with one "N passed, N failed" line
check:
	$(Q)sh tools/check.sh

## clean: remove the build tree
clean:
	rm -rf $(BUILD)

-include $(shell find $(BUILD) -name '*.d' 2>/dev/null)
