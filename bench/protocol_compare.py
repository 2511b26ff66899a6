#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
# Copyright (c) 2026, the pcl_phaser developers.
"""Totals of a protocol folder (bench/protocol.sh), and what changed against a baseline.

  python3 bench/protocol_compare.py RUN [BASELINE]

Success: the study's own (revisits: RRE < 5 deg and RTE < 0.6 m; random poses: the CSV's
`success`). A false accept is a converged failure. With a baseline: per file the rows whose
values differ (times and `stages_ms.*` excluded) and every trial whose success or claim
changed.
"""
import csv
import statistics
import sys

FILES = ("rev.csv", "der.csv", "rw5.csv", "rw25.csv", "w.csv", "w0.csv", "sw.csv")
KEY = ("method", "source", "target", "set", "sweep", "value", "pose")


def rows(folder, name):
    with open(f"{folder}/{name}") as f:
        return list(csv.DictReader(f))


def success(r):
    if "success" in r:
        return r["success"] == "1"
    return float(r["rre"]) < 5 and float(r["rte"]) < 0.6


def totals(folder):
    n = ok = claimed = false = 0
    medians = {}
    for name in FILES:
        table = rows(folder, name)
        for r in table:
            s, c = success(r), r["converged"] == "1"
            n, ok, claimed, false = n + 1, ok + s, claimed + (c and s), false + (c and not s)
        if name in ("rev.csv", "der.csv"):
            medians[name] = (statistics.median(float(r["rre"]) for r in table),
                             statistics.median(float(r["rte"]) for r in table))
    print(f"{folder}: {n} trials, {ok} successes, {claimed} converged successes, "
          f"{false} false accepts")
    for name, (rre, rte) in medians.items():
        print(f"  {name} median RRE {rre:.4f} deg, RTE {rte:.4f} m")


def timing(column):
    """Whether a CSV column holds a time (it differs from run to run)."""
    return column in ("ms", "time_ms") or column.startswith("stages_ms.")


def changes(run, baseline):
    for name in FILES:
        old = {tuple(r.get(k, "") for k in KEY): r for r in rows(baseline, name)}
        new = {tuple(r.get(k, "") for k in KEY): r for r in rows(run, name)}
        differing = 0
        for key, a in old.items():
            b = new.get(key)
            if b is None or any(a[c] != b.get(c) for c in a if not timing(c)):
                differing += 1
            if b is not None and (success(a), a["converged"]) != (success(b), b["converged"]):
                label = " ".join(v for v in key if v)
                print(f"  {name} {label}: success {success(a)} -> {success(b)}, "
                      f"converged {a['converged']} -> {b['converged']}")
        print(f"  {name}: {differing} of {len(old)} rows differ")


if __name__ == "__main__":
    if len(sys.argv) not in (2, 3):
        sys.exit(__doc__)
    totals(sys.argv[1])
    if len(sys.argv) == 3:
        totals(sys.argv[2])
        changes(sys.argv[1], sys.argv[2])
