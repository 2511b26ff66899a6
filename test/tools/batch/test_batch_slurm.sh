#!/usr/bin/env bash
# pcl_phaser_batch as a Slurm array job: starts a single-node Slurm on localhost (its own
# munged, slurmctld and slurmd, every file in a temporary folder), submits
# examples/slurm/loop_closures.sbatch as a 2-task array, waits, merges, compares with
# the serial run, and stops the daemons. Skips, naming the piece, only when a daemon
# cannot be installed or started here.
source "$(dirname "$0")/batch_test_support.sh"
SBATCH_SCRIPT=${SBATCH_SCRIPT:?SBATCH_SCRIPT must name examples/slurm/loop_closures.sbatch}
for tool in munged mungekey slurmctld slurmd sbatch sinfo; do
  command -v $tool > /dev/null || skip "$tool is not installed (Debian packages slurm-wlm, munge)"
done
[[ $(id -u) == 0 ]] || skip "starting munged and slurmd needs root"
serial_run

s=$work/slurm
mkdir -p "$s/state" "$s/spool" "$s/log"
chmod 700 "$s"
stop_daemons() {
  for f in slurmd slurmctld munged; do
    [[ -f $s/$f.pid ]] && kill "$(cat "$s/$f.pid")" 2> /dev/null || true
  done
  sleep 1
  for f in slurmd slurmctld munged; do
    [[ -f $s/$f.pid ]] && kill -KILL "$(cat "$s/$f.pid")" 2> /dev/null || true
  done
  cleanup_work
}
trap stop_daemons EXIT
show_logs() { tail -n 20 "$s"/log/*.log "$s"/munged.log 2> /dev/null || true; }

mungekey --create --keyfile="$s/munge.key" > /dev/null 2>&1 || skip "mungekey cannot create a key"
chmod 400 "$s/munge.key"
munged --force --key-file="$s/munge.key" --socket="$s/munge.socket" \
  --pid-file="$s/munged.pid" --log-file="$s/munged.log" --seed-file="$s/munged.seed" ||
  { show_logs; skip "munged does not start"; }
munge --socket="$s/munge.socket" -n | unmunge --socket="$s/munge.socket" | grep -q Success ||
  { show_logs; skip "munge credentials do not verify"; }

host=$(hostname -s)
port=$(( 20000 + $$ % 20000 ))
cat > "$s/slurm.conf" <<CONF
ClusterName=phasertest
SlurmctldHost=$host
SlurmUser=root
SlurmdUser=root
SlurmctldPort=$port
SlurmdPort=$(( port + 1 ))
AuthType=auth/munge
AuthInfo=socket=$s/munge.socket
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
MpiDefault=none
ReturnToService=2
StateSaveLocation=$s/state
SlurmdSpoolDir=$s/spool
SlurmctldPidFile=$s/slurmctld.pid
SlurmdPidFile=$s/slurmd.pid
SlurmctldLogFile=$s/log/slurmctld.log
SlurmdLogFile=$s/log/slurmd.log
NodeName=$host CPUs=$(nproc) State=UNKNOWN
PartitionName=batch Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF=$s/slurm.conf
slurmctld -f "$SLURM_CONF" || { show_logs; skip "slurmctld does not start"; }
slurmd -f "$SLURM_CONF" || { show_logs; skip "slurmd does not start"; }
for _ in $(seq 1 60); do
  sinfo -h -o %T 2> /dev/null | grep -q idle && break
  sleep 0.5
done
sinfo -h -o %T | grep -q idle || { show_logs; skip "the Slurm node does not become idle"; }

export PCL_PHASER_BATCH=$BATCH
(cd "$work" && timeout 600 sbatch --wait --array=0-1 --cpus-per-task=1 \
   --output="$s/log/task_%a.out" "$SBATCH_SCRIPT" "$work/slurm_out" --pairs "$work/pairs.txt") ||
  { show_logs; cat "$s"/log/task_*.out; fail "the array job failed"; }
"$BATCH" merge "$work/merged.jsonl" "$work"/slurm_out/part_{0,1}.jsonl || fail "merge"
"$BATCH" merge "$work/merged.g2o" "$work"/slurm_out/part_{0,1}.g2o || fail "merge of the graphs"
for k in 0 1; do [[ -s $work/slurm_out/part_$k.jsonl ]] || fail "array task $k aligned nothing"; done
same "$work/serial.jsonl" "$work/merged.jsonl"
cmp "$work/serial.g2o" "$work/merged.g2o" || fail "the merged graph differs from the serial one"
echo "PASSED: a 2-task Slurm array, merged, equals the serial run"
