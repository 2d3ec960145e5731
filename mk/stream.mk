# mk/stream.mk - streaming with real peers: a pyserial client and LinuxCNC's rs274.
# SPDX-License-Identifier: MIT

.PHONY: sim-pyserial
## sim-pyserial: docs/examples/run_job.py (pyserial) runs a job against fw_native --pty (word "pyserial")
sim-pyserial: $(BUILD)/host/fw_native
	$(Q)BUILD=$(BUILD) sh tools/pyserial_test.sh
