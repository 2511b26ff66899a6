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
echo "PASSED: 3 shards under GNU parallel, merged, equal the serial run"
