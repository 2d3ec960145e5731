# mk/sim.mk - POSIX port (native firmware), host_sim, pty sessions, robustness runs.
# SPDX-License-Identifier: MIT
#
# Included by the top Makefile (uses its BUILD, CC, WARN, FPFLAGS, INC, HOST_FW_OBJ, Q).
# _XOPEN_SOURCE is defined for hal/posix, host_sim and tests/fw_fake.c only, never
# for firmware/ (the firmware objects are the ones of the unit build).
#   build/host/fw_native   firmware/*.c + hal/posix (protocol on fd 0, or --tty PATH)
#   build/host/host_sim    host_sim/*.c (creates the pty, runs native/QEMU/any program)
#   build/host/fw_fake     tests/fw_fake.c (misbehaving firmwares for sim-robust)
#   build/host/test_sim_machine  tests/test_sim_machine.c + host_sim/sim_machine*.c

SIM_POSIX   := -D_XOPEN_SOURCE=600
SIM_CFLAGS  := $(WARN) -O2 -g $(SIM_POSIX) $(FW_INC) -Ihost_sim -Itests
# per-reply timeout of sim-native/sim-qemu (ms; the timeout rule of mk/m4f.mk: >= 5x the
# unloaded time): the slowest reply is QEMU's boot to the first $I answer, 34-45 ms
# (2026-11-26), other replies <= 7 ms; 2000 ms is 44x
SIM_TIMEOUT ?= 2000
SIM_JOB     ?= tests/jobs/handshake.job
QEMU        ?= qemu-system-arm

POSIX_SRC   := $(wildcard hal/posix/*.c)
POSIX_OBJ   := $(patsubst hal/posix/%.c,$(BUILD)/host/posix/%.o,$(POSIX_SRC))
HOSTSIM_SRC := $(wildcard host_sim/*.c)
HOSTSIM_OBJ := $(patsubst host_sim/%.c,$(BUILD)/host/host_sim_obj/%.o,$(HOSTSIM_SRC))
# one judge per row of firmware/models/models.def (CP_MODEL(NAME, name, ...)): host_sim/judge_<name>.c
# (in HOSTSIM_SRC) and its reference tests/ref_<name>.c
SIM_MODELS  := $(shell sed -n 's/^CP_MODEL[^,]*, *\([a-z0-9_]*\),.*/\1/p' firmware/models/models.def)
HOSTSIM_REF := $(patsubst %,$(BUILD)/host/host_sim_obj/ref_%.o,$(SIM_MODELS))

.PHONY: fw-native host-sim fw-fake sim-native sim-qemu sim-robust sim-machine

$(BUILD)/host/posix/%.o: hal/posix/%.c
	@mkdir -p $(@D)
	$(Q)$(CC) $(WARN) $(FPFLAGS) -O2 -g $(SIM_POSIX) $(INC) -MMD -MP -c $< -o $@

$(BUILD)/host/host_sim_obj/%.o: host_sim/%.c
	@mkdir -p $(@D)
	$(Q)$(CC) $(SIM_CFLAGS) -MMD -MP -c $< -o $@

##
## sim-machine: the grbl 1.1h and Marlin 2.x machine emulators (host_sim/sim_machine*.c)
##              against their self-test tests/test_sim_machine.c (word "machine")
SIM_MACHINE_OBJ := $(patsubst host_sim/%.c,$(BUILD)/host/host_sim_obj/%.o,$(wildcard host_sim/sim_machine*.c))
sim-machine: $(BUILD)/host/test_sim_machine
	$(Q)$(BUILD)/host/test_sim_machine

$(BUILD)/host/test_sim_machine: $(BUILD)/host/sim_machine/test_sim_machine.o $(SIM_MACHINE_OBJ)
	$(Q)$(CC) -o $@ $^ -lm

$(BUILD)/host/sim_machine/test_sim_machine.o: tests/test_sim_machine.c
	@mkdir -p $(@D)
	$(Q)$(CC) $(SIM_CFLAGS) -MMD -MP -c $< -o $@

## fw-native: build build/host/fw_native (firmware/*.c + hal/posix, serves the protocol on a pty)
fw-native: $(BUILD)/host/fw_native
$(BUILD)/host/fw_native: $(HOST_FW_OBJ) $(POSIX_OBJ)
	$(Q)$(CC) -o $@ $^ -lm

## host-sim: build build/host/host_sim (pty host simulator, docs/HOST_SIM.md)
host-sim: $(BUILD)/host/host_sim
$(BUILD)/host/host_sim: $(HOSTSIM_OBJ) $(HOSTSIM_REF) $(BUILD)/host/host_sim_obj/frame.o
	$(Q)$(CC) -o $@ $^ -lm

# the frame codec is portable C: host_sim links firmware/proto/frame.c (FRAMES receiver)
$(BUILD)/host/host_sim_obj/frame.o: firmware/proto/frame.c firmware/proto/frame.h
	@mkdir -p $(@D)
	$(Q)$(CC) $(SIM_CFLAGS) -MMD -MP -c $< -o $@

# each judge's independent reference model, tests/ref_<name>.c (no firmware code)
$(BUILD)/host/host_sim_obj/ref_%.o: tests/ref_%.c tests/ref_%.h
	@mkdir -p $(@D)
	$(Q)$(CC) $(SIM_CFLAGS) -Itests -MMD -MP -c $< -o $@

## fw-fake: build build/host/fw_fake (misbehaving firmwares for sim-robust)
fw-fake: $(BUILD)/host/fw_fake
$(BUILD)/host/fw_fake: tests/fw_fake.c
	@mkdir -p $(@D)
	$(Q)$(CC) $(WARN) -O2 -g -D_XOPEN_SOURCE=700 -o $@ $<

## sim-native: host_sim + fw_native over a pty on tests/jobs/handshake.job (runner word "sim")
sim-native: $(BUILD)/host/fw_native $(BUILD)/host/host_sim
	$(Q)$(BUILD)/host/host_sim --target native --fw $(BUILD)/host/fw_native --job $(SIM_JOB) \
	    --timeout-ms $(SIM_TIMEOUT) --log $(BUILD)/host/sim-native.log

## sim-qemu: the same job against build/m4f/fw.elf on qemu-system-arm mps2-an386 (word "sim")
ifneq ($(wildcard mk/m4f.mk),)
sim-qemu: $(BUILD)/host/host_sim m4f-fw
	$(Q)if ! command -v $(QEMU) >/dev/null 2>&1; then \
	    echo "sim-qemu: $(QEMU) not found (apt-get install qemu-system-arm)"; \
	    echo "sim: 0 passed, 1 failed"; exit 1; fi
	$(Q)$(BUILD)/host/host_sim --target qemu --qemu $(QEMU) --fw $(BUILD)/m4f/fw.elf \
	    --job $(SIM_JOB) --timeout-ms $(SIM_TIMEOUT) --log $(BUILD)/host/sim-qemu.log
else
sim-qemu:
	@echo "sim-qemu: mk/m4f.mk (target m4f-fw, build/m4f/fw.elf) is missing"
	@echo "sim: 0 passed, 1 failed"; exit 1
endif

## sim-robust: host_sim against every bad fw_fake mode: each must fail cleanly, in time (word "robust")
sim-robust: $(BUILD)/host/host_sim $(BUILD)/host/fw_fake
	$(Q)BUILD=$(BUILD) sh host_sim/robust.sh

# RUN suites (host_sim/sim_suite.sh): each prints "<word>: N passed, N failed"
.PHONY: example-model sim-run-native sim-run-qemu sim-baud sim-faults sim-resume sim-identical sim-models

## sim-models: every tests/jobs/model_<m>_*.job (GSR, CHANNEL, DRC) judged, native and QEMU (fw.elf, all models), streams identical (word "models")
sim-models: $(BUILD)/host/fw_native $(BUILD)/host/host_sim m4f-fw
	$(Q)BUILD=$(BUILD) QEMU=$(QEMU) sh host_sim/sim_suite.sh models

## example-model: the example model (SURFACE PLANE, docs/ARCHITECTURE.md) in a test build
##                (CP_WITH_PLANE=1, build/example), judged by host_sim; its judge must fail on a
##                point moved 5 um (word "example")
example-model: $(BUILD)/host/host_sim
	$(Q)$(MAKE) --no-print-directory BUILD=$(BUILD)/example CP_DEFS=-DCP_WITH_PLANE=1 \
	    $(BUILD)/example/host/fw_native
	$(Q)BUILD=$(BUILD) sh host_sim/sim_suite.sh example

## sim-machines: two-link cells: every demo and judged job in both dialects against host_sim's grbl 1.1h
##               and Marlin 2.x machines (sim_machine.h), natively and on QEMU (UART1) (word "machines")
.PHONY: sim-machines
sim-machines: $(BUILD)/host/fw_native $(BUILD)/host/host_sim m4f-fw
	$(Q)BUILD=$(BUILD) QEMU=$(QEMU) sh host_sim/sim_suite.sh machines

## sim-run-native: paper + boss + placed jobs, GCODE/CHECKSUM/FRAMES, and a closed arc refused (error:46) then streamed, judged, natively (word "run-native")
sim-run-native: $(BUILD)/host/fw_native $(BUILD)/host/host_sim
	$(Q)BUILD=$(BUILD) sh host_sim/sim_suite.sh run-native

## sim-run-qemu: the same jobs against build/m4f/fw.elf under QEMU (word "run-qemu")
sim-run-qemu: $(BUILD)/host/host_sim m4f-fw
	$(Q)BUILD=$(BUILD) QEMU=$(QEMU) sh host_sim/sim_suite.sh run-qemu

## sim-baud: paper job paced at 115200 baud, GCODE and FRAMES, wire utilization >= 95% (word "baud")
sim-baud: $(BUILD)/host/fw_native $(BUILD)/host/host_sim
	$(Q)BUILD=$(BUILD) sh host_sim/sim_suite.sh baud

## sim-faults: drop/flip/dup on the firmware->host bytes, FRAMES and GCODE+CHECKSUM, all points intact (word "faults")
sim-faults: $(BUILD)/host/fw_native $(BUILD)/host/host_sim
	$(Q)BUILD=$(BUILD) sh host_sim/sim_suite.sh faults

## sim-resume: hang-up mid-RUN, new firmware, RESUME k: CSV identical to the uninterrupted run (word "resume")
sim-resume: $(BUILD)/host/fw_native $(BUILD)/host/host_sim $(if $(wildcard mk/m4f.mk),m4f-fw)
	$(Q)BUILD=$(BUILD) QEMU=$(QEMU) sh host_sim/sim_suite.sh resume

## sim-identical: raw RUN streams of native and QEMU builds are byte-identical (word "identical")
sim-identical: $(BUILD)/host/fw_native $(BUILD)/host/host_sim m4f-fw
	$(Q)BUILD=$(BUILD) QEMU=$(QEMU) sh host_sim/sim_suite.sh identical
