#!/usr/bin/python3
"""stream_frames.py DEVICE OUT.csv - the paper's fillet built with the Job builders,
streamed as binary FRAMES with a progress line, and resumed where it stopped if the port
hangs up (docs/PROTOCOL.md "Resume"). Uses the Python host library (host_sim/python).
"""
import pathlib
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2] / "host_sim/python"))
from canalpath import Job, Link, LinkError, Progress  # noqa: E402

job = (Job().curve_arc(0, 0, 3, 0, 360)      # C: a circle r = 3, 0..360 deg
       .radius_cos(5.5, 10.5, 2)             # R = 5.5 cos 2t + 10.5
       .lines(8, -25, 10).tol(2)             # 8 curvature lines, 2 um chords
       .format("FRAMES"))                    # raises JobValueError on a value the firmware refuses


def show(p: Progress) -> None:
    eta = "%.1f s" % p.eta if p.eta is not None else "?"
    print("\r%d/%d points, %.0f points/s, ETA %s   " % (p.points, p.total, p.rate, eta), end="", file=sys.stderr)


points = []
for attempt in range(3):                     # a hang-up: reconnect, send the job again, RESUME k
    try:
        with Link.open(sys.argv[1]) as link:
            link.send_job(job)
            points.extend(link.run(resume=len(points) or None, progress=show))
        break
    except LinkError as e:
        print("\nlink lost after %d points (%s): resuming" % (len(points), e), file=sys.stderr)
print(file=sys.stderr)
with open(sys.argv[2], "w") as f:
    f.write("k,x,y,z,nx,ny,nz,line,index\n")
    for p in points:
        f.write("%d,%.4f,%.4f,%.4f,%.5f,%.5f,%.5f,%d,%d\n" % ((p.k, p.x, p.y, p.z) + p.normal + (p.line, p.index)))
print("%d points in %s" % (len(points), sys.argv[2]))
