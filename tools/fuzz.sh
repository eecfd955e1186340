#!/usr/bin/env bash
# Fuzzes the scene loader (glTF and scene files, their nesting included) and compare's image
# readers (PNG, EXR) for a bounded time:
#   tools/fuzz.sh [SECONDS] [IMAGE_SECONDS]   (default 600, and SECONDS / 2 for the images)
# Builds tests/fuzz/fuzz_scene and fuzz_image with clang (libFuzzer, ASan, UBSan) into
# build-fuzz/, seeds the first with the scene files and scenes/models/*.glb and the second with
# tests/fuzz/image-seeds/, runs one fuzzing process at a time and prints the executions of each.
# The corpora it grows are kept in build-fuzz/fuzz-corpus*/ for the next run; anything it finds
# is written to build-fuzz/fuzz-findings/ and the exit status is non-zero. Replay one finding
# with: build-fuzz/tests/fuzz/fuzz_scene FILE (or fuzz_image FILE)
set -euo pipefail
cd "$(dirname "$0")/.."

seconds=${1:-600}
image_seconds=${2:-$((seconds / 2))}
build=${SSGI_FUZZ_BUILD:-build-fuzz}
jobs=${JOBS:-2}
[[ "$seconds" =~ ^[0-9]+$ && "$seconds" -gt 0 && "$image_seconds" =~ ^[0-9]+$ ]] || {
    echo "usage: tools/fuzz.sh [SECONDS] [IMAGE_SECONDS]" >&2
    exit 2
}
command -v clang++ >/dev/null || {
    echo "error: clang++ not found (apt-get install clang libclang-rt-14-dev)" >&2
    exit 1
}
# tinygltf and stb_image are compiled into the target (instrumented) when the stb headers are
# there; without them the fuzzer only sees into our own code.
[ -f /usr/include/stb/stb_image.h ] ||
    echo "fuzz: /usr/include/stb/stb_image.h missing (libstb-dev): tinygltf stays uninstrumented"

if [ ! -f "$build/CMakeCache.txt" ]; then
    CC=clang CXX=clang++ cmake -S . -B "$build" -G Ninja -DSSGI_FUZZ=ON \
        -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
fi
cmake --build "$build" --target fuzz_scene fuzz_image -j"$jobs"

# Seeds are refreshed every run (the scene files may have changed); the corpus persists.
seeds=$build/fuzz-seeds corpus=$build/fuzz-corpus findings=$build/fuzz-findings
rm -rf "$seeds"
mkdir -p "$seeds" "$corpus" "$findings"
cp scenes/*.json tests/scenes/*.json "$seeds"/
for f in scenes/*/*.json; do [ -f "$f" ] && cp "$f" "$seeds/$(basename "$(dirname "$f")")-$(basename "$f")"; done
cp scenes/models/*.glb tests/fuzz/seeds/* "$seeds"/

# One process (the machine is shared); -max_len keeps executions fast: the large models are
# read as their first 512 KiB, which keeps their whole JSON chunk and truncates the binary one.
log=$build/fuzz.log
set +e
"$build/tests/fuzz/fuzz_scene" -max_total_time="$seconds" -timeout=30 -rss_limit_mb=2048 \
    -max_len=524288 -dict=tests/fuzz/scene.dict -artifact_prefix="$findings/" \
    -print_final_stats=1 "$corpus" "$seeds" 2>&1 | tee "$log" | grep -E '^#[0-9]+.*(pulse|REDUCE|NEW)' |
    awk 'NR % 50 == 1'
status=${PIPESTATUS[0]}
set -e

executions=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
echo "fuzz: scene loader: ${executions:-?} executions in ${seconds} s; corpus" \
    "$(ls "$corpus" | wc -l) inputs; log $log"

# The image readers: small inputs (a header and a few rows are what they parse). OpenImageIO's
# PNG reader leaks its error message when libpng longjmps out of its read callback (shown
# without our code; tests/fuzz/lsan-oiio.supp says how): that one stack is suppressed, and
# allocations are unwound fully (the fast unwinder stops in libstdc++, before OpenImageIO's
# frame), which costs executions.
image_status=0
if [ "$image_seconds" -gt 0 ]; then
    image_corpus=$build/fuzz-corpus-image image_log=$build/fuzz-image.log
    mkdir -p "$image_corpus"
    set +e
    ASAN_OPTIONS=${ASAN_OPTIONS:+$ASAN_OPTIONS:}fast_unwind_on_malloc=0 \
        LSAN_OPTIONS=suppressions=$PWD/tests/fuzz/lsan-oiio.supp:print_suppressions=0 \
        "$build/tests/fuzz/fuzz_image" -max_total_time="$image_seconds" -timeout=30 \
        -rss_limit_mb=2048 -max_len=65536 -artifact_prefix="$findings/image-" \
        -print_final_stats=1 "$image_corpus" tests/fuzz/image-seeds >"$image_log" 2>&1
    image_status=$?
    set -e
    executions=$(sed -n 's/^stat::number_of_executed_units: *//p' "$image_log" | tail -1)
    echo "fuzz: image readers: ${executions:-?} executions in ${image_seconds} s; corpus" \
        "$(ls "$image_corpus" | wc -l) inputs; log $image_log"
    [ "$image_status" -eq 0 ] || grep -E 'ERROR|SUMMARY|broke its promise|instead of' \
        "$image_log" | head -20
fi
if [ "$status" -ne 0 ] || [ "$image_status" -ne 0 ] || [ -n "$(ls -A "$findings")" ]; then
    echo "fuzz: FINDINGS (exit status $status):"
    ls -l "$findings"
    grep -E 'ERROR|SUMMARY|broke its promise|instead of InputError' "$log" | head -20
    exit 1
fi
echo "fuzz: no findings"
