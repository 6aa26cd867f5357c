#!/usr/bin/env bash
# Runs COMMAND with a one-node Slurm cluster of its own: starts one in a fresh temporary folder
# (tools/slurm-local.sh start), runs COMMAND with SLURM_CONF pointing at it (and WITH_SLURM_DIR at
# that folder: logs in $WITH_SLURM_DIR/log), and always stops it. The folder is removed when
# COMMAND succeeds and kept, its path printed, when it fails.
#   tests/cluster/with_slurm.sh COMMAND [ARG...]
# Exit status: COMMAND's; 77 when the cluster cannot be had here (slurm-wlm or munge not
# installed: tools/setup-debian.sh --cluster; not root), for ctest's SKIP_RETURN_CODE; 125 when
# the cluster did not start (the daemons' logs are printed).
# Stopped also when this script is killed outright (ctest's timeout sends SIGKILL): a watchdog,
# detached from it, stops the cluster once this script's process is gone.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
local_cluster=$root/tools/slurm-local.sh

if [ $# -eq 0 ]; then
  echo "usage: tests/cluster/with_slurm.sh COMMAND [ARG...]" >&2
  exit 2
fi

skip() {
  echo "with_slurm: skipped: $*"
  exit 77
}

missing=()
for c in munged mungekey slurmctld slurmd sbatch squeue scancel scontrol sinfo; do
  command -v "$c" > /dev/null || missing+=("$c")
done
[ ${#missing[@]} -eq 0 ] ||
  skip "not installed: ${missing[*]} (tools/setup-debian.sh --cluster installs slurm-wlm and munge)"
[ "$(id -u)" -eq 0 ] || skip "the local cluster runs its daemons as root; this is $(id -un)"

dir=$(mktemp -d "${TMPDIR:-/tmp}/slurm-local.XXXXXX")

# The watchdog: a grandchild, so that killing this process and its descendants leaves it alive.
watch_pid=$$
(
  trap '' INT TERM HUP
  # shellcheck disable=SC2016  # expanded by that bash
  setsid bash -c 'while kill -0 "$1" 2>/dev/null; do sleep 1; done; bash "$2" stop "$3"' \
    with_slurm-watchdog "$watch_pid" "$local_cluster" "$dir" < /dev/null > /dev/null 2>&1 &
)

status=125
# shellcheck disable=SC2317  # run by the trap
cleanup() {
  bash "$local_cluster" stop "$dir" || echo "with_slurm: stopping the cluster in $dir failed" >&2
  if [ "$status" -eq 0 ]; then
    rm -rf "$dir"
  else
    echo "with_slurm: kept $dir (the daemons' logs are in $dir/log)" >&2
  fi
}
trap cleanup EXIT
trap 'exit 130' INT
trap 'exit 143' TERM
trap 'exit 129' HUP

if ! bash "$local_cluster" start "$dir" > /dev/null; then
  echo "with_slurm: the cluster did not start" >&2
  exit 125
fi
# shellcheck source=/dev/null  # written by slurm-local.sh start
. "$dir/env.sh"
export WITH_SLURM_DIR=$dir
set +e
"$@"
status=$?
set -e
exit "$status"
