#!/usr/bin/env bash
# pcl_phaser_batch --region X,Y,Z,R: every source's sensor within R m of X,Y,Z of its
# target's frame. A region about the truth (3 m off, 10 m radius) registers the pair and
# converges; a region 40 m away does not converge; an --out of another region is refused.
source "$(dirname "$0")/batch_test_support.sh"
printf 'scans/full18.pcd scans/full36.pcd\n' > "$work/one.txt"
# T_target_source of full18 -> full36 (pairs.txt) puts the source's sensor at
# (-1.98, 2.36, 0.77) in the target's frame.
"$BATCH" --pairs "$work/one.txt" --out "$work/near.jsonl" --region 1.02,2.36,0.77,10 \
  2> "$work/near.log" || { cat "$work/near.log"; fail "the run with a region about the truth"; }
grep -q '"converged":true' "$work/near.jsonl" || fail "a region about the truth did not converge"
"$BATCH" --pairs "$work/one.txt" --out "$work/far.jsonl" --region 40,0,0,5 \
  2> "$work/far.log" || { cat "$work/far.log"; fail "the run with a region 40 m away"; }
grep -q '"converged":false' "$work/far.jsonl" || fail "a region 40 m away converged"
! "$BATCH" --pairs "$work/one.txt" --out "$work/near.jsonl" --region 40,0,0,5 \
  2> "$work/other.log" || fail "an --out written with another region was resumed"
grep -q "region" "$work/other.log" || { cat "$work/other.log"; fail "the refusal did not name the region"; }
! "$BATCH" --pairs "$work/one.txt" --out "$work/x.jsonl" --region 1,2 2> "$work/bad.log" ||
  fail "--region 1,2 was accepted"
grep -q "Invalid --region '1,2'" "$work/bad.log" || fail "no message for --region 1,2"
echo "PASSED: a region about the truth converges, one 40 m away does not"
