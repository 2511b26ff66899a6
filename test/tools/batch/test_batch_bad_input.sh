#!/usr/bin/env bash
# pcl_phaser_batch on bad input: a clear message and the documented exit code, never a
# crash; a missing cloud is recorded as a failed pair and the rest go on.
source "$(dirname "$0")/batch_test_support.sh"

# expect CODE MESSAGE ARGS...: the exit code and a piece of the message on stderr.
expect() {
  local code=$1 message=$2 rc=0
  shift 2
  "$BATCH" "$@" > "$work/out.txt" 2> "$work/err.txt" || rc=$?
  [[ $rc == "$code" ]] || { cat "$work/err.txt"; fail "'$*' exited $rc, not $code"; }
  grep -qF -- "$message" "$work/err.txt" || { cat "$work/err.txt"; fail "'$*' did not say '$message'"; }
}
o=$work/o.jsonl
expect 1 "Give either --pairs or --scans" --out "$o"
expect 1 "Unknown argument" --pairs "$work/pairs.txt" --out "$o" --bogus
expect 1 "Invalid shard '3/2'" --pairs "$work/pairs.txt" --out "$o" --shard 3/2
expect 1 "Invalid value 'x' for --cache" --pairs "$work/pairs.txt" --out "$o" --cache x
expect 1 "Invalid value '0' for --jobs" --pairs "$work/pairs.txt" --out "$o" --jobs 0
expect 1 "needs a value" --pairs
expect 1 "--out RESULTS.jsonl is required" --pairs "$work/pairs.txt"
expect 2 "cannot read '$work/none.txt'" --pairs "$work/none.txt" --out "$o"
printf 'scans/full0.pcd\n' > "$work/bad.txt"
expect 2 "line 1: expected SOURCE TARGET" --pairs "$work/bad.txt" --out "$o"
printf 'a b 1 2 3 4 5 6 7 8 9 10 11 x\n' > "$work/bad.txt"
expect 2 "line 1: the guess is not 12 finite numbers" --pairs "$work/bad.txt" --out "$o"
expect 3 "cannot write '/nonexistent/folder/o.jsonl'" --pairs "$work/pairs.txt" --out /nonexistent/folder/o.jsonl
expect 3 "its folder is not writable" --pairs "$work/pairs.txt" --out "$o" --g2o /nonexistent/g.g2o
printf 'scans/full0.pcd\nscans/full6.pcd\n' > "$work/scans.txt"
printf '1 0 0 0 0 1 0 0 0 0 1 0\n' > "$work/poses.txt"
expect 2 "holds 1 poses for the 2 scans" --scans "$work/scans.txt" --poses "$work/poses.txt" --radius 20 --min-gap 1 --print-pairs
expect 1 "--scans needs --radius" --scans "$work/scans.txt" --poses "$work/poses.txt" --min-gap 1 --print-pairs
expect 2 "cannot read" merge "$work/m.jsonl" "$work/none.jsonl"
expect 1 "--odometry needs --scans" --pairs "$work/pairs.txt" --out "$o" --odometry
expect 1 "--odometry-sigma needs --odometry" --pairs "$work/pairs.txt" --out "$o" --odometry-sigma 1,1
printf '1 0 0 0 0 1 0 0 0 0 1 0\n1 0 0 1 0 1 0 0 0 0 1 0\n' > "$work/poses2.txt"
expect 1 "Invalid --odometry-sigma '0.1'" --scans "$work/scans.txt" --poses "$work/poses2.txt" --radius 20 --min-gap 1 --out "$o" --g2o "$work/g.g2o" --odometry --odometry-sigma 0.1
expect 1 "Invalid --odometry-sigma '0,1'" --scans "$work/scans.txt" --poses "$work/poses2.txt" --radius 20 --min-gap 1 --out "$o" --g2o "$work/g.g2o" --odometry --odometry-sigma 0,1
printf '1 0 0 0 0 1 0 0 0 0 1\n' > "$work/poses1.txt"
expect 2 "line 1" --scans "$work/scans.txt" --poses "$work/poses1.txt" --radius 20 --min-gap 1 --out "$o" --g2o "$work/g.g2o" --odometry

# A missing and an unreadable cloud: recorded as failed with the reason, the rest aligned.
printf 'scans/full18.pcd scans/full36.pcd\nmissing.pcd scans/full36.pcd\nbad.txt scans/full36.pcd\n' > "$work/some.txt"
"$BATCH" --pairs "$work/some.txt" --out "$work/some.jsonl" --threads 2 2> "$work/err.txt" ||
  { cat "$work/err.txt"; fail "a run with a missing cloud must finish with exit 0"; }
[[ $(grep -c '"status":"failed"' "$work/some.jsonl") == 2 ]] || fail "the two bad clouds are not recorded as failed"
grep -q '"source":"missing.pcd".*"error":".*missing.pcd' "$work/some.jsonl" || fail "the failed record does not name the missing file"
grep -q '"source":"scans/full18.pcd".*"status":"ok"' "$work/some.jsonl" || fail "the good pair was not aligned"

# An output that belongs to another list is refused, not mixed.
expect 2 "was written by another run" --pairs "$work/pairs.txt" --out "$work/some.jsonl"
expect 2 "was written by another run" --pairs "$work/some.txt" --out "$work/some.jsonl" -b 32
# Every engine option that changes results is in the run's fingerprint, not only -b.
expect 2 "was written by another run" --pairs "$work/some.txt" --out "$work/some.jsonl" --min-inlier-fraction 0.3
expect 2 "was written by another run" --pairs "$work/some.txt" --out "$work/some.jsonl" --voxel-size 0.5
# The same engine options, under a name and an alias, and the same messages as pcl_phaser_align.
expect 1 "Option --bandwidth is given twice" --pairs "$work/pairs.txt" --out "$o" -b 32 --bandwidth 16
expect 1 "Invalid value '1' for -b: expected an integer in 2..256" --pairs "$work/pairs.txt" --out "$o" -b 1
expect 1 "Invalid --whitening '2': expected a number in 0..1" --pairs "$work/pairs.txt" --out "$o" --whitening 2

# Loop-closure candidates from a trajectory, printed as a list the tool reads back.
ls "$scans"/full*.pcd | sort -V > "$work/all_scans.txt"
"$BATCH" --scans "$work/all_scans.txt" --poses "$scans/poses_T_world_lidar.txt" --radius 20 --min-gap 10 --print-pairs > "$work/candidates.txt"
n=$(grep -vc '^#' "$work/candidates.txt")
(( n > 50 )) || fail "only $n loop-closure candidates within 20 m and 10 scans"
"$BATCH" --pairs "$work/candidates.txt" --print-pairs > "$work/again.txt"
cmp -s "$work/candidates.txt" "$work/again.txt" || fail "the printed candidates do not read back as the same list"
echo "PASSED: bad input handled; $n loop-closure candidates"
