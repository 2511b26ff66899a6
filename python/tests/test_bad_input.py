# SPDX-License-Identifier: BSD-3-Clause
# Copyright (c) 2026, the pcl_phaser developers.
"""Bad input raises ValueError / TypeError with a message and never crashes."""
import numpy as np
import pytest

import pcl_phaser


@pytest.fixture(scope="module")
def cloud():
    return np.random.default_rng(0).uniform(-10, 10, size=(500, 3))


@pytest.mark.parametrize("bad, error, message", [
    (np.zeros((0, 3)), ValueError, "empty"),
    (np.zeros((10, 2)), ValueError, "shape"),
    (np.zeros((10, 5)), ValueError, "shape"),
    (np.zeros(30), ValueError, "shape"),
    (np.zeros((2, 10, 3)), ValueError, "shape"),
    (np.full((10, 3), np.nan), ValueError, "finite"),
    (np.full((10, 3), np.inf), ValueError, "finite"),
    (np.zeros((10, 3), dtype=np.int32), TypeError, "float32 or float64"),
    (np.zeros((10, 3), dtype=np.float16), TypeError, "float32 or float64"),
    (np.zeros((10, 3), dtype=">f8"), TypeError, "native byte order"),
    ([[0.0, 1.0, 2.0]] * 10, TypeError, "numpy array"),
    (None, TypeError, "numpy array"),
    ("cloud.pcd", TypeError, "numpy array"),
])
def test_bad_clouds_raise(cloud, bad, error, message):
    with pytest.raises(error, match=message):
        pcl_phaser.align(bad, cloud)
    with pytest.raises(error, match=message):
        pcl_phaser.align(cloud, bad)
    with pytest.raises(error, match=message):
        pcl_phaser.Target(bad)


@pytest.mark.parametrize("guess, error, message", [
    (np.eye(3), ValueError, "shape"),
    (np.eye(4)[:3], ValueError, "shape"),
    (np.full((4, 4), np.nan), ValueError, "finite"),
    (np.diag([1, 1, 1, np.inf]), ValueError, "finite"),
    ("identity", TypeError, "4 x 4"),
    ([["a"] * 4] * 4, TypeError, "4 x 4"),
])
def test_bad_guesses_raise(cloud, guess, error, message):
    with pytest.raises(error, match=message):
        pcl_phaser.align(cloud, cloud, guess=guess)


def test_bad_parameters_and_channels_raise(cloud):
    with pytest.raises(TypeError, match="params"):
        pcl_phaser.align(cloud, cloud, params=64)
    with pytest.raises(ValueError, match="bandwidth"):
        pcl_phaser.align(cloud, cloud, params={"bandwidth": 1})
    with_intensity = np.hstack([cloud, np.ones((len(cloud), 1))])
    target = pcl_phaser.Target(with_intensity)
    with pytest.raises(ValueError, match="source has none"):
        target.align(cloud)
    with_intensity[3, 3] = np.nan
    with pytest.raises(ValueError, match="intensity of row 3"):
        pcl_phaser.align(with_intensity, with_intensity)


def test_an_engine_refusal_is_the_results_error(cloud):
    one_point = np.tile([1.0, 2.0, 3.0], (50, 1))
    result = pcl_phaser.align(one_point, cloud)
    assert not result.converged
    assert "one position" in result.error
    assert "error=" in repr(result)
    np.testing.assert_array_equal(result.transformation, np.eye(4))
    far = cloud + 2e6
    assert "1e6" in pcl_phaser.align(far, cloud).error
