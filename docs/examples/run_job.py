#!/usr/bin/python3
"""run_job.py DEVICE JOBFILE [OUT.ngc] - send a job file's settings to canalpath, RUN it and
count the points, with the Python host library (host_sim/python: `pip install
host_sim/python`, or run from the checkout as here). DEVICE: a serial port or the LINK of
`fw_native --pty LINK`. The library answers the G-code as the machine would ("ok").
"""
import pathlib, sys; sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2] / "host_sim/python"))
from canalpath import Job, Link

out = open(sys.argv[3] if len(sys.argv) > 3 else "/dev/null", "w")
with Link.open(sys.argv[1]) as link:
    link.send_job(Job.from_file(sys.argv[2]))
    points = sum(1 for _ in link.run(on_gcode=lambda line: out.write(line + "\n")))
print("pyserial: %d points, RUN ok" % points)
