#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
# Copyright (c) 2026, the pcl_phaser developers.
"""Loop-closure sketch over a pose file: candidates are scans within --radius meters of
each other and at least --min-gap scans apart; each candidate is registered (each target
prepared once) and the converged ones are printed as edges T_i_j with their covariance
and their difference from the odometry.

    PYTHONPATH=<prefix>/lib/python3/dist-packages python3 loop_closures.py \\
        ../shared/data/lidar/balm_handheld/poses_T_world_lidar.txt \\
        --scans '../shared/data/lidar/balm_handheld/full{}.pcd' [--scheduler local|tcp://HOST:8786]

Pose lines: a scan index, then (optionally other columns and) the row-major 3 x 4
T_world_scan as the last 12 numbers; '#' starts a comment. Scans are read as binary PCD
(x y z intensity) or KITTI .bin files.
"""
import argparse
import functools

import numpy as np

import pcl_phaser


def read_poses(path):
    """[(scan index, T_world_scan)] in file order."""
    poses = []
    for line in open(path):
        fields = line.split()
        if not fields or fields[0].startswith("#"):
            continue
        T = np.eye(4)
        T[:3] = np.array(fields[-12:], float).reshape(3, 4)
        poses.append((int(fields[0]), T))
    return poses


def read_scan(pattern, index):
    """Scan `index` as (N, 4) float32: x y z intensity."""
    path = pattern.format(index)
    if path.endswith(".bin"):
        return np.fromfile(path, dtype=np.float32).reshape(-1, 4)
    with open(path, "rb") as f:  # binary PCD whose first fields are x y z intensity
        header = {}
        while "DATA" not in header:
            key, _, value = f.readline().decode("ascii").strip().partition(" ")
            header[key] = value.split()
        size = sum(int(s) * int(c) for s, c in zip(header["SIZE"], header["COUNT"]))
        raw = np.frombuffer(f.read(), dtype=np.uint8)
        rows = raw[: int(header["POINTS"][0]) * size].reshape(-1, size)
        return rows[:, :16].copy().view(np.float32)


def candidates(poses, radius, min_gap):
    """(source j, target i) scan indices: within radius meters, min_gap scans apart."""
    pairs = []
    for a, (i, Ti) in enumerate(poses):
        for j, Tj in [p for p in poses[a + min_gap:]]:
            if np.linalg.norm(Ti[:3, 3] - Tj[:3, 3]) <= radius:
                pairs.append((j, i))
    return pairs


def angle_deg(R):
    return np.degrees(np.arccos(np.clip((np.trace(R) - 1) / 2, -1, 1)))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("poses")
    parser.add_argument("--scans", required=True, help="path pattern, {} = scan index")
    parser.add_argument("--radius", type=float, default=20.0)
    parser.add_argument("--min-gap", type=int, default=10)
    parser.add_argument("--scheduler", help="'local' (LocalCluster) or tcp://HOST:PORT")
    args = parser.parse_args()
    poses = read_poses(args.poses)
    world = dict(poses)
    pairs = candidates(poses, args.radius, args.min_gap)
    reader = functools.partial(read_scan, args.scans)
    params = pcl_phaser.Parameters(num_threads=1 if args.scheduler else 0)
    client = None
    if args.scheduler:
        from dask.distributed import Client, LocalCluster
        client = Client(LocalCluster(threads_per_worker=1) if args.scheduler == "local"
                        else args.scheduler)
    results = pcl_phaser.align_many(pairs, reader, params, client=client)
    print("# source target converged rot_vs_odometry_deg trans_vs_odometry_m sigma_t_m")
    for (j, i), r in zip(pairs, results):
        odometry = np.linalg.inv(world[i]) @ world[j]
        d = np.linalg.inv(odometry) @ r.transformation
        sigma = np.sqrt(np.trace(r.covariance[3:, 3:])) if r.converged else float("nan")
        print("%d %d %d %.3f %.3f %.4f" % (j, i, r.converged, angle_deg(d[:3, :3]),
                                           np.linalg.norm(d[:3, 3]), sigma))
    print("# %d of %d candidates converged" % (sum(r.converged for r in results),
                                                len(results)))
    if client is not None:
        client.close()


if __name__ == "__main__":
    main()
