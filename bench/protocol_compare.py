#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
# Copyright (c) 2026, the pcl_phaser developers.
"""Totals of a protocol folder (bench/protocol.sh), and what changed against a baseline.

  python3 bench/protocol_compare.py [--method M] RUN [BASELINE]

Success: the study's own (revisits: RRE < 5 deg and RTE < 0.6 m; random poses: the CSV's
`success`). A false accept is a converged failure. With a baseline: per file the rows whose
values differ (times and `stages_ms.*` excluded) and every trial whose success or claim
changed, and those whose error moved by over 0.05 deg or 1 cm. With --method M the run's rows of method M are compared with the baseline's
`phaser` rows (e.g. phaser_xyz: where intensity fusion changes the answer).
"""
import csv
import statistics
import sys

FILES = ("rev.csv", "der.csv", "rw5.csv", "rw25.csv", "w.csv", "w0.csv", "sw.csv")
KEY = ("method", "source", "target", "set", "sweep", "value", "pose")


def rows(folder, name, method=None):
    with open(f"{folder}/{name}") as f:
        return [r for r in csv.DictReader(f) if method in (None, r["method"])]


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


def error(r, name):
    """The row's rre (deg) or rte (m), whichever spelling its study writes."""
    return float(r[name] if name in r else r[name + ("_deg" if name == "rre" else "_m")])


def timing(column):
    """Whether a CSV column holds a time (it differs from run to run)."""
    return column in ("ms", "time_ms") or column.startswith("stages_ms.")


def changes(run, baseline, method=None):
    fields = KEY[1:] if method else KEY
    for name in FILES:
        old = {tuple(r.get(k, "") for k in fields): r
               for r in rows(baseline, name, "phaser" if method else None)}
        new = {tuple(r.get(k, "") for k in fields): r for r in rows(run, name, method)}
        differing = moved = 0
        for key, a in old.items():
            b = new.get(key)
            if b is None or any(a[c] != b.get(c) for c in a
                                if not timing(c) and c != "method"):
                differing += 1
            if b is not None and (abs(error(a, "rre") - error(b, "rre")) > 0.05 or
                                  abs(error(a, "rte") - error(b, "rte")) > 0.01):
                moved += 1
            if b is not None and (success(a), a["converged"]) != (success(b), b["converged"]):
                label = " ".join(v for v in key if v)
                print(f"  {name} {label}: success {success(a)} -> {success(b)}, "
                      f"converged {a['converged']} -> {b['converged']}")
        print(f"  {name}: {differing} of {len(old)} rows differ, {moved} by over "
              "0.05 deg or 1 cm of error")


if __name__ == "__main__":
    args = sys.argv[1:]
    method = None
    if args[:1] == ["--method"] and len(args) > 1:
        method, args = args[1], args[2:]
    if len(args) not in (1, 2):
        sys.exit(__doc__)
    totals(args[0])
    if len(args) == 2:
        totals(args[1])
        changes(args[0], args[1], method)
