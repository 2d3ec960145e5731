# mk/stream.mk - streaming with real peers: a pyserial client and LinuxCNC's rs274.
# SPDX-License-Identifier: MIT

.PHONY: sim-pyserial
## sim-pyserial: docs/examples/run_job.py (pyserial) runs a job against fw_native --pty (word "pyserial")
sim-pyserial: $(BUILD)/host/fw_native
	$(Q)BUILD=$(BUILD) sh tools/pyserial_test.sh

.PHONY: demo sim-rs274
## demo: the paper's example (G-code), a boss fillet (frames, ball tool) and one job of each model (GSR, channel, DRC fillet, SPINE helix bore) through the
##       firmware on a pty, judged by host_sim: summary tables, CSV, G-code and SVG in build/demo; then the paper
##       as a program to host_sim's grbl 1.1h on the machine link (two links)
demo: $(BUILD)/host/fw_native $(BUILD)/host/host_sim
	@mkdir -p $(BUILD)/demo
	$(Q)for j in paper_gcode boss_frames model_gsr_frames model_channel_frames model_drc_fillet model_spine_demo; do \
	    echo "== $$j: tests/jobs/$$j.job through build/host/fw_native on a pty"; \
	    $(BUILD)/host/host_sim --target native --fw $(BUILD)/host/fw_native --job tests/jobs/$$j.job \
	        --csv $(BUILD)/demo/$$j.csv --gcode $(BUILD)/demo/$$j.ngc --svg $(BUILD)/demo/$$j.svg \
	        | grep -v '^  PASS' || exit 1; done
	@echo "== paper_gcode.job in a two-link cell: the program to host_sim's grbl 1.1h on the machine link"
	$(Q)$(BUILD)/host/host_sim --target native --fw $(BUILD)/host/fw_native --job tests/jobs/paper_gcode.job \
	    --machine grbl --gcode $(BUILD)/demo/paper_grbl.ngc | grep -E '^sim: cell|FAIL|^sim: [0-9]' || exit 1
	@echo "demo: toolpaths drawn in $(BUILD)/demo/*.svg (the paper, a boss fillet, a GSR pipe, the channel, a fillet along a sketched edge, the bore of a helix tube); the grbl program in $(BUILD)/demo/paper_grbl.ngc"

## sim-rs274: LinuxCNC's rs274 runs every G-code program of the suite (the paper; the boss with a
##            ball tool; placed on an inclined face; the GSR, channel, DRC and SPINE jobs; 5-axis A/C words
##            with a spindle and a work offset; a job that first lacks FEED) with 0 errors: every
##            STRAIGHT_FEED equals the received point to 0.1 um, every STRAIGHT_TRAVERSE is at the
##            safe height above the cut, A/C equal the judged tool axis (word "rs274")
sim-rs274: $(BUILD)/host/fw_native $(BUILD)/host/host_sim
	@mkdir -p $(BUILD)/rs274
	$(Q)ok=0; bad=0; for j in paper_gcode boss_gcode placed_gcode model_gsr_gcode model_channel_gcode model_spine_gcode \
	    model_drc_curve axis5_ac no_feed; do \
	    if $(BUILD)/host/host_sim --target native --fw $(BUILD)/host/fw_native --job tests/jobs/$$j.job \
	        --csv $(BUILD)/rs274/$$j.csv --gcode $(BUILD)/rs274/$$j.ngc > $(BUILD)/rs274/$$j.log 2>&1; then \
	        out=$$(sh tools/rs274_check.sh $(BUILD)/rs274/$$j.ngc $(BUILD)/rs274/$$j.csv); echo "$$out" | sed '$$d'; \
	        p=$$(echo "$$out" | sed -n 's/^rs274: \([0-9]*\) passed, \([0-9]*\) failed$$/\1/p'); \
	        f=$$(echo "$$out" | sed -n 's/^rs274: \([0-9]*\) passed, \([0-9]*\) failed$$/\2/p'); \
	        ok=$$((ok + p)); bad=$$((bad + f)); \
	    else echo "  FAIL host_sim on $$j"; tail -3 $(BUILD)/rs274/$$j.log; bad=$$((bad + 1)); fi; done; \
	echo "rs274: $$ok passed, $$bad failed"; [ $$bad -eq 0 ]

.PHONY: sim-asan
## sim-asan: fw_native and host_sim built with ASan + UBSan (no recovery) run judged sessions:
##           G-code, frames, checksums with a dropped byte, a hang-up with RESUME (word "sim-asan")
SAN_CC := $(CC) -fsanitize=address,undefined -fno-sanitize-recover=all
sim-asan:
	$(Q)$(MAKE) --no-print-directory BUILD=$(BUILD)/asan CC="$(SAN_CC)" STACK_FN_MAX=65536 fw-native host-sim >/dev/null
	$(Q)ok=0; bad=0; A=$(BUILD)/asan/host; \
	for c in "paper_gcode.job" "paper_frames.job" "paper_gcode_cs.job --fault drop@5003" \
	         "paper_frames.job --fault hangup@40000 --resume" "boss_frames.job --fault flip@1000"; do \
	    set -- $$c; j=$$1; shift; \
	    if ASAN_OPTIONS=detect_leaks=0 $$A/host_sim --target native --fw $$A/fw_native \
	        --job tests/jobs/$$j "$$@" > $(BUILD)/asan/last.log 2>&1; then \
	        ok=$$((ok + 1)); echo "  PASS $$c"; \
	    else bad=$$((bad + 1)); echo "  FAIL $$c"; grep -E "ERROR|runtime error|FAIL" $(BUILD)/asan/last.log | head -5; fi; done; \
	echo "sim-asan: $$ok passed, $$bad failed"; [ $$bad -eq 0 ]
