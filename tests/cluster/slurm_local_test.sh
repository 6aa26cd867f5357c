#!/usr/bin/env bash
# The local cluster itself (tools/slurm-local.sh), run inside one by with_slurm.sh:
#   tests/cluster/with_slurm.sh tests/cluster/slurm_local_test.sh
# sbatch --wait on an array, its exit status when a task fails and how to find that task, one
# array task cancelled, a dependency met and one that never can be, --cpus-per-task and
# --exclusive, a requeue. 30 to 45 s, most of it sbatch --wait's polling and the requeue's
# wait (tools/slurm-local.sh: cred_expire).
# shellcheck disable=SC2016  # the jobs' scripts expand their own variables
set -euo pipefail
: "${SLURM_CONF:?run me with tests/cluster/with_slurm.sh}"
out=$WITH_SLURM_DIR/slurm_local_test
mkdir -p "$out"
cd "$out"

fail() {
  echo "FAIL: $*" >&2
  exit 1
}

# "TASK STATE" lines of job JOB (an array's tasks, or the job alone as "N/A STATE"), sorted.
states() {
  squeue --noheader --states=all --jobs="$1" --format='%K %T' | sort -n
}

# Waits until no task of job JOB is pending or running any more (at most 60 s).
wait_done() {
  local deadline=$((SECONDS + 60))
  while squeue --noheader --jobs="$1" --states=PENDING,RUNNING,COMPLETING,CONFIGURING,REQUEUED |
    grep -q .; do
    [ $SECONDS -lt $deadline ] || fail "job $1 not done after 60 s: $(states "$1" | tr '\n' ' ')"
    sleep 0.5
  done
}

echo "$SECONDS s == an array, sbatch --wait"
sbatch --wait --array=0-3 --output='array.%a' --wrap 'echo $SLURM_ARRAY_TASK_ID' ||
  fail "sbatch --wait --array=0-3: status $?"
for i in 0 1 2 3; do
  [ "$(cat "array.$i")" = "$i" ] || fail "array task $i wrote '$(cat "array.$i")'"
done

echo "$SECONDS s == a failed array task: sbatch --wait exits with the highest exit code of the tasks"
status=0
sbatch --wait --array=0-3 --output=/dev/null --job-name=fails \
  --wrap 'exit $((SLURM_ARRAY_TASK_ID == 2 ? 3 : 0))' || status=$?
[ $status -eq 3 ] || fail "sbatch --wait with task 2 exiting 3: status $status"
job=$(squeue --noheader --states=all --name=fails --format=%F | head -1)
[ "$(states "$job" | tr '\n' ' ')" = "0 COMPLETED 1 COMPLETED 2 FAILED 3 COMPLETED " ] ||
  fail "states of the failing array: $(states "$job" | tr '\n' ' ')"
scontrol show job "${job}_2" | grep -q 'ExitCode=3:0' || fail "scontrol show job ${job}_2: no ExitCode=3:0"

echo "$SECONDS s == one array task cancelled"
job=$(sbatch --parsable --array=0-1 --output=/dev/null --wrap 'sleep 30')
sleep 1
scancel "${job}_1"
sleep 1
[ "$(states "$job" | tr '\n' ' ')" = "0 RUNNING 1 CANCELLED " ] ||
  fail "after scancel ${job}_1: $(states "$job" | tr '\n' ' ')"
scancel "$job"
wait_done "$job"

echo "$SECONDS s == dependencies"
first=$(sbatch --parsable --output=first.out --wrap 'sleep 1; echo first')
second=$(sbatch --parsable --dependency=afterok:"$first" --output=second.out \
  --wrap 'cat first.out; echo second')
wait_done "$second"
[ "$(states "$second")" = "N/A COMPLETED" ] || fail "job after a successful one: $(states "$second")"
[ "$(tr '\n' ' ' < second.out)" = "first second " ] || fail "second.out: $(cat second.out)"
# afterok on a job that fails: cancelled at once (DependencyParameters=kill_invalid_depend), and
# sbatch --wait on it exits 0: a job that never ran has no exit code.
first=$(sbatch --parsable --output=/dev/null --wrap 'exit 1')
second=$(sbatch --parsable --dependency=afterok:"$first" --output=/dev/null --wrap true)
wait_done "$second"
[ "$(states "$second")" = "N/A CANCELLED" ] || fail "job after a failed one: $(states "$second")"

echo "$SECONDS s == --cpus-per-task and --exclusive"
cpus=$(nproc)
sbatch --wait --cpus-per-task="$cpus" --output=cpus.out --wrap 'echo $SLURM_CPUS_ON_NODE' ||
  fail "sbatch --cpus-per-task=$cpus: status $?"
[ "$(cat cpus.out)" = "$cpus" ] || fail "--cpus-per-task=$cpus: SLURM_CPUS_ON_NODE=$(cat cpus.out)"
sbatch --wait --exclusive --output=exclusive.out --wrap 'echo $SLURM_CPUS_ON_NODE' ||
  fail "sbatch --exclusive: status $?"
[ "$(cat exclusive.out)" = "$cpus" ] || fail "--exclusive: SLURM_CPUS_ON_NODE=$(cat exclusive.out)"

echo "$SECONDS s == a requeue"
job=$(sbatch --parsable --output=requeue.out --open-mode=append \
  --wrap 'echo run ${SLURM_RESTART_COUNT:-0}; sleep 2')
sleep 1
scontrol requeue "$job"
wait_done "$job"
[ "$(states "$job")" = "N/A COMPLETED" ] || fail "requeued job: $(states "$job")"
grep -qx 'run 1' requeue.out || fail "requeued job did not run again: $(cat requeue.out)"
scontrol show job "$job" | grep -q 'Restarts=1' || fail "requeued job: no Restarts=1"

echo "PASS"
