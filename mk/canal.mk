# mk/canal.mk - host tools of the canal core: demo renderer and accuracy bench.
# SPDX-License-Identifier: MIT

CANAL_FW := firmware/canal.c firmware/toolpath.c firmware/cp_math.c
TOOL_CFLAGS := -std=c99 -O2 -Wall -Wextra -Werror -D_GNU_SOURCE $(FPFLAGS) -Ifirmware -Ihal -Ibench

$(BUILD)/host/canal_demo: tools/canal_demo.c $(CANAL_FW) $(wildcard firmware/*.h)
	@mkdir -p $(@D)
	$(Q)$(CC) $(TOOL_CFLAGS) -o $@ tools/canal_demo.c $(CANAL_FW) -lm

$(BUILD)/host/accuracy_f: bench/accuracy.c bench/frenet.c bench/frenet.h $(CANAL_FW) $(wildcard firmware/*.h)
	@mkdir -p $(@D)
	$(Q)$(CC) $(TOOL_CFLAGS) -DCP_REAL_DOUBLE=0 -o $@ bench/accuracy.c bench/frenet.c $(CANAL_FW) -lm

$(BUILD)/host/accuracy_d: bench/accuracy.c bench/frenet.c bench/frenet.h $(CANAL_FW) $(wildcard firmware/*.h)
	@mkdir -p $(@D)
	$(Q)$(CC) $(TOOL_CFLAGS) -DCP_REAL_DOUBLE=1 -o $@ bench/accuracy.c bench/frenet.c $(CANAL_FW) -lm

.PHONY: demo-canal bench-accuracy
## demo-canal: stream the paper's example and a boss fillet, write CSV + SVG to build/demo
demo-canal: $(BUILD)/host/canal_demo
	@mkdir -p $(BUILD)/demo
	$(Q)$(BUILD)/host/canal_demo $(BUILD)/demo

## bench-accuracy: max error vs steps, contact frame vs the paper's Frenet form (host, float + double)
bench-accuracy: $(BUILD)/host/accuracy_f $(BUILD)/host/accuracy_d
	$(Q)$(BUILD)/host/accuracy_f
	$(Q)$(BUILD)/host/accuracy_d

.PHONY: guard-docs
## guard-docs: docs/PROTOCOL.md's status table equals the one generated from cp_status.def
guard-docs:
	@mkdir -p $(BUILD)
	$(Q)sed -n '/<!-- status-table:begin -->/,/<!-- status-table:end -->/p' docs/PROTOCOL.md | sed '1d;$$d' > $(BUILD)/status_doc.md
	$(Q)sh tools/gen_status_md.sh > $(BUILD)/status_gen.md
	$(Q)if cmp -s $(BUILD)/status_doc.md $(BUILD)/status_gen.md; then echo "guard-docs: 1 passed, 0 failed"; \
	else diff $(BUILD)/status_gen.md $(BUILD)/status_doc.md; echo "guard-docs: 0 passed, 1 failed"; exit 1; fi
