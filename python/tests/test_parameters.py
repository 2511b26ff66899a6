# SPDX-License-Identifier: BSD-3-Clause
# Copyright (c) 2026, the pcl_phaser developers.
"""pcl_phaser.Parameters: every row of the engine's range table is an attribute with the
C++ default, and values are validated as the engine validates them."""
import math
import pickle

import numpy as np
import pytest

import pcl_phaser


def test_every_row_of_the_range_table_is_an_attribute_with_its_default():
    p = pcl_phaser.Parameters()
    assert len(pcl_phaser.PARAMETER_RANGES) >= 16
    for row in pcl_phaser.PARAMETER_RANGES:
        value = getattr(p, row["name"])
        assert value == row["default"], row["name"]
        assert isinstance(value, int if row["type"] == "int" else float), row["name"]
        assert row["min"] <= value <= row["max"], row["name"]
        assert row["name"] in pcl_phaser.Parameters.fields()


def test_defaults_are_the_cpp_defaults():
    p = pcl_phaser.Parameters()
    assert (p.bandwidth, p.spatial_grid_size, p.voxel_size, p.passes) == (64, 128, 0.0, 3)
    assert (p.rotation_candidates, p.orientation_candidates, p.fusion_levels) == (3, 10, 5)
    assert p.min_inlier_fraction == 0.2 and p.max_free_space_violation == 0.02
    assert p.normalized_refinement is True
    assert p.projection_center == pcl_phaser.ProjectionCenter.Automatic
    assert p.channels == 0xFFFFFFFF
    assert repr(p) == "Parameters()"


def test_out_of_range_values_raise_the_engines_reason_and_keep_the_old_value():
    p = pcl_phaser.Parameters()
    for row in pcl_phaser.PARAMETER_RANGES:
        name = row["name"]
        if name == "spatial_grid_size":  # legal at any value when voxel_size > 0
            assert p.voxel_size == 0.0
        below = row["min"] - 1
        with pytest.raises(ValueError, match=name + " = .* is outside its range"):
            setattr(p, name, int(below) if row["type"] == "int" else below)
        if math.isfinite(row["max"]):
            above = row["max"] + 1
            with pytest.raises(ValueError, match="outside its range"):
                setattr(p, name, int(above) if row["type"] == "int" else above)
        assert getattr(p, name) == row["default"]
    with pytest.raises(ValueError, match="whitening"):
        p.whitening = float("nan")
    with pytest.raises(ValueError, match="bandwidth"):
        p.bandwidth = 10**30


def test_wrong_types_and_names_raise_type_error():
    p = pcl_phaser.Parameters()
    with pytest.raises(TypeError, match="bandwidth takes an int"):
        p.bandwidth = 32.0
    with pytest.raises(TypeError):
        p.whitening = "0.5"
    with pytest.raises(TypeError):
        p.normalized_refinement = 1
    with pytest.raises(TypeError, match="no field 'bandwith'"):
        pcl_phaser.Parameters(bandwith=32)
    with pytest.raises(ValueError):
        p.projection_center = "middle"
    with pytest.raises(ValueError):
        pcl_phaser.align_many([("a",)], {})


def test_keywords_repr_equality_and_pickle():
    p = pcl_phaser.Parameters(bandwidth=32, voxel_size=0.5, projection_center="auto",
                              num_threads=1)
    assert p.bandwidth == 32 and p.voxel_size == 0.5
    assert p.projection_center == pcl_phaser.ProjectionCenter.Automatic
    p.spatial_grid_size = 4  # out of its range, but ignored while voxel_size > 0
    with pytest.raises(ValueError, match="spatial_grid_size"):
        p.voxel_size = 0.0
    assert "bandwidth=32" in repr(p) and "num_threads=1" in repr(p)
    assert pickle.loads(pickle.dumps(p)) == p
    assert p != pcl_phaser.Parameters()
    assert p.to_dict()["bandwidth"] == 32


def test_region_fields_make_the_position_prior_and_radius_zero_removes_it():
    p = pcl_phaser.Parameters(region_x=1.0, region_y=2.0, region_radius=10.0)
    assert (p.region_x, p.region_y, p.region_z, p.region_radius) == (1.0, 2.0, 0.0, 10.0)
    assert pickle.loads(pickle.dumps(p)) == p
    p.region_radius = 0.0  # no prior: the center goes with it
    assert (p.region_x, p.region_y, p.region_radius) == (0.0, 0.0, 0.0)
    assert p == pcl_phaser.Parameters()
    p.region_x = 5.0  # a center may come before its radius; align() wants the radius
    cloud = np.array([[x, y, 0.1 * x * y] for x in range(-5, 6) for y in range(-5, 6)])
    assert "region_radius = 0 with a region" in pcl_phaser.align(cloud, cloud, params=p).error
    with pytest.raises(ValueError, match="region_radius = 0 with a region"):
        pcl_phaser.Parameters(region_x=5.0)


def test_bool_enum_and_flag_fields_come_from_the_table_and_are_checked():
    p = pcl_phaser.Parameters(normalized_refinement=False, projection_center="sensor_origin",
                              channels=pcl_phaser.CHANNEL_RANGE)
    assert p.normalized_refinement is False
    assert p.projection_center == pcl_phaser.ProjectionCenter.SensorOrigin
    assert p.channels == pcl_phaser.CHANNEL_RANGE
    assert (pcl_phaser.CHANNEL_INTENSITY, pcl_phaser.CHANNEL_COLOR) == (2, 16)
    assert "normalized_refinement=False" in repr(p)
    assert pickle.loads(pickle.dumps(p)) == p
    for name in ("normalized_refinement", "projection_center", "channels"):
        assert name in pcl_phaser.Parameters.fields()
        assert getattr(pcl_phaser.Parameters, name).__doc__
    p.projection_center = pcl_phaser.ProjectionCenter.Centroid
    assert p.projection_center == pcl_phaser.ProjectionCenter.Centroid
    with pytest.raises(ValueError, match="'sensor', 'centroid', 'auto'"):
        p.projection_center = "bogus"
    with pytest.raises(TypeError, match="ProjectionCenter"):
        p.projection_center = 1
    with pytest.raises(TypeError, match="normalized_refinement takes a bool"):
        p.normalized_refinement = "off"
    with pytest.raises(ValueError, match="channels = -1 is outside its range"):
        p.channels = -1
    with pytest.raises(ValueError, match="outside its range"):
        p.channels = 2**32
    with pytest.raises(TypeError):
        p.channels = True
    assert p.projection_center == pcl_phaser.ProjectionCenter.Centroid  # kept
    assert p.channels == pcl_phaser.CHANNEL_RANGE
