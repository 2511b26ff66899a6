#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
# Copyright (c) 2026, the pcl_phaser developers.
"""pcl_phaser against Open3D's global registration (FPFH + RANSAC) on the revisit pairs.

Both run in this process on the same pairs, one after the other per pair, with the same
number of threads; times are wall-clock per pair (file reading excluded, Open3D's
downsampling, normals and features included) and reported as medians and as the ratio
of Open3D's time to pcl_phaser's. A second table gives each method's stages (Open3D's
describe: downsampling, normals and FPFH of both clouds, then its RANSAC; pcl_phaser's
result.times), medians over the pairs in ms and as shares of pcl_phaser's median total. Open3D follows its own tutorial's recipe at a voxel v
(normals within 2 v, FPFH within 5 v, RANSAC with mutual-free matching, 1.5 v inlier
distance, edge-length 0.9 and distance checkers, 100,000 iterations, confidence 0.999).
Success as in pcl_phaser_bench revisits: RRE < 5 deg and RTE < 2 m.

  PYTHONPATH=build/python python3 bench/revisits_open3d.py [--data DIR] [--threads N]
      [--voxel V] [--max-pairs N] [--csv FILE]
"""
import argparse
import os
import sys
import time


def parse():
    here = os.path.dirname(os.path.abspath(__file__))
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--data", default=os.path.join(here, "..", "..", "shared", "data"))
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--voxel", type=float, default=1.0, help="Open3D's voxel v (m)")
    ap.add_argument("--max-pairs", type=int, default=0, help="0: all")
    ap.add_argument("--csv", default="", help="every trial as CSV")
    return ap.parse_args()


ARGS = parse()
# OpenMP reads its thread count when Open3D loads.
os.environ["OMP_NUM_THREADS"] = str(ARGS.threads)
import numpy as np  # noqa: E402
import open3d as o3d  # noqa: E402
import pcl_phaser  # noqa: E402


def read_pairs(path):
    pairs = []
    with open(path) as f:
        for line in f:
            if line.startswith("#") or not line.strip():
                continue
            w = line.split()
            T = np.array([float(x) for x in w[5:21]]).reshape(4, 4)
            pairs.append((w[0], w[1], float(w[2]), T))
    return pairs


def errors(T_est, T_ref):
    dR = T_est[:3, :3] @ T_ref[:3, :3].T
    angle = np.degrees(np.arccos(np.clip((np.trace(dR) - 1.0) / 2.0, -1.0, 1.0)))
    return angle, float(np.linalg.norm(T_est[:3, 3] - T_ref[:3, 3]))


# pcl_phaser's stages, as result.times names them (visitStageTimes() order).
PHASER_STAGES = ("target", "sampling", "sht", "so3", "refinement", "translation",
                 "orientation", "verification")


def open3d_align(source, target, v):
    """Open3D's T_target_source, whether RANSAC found one, and its stages (ms)."""
    reg = o3d.pipelines.registration

    def describe(points):
        pc = o3d.geometry.PointCloud(o3d.utility.Vector3dVector(points))
        down = pc.voxel_down_sample(v)
        down.estimate_normals(o3d.geometry.KDTreeSearchParamHybrid(radius=2 * v, max_nn=30))
        fpfh = reg.compute_fpfh_feature(
            down, o3d.geometry.KDTreeSearchParamHybrid(radius=5 * v, max_nn=100))
        return down, fpfh

    start = time.perf_counter()
    s, fs = describe(source)
    t, ft = describe(target)
    described = time.perf_counter()
    result = reg.registration_ransac_based_on_feature_matching(
        s, t, fs, ft, False, 1.5 * v, reg.TransformationEstimationPointToPoint(False), 3,
        [reg.CorrespondenceCheckerBasedOnEdgeLength(0.9),
         reg.CorrespondenceCheckerBasedOnDistance(1.5 * v)],
        reg.RANSACConvergenceCriteria(100000, 0.999))
    stages = {"describe": 1e3 * (described - start),
              "ransac": 1e3 * (time.perf_counter() - described)}
    return np.asarray(result.transformation), result.fitness > 0.0, stages


def main():
    folder = os.path.join(ARGS.data, "lidar", "balm_handheld")
    pairs_file = os.path.join(folder, "pairs.txt")
    if not os.path.exists(pairs_file):
        print(f"skipped: {pairs_file} not found (the shared data is absent)")
        return 0
    pairs = read_pairs(pairs_file)
    if ARGS.max_pairs > 0:
        pairs = pairs[:ARGS.max_pairs]
    if hasattr(o3d.utility, "random"):
        o3d.utility.random.seed(1)
    params = pcl_phaser.Parameters()
    params.num_threads = ARGS.threads
    load = lambda name: np.asarray(
        o3d.io.read_point_cloud(os.path.join(folder, name)).points)
    pcl_phaser.warm_up(params)
    rows = []
    for k, (src, tgt, dist, T_ref) in enumerate(pairs):
        S, T = load(src), load(tgt)
        for method in ("pcl_phaser", "open3d"):
            start = time.perf_counter()
            if method == "pcl_phaser":
                r = pcl_phaser.align(S, T, params=params)
                T_est, valid = np.asarray(r.transformation), r.converged
                stages = {name: getattr(r.times, name) for name in PHASER_STAGES}
            else:
                T_est, valid, stages = open3d_align(S, T, ARGS.voxel)
            ms = 1e3 * (time.perf_counter() - start)
            rre, rte = errors(T_est, T_ref)
            rows.append((method, src, tgt, dist, rre, rte, valid, ms, stages))
            print(f"[{k + 1}/{len(pairs)}] {src} -> {tgt} {method:10s} RRE {rre:7.2f} "
                  f"deg RTE {rte:7.3f} m valid {int(valid)} {ms:7.0f} ms", file=sys.stderr)
    if ARGS.csv:
        with open(ARGS.csv, "w") as f:
            names = list(PHASER_STAGES) + ["describe", "ransac"]
            f.write("method,source,target,dist,rre,rte,valid,ms," +
                    ",".join("stages_ms." + n for n in names) + "\n")
            for r in rows:
                f.write(",".join(str(x) for x in r[:8]) + "," +
                        ",".join(str(r[8].get(n, "")) for n in names) + "\n")
    report(rows, len(pairs))
    return 0


def report(rows, n):
    print(f"Revisit pairs: {n} of balm_handheld/pairs.txt, {ARGS.threads} threads, "
          f"Open3D {o3d.__version__} at voxel {ARGS.voxel} m; load "
          f"{os.getloadavg()[0]:.2f}. Success: RRE < 5 deg and RTE < 2 m.\n")
    print("| method | success | median RRE (deg) | median RTE (m) | valid but wrong |"
          " median time (ms) | time / pcl_phaser's (median of pairs) |")
    print("|---|---|---|---|---|---|---|")
    phaser_ms = {(r[1], r[2]): r[7] for r in rows if r[0] == "pcl_phaser"}
    for method in ("pcl_phaser", "open3d"):
        mine = [r for r in rows if r[0] == method]
        ok = [r for r in mine if r[4] < 5.0 and r[5] < 2.0]
        wrong_valid = sum(1 for r in mine if r[6] and not (r[4] < 5.0 and r[5] < 2.0))
        ratio = np.median([r[7] / phaser_ms[(r[1], r[2])] for r in mine])
        med = lambda xs: f"{np.median(xs):.2f}" if xs else "-"
        print(f"| {method} | {len(ok)} / {len(mine)} | {med([r[4] for r in ok])} | "
              f"{med([r[5] for r in ok])} | {wrong_valid} | "
              f"{np.median([r[7] for r in mine]):.0f} | {ratio:.2f} |")
    report_stages(rows)


def report_stages(rows):
    """Each method's median total and stages, in ms and x pcl_phaser's median total."""
    reference = np.median([r[7] for r in rows if r[0] == "pcl_phaser"])
    print("\nWhere the time goes: medians over the pairs.\n")
    print("| method | stage | median (ms) | x pcl_phaser's total |\n|---|---|---|---|")
    for method in ("pcl_phaser", "open3d"):
        mine = [r for r in rows if r[0] == method]
        lines = [("total", np.median([r[7] for r in mine]))]
        lines += [(name, np.median([r[8][name] for r in mine])) for name in mine[0][8]]
        for name, ms in lines:
            print(f"| {method} | {name} | {ms:.1f} | {ms / reference:.3f} |")


if __name__ == "__main__":
    sys.exit(main())
