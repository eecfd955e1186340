#!/usr/bin/env bash
# Long run: do walkthrough and render hold their memory flat? Each renders for a short run
# (FRAMES/10) and a long one (FRAMES) — walkthrough along the scene's camera path with the cache
# on, render from the scene's camera — sampling the process's resident memory (VmRSS, and its
# peak VmHWM, from /proc/PID/status) as it goes, and compares them:
#   tools/long_run.sh [FRAMES] [WxH] [SCENE]     (default 2000 64x64 scenes/cornell-box.json)
# On lavapipe device memory is host memory, so a leak of Vulkan objects or device memory shows
# in the resident memory as well. Exits 1 when either program's long run peaks more than
# SSGI_LONG_RUN_TOLERANCE_MB (default 8) above its short run. Uses build/ (or $SSGI_BUILD).
set -euo pipefail
cd "$(dirname "$0")/.."

frames=${1:-2000}
size=${2:-64x64}
scene=${3:-scenes/cornell-box.json}
build=${SSGI_BUILD:-build}
tolerance=${SSGI_LONG_RUN_TOLERANCE_MB:-8}
for program in walkthrough render; do
    [ -x "$build/$program" ] || {
        echo "error: $build/$program is not built (tools/setup.sh, or set SSGI_BUILD)" >&2
        exit 1
    }
done
out=$build/long-run
mkdir -p "$out"

# run PROGRAM FRAMES: renders, samples memory every 0.2 s into $out/rss-PROGRAM-FRAMES.csv,
# prints "FRAMES SECONDS PEAK_KB RSS25 RSS50 RSS75 RSS_END" (KB at those fractions of the samples).
run() {
    local program=$1 n=$2 started=$EPOCHREALTIME
    local samples=$out/rss-$program-$n.csv text=$out/$program-$n.txt
    if [ "$program" = walkthrough ]; then
        "$build/walkthrough" "$scene" --frames "$n" --size "$size" --cache 1 \
            --timings "$out/timings-$n.csv" >"$text" 2>&1 &
    else
        "$build/render" "$scene" --frames "$n" --size "$size" --output "$out/render-$n.png" \
            >"$text" 2>&1 &
    fi
    local pid=$! peak=0 rss hwm
    echo "seconds,rss_kb" >"$samples"
    while [ -r "/proc/$pid/status" ]; do
        read -r rss hwm < <(awk '/^VmRSS:/ {r = $2} /^VmHWM:/ {h = $2} END {print r, h}' \
            "/proc/$pid/status" 2>/dev/null || true)
        [ -n "${rss:-}" ] && echo "$(awk -v a="$started" -v b="$EPOCHREALTIME" \
            'BEGIN {print b - a}'),$rss" >>"$samples"
        [ -n "${hwm:-}" ] && [ "$hwm" -gt "$peak" ] && peak=$hwm
        sleep 0.2
    done
    local status=0
    wait "$pid" || status=$?
    if [ "$status" -ne 0 ]; then
        echo "error: $program failed (status $status):" >&2
        tail -5 "$text" >&2
        exit 1
    fi
    awk -F, -v n="$n" -v a="$started" -v b="$EPOCHREALTIME" -v peak="$peak" \
        'NR > 1 { rss[++k] = $2 }
        END { printf "%d %.1f %d %d %d %d %d\n", n, b - a, peak, rss[int(k * 0.25) + 1],
              rss[int(k * 0.5) + 1], rss[int(k * 0.75) + 1], rss[k] }' "$samples"
}

failed=0
for program in walkthrough render; do
    short=$(run "$program" $((frames / 10)))
    long=$(run "$program" "$frames")
    echo "long run: $program, $scene at $size$([ "$program" = walkthrough ] && echo ", cache on")"
    echo "$short
$long" | awk -v tol="$tolerance" -v dir="$out" -v program="$program" '
    { n[NR] = $1; s[NR] = $2; peak[NR] = $3 / 1024; q1[NR] = $4 / 1024; end_[NR] = $7 / 1024
      line[NR] = sprintf("%7d %9.1f %10.1f   %.1f / %.1f / %.1f / %.1f", $1, $2, $3 / 1024,
                         $4 / 1024, $5 / 1024, $6 / 1024, $7 / 1024) }
    END {
        printf "%7s %9s %10s   %s\n", "frames", "seconds", "peak MB",
               "resident MB at 25% / 50% / 75% / end"
        print line[1]; print line[2]
        growth = peak[2] - peak[1]
        printf "peak growth from %d to %d frames: %.1f MB; resident growth over the last " \
               "three quarters of the long run: %.1f MB (samples in %s)\n", n[1], n[2], growth,
               end_[2] - q1[2], dir
        if (growth > tol) { printf "%s: memory grows (more than %s MB)\n", program, tol; exit 1 }
        printf "%s: memory flat (within %s MB)\n", program, tol
    }' || failed=1
done
exit "$failed"
