# Shared by the pcl_phaser_batch end-to-end tests (sourced, not run).
#   BATCH   the pcl_phaser_batch binary      DATA   the shared data folder
# A test that lacks the data (or a tool) prints why and exits 77, which CTest reports
# as skipped.
set -euo pipefail
BATCH=${BATCH:?BATCH must name the pcl_phaser_batch binary}
DATA=${PCL_PHASER_DATA:-${DATA:?DATA must name the shared data folder}}
scans=$DATA/lidar/balm_handheld

skip() { echo "SKIPPED: $*"; exit 77; }
fail() { echo "FAILED: $*" >&2; exit 1; }

[[ -f $scans/full120.pcd ]] || skip "the shared scans are absent ($scans/full120.pcd)"
work=$(mktemp -d /tmp/pcl_phaser_batch_e2e.XXXXXX)
cleanup_work() { rm -rf "$work"; }
trap cleanup_work EXIT

# Eight revisit pairs of pairs.txt (two targets twice), as paths relative to the list.
ln -s "$scans" "$work/scans"
cat > "$work/pairs.txt" <<'LIST'
# source target (relative to this list)
scans/full18.pcd scans/full36.pcd
scans/full108.pcd scans/full168.pcd
scans/full42.pcd scans/full54.pcd
scans/full18.pcd scans/full120.pcd
scans/full120.pcd scans/full132.pcd
scans/full0.pcd scans/full120.pcd
scans/full6.pcd scans/full126.pcd
scans/full6.pcd scans/full36.pcd
LIST
npairs=8

# The records without their timings, in pair order: what must be equal between runs.
normalized() {
  sed -E 's/,"stages_ms":\{[^}]*\},"time_ms":[^,}]*//; s/,"run":"[^"]*"//' "$1" | sort -t: -k2,2n
}

# The uninterrupted serial run (one job of two engine threads) every other run (other
# job and thread counts, shards) is compared with.
serial_run() {
  "$BATCH" --pairs "$work/pairs.txt" --out "$work/serial.jsonl" --g2o "$work/serial.g2o" --jobs 1 \
    --threads 2 2> "$work/serial.log" || { cat "$work/serial.log"; fail "the serial run"; }
  [[ $(wc -l < "$work/serial.jsonl") == "$npairs" ]] || fail "the serial run recorded $(wc -l < "$work/serial.jsonl") pairs, not $npairs"
  grep -q '"converged":true' "$work/serial.jsonl" || fail "no pair converged in the serial run"
}

# same A B: the two outputs hold the same records (timings aside).
same() {
  diff <(normalized "$1") <(normalized "$2") > "$work/diff.txt" ||
    { head -c 2000 "$work/diff.txt"; fail "$1 and $2 differ"; }
}
