# SPDX-License-Identifier: BSD-3-Clause
# Copyright (c) 2026, the pcl_phaser developers.
"""PHASER global point-cloud registration on numpy arrays.

    import numpy as np, pcl_phaser
    result = pcl_phaser.align(source, target)        # (N, 3) or (N, 4) float32/float64
    if result.converged:
        T = result.transformation                      # 4 x 4, p_target = T p_source

``Target(points)`` keeps what depends on the target for many sources; ``Parameters``
holds every setting (C++ names and defaults); ``align_many`` runs many pairs, serially
or on a dask.distributed cluster. The GIL is released while an align runs.
"""
from ._pcl_phaser import (CHANNEL_AMBIENT, CHANNEL_COLOR, CHANNEL_INTENSITY,
                          CHANNEL_RANGE, CHANNEL_REFLECTIVITY, PARAMETER_RANGES,
                          Diagnostics, Hypothesis, Parameters, ProjectionCenter,
                          Result, StageTimes, Target, Verification, align, warm_up)
from .many import align_many

__all__ = ["align", "align_many", "warm_up", "Parameters", "ProjectionCenter",
           "Target", "Result", "Diagnostics", "Hypothesis", "StageTimes",
           "Verification", "PARAMETER_RANGES", "CHANNEL_RANGE", "CHANNEL_INTENSITY",
           "CHANNEL_REFLECTIVITY", "CHANNEL_AMBIENT", "CHANNEL_COLOR"]
