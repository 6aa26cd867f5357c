# shellcheck shell=bash
# The parts of tools/gpu-report.sh, sourced by it. Each part writes under WORK/PART/ and records
# each of its steps in WORK/PART/steps.tsv: name, status (ok, "failed (exit N)", cut: stopped at
# the deadline, skipped: the deadline had passed), seconds.
# Environment: GPU_REPORT_QUICK (1: small sizes), GPU_REPORT_ROOT, GPU_REPORT_BIN.

quick() { [ "$GPU_REPORT_QUICK" = 1 ]; }

# step WORK PART NAME DEADLINE LOG COMMAND...: runs COMMAND, its output to LOG, until DEADLINE.
step() {
  local work=$1 part=$2 name=$3 deadline=$4 log=$5; shift 5
  local start status rc
  start=$(date +%s)
  if [ "$start" -ge "$deadline" ]; then
    printf '%s\tskipped\t0\n' "$name" >> "$work/$part/steps.tsv"
    echo "gpu-report: $part/$name skipped: the part's time is up"
    return 0
  fi
  rc=0
  timeout -k 10 $((deadline - start)) "$@" > "$log" 2>&1 || rc=$?
  case $rc in 0) status=ok ;; 124|137) status=cut ;; *) status="failed (exit $rc)" ;; esac
  printf '%s\t%s\t%s\n' "$name" "$status" $(($(date +%s) - start)) >> "$work/$part/steps.tsv"
  echo "gpu-report: $part/$name: $status, $(($(date +%s) - start)) s"
}

# A python3 that can import the modules named, or nothing. Debian's comes first: another one
# earlier on the PATH may lack them.
python_with() {
  local candidate
  for candidate in /usr/bin/python3 "$(command -v python3 || true)"; do
    [ -x "$candidate" ] && "$candidate" -c "import ${1:-sys}" 2>/dev/null && { echo "$candidate"; return; }
  done
  return 0
}

describe_machine() {
  local work=$1 budget=$2 parts=$3
  {
    echo "date: $(date -u '+%Y-%m-%d %H:%M UTC')"
    echo "commit: $("$GPU_REPORT_BIN/trs-bench" --version | sed 's/.*commit //')"
    echo "cpu: $(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -1)"
    echo "cores: $(nproc)"
    echo "memory: $(awk '/MemTotal/ { printf "%.0f GiB", $2 / 1048576 }' /proc/meminfo)"
    if command -v nvidia-smi > /dev/null; then
      echo "nvidia-smi: $(nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv,noheader | head -1)"
    fi
    "$GPU_REPORT_BIN/trs-bench" --list-devices | sed 's/^/vulkan: /'
    echo "command: tools/gpu-report.sh$(quick && echo ' --quick') --budget $budget --parts $parts"
  } > "$work/machine.txt"
}

# ---------------------------------------------------------------------------------------------

part_tests() {
  local work=$1 deadline=$2 test filter
  for test in "${report_tests[@]}"; do
    filter='*'
    # --quick: the first test of each binary, so that every binary still loads and runs.
    quick && filter=$("$GPU_REPORT_BIN/$test" --gtest_list_tests | awk '/^[^ ]/ { s = $1 } /^  / { print s $1; exit }')
    step "$work" tests "$test" "$deadline" "$work/tests/$test.log" \
      env LIGHTSAMPLER_VULKAN_VALIDATION=1 LIGHTSAMPLER_REQUIRE_VULKAN=1 "$GPU_REPORT_BIN/$test" --gtest_filter="$filter"
  done
}

# The sizes of the trs-bench runs: the docs' tables, or --quick's.
bench_sizes() {
  if quick; then
    meshes=grid:5k counting_meshes=grid:5k,sphere:2k maps=smooth,sparse counts=1e4,1e5 big=1e5
    sliver_counts=1e4,1e5 measure=(--map-size 256 --warmup 1 --repeats 2 --budget 2) refines=(0 0.85)
  else
    meshes=grid:5k,sphere:100k,grid:2M maps=smooth,sparse counts=1e7,1e8 big=1e8 sliver_counts=1e6,1e7,1e8
    counting_meshes=grid:5k,grid:50k,grid:500k,grid:2M,sphere:20k,sphere:100k,sphere:500k,sphere:2M
    measure=(--warmup 1 --repeats 10) refines=(0 0.3 0.5 0.7 0.85)
  fi
}

# trs-bench BACKEND PART NAME ARGS...: one run into WORK/PART/NAME.csv (rewritten after each case,
# so that a run cut short keeps the cases it finished).
trs_bench() {
  local backend=$1 part=$2 name=$3; shift 3
  step "$work" "$part" "$name" "$deadline" "$work/$part/$name.log" \
    "$GPU_REPORT_BIN/trs-bench" --backends "$backend" "${measure[@]}" "$@" --csv "$work/$part/$name.csv"
}

part_bench() {
  local work=$1 deadline=$2 meshes counting_meshes maps counts big sliver_counts measure refines r
  bench_sizes
  local sampling=(--experiments sampling --methods trs,rs --counting auto --meshes "$meshes" --maps "$maps" --counts "$counts")
  trs_bench vulkan bench sampling "${sampling[@]}"
  trs_bench vulkan bench sampling-recount "${sampling[@]}" --recount
  trs_bench vulkan bench counting --experiments sampling --methods trs --recount \
    --counting auto,compute,per-triangle,raster --meshes "$counting_meshes" --maps smooth --counts "${counts%%,*}"
  trs_bench vulkan bench ablation --experiments ablation --meshes "${meshes%,*}" --maps "$maps" --counts "$counts"
  trs_bench vulkan bench scan --experiments scan --meshes "$meshes" --maps smooth
  trs_bench vulkan bench sliver --experiments sliver --counts "$sliver_counts"
  for r in "${refines[@]}"; do
    trs_bench vulkan bench "refine-$r" --experiments sampling --methods trs --counting auto --refine "$r" \
      --meshes "$meshes" --maps "$maps,hifreq" --counts "$big"
  done
}

# The figures in the order they are worth most to a short run: the sample count, the scans and
# the ablations first, the triangle sweep (meshes of up to 5M triangles) last.
part_figures() {
  local work=$1 deadline=$2 python figure figures=(fig08 fig13 fig14 fig10 fig11 fig12 fig09)
  local args=(--backends vulkan --trs-bench "$GPU_REPORT_BIN/trs-bench" --trs-sample "$GPU_REPORT_BIN/trs-sample"
              --out "$work/figures")
  quick && { args+=(--quick); figures=(fig08 fig13); }
  python=$(python_with "numpy, matplotlib")
  if [ -z "$python" ]; then
    python=$(python_with)
    args+=(--csv-only)
  fi
  [ -n "$python" ] || { printf 'figures\tfailed (no python3)\t0\n' >> "$work/figures/steps.tsv"; return; }
  for figure in "${figures[@]}"; do
    step "$work" figures "$figure" "$deadline" "$work/figures/$figure.out" \
      "$python" "$GPU_REPORT_ROOT/tools/figures" "${args[@]}" --only "$figure"
  done
}

# trs-render on each shipped scene with each light sampler: at the scene's own settings for the
# times (and its reference, where it ships one), and at the test settings against the test
# references; then the two backends' images against each other.
part_render() {
  local work=$1 deadline=$2 scene name backend small_spp=256 own=()
  local d=$work/render refs=$GPU_REPORT_ROOT/tests/render/references
  local small; small=$(sed -n 's/^set(TRS_REFERENCE_SETTINGS \(.*\))$/\1/p' "$GPU_REPORT_ROOT/tests/render/reference_settings.cmake")
  local reference_spp; reference_spp=$(sed -n 's/^set(TRS_REFERENCE_SPP \(.*\))$/\1/p' "$GPU_REPORT_ROOT/tests/render/reference_settings.cmake")
  quick && { small_spp=16; own=(--spp 4 --width 96 --height 54); }
  for scene in "$GPU_REPORT_ROOT"/scenes/*/render.toml; do
    scene=$(dirname "$scene"); name=$(basename "$scene")
    # Each backend its own seed: the tile test needs independent images.
    for backend in cpu vulkan; do
      local base=$d/$name.$backend seed=1
      [ "$backend" = vulkan ] && seed=2
      step "$work" render "$name.$backend" "$deadline" "$base.log" \
        "$GPU_REPORT_BIN/trs-render" "$scene/$name.gltf" --settings "$scene/render.toml" "${own[@]}" \
        --strategy trs --backend "$backend" --seed "$seed" --quiet --out "$base.exr" --variance "$base.variance.exr" \
        --stats "$base.json"
      # shellcheck disable=SC2086  # the settings are words
      step "$work" render "$name.$backend.small" "$deadline" "$base.small.log" \
        "$GPU_REPORT_BIN/trs-render" "$scene/$name.gltf" $small --threads 0 --spp "$small_spp" \
        --strategy trs --backend "$backend" --seed "$seed" --quiet --out "$base.small.exr" \
        --variance "$base.small.variance.exr" --emitter-mask "$base.small.mask.exr" --stats "$base.small.json"
      compare "$base.small-reference" "$base.small" "$small_spp" "$refs/$name" "$reference_spp" --mask "$base.small.mask.exr"
      if [ -f "$scene/reference.exr" ] && ! quick; then
        compare "$base.full-reference" "$base" "" "$scene/reference" "" --mask "$scene/reference-emitter-mask.exr"
      fi
    done
    local spp; spp=$(sed -n 's/^spp = //p' "$scene/render.toml"); quick && spp=4
    compare "$d/$name.agree" "$d/$name.vulkan" "$spp" "$d/$name.cpu" "$spp"
  done
}

# compare OUT TEST TEST_SPP REFERENCE REFERENCE_SPP [ARGS...]: trs-imgdiff into OUT.json, with the
# tile test where both sample counts are given (each image beside its variance image).
compare() {
  local out=$1 test=$2 test_spp=$3 reference=$4 reference_spp=$5; shift 5
  local args=("$@")
  [ -n "$test_spp" ] && args+=(--variance "$test.variance.exr" --reference-variance "$reference.variance.exr"
                               --spp "$test_spp" --reference-spp "$reference_spp")
  [ -f "$test.exr" ] && [ -f "$reference.exr" ] || return 0
  "$GPU_REPORT_BIN/trs-imgdiff" "$test.exr" "$reference.exr" "${args[@]}" --json "$out.json" > "$out.log" 2>&1 || true
}

part_cpu() {
  local work=$1 deadline=$2 meshes counting_meshes maps counts big sliver_counts measure refines
  bench_sizes
  quick || measure=(--warmup 1 --repeats 5)
  trs_bench cpu cpu sampling --experiments sampling --methods trs,rs --meshes "$meshes" --maps "$maps" --counts "$counts"
}

# run_part WORK PART DEADLINE: the part's earlier results are replaced by this run's.
run_part() {
  local work=$1 part=$2 deadline=$3
  rm -rf "${work:?}/$part"; mkdir -p "$work/$part"
  echo "gpu-report: part $part, until $(date -d "@$deadline" '+%H:%M:%S')"
  "part_$part" "$work" "$deadline"
}

# publish WORK OUT: report.md and data.tar.gz, each written whole under a temporary name first.
publish() {
  local work=$1 out=$2 python
  python=$(python_with)
  if [ -n "$python" ]; then
    "$python" "$GPU_REPORT_ROOT/tools/gpu-report/tables.py" "$work" > "$out/report.md.partial"
  else
    printf '# GPU report: tables not made (no python3 on this machine)\n\n%s\n' \
      "The results are in data.tar.gz; tools/gpu-report.sh --tables OUT_DIR makes the tables elsewhere." \
      > "$out/report.md.partial"
  fi
  mv "$out/report.md.partial" "$out/report.md"
  tar -czf "$out/data.tar.gz.partial" -C "$work" .
  mv "$out/data.tar.gz.partial" "$out/data.tar.gz"
}
