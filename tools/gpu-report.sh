#!/usr/bin/env bash
# The GPU report: every GPU figure of the project from one command, on a machine with a GPU.
#
#   tools/gpu-report.sh [--quick] [--budget MINUTES] [--build DIR] [--parts LIST] OUT_DIR
#   tools/gpu-report.sh --bundle [--build DIR]
#   tools/gpu-report.sh --tables OUT_DIR
#
# Runs five parts, most important first, and after each one rewrites OUT_DIR/report.md and
# OUT_DIR/data.tar.gz (CSVs, logs, figure PNGs), so that a run cut off early keeps what it did:
#   tests    each Vulkan test binary, whole, in one process, with the validation layer on
#   bench    trs-bench on the Vulkan backend: sampling (counts kept, and every frame counting),
#            counting paths, ablation, scans, slivers, the --refine sweep
#   figures  tools/figures on the Vulkan backend (the paper's Figures 8 to 14)
#   render   trs-render on every shipped scene, Vulkan light sampler against the CPU's
#   cpu      the CPU backend's sampling table on the same machine, for the ratio
# --parts runs some of them (comma-separated); the others' results already in OUT_DIR stay, so
# a report can be made in several runs. --budget (default 20) is the run's minutes: each part
# stops at its share of them, counted from the start, and keeps what it finished. --quick runs
# every part at small sizes (a few minutes on lavapipe; ctest gpu_report_quick). --build names
# the build tree whose bin/ holds the programs (default build/), or a bundle.
#
# --bundle packs the programs, their libraries (compressed), the validation layer and the Vulkan
# loader into .device/ for a machine with an NVIDIA driver and nothing else; there, from a copy
# of the checkout: bash tools/gpu-report.sh --build .device OUT_DIR (docs/benchmarks.md, "The GPU report").
# --tables writes OUT_DIR/report.md again from OUT_DIR/data.tar.gz (python3 needed).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)

quick=0 budget=20 build=build parts=tests,bench,figures,render,cpu bundle=0 tables=0 out=
usage() { sed -n '4,6p' "$0" | sed 's/^# *//' >&2; exit 2; }
while [ $# -gt 0 ]; do
  case "$1" in
    --quick) quick=1 ;;
    --budget) budget=${2:?}; shift ;;
    --build) build=${2:?}; shift ;;
    --parts) parts=${2:?}; shift ;;
    --bundle) bundle=1 ;;
    --tables) tables=1 ;;
    -h|--help) sed -n '2,26p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    -*) echo "gpu-report: unknown option $1" >&2; usage ;;
    *) [ -z "$out" ] || usage; out=$1 ;;
  esac
  shift
done
[[ "$budget" =~ ^[0-9]+([.][0-9]+)?$ ]] || { echo "gpu-report: --budget takes minutes, not '$budget'" >&2; exit 2; }
for part in ${parts//,/ }; do
  case "$part" in tests|bench|figures|render|cpu) ;; *) echo "gpu-report: unknown part '$part'" >&2; exit 2 ;; esac
done
case "$build" in /*) ;; *) build="$PWD/$build" ;; esac

source "$root/tools/gpu-report/programs.sh"
if [ "$bundle" = 1 ]; then
  [ -z "$out" ] || usage
  exec bash "$root/tools/gpu-report/bundle.sh" "$build" "$root/.device"
fi
[ -n "$out" ] || usage
mkdir -p "$out"; out=$(cd "$out" && pwd)
export GPU_REPORT_QUICK=$quick GPU_REPORT_ROOT=$root GPU_REPORT_BIN=$build/bin
source "$root/tools/gpu-report/parts.sh"
work=$(mktemp -d "${TMPDIR:-/tmp}/gpu-report.XXXXXX")
BUNDLE_LIBS=$(mktemp -d "${TMPDIR:-/tmp}/gpu-report-libraries.XXXXXX")
trap 'rm -rf "$work" "$BUNDLE_LIBS"' EXIT
# Results of earlier runs into the same OUT_DIR are kept; a part that runs again replaces its own.
if [ -f "$out/data.tar.gz" ]; then
  tar -xzf "$out/data.tar.gz" -C "$work"
fi
if [ "$tables" = 1 ]; then
  publish "$work" "$out"
  exit 0
fi

# A bundle brings its libraries, the validation layer and the loader; a build tree uses the
# system's.
if [ -f "$build/libraries.tar.gz" ]; then
  source "$root/tools/gpu-report/use_bundle.sh" "$build"
fi
for program in "${report_programs[@]}"; do
  [ -x "$build/bin/$program" ] || { echo "gpu-report: $build/bin/$program is missing (build it, or name the build with --build)" >&2; exit 1; }
done

started=$(date +%s)
budget_s=$(awk -v m="$budget" 'BEGIN { printf "%d", m * 60 }')
describe_machine "$work" "$budget" "$parts"
# A part's deadline is its share of the budget, counted from the start: a part that finishes
# early leaves its time to the next ones.
declare -A share=([tests]=15 [bench]=40 [figures]=25 [render]=10 [cpu]=10)
selected=() total=0 spent=0
for part in tests bench figures render cpu; do
  case ",$parts," in *",$part,"*) selected+=("$part"); total=$((total + share[$part])) ;; esac
done
for part in "${selected[@]}"; do
  spent=$((spent + share[$part]))
  deadline=$((started + budget_s * spent / total))
  run_part "$work" "$part" "$deadline"
  publish "$work" "$out"
done
echo "gpu-report: wrote $out/report.md and $out/data.tar.gz"
