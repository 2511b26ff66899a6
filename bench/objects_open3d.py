#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
# Copyright (c) 2026, the pcl_phaser developers.
"""pcl_phaser against Open3D's FPFH + RANSAC on partial range scans of an object.

The Stanford bunny views of object/stanford_bunny, truth from Stanford's bun.conf
(p_bun000 = R(q)^T p + t, so T_target_source = T_000_target^-1 T_000_source), as in
pcl_phaser_bench objects. Pairs: every ordered pair of the views present whose
source has at least --min-overlap of its points within 2 mm of the target after the
truth; the other ordered pairs are aligned by pcl_phaser too, whose converged flag should
not claim them. Right: rotation error < 5 deg and translation error < 5 mm.

Both run in this process on the same pairs, pair after pair, the order of the two
swapped at every pair, with the same threads, after one untimed align each of the first
pair. Times are wall-clock per align (reading excluded; Open3D's downsampling, normals
and features included), reported as medians and as the ratio of Open3D's median to
pcl_phaser's. pcl_phaser runs at its defaults but the threads. Open3D follows its
tutorial's recipe at a voxel v: normals within 2 v (30 neighbors), FPFH within 5 v (100),
RANSAC on mutual feature matches with 3 points, 1.5 v inlier distance, edge-length 0.9
and distance checkers, 100,000 iterations, confidence 0.999. Open3D reports no
convergence.

  PYTHONPATH=build/python python3 bench/objects_open3d.py [--data DIR] [--threads N]
      [--voxel V] [--min-overlap F] [--no-mutual-filter] [--csv FILE]
"""
import argparse
import itertools
import os
import sys
import time


def parse():
    here = os.path.dirname(os.path.abspath(__file__))
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--data", default=os.path.join(here, "..", "..", "shared", "data"))
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--voxel", type=float, default=0.004, help="Open3D's voxel v (m)")
    ap.add_argument("--min-overlap", type=float, default=0.3)
    ap.add_argument("--no-mutual-filter", dest="mutual", action="store_false",
                    help="Open3D's RANSAC on one-way feature matches")
    ap.add_argument("--csv", default="", help="every trial as CSV")
    return ap.parse_args()


ARGS = parse()
os.environ["OMP_NUM_THREADS"] = str(ARGS.threads)  # read when Open3D loads
import numpy as np  # noqa: E402
import open3d as o3d  # noqa: E402
import pcl_phaser  # noqa: E402

RIGHT_DEG, RIGHT_M, OVERLAP_RADIUS = 5.0, 0.005, 0.002


def read_ply(path):
    """x y z of the vertices of an ASCII PLY; elements after the vertices (the scanner's
    range_grid) are not read."""
    with open(path) as f:
        if f.readline().strip() != "ply":
            raise ValueError(f"{path}: not a PLY file")
        count, names, element = None, [], None
        for line in f:
            w = line.split()
            if w[:1] == ["format"] and w[1] != "ascii":
                raise ValueError(f"{path}: {w[1]} PLY, only ascii is read")
            if w[:1] == ["element"]:
                element = w[1]
                count = int(w[2]) if element == "vertex" else count
            if w[:1] == ["property"] and element == "vertex":
                names.append(w[-1])
            if w[:1] == ["end_header"]:
                break
        columns = [names.index(axis) for axis in ("x", "y", "z")]
        return np.loadtxt(f, max_rows=count, usecols=columns, ndmin=2)


def read_views(folder):
    """{view: T_000_view} of the bmesh lines of bun.conf whose PLY is present."""
    views = {}
    with open(os.path.join(folder, "bun.conf")) as f:
        for line in f:
            w = line.split()
            if len(w) != 9 or w[0] != "bmesh":
                continue
            if os.path.exists(os.path.join(folder, w[1])):
                qx, qy, qz, qw = map(float, w[5:9])
                T = np.eye(4)
                T[:3, :3] = o3d.geometry.get_rotation_matrix_from_quaternion(
                    np.array([qw, qx, qy, qz]) / np.linalg.norm([qw, qx, qy, qz])).T
                T[:3, 3] = [float(x) for x in w[2:5]]
                views[w[1]] = T
    return views


def overlap(source, target, truth):
    """Share of the source's points within OVERLAP_RADIUS of the target after truth."""
    cloud = lambda p: o3d.geometry.PointCloud(o3d.utility.Vector3dVector(p))
    moved = source @ truth[:3, :3].T + truth[:3, 3]
    d = np.asarray(cloud(moved).compute_point_cloud_distance(cloud(target)))
    return float(np.mean(d <= OVERLAP_RADIUS))


def errors(T_est, T_ref):
    """Rotation (deg) and translation (m) errors."""
    dR = T_est[:3, :3] @ T_ref[:3, :3].T
    angle = np.degrees(np.arccos(np.clip((np.trace(dR) - 1.0) / 2.0, -1.0, 1.0)))
    return float(angle), float(np.linalg.norm(T_est[:3, 3] - T_ref[:3, 3]))


def open3d_align(source, target, v):
    """Open3D's tutorial global registration; no convergence verdict (None)."""
    reg = o3d.pipelines.registration

    def describe(points):
        down = o3d.geometry.PointCloud(o3d.utility.Vector3dVector(points)).voxel_down_sample(v)
        down.estimate_normals(o3d.geometry.KDTreeSearchParamHybrid(radius=2 * v, max_nn=30))
        return down, reg.compute_fpfh_feature(
            down, o3d.geometry.KDTreeSearchParamHybrid(radius=5 * v, max_nn=100))

    (s, fs), (t, ft) = describe(source), describe(target)
    result = reg.registration_ransac_based_on_feature_matching(
        s, t, fs, ft, ARGS.mutual, 1.5 * v, reg.TransformationEstimationPointToPoint(False),
        3, [reg.CorrespondenceCheckerBasedOnEdgeLength(0.9),
            reg.CorrespondenceCheckerBasedOnDistance(1.5 * v)],
        reg.RANSACConvergenceCriteria(100000, 0.999))
    return np.asarray(result.transformation), None


def run(method, source, target, params):
    """(T_target_source, converged or None, ms) of one align."""
    start = time.perf_counter()
    if method == "pcl_phaser":
        r = pcl_phaser.align(source, target, params=params)
        T, converged = np.asarray(r.transformation), bool(r.converged)
    else:
        T, converged = open3d_align(source, target, ARGS.voxel)
    return T, converged, 1e3 * (time.perf_counter() - start)


def main():
    folder = os.path.join(ARGS.data, "object", "stanford_bunny")
    if not os.path.exists(os.path.join(folder, "bun.conf")):
        print(f"skipped: {folder}/bun.conf not found (the shared data is absent)")
        return 0
    poses = read_views(folder)
    clouds = {v: read_ply(os.path.join(folder, v)) for v in poses}
    if hasattr(o3d.utility, "random"):
        o3d.utility.random.seed(1)
    params = pcl_phaser.Parameters(num_threads=ARGS.threads)
    pairs = []
    for src, tgt in itertools.permutations(poses, 2):
        truth = np.linalg.inv(poses[tgt]) @ poses[src]
        share = overlap(clouds[src], clouds[tgt], truth)
        print(f"{src} -> {tgt} overlap {share:.3f}", file=sys.stderr)
        pairs.append((src, tgt, share, truth))
    chosen = [p for p in pairs if p[2] >= ARGS.min_overlap]
    for method in ("pcl_phaser", "open3d"):  # untimed: the first align plans its work
        run(method, clouds[chosen[0][0]], clouds[chosen[0][1]], params)
    rows = []
    for k, (src, tgt, share, truth) in enumerate(chosen):
        for method in ("pcl_phaser", "open3d")[::1 if k % 2 == 0 else -1]:
            T, converged, ms = run(method, clouds[src], clouds[tgt], params)
            rre, rte = errors(T, truth)
            rows.append((method, src, tgt, share, rre, rte, converged, ms))
            print(f"{src} -> {tgt} ({share:.2f}) {method:10s} {rre:6.2f} deg "
                  f"{1e3 * rte:7.2f} mm converged {converged} {ms:6.0f} ms", file=sys.stderr)
    others = [run("pcl_phaser", clouds[s], clouds[t], params)[1]
              for s, t, share, _ in pairs if share < ARGS.min_overlap]
    if ARGS.csv:
        with open(ARGS.csv, "w") as f:
            f.write("method,source,target,overlap,rre_deg,rte_m,converged,right,ms\n")
            for r in rows:
                right = r[4] < RIGHT_DEG and r[5] < RIGHT_M
                f.write(",".join(str(x) for x in r[:7] + (right, r[7])) + "\n")
    report(rows, others)
    return 0


def report(rows, others):
    right = lambda r: r[4] < RIGHT_DEG and r[5] < RIGHT_M
    med = lambda xs, k=1.0: f"{k * np.median(xs):.2f}" if xs else "-"
    print(f"Bunny views: {len(rows) // 2} ordered pairs with overlap >= {ARGS.min_overlap}, "
          f"{ARGS.threads} threads, Open3D {o3d.__version__} at voxel {ARGS.voxel} m "
          f"(mutual filter {'on' if ARGS.mutual else 'off'}), load average "
          f"{os.getloadavg()[0]:.2f}. Right: 5 deg / 5 mm.\n")
    print("| method | right | converged | valid but wrong | median RRE of the right (deg)"
          " | median RTE of the right (mm) | median time (ms) |")
    print("|---|---|---|---|---|---|---|")
    medians = {}
    for method in ("pcl_phaser", "open3d"):
        mine = [r for r in rows if r[0] == method]
        ok = [r for r in mine if right(r)]
        medians[method] = float(np.median([r[7] for r in mine]))
        flags = [r[6] for r in mine if r[6] is not None]
        conv = f"{sum(flags)}" if flags else "- (none reported)"
        wrong = f"{sum(1 for r in mine if r[6] and not right(r))}" if flags else "-"
        print(f"| {method} | {len(ok)} / {len(mine)} | {conv} | {wrong} | "
              f"{med([r[4] for r in ok])} | {med([r[5] for r in ok], 1e3)} | "
              f"{medians[method]:.0f} |")
    print(f"\nOpen3D's median time / pcl_phaser's: "
          f"{medians['open3d'] / medians['pcl_phaser']:.2f}. The {len(others)} ordered "
          f"pairs below the overlap: pcl_phaser converged on {sum(others)}.")


if __name__ == "__main__":
    sys.exit(main())
