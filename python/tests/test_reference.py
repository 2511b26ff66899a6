# SPDX-License-Identifier: BSD-3-Clause
# Copyright (c) 2026, the pcl_phaser developers.
"""The module's results equal the C++ library's (pcl::PhaserRegistration) on the same
float32 clouds, to the bit: pcl_phaser_reference_align prints every figure as a
hexadecimal float."""
import os
import shutil
import subprocess

import numpy as np
import pytest

import pcl_phaser
from conftest import data_path, read_kitti, read_pcd


def reference_program():
    path = os.environ.get("PCL_PHASER_REFERENCE_ALIGN") or shutil.which(
        "pcl_phaser_reference_align")
    if not path or not os.path.exists(path):
        pytest.skip("pcl_phaser_reference_align not found (set "
                    "PCL_PHASER_REFERENCE_ALIGN; ctest sets it)")
    return path


def cpp_align(tmp_path, source, target, threads):
    """{name: [floats]} printed by the C++ library for these float32 clouds."""
    files = []
    for name, cloud in (("source", source), ("target", target)):
        files.append(tmp_path / (name + ".f32"))
        np.ascontiguousarray(cloud, dtype=np.float32).tofile(files[-1])
    out = subprocess.run([reference_program(), str(files[0]), str(files[1]),
                          str(source.shape[1]), str(threads)],
                         check=True, capture_output=True, text=True).stdout
    figures = {"hypothesis": []}
    for line in out.splitlines():
        name, _, values = line.partition(" ")
        if name == "error":
            figures[name] = values
        elif name == "hypothesis":
            figures[name].append([float.fromhex(v) for v in values.split()])
        else:
            figures[name] = [float.fromhex(v) for v in values.split()]
    return figures


def bits(values):
    """The IEEE-754 bit patterns of values (so that -0.0 != 0.0 and NaN == NaN)."""
    return np.asarray(values, dtype=np.float64).ravel().view(np.uint64).tolist()


def expect_bit_equal(tmp_path, source, target, threads):
    cpp = cpp_align(tmp_path, source, target, threads)
    py = pcl_phaser.align(source, target, params={"num_threads": threads})
    assert cpp["error"] == py.error
    assert bits(cpp["transformation"]) == bits(py.transformation)
    assert cpp["converged"] == [float(py.converged)]
    assert bits(cpp["covariance"]) == bits(py.covariance)
    v = py.verification
    assert bits(cpp["verification"]) == bits(
        [v.inlier_fraction, v.score, v.free_space_violation,
         v.reverse_free_space_violation, v.constraint, v.rank])
    assert cpp["chosen_hypothesis"] == [py.chosen_hypothesis]
    assert len(cpp["hypothesis"]) == len(py.hypotheses)
    for c, h in zip(cpp["hypothesis"], py.hypotheses):
        assert bits(c) == bits(h.transformation)
    return py


@pytest.mark.parametrize("columns", [3, 4])
def test_synthetic_pair_equals_the_cpp_library(tmp_path, synthetic_pair, columns):
    source, target, _ = synthetic_pair
    expect_bit_equal(tmp_path, source[:, :columns], target[:, :columns], 1)


def test_balm_revisit_equals_the_cpp_library(tmp_path):
    source = read_pcd(data_path("lidar/balm_handheld/full18.pcd"))
    target = read_pcd(data_path("lidar/balm_handheld/full36.pcd"))
    assert expect_bit_equal(tmp_path, source, target, 2).converged


def test_kitti_pair_with_nan_rows_equals_the_cpp_library(tmp_path):
    source = read_kitti(data_path("lidar/kitti_raw_hdl64/0000000001.bin"))
    target = read_kitti(data_path("lidar/kitti_raw_hdl64/0000000000.bin"))
    source[::997, 1] = np.nan  # skipped by both, as non-finite points
    assert expect_bit_equal(tmp_path, source, target, 2).error == ""
