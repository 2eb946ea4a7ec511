#!/usr/bin/env python3
"""ATE (RMSE after an SE(3) alignment, m) of runs against a dataset's own
reference trajectory (DATASET/optimized_poses.txt, KITTI, stamped by
DATASET/times.txt). A run is OUT/poses_tum.txt or OUT/session-k/poses_tum.txt.

  ate_reference.py DATASET OUT [OUT ...]
"""
import os
import sys

import numpy as np


def read_tum(path):
    return {round(r[0], 6): r[1:4] for r in np.loadtxt(path, comments="#", ndmin=2)}


def run_positions(out):
    files = [os.path.join(out, "poses_tum.txt")]
    k = 0
    while os.path.isdir(os.path.join(out, f"session-{k}")):
        files.append(os.path.join(out, f"session-{k}", "poses_tum.txt"))
        k += 1
    positions = {}
    for f in files:
        if os.path.exists(f):
            for stamp, p in read_tum(f).items():
                positions.setdefault(stamp, p)
    return positions


def main():
    dataset = sys.argv[1]
    ref = np.loadtxt(os.path.join(dataset, "optimized_poses.txt")).reshape(-1, 3, 4)[:, :, 3]
    stamps = np.array([float(t) for t in open(os.path.join(dataset, "times.txt")).read().split()])
    for out in sys.argv[2:]:
        est = run_positions(out)
        # Each estimate paired with the reference frame of the nearest stamp (within 1 ms).
        keys, frames = [], []
        for k in sorted(est):
            i = int(np.argmin(np.abs(stamps - k)))
            if abs(stamps[i] - k) < 1e-3:
                keys.append(k)
                frames.append(i)
        p = np.array([est[k] for k in keys])
        q = ref[frames]
        mp, mq = p.mean(0), q.mean(0)
        u, _, vt = np.linalg.svd((p - mp).T @ (q - mq))
        d = np.eye(3)
        d[2, 2] = np.sign(np.linalg.det(vt.T @ u.T))
        r = vt.T @ d @ u.T
        e = np.linalg.norm((r @ (p - mp).T).T + mq - q, axis=1)
        print(f"{out}: {len(keys)} frames, ATE {np.sqrt(np.mean(e ** 2)):.3f} m")


if __name__ == "__main__":
    main()
