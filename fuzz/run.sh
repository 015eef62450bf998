#!/usr/bin/env bash
# Fuzzes the glTF loader for SECONDS (default 1800) with libFuzzer, AddressSanitizer and
# UndefinedBehaviorSanitizer, starting from the committed corpus, then merges what it found
# back into the corpus (the smallest set of inputs with the same coverage).
#   fuzz/run.sh [SECONDS]
# Needs clang (Debian: apt-get install clang). Builds in build-fuzz/; crashes land in
# build-fuzz/findings/ and fail the run.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-1800}"
command -v clang++ > /dev/null || { echo "fuzz: clang++ not found (apt-get install clang)" >&2; exit 1; }

cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ -DHMB_FUZZ=ON \
    -DHMB_BUILD_TESTS=OFF > /dev/null
cmake --build build-fuzz -j "$(nproc)" --target gltf_loader_fuzzer

corpus=fuzz/corpus/gltf_loader
mkdir -p "$corpus" build-fuzz/findings build-fuzz/new
cp -n tests/scenes/malformed/*.gltf tests/scenes/malformed/*.glb fuzz/seeds/* "$corpus"/ 2>/dev/null || true

export ASAN_OPTIONS="detect_leaks=1:allocator_may_return_null=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
# New inputs go to build-fuzz/new and are merged into the committed corpus afterwards.
build-fuzz/fuzz/gltf_loader_fuzzer build-fuzz/new "$corpus" -dict=fuzz/gltf.dict -max_total_time="$seconds" \
    -timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=1024 -max_len=65536 -print_final_stats=1 \
    -artifact_prefix=build-fuzz/findings/
build-fuzz/fuzz/gltf_loader_fuzzer -merge=1 "$corpus" build-fuzz/new > /dev/null 2>&1
echo "fuzz: $(ls "$corpus" | wc -l) inputs in $corpus; findings: $(ls build-fuzz/findings | wc -l)"
