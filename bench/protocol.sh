#!/usr/bin/env bash
# The 628 protocol trials (doc/benchmarks.md, *How to reproduce*) into one folder of
# CSVs, compared with a baseline folder when one is given:
#   bench/protocol.sh OUT [BASELINE]     (env: BUILD=build, DATA=../shared/data)
# METHOD=phaser_xyz (PointXYZ: range alone, no intensity) runs the same trials with that
# method only, compared trial by trial with the baseline's `phaser` rows: where fusion
# changes the answer.
# Each engine change is judged by the totals it prints (successes, converged successes,
# false accepts), the revisit medians and the trials whose success or claim changed.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
out=${1:?usage: bench/protocol.sh OUT [BASELINE]}
baseline=${2:-}
B=${BUILD:-$here/build}/bench/pcl_phaser_bench
data=(--data "${DATA:-$here/../shared/data}")
[[ -x $B ]] || { echo "no $B: build with -DPCL_PHASER_BUILD_BENCH=ON" >&2; exit 2; }
mkdir -p "$out"
method=${METHOD:-phaser}
run() { local sub=$1 csv=$2; shift 2; "$B" "$sub" "${data[@]}" "$@" --methods "$method" --csv "$out/$csv" >>"$out/log" 2>&1; }
: >"$out/log"
run revisits rev.csv
run revisits der.csv --derived-pairs 10
run revisits rw5.csv --source-wedge 0.5
run revisits rw25.csv --source-wedge 0.25
run compare w.csv --poses 10 --conditions overlap:0.5,overlap:0.25,overlap:0.1
run compare w0.csv --poses 10 --conditions overlap:0.5,overlap:0.25,overlap:0.1 --t-max 0
[[ $method == phaser ]] && sweep_methods=phaser,phaser_xyz || sweep_methods=$method
"$B" compare "${data[@]}" --poses 10 --methods "$sweep_methods" \
  --conditions clean,noise:50,noise:40,sparsity:0.25,sparsity:0.1 --csv "$out/sw.csv" >>"$out/log" 2>&1
python3 "$here/bench/protocol_compare.py" ${METHOD:+--method "$METHOD"} "$out" ${baseline:+"$baseline"}
