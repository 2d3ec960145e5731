# mk/hardening.mk - soak runs, worst-case instructions per point, measured stack after
# soak-like sessions (docs/SOAK.md). The top Makefile includes it with
# `-include mk/hardening.mk` after mk/m4f.mk and mk/sim.mk (uses their BUILD, M4F,
# M4F_CC, M4F_FW_OBJ, M4F_SEMI_OBJ, M4F_LDFLAGS, M4F_TEST_STACK, M4F_STACK, M4F_NM,
# QEMU, PYTHON, Q).
# SPDX-License-Identifier: MIT
#
# Targets (each closes with "<word>: N passed, N failed"):
#   soak        >= 1e6 points natively + >= 1e5 under QEMU, every point judged, one
#               seeded random fault per session (host_sim/soak.sh)        word "soak"
#   soak-quick  the same with a small fraction of the sessions (< 40 s)   word "soak"
#   maxpoint    max/mean/min instructions per canal_path_next on QEMU       word "maxpoint"
#   pollgap     the worst gap between two reads of the host link during RUN's check, '?'
#               answered and Ctrl-X cancelling within it, on QEMU          word "pollgap"
#   stack-soak  painted stack of fw.elf after soak-like sessions and the fuzz corpus
#               replay, next to the static worst path of `make stack`    word "stack-soak"

SOAK_SEED ?= 1
NICE      ?= nice -n 5

.PHONY: soak soak-quick maxpoint pollgap stack-soak

##
## soak: >=1e6 native + >=1e5 QEMU points judged, seeded random drop/flip/dup/hang-up faults (word "soak")
soak: $(BUILD)/host/fw_native $(BUILD)/host/host_sim $(M4F)/fw.elf
	$(Q)BUILD=$(BUILD) QEMU=$(QEMU) SOAK_SEED=$(SOAK_SEED) $(NICE) sh host_sim/soak.sh full

## soak-quick: a fraction of soak (< 40 s) for make check (word "soak")
soak-quick: $(BUILD)/host/fw_native $(BUILD)/host/host_sim $(M4F)/fw.elf
	$(Q)BUILD=$(BUILD) QEMU=$(QEMU) SOAK_SEED=$(SOAK_SEED) $(NICE) sh host_sim/soak.sh quick

## maxpoint: worst-case instructions per canal_path_next over whole jobs on QEMU, run twice (word "maxpoint")
# (timeout 600 per QEMU run: one run takes about 1 s unloaded, 2026-11-26; the rule of
# mk/m4f.mk is >= 5x. The counts are -icount instructions, not wall-clock.)
maxpoint: $(M4F)/maxpoint.elf
	$(Q)for i in 1 2; do \
	    timeout 600 $(NICE) $(QEMU) -M mps2-an386 -display none -monitor none -serial null \
	        -semihosting-config enable=on,target=native -icount shift=7 -kernel $< \
	        > $(M4F)/maxpoint.run$$i 2>&1; echo $$? > $(M4F)/maxpoint.rc$$i; done; \
	cat $(M4F)/maxpoint.run1; \
	if cmp -s $(M4F)/maxpoint.run1 $(M4F)/maxpoint.run2; then \
	    echo "maxpoint: 2 QEMU runs, identical counts"; \
	else echo "maxpoint: runs DIFFER:"; diff $(M4F)/maxpoint.run1 $(M4F)/maxpoint.run2; \
	    echo "maxpoint: 0 passed, 1 failed"; exit 1; fi; \
	grep -q '^maxpoint: [0-9]* passed, [0-9]* failed$$' $(M4F)/maxpoint.run1 || \
	    { echo "maxpoint: no result line (qemu exit $$(cat $(M4F)/maxpoint.rc1))"; \
	      echo "maxpoint: 0 passed, 1 failed"; exit 1; }; \
	exit $$(cat $(M4F)/maxpoint.rc1)

$(M4F)/maxpoint.elf: $(M4F_FW_OBJ) $(M4F)/bench/maxpoint_m4f.o $(M4F)/bench/bench_print.o $(M4F_SEMI_OBJ) \
                     linker/mps2_an386_test.ld linker/cortex_m_common.ld
	$(Q)$(M4F_CC) $(M4F_LDFLAGS) -T mps2_an386_test.ld \
	    -Wl,--defsym=CP_STACK=$(M4F_TEST_STACK) -Wl,-Map=$@.map -o $@ \
	    $(M4F_FW_OBJ) $(M4F)/bench/maxpoint_m4f.o $(M4F)/bench/bench_print.o $(M4F_SEMI_OBJ) -lm

## pollgap: the worst gap between two reads of the host link during RUN's check (<= 1 M
##          instructions) and '?' / Ctrl-X acting within it, on QEMU, run twice (word "pollgap")
# (timeout 600 per QEMU run: one run takes about 6 s unloaded, 2026-11-27; >= 5x. The counts
# are -icount instructions, not wall-clock.)
pollgap: $(M4F)/pollgap.elf
	$(Q)for i in 1 2; do \
	    timeout 600 $(NICE) $(QEMU) -M mps2-an386 -display none -monitor none -serial null \
	        -semihosting-config enable=on,target=native -icount shift=7 -kernel $< \
	        > $(M4F)/pollgap.run$$i 2>&1; echo $$? > $(M4F)/pollgap.rc$$i; done; \
	cat $(M4F)/pollgap.run1; \
	if cmp -s $(M4F)/pollgap.run1 $(M4F)/pollgap.run2; then \
	    echo "pollgap: 2 QEMU runs, identical counts"; \
	else echo "pollgap: runs DIFFER:"; diff $(M4F)/pollgap.run1 $(M4F)/pollgap.run2; \
	    echo "pollgap: 0 passed, 1 failed"; exit 1; fi; \
	grep -q '^pollgap: [0-9]* passed, [0-9]* failed$$' $(M4F)/pollgap.run1 || \
	    { echo "pollgap: no result line (qemu exit $$(cat $(M4F)/pollgap.rc1))"; \
	      echo "pollgap: 0 passed, 1 failed"; exit 1; }; \
	exit $$(cat $(M4F)/pollgap.rc1)

$(M4F)/pollgap.elf: $(M4F_FW_OBJ) $(M4F)/bench/pollgap_m4f.o $(M4F)/bench/bench_print.o \
                    $(M4F)/tests/hal_mem.o $(M4F_SEMI_OBJ) \
                    linker/mps2_an386_test.ld linker/cortex_m_common.ld
	$(Q)$(M4F_CC) $(M4F_LDFLAGS) -T mps2_an386_test.ld \
	    -Wl,--defsym=CP_STACK=$(M4F_TEST_STACK) -Wl,-Map=$@.map -o $@ \
	    $(M4F_FW_OBJ) $(M4F)/bench/pollgap_m4f.o $(M4F)/bench/bench_print.o $(M4F)/tests/hal_mem.o \
	    $(M4F_SEMI_OBJ) -lm

## stack-soak: painted stack of fw.elf after soak-like sessions + fuzz corpus replay vs `make stack` (word "stack-soak")
stack-soak: $(M4F)/fw.elf $(BUILD)/host/host_sim
	$(Q)sh tools/stack.sh $(M4F_STACK_ARGS) > $(M4F)/stack_static.txt 2>&1 || true
	$(Q)BUILD=$(BUILD) QEMU=$(QEMU) $(NICE) $(PYTHON) tools/m4f_stack_soak.py $< \
	    $$($(M4F_NM) $< | awk '$$3 == "_sstack" {print $$1}') $(M4F_STACK) $(M4F)/stack_static.txt
