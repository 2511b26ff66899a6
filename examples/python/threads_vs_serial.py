#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
# Copyright (c) 2026, the pcl_phaser developers.
"""Two Python threads aligning at once against the same two aligns one after the other
(one engine thread each): prints both wall times and their ratio, the median of --runs.

    PYTHONPATH=build/python python3 examples/python/threads_vs_serial.py \\
        SOURCE.pcd TARGET.pcd [--runs 7] [--layout f32x4|f32x3|f64x3|f32x3F]

Reads binary PCD (x y z intensity first) or KITTI .bin; the second align is the pair
swapped, so both threads have the same amount of work. --layout: the arrays handed to
pcl_phaser, float32 (N, 4) as read (default), float32 or float64 (N, 3), or float32 (N, 3)
in Fortran order.
"""
import argparse
import os
import statistics
import threading
import time

import numpy as np

import pcl_phaser
from loop_closures import read_scan


def timed(function):
    start = time.perf_counter()
    function()
    return time.perf_counter() - start


def layout(cloud, kind):
    """\a cloud (N, 4) float32 in the array layout \a kind."""
    if kind == "f32x4":
        return cloud
    xyz = cloud[:, :3].astype(np.float64 if kind == "f64x3" else np.float32)
    return np.asfortranarray(xyz) if kind == "f32x3F" else np.ascontiguousarray(xyz)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("source")
    parser.add_argument("target")
    parser.add_argument("--runs", type=int, default=7)
    parser.add_argument("--layout", default="f32x4",
                        choices=["f32x4", "f32x3", "f64x3", "f32x3F"])
    args = parser.parse_args()
    a, b = (layout(read_scan(path, ""), args.layout) for path in (args.source, args.target))
    params = pcl_phaser.Parameters(num_threads=1)
    jobs = [lambda: pcl_phaser.align(a, b, params=params),
            lambda: pcl_phaser.align(b, a, params=params)]
    pcl_phaser.warm_up(params, points=len(a))
    for job in jobs:  # first aligns of the process, not measured
        job()

    def serial():
        for job in jobs:
            job()

    def threads():
        workers = [threading.Thread(target=job) for job in jobs]
        for w in workers:
            w.start()
        for w in workers:
            w.join()

    rows = []
    for _ in range(args.runs):  # interleaved, so that drifts hit both alike
        rows.append((timed(serial), timed(threads)))
    s = statistics.median(r[0] for r in rows)
    t = statistics.median(r[1] for r in rows)
    ratios = sorted(r[0] / r[1] for r in rows)
    print("serial %.1f ms, two threads %.1f ms (medians of %d); serial / threads %.2f "
          "(range %.2f-%.2f); load average %.1f" % (1e3 * s, 1e3 * t, args.runs, s / t,
                                                    ratios[0], ratios[-1],
                                                    os.getloadavg()[0]))


if __name__ == "__main__":
    main()
