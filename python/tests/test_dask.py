# SPDX-License-Identifier: BSD-3-Clause
# Copyright (c) 2026, the pcl_phaser developers.
"""align_many on a dask.distributed LocalCluster (2 worker processes, 1 thread each)
equals the serial run to the bit."""
import numpy as np
import pytest

import pcl_phaser
from conftest import data_dir, read_pcd, synthetic_scan, transform
from test_align import same

distributed = pytest.importorskip(
    "distributed", reason="dask.distributed not installed (Debian: python3-distributed)")


def balm_reader(name):
    """Runs on the workers: a balm_handheld scan by file name."""
    return read_pcd(data_dir() / "lidar/balm_handheld" / name)


def pairs_and_clouds():
    """Revisit pairs (two targets) when the shared data is there, else synthetic."""
    if (data_dir() / "lidar/balm_handheld/full36.pcd").exists():
        pairs = [("full18.pcd", "full36.pcd"), ("full42.pcd", "full54.pcd"),
                 ("full0.pcd", "full36.pcd"), ("full24.pcd", "full36.pcd")]
        return pairs, balm_reader
    clouds = {k: synthetic_scan(k) for k in range(4)}
    shift = np.eye(4)
    shift[:3, 3] = [0.3, 0.2, 0.0]
    clouds[4] = transform(shift, clouds[3])
    return [(1, 0), (2, 0), (4, 3), (0, 3)], clouds


def test_local_cluster_equals_serial():
    pairs, clouds = pairs_and_clouds()
    params = pcl_phaser.Parameters(num_threads=1)
    serial = pcl_phaser.align_many(pairs, clouds, params)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        spread = pcl_phaser.align_many(pairs, clouds, params, client=client)
        workers = len(client.scheduler_info()["workers"])
    assert workers == 2
    assert len(spread) == len(pairs)
    for a, b in zip(spread, serial):
        same(a, b)
    one = pcl_phaser.align(clouds(pairs[0][0]) if callable(clouds) else clouds[pairs[0][0]],
                           clouds(pairs[0][1]) if callable(clouds) else clouds[pairs[0][1]],
                           params=params)
    same(one, serial[0])
