#!/usr/bin/env bash
# pcl_phaser_batch sharded over GNU parallel (3 shards, 2 jobs at a time, one engine
# thread each) and merged equals the serial run (two engine threads) bit for bit: every
# transformation, covariance and verdict.
source "$(dirname "$0")/batch_test_support.sh"
command -v parallel > /dev/null || skip "GNU parallel is not installed (Debian package 'parallel')"
serial_run
parallel --will-cite --halt now,fail=1 -j 2 \
  "$BATCH" --pairs "$work/pairs.txt" --out "$work/part{}.jsonl" --g2o "$work/part{}.g2o" \
  --threads 1 --shard {}/3 2> "$work/parallel.log" ::: 0 1 2 ||
  { cat "$work/parallel.log"; fail "a shard failed under GNU parallel"; }
"$BATCH" merge "$work/merged.jsonl" "$work"/part{0,1,2}.jsonl || fail "merge of the records"
"$BATCH" merge "$work/merged.g2o" "$work"/part{0,1,2}.g2o || fail "merge of the graphs"
same "$work/serial.jsonl" "$work/merged.jsonl"
cmp "$work/serial.g2o" "$work/merged.g2o" || fail "the merged graph differs from the serial one"
for k in 0 1 2; do [[ -s $work/part$k.jsonl ]] || fail "shard $k got no pairs"; done
! "$BATCH" merge "$work/m.jsonl" "$work"/part{0,1}.jsonl 2> "$work/err.txt" || fail "a missing shard merged"
grep -q "missing" "$work/err.txt" || fail "merge did not name the missing pairs"

# A complete pose graph (--odometry: FIX 0 and an edge between consecutive scans in
# every part) merges into the serial run's graph too.
for i in 0 1 2 3 4 5 6 7 8 9; do echo "scans/full$((6 * i)).pcd"; done > "$work/scans.txt"
grep -v '^#' "$scans/poses_T_world_lidar.txt" | head -10 > "$work/poses.txt"
loops=(--scans "$work/scans.txt" --poses "$work/poses.txt" --radius 4 --min-gap 4 --odometry)
"$BATCH" "${loops[@]}" --out "$work/lserial.jsonl" --g2o "$work/lserial.g2o" --threads 2 \
  2> "$work/lserial.log" || { cat "$work/lserial.log"; fail "the serial run with --odometry"; }
parallel --will-cite --halt now,fail=1 -j 2 \
  "$BATCH" "${loops[@]}" --out "$work/lpart{}.jsonl" --g2o "$work/lpart{}.g2o" \
  --threads 1 --jobs 1 --shard {}/2 2> "$work/lparallel.log" ::: 0 1 ||
  { cat "$work/lparallel.log"; fail "a shard with --odometry failed"; }
"$BATCH" merge "$work/lmerged.g2o" "$work"/lpart{0,1}.g2o || fail "merge of the pose graphs"
cmp "$work/lserial.g2o" "$work/lmerged.g2o" || fail "the merged pose graph differs from the serial one"
grep -qx "FIX 0" "$work/lmerged.g2o" || fail "no FIX 0 in the pose graph"
[[ $(grep -c "^EDGE_SE3:QUAT \([0-9]*\) " "$work/lmerged.g2o") -ge 10 ]] ||
  fail "the pose graph lacks its 9 odometry edges and a loop edge"
echo "PASSED: 3 shards under GNU parallel, merged, equal the serial run; so do 2 shards of a pose graph"
