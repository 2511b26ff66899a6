#!/usr/bin/env bash
# One align per process against the warm align (doc/benchmarks.md, *One align per
# process*): pcl_phaser_align SOURCE TARGET --threads 2 on the first N revisit pairs,
# wall time and minor page faults per run, then pcl_phaser_bench speed on the same pairs
# (its "2, fresh" row: a warm process, fresh target), and the ratio of the medians; then
# pcl_phaser_batch --pairs over the same pairs (default jobs and threads): its wall time
# per pair against the warm align.
#   bench/per_process.sh [N]     (env: BUILD=build, DATA=../shared/data; N = 36)
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build=${BUILD:-$here/build}
data=${DATA:-$here/../shared/data}
count=${1:-36}
align=$build/tools/pcl_phaser_align
batch=$build/tools/pcl_phaser_batch
bench=$build/bench/pcl_phaser_bench
dir=$data/lidar/balm_handheld
for program in "$align" "$batch" "$bench"; do
  [[ -x $program ]] || { echo "no $program: build the tools and bench/" >&2; exit 2; }
done
[[ -f $dir/pairs.txt ]] || { echo "skipped: $dir/pairs.txt not found (no shared data)"; exit 0; }

median() { sort -g | awk '{v[NR] = $1} END {print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2}'; }
walls=$(mktemp) faults=$(mktemp) run=$(mktemp) work=$(mktemp -d)
trap 'rm -rf "$walls" "$faults" "$run" "$work"' EXIT
while read -r source target _; do
  # Exit 3: the align ran but did not converge (doc/cli.md), a full align all the same.
  code=0
  /usr/bin/time -f "%e %R" -o "$run" "$align" "$dir/$source" "$dir/$target" --threads 2 \
    >/dev/null 2>&1 || code=$?
  ((code == 0 || code == 3)) || { echo "failed ($code): $source $target" >&2; exit 1; }
  read -r wall minor <"$run"
  echo "$wall" >>"$walls"
  echo "$minor" >>"$faults"
done < <(grep -v '^#' "$dir/pairs.txt" | head -n "$count")
grep -v '^#' "$dir/pairs.txt" | head -n "$count" | awk -v d="$dir" '{print d "/" $1, d "/" $2}' >"$work/pairs.txt"
start=$(date +%s.%N)
"$batch" --pairs "$work/pairs.txt" --out "$work/records.jsonl" >/dev/null 2>&1 ||
  { echo "pcl_phaser_batch failed" >&2; exit 1; }
batch_ms=$(echo "$start $(date +%s.%N) $(wc -l <"$work/pairs.txt")" | awk '{printf "%.0f", 1000 * ($2 - $1) / $3}')
wall_ms=$(median <"$walls" | awk '{printf "%.0f", 1000 * $1}')
warm_row=$("$bench" speed --data "$data" --max-pairs "$count" | grep '^| 2, fresh |')
warm_ms=$(echo "$warm_row" | awk -F'|' '{split($3, t, " "); print t[1]}')
echo "pcl_phaser_align, one align per process, $(wc -l <"$walls") pairs: median wall" \
  "$wall_ms ms, median minor faults $(median <"$faults")"
echo "warm fresh align (pcl_phaser_bench speed, 2 threads): median $warm_ms ms"
awk -v a="$wall_ms" -v w="$warm_ms" 'BEGIN {printf "one align per process / warm align: %.2fx\n", a / w}'
awk -v b="$batch_ms" -v w="$warm_ms" 'BEGIN {printf "pcl_phaser_batch --pairs: %d ms a pair (wall / pairs) = %.2fx the warm align\n", b, b / w}'
