#!/usr/bin/env python3
"""Optimizes a sequence held in numpy arrays with hba, and measures the result.

    hba simulate --frames 100 --seed 1 -o /tmp/sim
    PYTHONPATH=build/python python3 python/examples/optimize_numpy.py /tmp/sim

Any folder `hba optimize` reads works; the scans could as well come from your
own pipeline, as (N, 3) or (N, 4) float arrays in the sensor frame.
"""
import argparse
import os

import hba


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("folder", help="a dataset folder (hba, scans or kitti layout)")
    parser.add_argument("--window", type=int, default=10, help="frames per local window")
    parser.add_argument("--output", help="write the optimized poses here (KITTI format)")
    args = parser.parse_args()

    dataset = hba.open_dataset(args.folder)
    scans = [dataset[i] for i in range(len(dataset))]  # a list of (N, 4) float32 arrays
    poses = dataset.poses                                # (K, 4, 4) sensor-to-world
    print(f"{len(scans)} scans, {sum(len(s) for s in scans)} points")

    result = hba.optimize(scans, poses, window=args.window, local={"max_iterations": 10})
    report = result.report
    print(f"{report['layers']} layers on {report['threads']} threads, "
          f"{report['seconds']['total']:.1f} s; largest move "
          f"{report['largest_update']['translation_m']:.3f} m")

    before, after = hba.mme(scans, poses), hba.mme(scans, result.poses)
    print(f"mean map entropy: {before:.3f} -> {after:.3f} (lower is crisper)")

    gt_file = os.path.join(args.folder, "gt.txt")  # the simulator's ground truth
    if os.path.exists(gt_file):
        gt = hba.read_poses(gt_file)
        for name, estimate in (("input", poses), ("optimized", result.poses)):
            ate = hba.ate(gt, estimate)["translation_m"]
            print(f"ATE {name:9s}: rmse {ate['rmse']:.4f} m, max {ate['max']:.4f} m")

    if args.output:
        hba.write_poses(args.output, result.poses, format="kitti")
        print(f"wrote {args.output}")


if __name__ == "__main__":
    main()
