#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
# Copyright (c) 2026, the pcl_phaser developers.
"""Register two scans read with Open3D: pcl_phaser for the global pose, Open3D's ICP to
refine it, and a PNG of the overlay (source red, target green) rendered headless.

    PYTHONPATH=<prefix>/lib/python3/dist-packages python3 register_open3d.py \\
        SOURCE.pcd TARGET.pcd [overlay.png]

The PNG comes from Open3D's renderer when it has a display (run under xvfb-run for
one without); otherwise, or if that fails, from matplotlib as a top view.
"""
import os
import sys

import numpy as np
import open3d as o3d

import pcl_phaser


def read_points(path):
    """x y z (and intensity when the file has it) as an (N, 3) / (N, 4) float32 array."""
    cloud = o3d.t.io.read_point_cloud(path)
    xyz = cloud.point["positions"].numpy().astype(np.float32)
    if "intensity" in cloud.point:
        return np.hstack([xyz, cloud.point["intensity"].numpy().reshape(-1, 1)])
    return xyz


def refine_with_icp(source, target, start):
    """Open3D point-to-plane ICP from the global pose; returns its 4 x 4."""
    src = o3d.geometry.PointCloud(o3d.utility.Vector3dVector(source[:, :3]))
    tgt = o3d.geometry.PointCloud(o3d.utility.Vector3dVector(target[:, :3]))
    src, tgt = src.voxel_down_sample(0.1), tgt.voxel_down_sample(0.1)
    tgt.estimate_normals(o3d.geometry.KDTreeSearchParamHybrid(radius=0.5, max_nn=30))
    icp = o3d.pipelines.registration.registration_icp(
        src, tgt, 0.5, start,
        o3d.pipelines.registration.TransformationEstimationPointToPlane())
    return icp.transformation


def render_open3d(source, target, T, png):
    """The overlay from above with Open3D's (hidden) window; False when it cannot."""
    try:
        src = o3d.geometry.PointCloud(o3d.utility.Vector3dVector(source[:, :3]))
        tgt = o3d.geometry.PointCloud(o3d.utility.Vector3dVector(target[:, :3]))
        src.transform(T)
        src.paint_uniform_color([0.9, 0.1, 0.1])
        tgt.paint_uniform_color([0.1, 0.7, 0.1])
        vis = o3d.visualization.Visualizer()
        if not vis.create_window(visible=False, width=1024, height=768):
            return False
        vis.add_geometry(tgt)
        vis.add_geometry(src)
        vis.get_render_option().point_size = 1.5
        vis.get_view_control().set_front([0, 0, 1])
        vis.get_view_control().set_up([0, 1, 0])
        vis.poll_events()
        vis.update_renderer()
        if os.path.exists(png):
            os.remove(png)
        vis.capture_screen_image(png, do_render=True)  # returns None in Open3D 0.16
        vis.destroy_window()
        return os.path.exists(png) and os.path.getsize(png) > 0
    except Exception:  # no display, no OpenGL: use the fallback
        return False


def render_matplotlib(source, target, T, png):
    """The overlay as a top-view scatter with matplotlib (no display needed)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    moved = source[:, :3] @ T[:3, :3].T + T[:3, 3]
    fig, ax = plt.subplots(figsize=(8, 8), dpi=120)
    ax.scatter(target[::2, 0], target[::2, 1], s=0.2, c="tab:green", label="target")
    ax.scatter(moved[::2, 0], moved[::2, 1], s=0.2, c="tab:red", label="source")
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.legend(markerscale=20, loc="upper right")
    fig.savefig(png, bbox_inches="tight")
    plt.close(fig)


def main(argv):
    if len(argv) not in (3, 4):
        print(__doc__, file=sys.stderr)
        return 1
    source, target = read_points(argv[1]), read_points(argv[2])
    png = argv[3] if len(argv) == 4 else "overlay.png"
    result = pcl_phaser.align(source, target)
    print(result)
    if not result.converged:
        print("not converged: the pose is not claimed", file=sys.stderr)
        return 3
    T = refine_with_icp(source, target, result.transformation)
    np.set_printoptions(precision=6, suppress=True)
    print("pcl_phaser:\n", result.transformation, "\nafter Open3D ICP:\n", T)
    renderer = "Open3D" if render_open3d(source, target, T, png) else "matplotlib"
    if renderer == "matplotlib":
        render_matplotlib(source, target, T, png)
    print("overlay (%s): %s" % (renderer, png))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
