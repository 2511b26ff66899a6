# SPDX-License-Identifier: BSD-3-Clause
# Copyright (c) 2026, the pcl_phaser developers.
"""The GIL is released during an align: Python threads run while it runs, and two
aligns run at once with the serial results. Nothing here asserts a speed."""
import threading
import time

import numpy as np

import pcl_phaser
from test_align import same


def test_a_python_thread_runs_while_an_align_runs(synthetic_pair):
    source, target, _ = synthetic_pair
    interval = []
    def run():
        interval.append(time.perf_counter())
        pcl_phaser.align(source, target, params={"num_threads": 1})
        interval.append(time.perf_counter())
    worker = threading.Thread(target=run)
    ticks = []
    worker.start()
    while worker.is_alive():
        ticks.append(time.perf_counter())
        time.sleep(0.001)
    worker.join()
    start, end = interval
    inside = sum(start < t < end for t in ticks)
    # With the GIL held this thread could not run until the align returned.
    assert inside >= 20, (inside, end - start)


def test_two_threads_align_at_once_with_the_serial_results(synthetic_pair):
    source, target, _ = synthetic_pair
    params = pcl_phaser.Parameters(num_threads=1)
    pairs = [(source, target), (target, source)]
    serial = [pcl_phaser.align(s, t, params=params) for s, t in pairs]
    barrier = threading.Barrier(2)
    intervals, results = [None, None], [None, None]
    def run(k):
        barrier.wait()
        start = time.perf_counter()
        results[k] = pcl_phaser.align(*pairs[k], params=params)
        intervals[k] = (start, time.perf_counter())
    threads = [threading.Thread(target=run, args=(k,)) for k in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    (a0, a1), (b0, b1) = intervals
    assert a0 < b1 and b0 < a1, "the two aligns did not overlap in time"
    for parallel, alone in zip(results, serial):
        same(parallel, alone)
