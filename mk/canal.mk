# mk/canal.mk - host tools of the canal core: demo renderer and accuracy bench.
# SPDX-License-Identifier: MIT

CANAL_FW := firmware/models/canal.c firmware/models/canal_path.c firmware/models/raster.c firmware/base/cp_math.c
TOOL_CFLAGS := -std=c99 -O2 -Wall -Wextra -Werror -D_GNU_SOURCE $(FPFLAGS) $(FW_INC) -Ibench

$(BUILD)/host/canal_demo: tools/canal_demo.c $(CANAL_FW) $(wildcard firmware/*/*.h)
	@mkdir -p $(@D)
	$(Q)$(CC) $(TOOL_CFLAGS) -o $@ tools/canal_demo.c $(CANAL_FW) -lm

$(BUILD)/host/accuracy_f: bench/accuracy.c bench/frenet.c bench/frenet.h $(CANAL_FW) $(wildcard firmware/*/*.h)
	@mkdir -p $(@D)
	$(Q)$(CC) $(TOOL_CFLAGS) -DCP_REAL_DOUBLE=0 -o $@ bench/accuracy.c bench/frenet.c $(CANAL_FW) -lm

$(BUILD)/host/accuracy_d: bench/accuracy.c bench/frenet.c bench/frenet.h $(CANAL_FW) $(wildcard firmware/*/*.h)
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

.PHONY: sizes
## sizes: sizeof of every firmware context on the M4F (float) and the host double build
sizes: $(BUILD)/m4f/sizes_probe.o $(BUILD)/hostd/sizes_probe.o
	@echo "context sizes (bytes)        M4F float   host double"
	$(Q)for s in canal_path canal gsr_path channel_path drc_path path path_geom job frame_rx proto; do \
	    a=$$(arm-none-eabi-nm -S $(BUILD)/m4f/sizes_probe.o | awk -v n=sizeof_$$s '$$4 == n {print $$2}'); \
	    b=$$(nm -S $(BUILD)/hostd/sizes_probe.o | awk -v n=sizeof_$$s '$$4 == n {print $$2}'); \
	    printf "  struct %-20s %9d   %11d\n" $$s $$((0x$$a)) $$((0x$$b)); done
	@echo "  (struct canal_path <= $$(sed -n 's/^#define CP_CANAL_PATH_BUDGET \([0-9]*\)$$/\1/p' firmware/base/cp_config.h) bytes in the float build: static assert in canal_path.c)"

$(BUILD)/m4f/sizes_probe.o: tools/sizes_probe.c $(wildcard firmware/*/*.h)
	@mkdir -p $(@D)
	$(Q)arm-none-eabi-gcc -mcpu=cortex-m4 -mthumb -mfloat-abi=hard -mfpu=fpv4-sp-d16 -std=c99 -Os -fno-common $(FW_INC) -c $< -o $@

$(BUILD)/hostd/sizes_probe.o: tools/sizes_probe.c $(wildcard firmware/*/*.h)
	@mkdir -p $(@D)
	$(Q)$(CC) -std=c99 -O2 -fno-common -DCP_REAL_DOUBLE=1 $(FW_INC) -c $< -o $@

size: sizes

.PHONY: guard-readme
## guard-readme: the C example in README.md compiles and streams every point
guard-readme:
	$(Q)BUILD=$(BUILD) CC=$(CC) sh tools/readme_example.sh

.PHONY: format
## format: clang-format firmware/ (house style: .clang-format)
format:
	$(Q)clang-format -i firmware/*/*.c firmware/*/*.h
