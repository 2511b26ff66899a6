# SPDX-License-Identifier: BSD-3-Clause
# Copyright (c) 2026, the pcl_phaser developers.
"""Shared helpers of the Python tests: the shared data, tiny cloud readers, pose errors,
and a synthetic scan pair for the tests that need no data."""
import os
import pathlib

import numpy as np
import pytest

REPO = pathlib.Path(__file__).resolve().parents[2]


def data_dir():
    """$PCL_PHASER_DATA, else the build's PCL_PHASER_DATA_DIR, else ../shared/data."""
    for variable in ("PCL_PHASER_DATA", "PCL_PHASER_DATA_DIR"):
        if os.environ.get(variable):
            return pathlib.Path(os.environ[variable])
    return REPO.parent / "shared" / "data"


def data_path(relative):
    """The path of a shared file; skips the test with a message when it is absent."""
    path = data_dir() / relative
    if not path.exists():
        pytest.skip("shared test data not found: %s (set PCL_PHASER_DATA to the shared "
                    "data directory)" % path)
    return path


_PCD_TYPES = {("F", 4): "<f4", ("F", 8): "<f8", ("U", 1): "u1", ("U", 2): "<u2",
              ("U", 4): "<u4", ("I", 1): "i1", ("I", 2): "<i2", ("I", 4): "<i4"}


def read_pcd(path, columns=("x", "y", "z", "intensity")):
    """The named fields of a binary PCD file as an (N, len(columns)) float32 array."""
    with open(path, "rb") as f:
        header = {}
        while True:
            line = f.readline().decode("ascii").strip()
            if not line or line.startswith("#"):
                continue
            key, _, value = line.partition(" ")
            header[key] = value.split()
            if key == "DATA":
                break
        assert header["DATA"] == ["binary"], "only binary PCD files are read here"
        fields = [(name, _PCD_TYPES[(t, int(s))], int(c)) for name, s, t, c in
                  zip(header["FIELDS"], header["SIZE"], header["TYPE"], header["COUNT"])]
        dtype = np.dtype([(n, t) if c == 1 else (n, t, (c,)) for n, t, c in fields])
        points = int(header["POINTS"][0])
        records = np.frombuffer(f.read(points * dtype.itemsize), dtype=dtype)
    return np.stack([records[name].astype(np.float32) for name in columns], axis=1)


def read_kitti(path):
    """A KITTI .bin scan: (N, 4) float32 x y z reflectance."""
    return np.fromfile(path, dtype=np.float32).reshape(-1, 4)


def errors(estimate, truth):
    """(rotation error in degrees, translation error in meters)."""
    dR = estimate[:3, :3].T @ truth[:3, :3]
    angle = np.degrees(np.arccos(np.clip((np.trace(dR) - 1.0) / 2.0, -1.0, 1.0)))
    return angle, float(np.linalg.norm(estimate[:3, 3] - truth[:3, 3]))


def random_pose(rng, max_translation):
    """A uniform random rotation and a translation up to max_translation meters."""
    q = rng.normal(size=4)
    w, x, y, z = q / np.linalg.norm(q)
    T = np.eye(4)
    T[:3, :3] = [[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                 [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                 [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]]
    direction = rng.normal(size=3)
    T[:3, 3] = direction / np.linalg.norm(direction) * rng.uniform(0, max_translation)
    return T


def transform(T, cloud):
    """The rows of cloud (x y z [intensity]) mapped by T, in the cloud's dtype."""
    out = cloud.copy()
    out[:, :3] = (cloud[:, :3].astype(np.float64) @ T[:3, :3].T + T[:3, 3]).astype(
        cloud.dtype)
    return out


def synthetic_scan(seed, n=20000):
    """A LiDAR-like scan of a room with pillars and a ramp: (N, 4) float32 with an
    intensity that depends on the surface."""
    rng = np.random.default_rng(seed)
    parts = []
    def plane(origin, u, v, count, value):
        a, b = rng.uniform(size=(2, count, 1))
        parts.append(np.hstack([origin + a * u + b * v,
                                np.full((count, 1), value)]))
    plane(np.array([-12, -8, -1.5]), np.array([24, 0, 0]), np.array([0, 16, 0]), n // 4, 5)
    plane(np.array([-12, -8, -1.5]), np.array([24, 0, 0]), np.array([0, 0, 4]), n // 10, 20)
    plane(np.array([-12, 8, -1.5]), np.array([19, 0, 0]), np.array([0, 0, 4]), n // 10, 30)
    plane(np.array([-12, -8, -1.5]), np.array([0, 16, 0]), np.array([0, 0, 4]), n // 10, 40)
    plane(np.array([12, -8, -1.5]), np.array([0, 10, 0]), np.array([0, 0, 4]), n // 10, 50)
    for k, (x, y) in enumerate([(3, 2), (-5, -3), (6, -5), (-7, 4)]):
        plane(np.array([x, y, -1.5]), np.array([1 + k * 0.3, 0, 0]), np.array([0, 0, 3]),
              n // 25, 60 + k)
        plane(np.array([x, y, -1.5]), np.array([0, 0.8, 0]), np.array([0, 0, 3]),
              n // 25, 70 + k)
    plane(np.array([-3, 4, -1.5]), np.array([4, 0, 1.2]), np.array([0, 2.5, 0]), n // 20, 90)
    cloud = np.vstack(parts)
    cloud[:, :3] += rng.normal(scale=0.01, size=(len(cloud), 3))
    return cloud.astype(np.float32)


@pytest.fixture(scope="session")
def synthetic_pair():
    """(source, target, T_target_source): two samplings of the room, the source seen
    from a pose 1.2 m and 70 degrees away."""
    target = synthetic_scan(1)
    truth = np.eye(4)
    c, s = np.cos(np.radians(70)), np.sin(np.radians(70))
    truth[:3, :3] = [[c, -s, 0], [s, c, 0], [0, 0, 1]]
    truth[:3, 3] = [1.0, -0.6, 0.1]
    source = transform(np.linalg.inv(truth), synthetic_scan(2))
    return source, target, truth
