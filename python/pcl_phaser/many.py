# SPDX-License-Identifier: BSD-3-Clause
# Copyright (c) 2026, the pcl_phaser developers.
"""Many registrations: serially in this process or on a dask.distributed cluster.

One machine::

    from dask.distributed import Client, LocalCluster
    with LocalCluster(n_workers=2, threads_per_worker=1) as cluster, Client(cluster) as client:
        results = pcl_phaser.align_many(pairs, read_cloud,
                                        pcl_phaser.Parameters(num_threads=1), client=client)

Many machines: the same call with ``Client("tcp://SCHEDULER:8786")`` after
``dask scheduler`` on one machine and ``dask worker tcp://SCHEDULER:8786 --nthreads 1``
on each; ``read_cloud`` then reads paths every worker can see.
"""
from collections import OrderedDict

from ._pcl_phaser import Target


def _cloud(clouds, key):
    """The array of ``key``: ``clouds(key)`` when callable, else ``clouds[key]``."""
    return clouds(key) if callable(clouds) else clouds[key]


def _align_group(target_key, items, clouds, params):
    """Prepares the target once and aligns every (index, source_key, guess) of it."""
    target = Target(_cloud(clouds, target_key), params)
    return [(index, target.align(_cloud(clouds, source_key), guess))
            for index, source_key, guess in items]


def _groups(pairs):
    """The pairs grouped by target, in order of first appearance."""
    groups = OrderedDict()
    count = 0
    for count, pair in enumerate(pairs, 1):
        if len(pair) not in (2, 3):
            raise ValueError("a pair is (source, target) or (source, target, guess), "
                             "not %r" % (pair,))
        guess = pair[2] if len(pair) == 3 else None
        groups.setdefault(pair[1], []).append((count - 1, pair[0], guess))
    return groups, count


def _needed(clouds, target_key, items):
    """What a task needs of ``clouds``: the loader itself, or only its arrays."""
    if callable(clouds):
        return clouds
    keys = {target_key, *(source_key for _, source_key, _ in items)}
    return {key: clouds[key] for key in keys}


def align_many(pairs, clouds, params=None, client=None):
    """Registers many pairs; each target is prepared once.

    pairs:  (source_key, target_key) or (source_key, target_key, guess 4 x 4) tuples.
    clouds: a mapping key -> (N, 3) / (N, 4) array, or a callable key -> array (a file
            reader, say); with a client it runs on the workers.
    params: Parameters (or a dict) of every align; on a cluster num_threads=1 with one
            worker process per core is the usual choice (results are bit-identical for
            any thread count).
    client: a dask.distributed.Client: one task per target and its sources, spread
            over the workers; None runs the same tasks here, one after the other.

    Returns the Results in the order of ``pairs``: bit for bit what serial aligns give.
    Bad input (a wrong array, a missing key) raises, as align does.
    """
    groups, count = _groups(pairs)
    results = [None] * count
    if client is None:
        done = [_align_group(key, items, clouds, params)
                for key, items in groups.items()]
    else:
        futures = [client.submit(_align_group, key, items,
                                 _needed(clouds, key, items), params, pure=False)
                   for key, items in groups.items()]
        done = client.gather(futures)
    for group in done:
        for index, result in group:
            results[index] = result
    return results
