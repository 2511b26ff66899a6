#!/usr/bin/env bash
# The loop-closure study of doc/benchmarks.md: on the shared BALM sequence, every pair of
# scans within RADIUS m and at least GAP scans apart, run through pcl_phaser_batch
# (one process; two shards under GNU parallel) and through a per-pair pcl_phaser_align
# loop, all timed in one run beside the FFT yardstick, then judged against the
# reference poses (pcl_phaser_loop_closure_report).
#   bench/loop_closures.sh [BUILD_DIR] [OUT_DIR]     (RADIUS=20 GAP=10 THREADS=2)
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${1:-$here/build}
out=${2:-loop_closures}
data=${PCL_PHASER_DATA:-$here/../shared/data}/lidar/balm_handheld
radius=${RADIUS:-20} gap=${GAP:-10} threads=${THREADS:-2}
[[ -f $data/poses_T_world_lidar.txt ]] || { echo "SKIPPED: $data is absent"; exit 0; }
batch=$build/tools/pcl_phaser_batch
mkdir -p "$out"
rm -f "$out"/serial.* "$out"/part*.* "$out"/merged.* "$out"/align_loop.*
awk '!/^#/ { print "'"$data"'/full" $1 ".pcd" }' "$data/poses_T_world_lidar.txt" > "$out/scans.txt"
cand=(--scans "$out/scans.txt" --poses "$data/poses_T_world_lidar.txt" --radius "$radius" --min-gap "$gap")
"$batch" "${cand[@]}" --print-pairs > "$out/pairs.txt"
n=$(grep -vc '^#' "$out/pairs.txt")
now() { date +%s.%N; }
yard() { "$build/bench/pcl_phaser_loop_closure_report" --yardstick; }
echo "candidates: $n (within $radius m, >= $gap scans apart); $(nproc) cores, $threads threads"
echo "yardstick before: $(yard) ms"

t0=$(now)
"$batch" "${cand[@]}" --out "$out/serial.jsonl" --g2o "$out/serial.g2o" --threads "$threads" 2> "$out/serial.log"
t1=$(now)
parallel --will-cite -j 2 "$batch" "${cand[@]}" --out "$out/part{}.jsonl" --g2o "$out/part{}.g2o" \
  --threads $(( threads > 1 ? threads / 2 : 1 )) --shard {}/2 2> "$out/parallel.log" ::: 0 1
"$batch" merge "$out/merged.jsonl" "$out"/part{0,1}.jsonl
"$batch" merge "$out/merged.g2o" "$out"/part{0,1}.g2o
t2=$(now)
grep -v '^#' "$out/pairs.txt" | while read -r s t; do
  "$build/tools/pcl_phaser_align" "$s" "$t" --threads "$threads" --json > /dev/null 2>> "$out/align_loop.log" || true
done
t3=$(now)
echo "yardstick after: $(yard) ms"
awk -v n="$n" -v a="$t0" -v b="$t1" -v c="$t2" -v d="$t3" 'BEGIN {
  printf "| run | wall (s) | pairs/s | vs the align loop |\n|---|---|---|---|\n";
  printf "| pcl_phaser_batch, 1 process | %.1f | %.2f | %.2fx |\n", b-a, n/(b-a), (b-a)/(d-c);
  printf "| pcl_phaser_batch, 2 shards under GNU parallel + merge | %.1f | %.2f | %.2fx |\n", c-b, n/(c-b), (c-b)/(d-c);
  printf "| pcl_phaser_align per pair | %.1f | %.2f | 1x |\n", d-c, n/(d-c) }'
cmp -s <(sed -E 's/,"time_ms":[^,]*,"target_ms":[^,}]*//' "$out/serial.jsonl" | sort -t: -k2,2n) \
       <(sed -E 's/,"time_ms":[^,]*,"target_ms":[^,}]*//' "$out/merged.jsonl") &&
  echo "sharded = serial: identical records" || echo "sharded != serial"
"$build/bench/pcl_phaser_loop_closure_report" --records "$out/serial.jsonl" --scans "$out/scans.txt" \
  --poses "$data/poses_T_world_lidar.txt" --csv "$out/pairs.csv"
