#!/usr/bin/env bash
# The device check: on whatever Vulkan device this machine has (the default pick prefers a
# discrete GPU), build, run the test suite, run the passes, bvh, raster and kernels suites at
# sizes that fit the device, and write every result and a one-page summary (device, driver,
# each method's frame, the hybrid over post-process, build and trace rates, test failures) to
# bench/results/<device>/, and to $OUT as well when it is set.
#
#   scripts/device-check.sh                 # about 8 minutes on a GPU, under 15 on lavapipe
#   scripts/device-check.sh --skip-tests    # the benchmarks alone
#
# A GPU gets the full sizes; a CPU device (lavapipe) smaller ones, so that the whole check
# stays within 15 minutes on 2 cores. Set HMB_DEVICE_PROFILE to force a profile
# (docs: README "Devices"). It installs nothing where the build already exists: a GPU machine
# may have no network.
set -uo pipefail
cd "$(dirname "$0")/.."

skip_tests=0
for arg in "$@"; do
  case "$arg" in
    --skip-tests) skip_tests=1 ;;
    -h|--help) sed -n '2,14p' "$0"; exit 0 ;;
    *) echo "device-check: unknown argument '$arg' (expected --skip-tests)" >&2; exit 2 ;;
  esac
done

build=${BUILD_DIR:-build}
export XDG_RUNTIME_DIR=${XDG_RUNTIME_DIR:-/tmp}
work=$(mktemp -d "${TMPDIR:-/tmp}/hmb-device-check.XXXXXX")
trap 'rm -rf "$work"' EXIT
log() { echo "device-check: $*" >&2; }
started=$(date +%s)

# Build: configure where there is no build yet (installing what is missing only then).
if [ ! -x "$build/hmblur-bench" ] || [ ! -f "$build/CMakeCache.txt" ]; then
  if ! command -v cmake >/dev/null || ! command -v glslangValidator >/dev/null; then
    bash scripts/install-deps.sh || { log "cannot install the build's packages"; exit 1; }
  fi
  cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release >/dev/null || { log "configure failed"; exit 1; }
fi
cmake --build "$build" -j "$(nproc)" >"$work/build.log" 2>&1 || { tail -40 "$work/build.log" >&2; log "build failed"; exit 1; }
log "built in $(( $(date +%s) - started )) s"

bench="$build/hmblur-bench"
device_type=$("$build/hmblur" list-devices | awk -F'[][]' 'NR == 1 { print $2 }')
# The device the default pick takes: a discrete GPU first, then any.
if "$build/hmblur" list-devices | grep -q '\[discrete-gpu\]'; then device_type=discrete-gpu; fi
log "device type: $device_type"

results="$work/results"
mkdir -p "$results"
if [ "$device_type" = cpu ]; then
  passes_sizes=320x180,1280x720
  passes_repeats=5
  bvh_scenes=living-room,temple,bistro,cube-sphere-1m
  raster_sizes=640x360
  kernel_sizes=320x180
  test_timeout=900
else
  passes_sizes=640x360,1280x720,1920x1080
  passes_repeats=7
  bvh_scenes=living-room,temple,bistro,cube-sphere-1m
  raster_sizes=640x360,1280x720,1920x1080
  kernel_sizes=1280x720
  test_timeout=300
fi

# The test suite, every test's verdict kept (JUnit XML) and the failures listed.
if [ "$skip_tests" -eq 0 ]; then
  log "tests"
  (cd "$build" && timeout "$test_timeout" ctest -j "$(nproc)" --timeout 240 \
     --output-junit "$results/tests.xml" >"$results/tests.log" 2>&1)
  echo $? >"$results/tests.exit"
  tail -3 "$results/tests.log" >&2
fi

run_suite() {  # name, then the suite's arguments
  local name=$1
  shift
  log "$name"
  if ! timeout 600 "$bench" --quiet "$@" >"$results/$name.out" 2>"$results/$name.err"; then
    log "$name failed: $(tail -1 "$results/$name.err")"
  fi
}
run_suite passes passes --sizes "$passes_sizes" --repeats "$passes_repeats" \
  --methods sharp,postprocess,hybrid,hybrid-rays --out "$results/passes.json"
run_suite bvh bvh --scenes "$bvh_scenes" --repeats 3 --out "$results/bvh.json"
run_suite raster raster --sizes "$raster_sizes" --repeats 7 --out "$results/raster.json"
run_suite kernels kernels --sizes "$kernel_sizes" --out "$results/kernels.json"

elapsed=$(( $(date +%s) - started ))
folder=$(/usr/bin/env python3 bench/scripts/device_summary.py "$results" --seconds "$elapsed" \
           --command "scripts/device-check.sh $*") || { log "summary failed"; exit 1; }
if [ -n "${OUT:-}" ]; then mkdir -p "$OUT/$folder" && cp -r "$results"/. "$OUT/$folder/"; fi
# What is committed stays small (bench/results has a size bar): the JUnit XML repeats
# tests.log, a suite's stdout repeats its .md, and an empty stderr says nothing.
rm -f "$results/tests.xml"
for f in "$results"/*.err; do [ -s "$f" ] || rm -f "$f"; done
for f in "$results"/*.out; do cmp -s "$f" "${f%.out}.md" && rm -f "$f"; done
mkdir -p "bench/results/$folder"
cp -r "$results"/. "bench/results/$folder/"
log "results in bench/results/$folder${OUT:+ and $OUT/$folder} after $elapsed s"
cat "$results/summary.md"
