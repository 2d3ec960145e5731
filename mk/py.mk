# mk/py.mk - the Python host library (host_sim/python: package canalpath, pytest suite).
# SPDX-License-Identifier: MIT

.PHONY: py-test bench-py
## py-test: the Python host library's pytest suite (host_sim/python/tests) against fw_native
##          on a pty and fw.elf under QEMU: every demo job gives host_sim's points, hang-up +
##          RESUME, corrupted frames recovered, bad input typed, pip install in a venv (word "py")
py-test: $(BUILD)/host/fw_native $(BUILD)/host/host_sim m4f-fw
	$(Q)BUILD=$(BUILD) sh tools/py_test.sh

## bench-py: the library's figures: FRAMES receive path in frames/s, wire utilization at
##           115200 baud in both formats (tools/baud_relay.py between fw_native and the library)
bench-py: $(BUILD)/host/fw_native
	$(Q)/usr/bin/python3 tools/bench_py.py $(BUILD)
