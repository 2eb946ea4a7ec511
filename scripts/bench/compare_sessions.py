#!/usr/bin/env python3
"""Compare a several-session run's poses (OUT/session-k/poses_tum.txt, or
OUT/poses_tum.txt for one session) with a
single-session run's (REF/poses_tum.txt), frame by frame (matched by stamp),
in the first session's frame, without any alignment. Prints the RMS and the
largest translation difference (m) and the largest rotation difference (deg)."""
import math
import os
import sys

import numpy as np


def read_tum(path):
    rows = np.loadtxt(path, comments="#", ndmin=2)
    return {round(r[0], 6): r[1:] for r in rows}


def quat_angle_deg(a, b):
    dot = abs(float(np.dot(a / np.linalg.norm(a), b / np.linalg.norm(b))))
    return math.degrees(2.0 * math.acos(min(1.0, dot)))


def main():
    ref_dir, out_dir = sys.argv[1], sys.argv[2]
    reference = read_tum(os.path.join(ref_dir, "poses_tum.txt"))
    k = 0
    summary = []
    if not os.path.isdir(os.path.join(out_dir, "session-0")):
        sessions = [out_dir]
    else:
        sessions = []
        while os.path.isdir(os.path.join(out_dir, f"session-{k}")):
            sessions.append(os.path.join(out_dir, f"session-{k}"))
            k += 1
    for k, folder in enumerate(sessions):
        est = read_tum(os.path.join(folder, "poses_tum.txt"))
        shared = [s for s in est if s in reference]
        if not shared:
            sys.exit(f"session-{k}: no stamp in common with {ref_dir}")
        dt = np.array([np.linalg.norm(est[s][:3] - reference[s][:3]) for s in shared])
        dr = np.array([quat_angle_deg(est[s][3:], reference[s][3:]) for s in shared])
        summary.append(f"session-{k}: {len(shared)} frames, rms {math.sqrt(np.mean(dt ** 2)) * 100:.2f} cm, "
                       f"max {dt.max() * 100:.2f} cm, max {dr.max():.3f} deg")
    print("; ".join(summary))


if __name__ == "__main__":
    main()
