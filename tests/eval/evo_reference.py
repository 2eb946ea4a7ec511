#!/usr/bin/env python3
"""Independent reference for `hba eval` (numpy only), following evo's definitions.

Usage: evo_reference.py GT.kitti EST.kitti [se3|sim3|none] [DELTA_FRAMES]
Prints ATE/RPE statistics (rmse mean median max) for translation (m) and
rotation (deg). Written separately from the C++ code, in a different style
(matrices, arccos of the trace), to cross-check it; the numbers it printed for
hku1 are recorded in test_eval_cli.cpp and docs/eval.md.
"""
import sys
import numpy as np


def read_kitti(path):
    rows = np.loadtxt(path).reshape(-1, 12)
    poses = np.tile(np.eye(4), (len(rows), 1, 1))
    poses[:, :3, :4] = rows.reshape(-1, 3, 4)
    # Text files round the matrices (6 digits in hku1): use the nearest
    # rotation, as hba's reader does (evo's scipy conversion does likewise).
    for pose in poses:
        u, _, vt = np.linalg.svd(pose[:3, :3])
        pose[:3, :3] = u @ vt
    return poses


def umeyama(x, y, with_scale):
    """s, R, t minimising sum |y - (s R x + t)|^2; x, y are 3xN."""
    mx, my = x.mean(axis=1, keepdims=True), y.mean(axis=1, keepdims=True)
    xc, yc = x - mx, y - my
    n = x.shape[1]
    sigma = yc @ xc.T / n
    u, d, vt = np.linalg.svd(sigma)
    s_mat = np.eye(3)
    if np.linalg.det(u) * np.linalg.det(vt) < 0:
        s_mat[2, 2] = -1
    r = u @ s_mat @ vt
    c = np.trace(np.diag(d) @ s_mat) / (np.sum(xc ** 2) / n) if with_scale else 1.0
    t = my - c * r @ mx
    return c, r, t


def angle_deg(r):
    return np.degrees(np.arccos(np.clip((np.trace(r) - 1.0) / 2.0, -1.0, 1.0)))


def stats(e):
    e = np.asarray(e)
    return np.sqrt(np.mean(e ** 2)), np.mean(e), np.median(e), np.max(e)


def main():
    gt, est = read_kitti(sys.argv[1]), read_kitti(sys.argv[2])
    align = sys.argv[3] if len(sys.argv) > 3 else "se3"
    delta = int(sys.argv[4]) if len(sys.argv) > 4 else 1
    aligned = est.copy()
    if align != "none":
        c, r, t = umeyama(est[:, :3, 3].T, gt[:, :3, 3].T, align == "sim3")
        s_transform = np.eye(4)
        s_transform[:3, :3] = r
        s_transform[:3, 3] = t.ravel()
        for k in range(len(est)):
            p = est[k].copy()
            p[:3, 3] *= c
            aligned[k] = s_transform @ p
    ate_t = [np.linalg.norm(gt[k][:3, 3] - aligned[k][:3, 3]) for k in range(len(gt))]
    ate_r = [angle_deg(gt[k][:3, :3].T @ aligned[k][:3, :3]) for k in range(len(gt))]
    rpe_t, rpe_r = [], []
    for i in range(len(gt) - delta):
        j = i + delta
        q = np.linalg.inv(gt[i]) @ gt[j]
        p = np.linalg.inv(aligned[i]) @ aligned[j]
        e = np.linalg.inv(q) @ p
        rpe_t.append(np.linalg.norm(e[:3, 3]))
        rpe_r.append(angle_deg(e[:3, :3]))
    for name, values in (("ATE trans m", ate_t), ("ATE rot deg", ate_r),
                         ("RPE trans m", rpe_t), ("RPE rot deg", rpe_r)):
        print("%-12s rmse %.9f mean %.9f median %.9f max %.9f" % ((name,) + stats(values)))


if __name__ == "__main__":
    main()
