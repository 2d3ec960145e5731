# mk/stream.mk - streaming with real peers: a pyserial client and LinuxCNC's rs274.
# SPDX-License-Identifier: MIT

.PHONY: sim-pyserial
## sim-pyserial: docs/examples/run_job.py (pyserial) runs a job against fw_native --pty (word "pyserial")
sim-pyserial: $(BUILD)/host/fw_native
	$(Q)BUILD=$(BUILD) sh tools/pyserial_test.sh

.PHONY: demo sim-rs274
## demo: the paper's example (G-code) and a boss fillet (frames, ball tool) through the
##       firmware on a pty, judged by host_sim: summary tables, CSV, G-code and SVG in build/demo
demo: $(BUILD)/host/fw_native $(BUILD)/host/host_sim
	@mkdir -p $(BUILD)/demo
	$(Q)for j in paper_gcode boss_frames; do \
	    echo "== $$j: tests/jobs/$$j.job through build/host/fw_native on a pty"; \
	    $(BUILD)/host/host_sim --target native --fw $(BUILD)/host/fw_native --job tests/jobs/$$j.job \
	        --csv $(BUILD)/demo/$$j.csv --gcode $(BUILD)/demo/$$j.ngc --svg $(BUILD)/demo/$$j.svg \
	        | grep -v '^  PASS' || exit 1; done
	@echo "demo: toolpaths drawn in $(BUILD)/demo/paper_gcode.svg and $(BUILD)/demo/boss_frames.svg"

## sim-rs274: LinuxCNC's rs274 runs the streamed G-code (paper; boss with a ball tool) with 0
##            errors and every STRAIGHT_FEED equals the received point to 0.1 um (word "rs274")
sim-rs274: $(BUILD)/host/fw_native $(BUILD)/host/host_sim
	@mkdir -p $(BUILD)/rs274
	$(Q)ok=0; bad=0; for j in paper_gcode boss_gcode; do \
	    if $(BUILD)/host/host_sim --target native --fw $(BUILD)/host/fw_native --job tests/jobs/$$j.job \
	        --csv $(BUILD)/rs274/$$j.csv --gcode $(BUILD)/rs274/$$j.ngc > $(BUILD)/rs274/$$j.log 2>&1; then \
	        out=$$(sh tools/rs274_check.sh $(BUILD)/rs274/$$j.ngc $(BUILD)/rs274/$$j.csv); echo "$$out" | sed '$$d'; \
	        p=$$(echo "$$out" | sed -n 's/^rs274: \([0-9]*\) passed, \([0-9]*\) failed$$/\1/p'); \
	        f=$$(echo "$$out" | sed -n 's/^rs274: \([0-9]*\) passed, \([0-9]*\) failed$$/\2/p'); \
	        ok=$$((ok + p)); bad=$$((bad + f)); \
	    else echo "  FAIL host_sim on $$j"; tail -3 $(BUILD)/rs274/$$j.log; bad=$$((bad + 1)); fi; done; \
	echo "rs274: $$ok passed, $$bad failed"; [ $$bad -eq 0 ]
