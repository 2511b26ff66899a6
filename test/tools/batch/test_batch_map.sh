#!/usr/bin/env bash
# pcl_phaser_map builds a prior map from every second scan of the handheld sequence
# (0.1 m voxels), and pcl_phaser_batch --region relocalizes a scan left out of it (scan
# 90) against it: with a 10 m region about a point 4.8 m from its true position, it
# converges within 0.2 m of it; with a region 25 m away it does not converge.
source "$(dirname "$0")/batch_test_support.sh"
MAP=${MAP:?MAP must name the pcl_phaser_map binary}
python=$(command -v /usr/bin/python3 || command -v python3)
grep -v '^#' "$scans/poses_T_world_lidar.txt" > "$work/all_poses.txt"
awk 'NR % 2 == 1' "$work/all_poses.txt" > "$work/map_poses.txt"
awk 'NR % 2 == 1 {print "scans/full" $1 ".pcd"}' "$work/all_poses.txt" > "$work/map_scans.txt"
"$MAP" "$work/map_scans.txt" "$work/map_poses.txt" "$work/map.pcd" > "$work/map.log" ||
  { cat "$work/map.log"; fail "pcl_phaser_map"; }
grep -q "^15 scans, .* -> .* map points (voxel 0.1 m)" "$work/map.log" || fail "$(cat "$work/map.log")"
printf 'scans/full90.pcd map.pcd\n' > "$work/query.txt"
"$BATCH" --pairs "$work/query.txt" --out "$work/near.jsonl" --region -11,14,-0.7,10 \
  2> "$work/near.log" || { cat "$work/near.log"; fail "the query with a region"; }
# Scan 90's true position: line 16 of the poses (x, y, z at fields 6, 10, 14).
truth=$(sed -n 16p "$work/all_poses.txt" | awk '{print $6, $10, $14}')
"$python" - "$work/near.jsonl" $truth <<'PY' || fail "the relocalized pose"
import json, math, sys
record = json.loads(open(sys.argv[1]).readline())
t = [row[3] for row in record["transformation"][:3]]
error = math.dist(t, [float(v) for v in sys.argv[2:5]])
print("scan 90 in the map: converged %s, %.3f m from its position" % (record["converged"], error))
sys.exit(0 if record["converged"] and error < 0.2 else 1)
PY
"$BATCH" --pairs "$work/query.txt" --out "$work/far.jsonl" --region 5,-5,0,10 \
  2> "$work/far.log" || { cat "$work/far.log"; fail "the query with a far region"; }
grep -q '"converged":false' "$work/far.jsonl" || fail "a region 25 m away converged"
! "$MAP" "$work/map_scans.txt" "$work/all_poses.txt" "$work/m.pcd" 2> "$work/err.txt" ||
  fail "pcl_phaser_map took 30 poses for 15 scans"
grep -q "holds 30 poses for the 15 scans" "$work/err.txt" || fail "$(cat "$work/err.txt")"
echo "PASSED: a map from 15 scans; a query left out of it relocalized within a region"
