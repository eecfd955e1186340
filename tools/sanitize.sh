#!/usr/bin/env bash
# Builds the project and its tests with clang's AddressSanitizer and UndefinedBehaviorSanitizer
# into build-asan/ and runs ctest there (the Vulkan tests with the validation layer, as usual):
#   tools/sanitize.sh                  every test
#   tools/sanitize.sh -R 'scene|cli'   ctest's own options select and shape the run
# Any ASan report, UBSan report or leak in our code fails the test it happens in.
#
# Leaks: Mesa's lavapipe (with LLVM behind it) and the validation layer keep allocations past
# exit, and the Vulkan loader unloads them before LeakSanitizer looks, so their stacks end in
# "<unknown module>" and nothing could tell them from ours. A tiny preloaded library
# (build-asan/keep_loaded.so, built below) opens both once with RTLD_NODELETE, so they stay
# mapped and their leaks are suppressed by library name (build-asan/lsan.supp). Leak detection
# stays on for everything else, our code included.
set -euo pipefail
cd "$(dirname "$0")/.."

build=${SSGI_ASAN_BUILD:-build-asan}
jobs=${JOBS:-2}
command -v clang++ >/dev/null || {
    echo "error: clang++ not found (apt-get install clang libclang-rt-14-dev)" >&2
    exit 1
}
mkdir -p "$build"

cat >"$build/lsan.supp" <<'SUPP'
# Driver and layer allocations kept past exit; not ours to free.
leak:libvulkan_lvp.so
leak:libLLVM
leak:libVkLayer_khronos_validation.so
leak:libvulkan.so
SUPP
# RTLD_LOCAL: kept mapped, but their symbols must not interpose on the loader's vk* functions.
cat >"$build/keep_loaded.c" <<'SHIM'
#include <dlfcn.h>
#include <stdlib.h>
#include <string.h>
__attribute__((constructor)) static void keep_loaded(void) {
    const char* list = getenv("SSGI_KEEP_LOADED");
    char paths[4096];
    if (!list || strlen(list) >= sizeof paths) return;
    strcpy(paths, list);
    for (char* path = strtok(paths, ":"); path; path = strtok(NULL, ":"))
        dlopen(path, RTLD_NOW | RTLD_LOCAL | RTLD_NODELETE);
}
SHIM
clang -shared -fPIC -O2 -o "$build/keep_loaded.so" "$build/keep_loaded.c"
keep=""
for lib in libvulkan_lvp.so libVkLayer_khronos_validation.so; do
    for path in /usr/lib/*/"$lib" /usr/lib/"$lib" /usr/local/lib/"$lib"; do
        if [ -f "$path" ]; then
            keep="$keep${keep:+:}$path"
            break
        fi
    done
done
export SSGI_KEEP_LOADED=$keep

# halt_on_error makes a UBSan report fail the test (its default is to print and go on).
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
export ASAN_OPTIONS=detect_leaks=1
export LSAN_OPTIONS=suppressions=$PWD/$build/lsan.supp:print_suppressions=0

flags="-fsanitize=address,undefined -fno-omit-frame-pointer"
CC=clang CXX=clang++ cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_C_FLAGS="$flags" -DCMAKE_CXX_FLAGS="$flags" \
    -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" \
    -DCMAKE_SHARED_LINKER_FLAGS="-fsanitize=address,undefined" >/dev/null
# Test discovery runs each test binary while building, so the options above apply there too.
# -k 0: a target that does not build (someone's work in progress) does not stop the others.
build_status=0
cmake --build "$build" -j"$jobs" -- -k 0 || build_status=$?
[ "$build_status" -eq 0 ] || echo "sanitize: some targets did not build (status $build_status)"

start=$(date +%s)
set +e
LD_PRELOAD=$PWD/$build/keep_loaded.so${LD_PRELOAD:+:$LD_PRELOAD} \
    ctest --test-dir "$build" --output-on-failure -j"$jobs" --timeout 1800 "$@"
status=$?
set -e
echo "sanitize: ctest exit status $status after $(($(date +%s) - start)) s (build status" \
    "$build_status)"
exit $((status != 0 ? status : build_status))
