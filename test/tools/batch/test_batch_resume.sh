#!/usr/bin/env bash
# pcl_phaser_batch resumes: killed (SIGKILL) at some moment, or with a record cut short
# in the middle of its line, or stopped by SIGINT, the same command finishes the run and
# the output equals an uninterrupted run's; the g2o graph holds an edge per converged
# pair, target first.
source "$(dirname "$0")/batch_test_support.sh"
serial_run

# Wait until FILE holds at least N lines (or the process PID ended); fail after 10 min.
wait_lines() {
  for _ in $(seq 1 6000); do
    [[ -f $1 && $(wc -l < "$1") -ge $2 ]] && return 0
    kill -0 "$3" 2> /dev/null || return 0
    sleep 0.1
  done
  fail "no $2 records in $1 after 10 minutes"
}

# 1. SIGKILL after two records, then a torn line as a kill inside write() would leave.
"$BATCH" --pairs "$work/pairs.txt" --out "$work/killed.jsonl" --threads 1 2> /dev/null &
pid=$!
wait_lines "$work/killed.jsonl" 2 $pid
kill -KILL $pid 2> /dev/null || true
wait $pid 2> /dev/null || true
done_lines=$(wc -l < "$work/killed.jsonl")
(( done_lines >= 2 && done_lines < npairs )) || fail "the kill came too late ($done_lines records)"
head -c 57 "$work/serial.jsonl" >> "$work/killed.jsonl"
"$BATCH" --pairs "$work/pairs.txt" --out "$work/killed.jsonl" --threads 1 2> "$work/resume.log" ||
  { cat "$work/resume.log"; fail "the resumed run"; }
grep -q "Resuming: $done_lines of $npairs" "$work/resume.log" || fail "the resume did not skip the recorded pairs"
same "$work/serial.jsonl" "$work/killed.jsonl"
[[ $(wc -l < "$work/killed.jsonl") == "$npairs" ]] || fail "the resumed run did not record each pair once"

# 2. SIGINT: the pair in flight finishes, exit 130, and the same command resumes.
"$BATCH" --pairs "$work/pairs.txt" --out "$work/int.jsonl" --threads 1 2> "$work/int.log" &
pid=$!
wait_lines "$work/int.jsonl" 1 $pid
[[ -s $work/int.jsonl ]] || fail "the run ended before SIGINT could be sent"
# A second process on the same output is refused while the first writes it.
rc=0; "$BATCH" --pairs "$work/pairs.txt" --out "$work/int.jsonl" 2> "$work/second.log" || rc=$?
[[ $rc == 3 ]] && grep -q "another process is writing it" "$work/second.log" ||
  { cat "$work/second.log"; fail "a second process on the same --out exited $rc"; }
kill -INT $pid 2> /dev/null || true
rc=0; wait $pid || rc=$?
[[ $rc == 130 ]] || fail "SIGINT gave exit code $rc, not 130"
grep -q "run the same command again" "$work/int.log" || fail "no resume hint after SIGINT"
"$BATCH" --pairs "$work/pairs.txt" --out "$work/int.jsonl" --threads 1 2> /dev/null
same "$work/serial.jsonl" "$work/int.jsonl"

# 3. The g2o graph: an edge per converged pair, ids of first appearance, target first.
edges=$(grep -c '^EDGE_SE3:QUAT' "$work/serial.g2o" || true)
accepted=$(grep -c '"converged":true' "$work/serial.jsonl")
[[ $edges == "$accepted" ]] || fail "$edges edges for $accepted converged pairs"
grep -q '^EDGE_SE3:QUAT 1 0 ' "$work/serial.g2o" || fail "no edge full36 (id 1) <- full18 (id 0)"
awk '/^EDGE/ && NF != 3 + 7 + 21 { exit 1 }' "$work/serial.g2o" || fail "an edge line without 31 fields"
echo "PASSED: resume after SIGKILL, a torn line and SIGINT equals the serial run ($accepted of $npairs converged)"
