#!/usr/bin/env python3
"""Split a real dataset folder (Scans/, KITTI odom_poses.txt, times.txt) into
two sessions for the several-session benchmarks: frames [a0, a1) and [b0, b1),
the second given in a frame moved by a translation, yaw and roll. The scans
are symbolic links: the input is never modified.

  split_sessions.py DATASET OUT A0:A1 B0:B1 [--shift X,Y,Z] [--yaw DEG] [--roll DEG]
"""
import argparse
import math
import os
import sys

import numpy as np


def rotation(yaw_deg, roll_deg):
    y, r = math.radians(yaw_deg), math.radians(roll_deg)
    rz = np.array([[math.cos(y), -math.sin(y), 0], [math.sin(y), math.cos(y), 0], [0, 0, 1]])
    rx = np.array([[1, 0, 0], [0, math.cos(r), -math.sin(r)], [0, math.sin(r), math.cos(r)]])
    return rz @ rx


def write_session(src, out, first, end, transform):
    poses = np.loadtxt(os.path.join(src, "odom_poses.txt")).reshape(-1, 3, 4)
    times = open(os.path.join(src, "times.txt")).read().split()
    scans = sorted(os.listdir(os.path.join(src, "Scans")))
    if not (0 <= first < end <= len(poses)):
        sys.exit(f"{src}: frames {first}:{end} outside 0:{len(poses)}")
    os.makedirs(os.path.join(out, "Scans"))
    with open(os.path.join(out, "odom_poses.txt"), "w") as f:
        for k in range(first, end):
            m = np.vstack([poses[k], [0, 0, 0, 1]])
            m = transform @ m
            f.write(" ".join(f"{v:.9g}" for v in m[:3].reshape(-1)) + "\n")
    with open(os.path.join(out, "times.txt"), "w") as f:
        f.write("\n".join(times[first:end]) + "\n")
    ext = os.path.splitext(scans[0])[1]
    for i, k in enumerate(range(first, end)):
        os.symlink(os.path.abspath(os.path.join(src, "Scans", scans[k])),
                   os.path.join(out, "Scans", f"{i:06d}{ext}"))


def main():
    p = argparse.ArgumentParser()
    p.add_argument("dataset")
    p.add_argument("out")
    p.add_argument("a")
    p.add_argument("b")
    p.add_argument("--shift", default="0,0,0")
    p.add_argument("--yaw", type=float, default=0.0)
    p.add_argument("--roll", type=float, default=0.0)
    args = p.parse_args()
    a0, a1 = (int(v) for v in args.a.split(":"))
    b0, b1 = (int(v) for v in args.b.split(":"))
    moved = np.eye(4)
    moved[:3, :3] = rotation(args.yaw, args.roll)
    moved[:3, 3] = [float(v) for v in args.shift.split(",")]
    write_session(args.dataset, os.path.join(args.out, "A"), a0, a1, np.eye(4))
    write_session(args.dataset, os.path.join(args.out, "B"), b0, b1, moved)


if __name__ == "__main__":
    main()
