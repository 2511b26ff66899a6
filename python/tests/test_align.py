# SPDX-License-Identifier: BSD-3-Clause
# Copyright (c) 2026, the pcl_phaser developers.
"""Known poses on the shared scans (the C++ real-data tests' tolerances), revisit pairs
of balm_handheld/pairs.txt, Target reuse, input layouts and the Result."""
import pickle

import numpy as np
import pytest

import pcl_phaser
from conftest import data_path, errors, random_pose, read_kitti, read_pcd, transform

BALM = "lidar/balm_handheld/"


def same(a, b):
    """Two Results equal to the bit in every figure compared here."""
    assert a.error == b.error
    assert a.converged == b.converged
    np.testing.assert_array_equal(a.transformation, b.transformation)
    np.testing.assert_array_equal(a.covariance, b.covariance)
    assert a.verification.rank == b.verification.rank
    assert len(a.hypotheses) == len(b.hypotheses)
    for g, h in zip(a.hypotheses, b.hypotheses):
        np.testing.assert_array_equal(g.transformation, h.transformation)


def test_target_reuse_layouts_and_nan_rows_give_the_one_shot_result(synthetic_pair):
    source, target, _ = synthetic_pair
    params = pcl_phaser.Parameters(num_threads=1)
    once = pcl_phaser.align(source, target, params=params)
    prepared = pcl_phaser.Target(target, params)
    first = prepared.align(source)
    assert first.times.target > 0.0
    second = prepared.align(source)
    assert second.times.target == 0.0  # from the target's cache
    same(once, first)
    same(once, second)
    same(once, pcl_phaser.align(source.astype(np.float64), np.asfortranarray(target),
                                params=params))
    with_nan = np.insert(source, [0, 100, 7000], np.nan, axis=0)
    same(once, prepared.align(with_nan))
    same(once, pickle.loads(pickle.dumps(prepared)).align(source))


def test_result_fields_repr_and_pickle(synthetic_pair):
    source, target, truth = synthetic_pair
    result = pcl_phaser.align(source, target, params={"num_threads": 1})
    assert result.error == ""
    rotation, translation = errors(result.transformation, truth)
    assert result.converged and rotation < 1.0 and translation < 0.05, result
    assert result.transformation.shape == (4, 4) and result.covariance.shape == (6, 6)
    np.testing.assert_array_equal(result.transformation[3], [0, 0, 0, 1])
    assert len(result.hypotheses) >= 1
    assert 0 <= result.chosen_hypothesis < len(result.hypotheses)
    assert result.times.total > 0.0
    assert result.diagnostics.verification_samples > 0
    if result.converged:
        np.testing.assert_allclose(result.covariance, result.covariance.T, rtol=1e-12)
        assert np.all(np.linalg.eigvalsh(result.covariance) > 0)
    else:
        assert not result.covariance.any()
    assert "converged=" in repr(result) and "hypotheses" in repr(result)
    same(result, pickle.loads(pickle.dumps(result)))
    copy = pickle.loads(pickle.dumps(result))
    assert copy.diagnostics.passes == result.diagnostics.passes
    np.testing.assert_array_equal(np.array(copy.diagnostics.rotation_samples),
                                  np.array(result.diagnostics.rotation_samples))
    same_fields(copy.to_dict(), result.to_dict())


def same_fields(a, b):
    """Two to_dict()s equal to the bit, nested groups and lists of dicts too."""
    assert list(a) == list(b)
    for key, value in a.items():
        if isinstance(value, dict):
            same_fields(value, b[key])
        elif isinstance(value, list) and value and isinstance(value[0], dict):
            assert len(value) == len(b[key])
            for x, y in zip(value, b[key]):
                same_fields(x, y)
        else:
            np.testing.assert_array_equal(value, b[key], err_msg=key)


def test_to_dict_has_the_keys_of_the_tools_json(synthetic_pair):
    source, target, _ = synthetic_pair
    result = pcl_phaser.align(source, target, params={"num_threads": 1})
    fields = result.to_dict()
    shared = ["covariance", "rotation_score", "translation_score", "normalized_overlap",
              "inlier_fraction", "verification_score", "free_space_violation",
              "reverse_free_space_violation", "constraint", "verification_rank",
              "runner_up_rank", "runner_up_error", "verification_radius",
              "verification_samples", "verified", "refusal", "passes", "stages_ms"]
    keys = list(fields)
    assert keys[keys.index("covariance"):][:len(shared)] == shared
    assert fields["verification_rank"] == result.verification.rank
    assert fields["verification_score"] == result.verification.score
    assert fields["stages_ms"]["sht"] == result.times.sht
    assert list(fields["stages_ms"]) == ["target", "sampling", "sht", "so3", "refinement",
                                         "translation", "orientation", "verification"]
    assert fields["projection_center"] == result.projection_center
    assert len(fields["hypotheses"]) == len(result.hypotheses)
    assert fields["hypotheses"][0]["verification_rank"] == \
        result.hypotheses[0].verification.rank
    np.testing.assert_array_equal(fields["transformation"], result.transformation)
    broken = pcl_phaser.Result.__new__(pcl_phaser.Result)
    del fields["passes"]
    with pytest.raises(ValueError, match="bad state"):
        broken.__setstate__(fields)


def test_every_field_is_an_attribute_named_by_its_key(synthetic_pair):
    # Result, Diagnostics, Hypothesis and StageTimes attributes come from core/result.h's
    # field lists: each key of to_dict() is an attribute holding the same value.
    source, target, _ = synthetic_pair
    result = pcl_phaser.align(source, target, params={"num_threads": 1})
    fields = result.to_dict()
    for key, value in fields.items():
        if key == "hypotheses":
            for h, d in zip(result.hypotheses, value):
                for k, v in d.items():
                    np.testing.assert_array_equal(getattr(h, k), v, err_msg=k)
        elif key == "stages_ms":
            assert getattr(result, key) == value == result.diagnostics.stages_ms
            assert all(getattr(result.times, k) == v for k, v in value.items())
        else:
            np.testing.assert_array_equal(getattr(result, key), value, err_msg=key)
    for key in ["verification_rank", "runner_up_rank", "passes", "refusal"]:
        assert getattr(result.diagnostics, key) == fields[key]
    assert result.verification.verification_rank == result.verification.rank


def test_a_guess_is_composed(synthetic_pair):
    source, target, _ = synthetic_pair
    params = pcl_phaser.Parameters(num_threads=1)
    plain = pcl_phaser.align(source, target, params=params)
    shift = np.eye(4)
    shift[:3, 3] = [0.5, 0.0, 0.0]
    moved = transform(np.linalg.inv(shift), source)
    guessed = pcl_phaser.align(moved, target, guess=shift, params=params)
    assert errors(guessed.transformation @ np.linalg.inv(shift),
                  plain.transformation)[0] < 1.0


def test_hdl32_pair_against_its_reference():
    reference = np.loadtxt(data_path("lidar/hdl32_fastgicp/relative.txt"))
    source = read_pcd(data_path("lidar/hdl32_fastgicp/251371071.pcd"))[:, :3]
    target = read_pcd(data_path("lidar/hdl32_fastgicp/251370668.pcd"))[:, :3]
    for center in ("sensor", "auto"):
        result = pcl_phaser.align(source, target, params={"projection_center": center})
        assert result.converged, result
        assert result.projection_center == pcl_phaser.ProjectionCenter.SensorOrigin
        rotation, translation = errors(result.transformation, reference)
        assert rotation < 1.0 and translation < 0.3, result


def test_kitti_scan_seen_from_random_poses():
    scan = read_kitti(data_path("lidar/kitti_raw_hdl64/0000000000.bin"))
    target = pcl_phaser.Target(scan, pcl_phaser.Parameters(num_threads=2))
    rng = np.random.default_rng(1)
    for k in range(3):
        truth = random_pose(rng, 2.0)
        result = target.align(transform(np.linalg.inv(truth), scan))
        rotation, translation = errors(result.transformation, truth)
        assert result.converged, (k, result)
        assert rotation < 2.0 and translation < 0.3, (k, result)


def balm_pairs():
    """The revisit pairs of the C++ test (the first of each distance bin) with their
    reference poses from pairs.txt."""
    wanted = [("full18.pcd", "full36.pcd"), ("full90.pcd", "full108.pcd"),
              ("full84.pcd", "full162.pcd"), ("full54.pcd", "full156.pcd")]
    poses = {}
    for line in open(data_path(BALM + "pairs.txt")):
        fields = line.split()
        if fields and not line.startswith("#"):
            poses[(fields[0], fields[1])] = np.array(fields[5:21], float).reshape(4, 4)
    return [(s, t, poses[(s, t)]) for s, t in wanted]


def test_balm_revisits_meters_apart_register_and_converge():
    for source, target, truth in balm_pairs():
        result = pcl_phaser.align(read_pcd(data_path(BALM + source)),
                                  read_pcd(data_path(BALM + target)),
                                  params={"num_threads": 2})
        rotation, translation = errors(result.transformation, truth)
        assert result.converged, (source, target, result)
        assert rotation < 5.0 and translation < 0.6, (source, target, result)
