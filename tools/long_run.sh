#!/usr/bin/env bash
# Long run: does a walkthrough hold its memory flat? Renders a scene's camera path with the cache
# on for a short run (FRAMES/10) and a long one (FRAMES), sampling the process's resident memory
# (VmRSS, and its peak VmHWM, from /proc/PID/status) as it goes, and compares them:
#   tools/long_run.sh [FRAMES] [WxH] [SCENE]     (default 2000 64x64 scenes/cornell-box.json)
# On lavapipe device memory is host memory, so a leak of Vulkan objects or device memory shows
# in the resident memory as well. Exits 1 when the long run's peak exceeds the short run's by
# more than SSGI_LONG_RUN_TOLERANCE_MB (default 8). Uses build/walkthrough (or $SSGI_BUILD).
set -euo pipefail
cd "$(dirname "$0")/.."

frames=${1:-2000}
size=${2:-64x64}
scene=${3:-scenes/cornell-box.json}
build=${SSGI_BUILD:-build}
tolerance=${SSGI_LONG_RUN_TOLERANCE_MB:-8}
exe=$build/walkthrough
[ -x "$exe" ] || {
    echo "error: $exe is not built (tools/setup.sh, or set SSGI_BUILD)" >&2
    exit 1
}
out=$build/long-run
mkdir -p "$out"

# run FRAMES: renders, samples memory every 0.2 s into $out/rss-FRAMES.csv, prints
# "FRAMES SECONDS PEAK_KB RSS25 RSS50 RSS75 RSS_END" (KB at those fractions of the samples).
run() {
    local n=$1 samples=$out/rss-$1.csv started=$EPOCHREALTIME
    "$exe" "$scene" --frames "$n" --size "$size" --cache 1 --timings "$out/timings-$n.csv" \
        >"$out/walkthrough-$n.txt" 2>&1 &
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
        echo "error: walkthrough failed (status $status):" >&2
        tail -5 "$out/walkthrough-$n.txt" >&2
        exit 1
    fi
    awk -F, -v n="$n" -v a="$started" -v b="$EPOCHREALTIME" -v peak="$peak" \
        'NR > 1 { rss[++k] = $2 }
        END { printf "%d %.1f %d %d %d %d %d\n", n, b - a, peak, rss[int(k * 0.25) + 1],
              rss[int(k * 0.5) + 1], rss[int(k * 0.75) + 1], rss[k] }' "$samples"
}

short=$(run $((frames / 10)))
long=$(run "$frames")
device=$(sed -n 's/.*device \(.*\)$/\1/p' "$out/walkthrough-$frames.txt" | head -1)
echo "long run: $scene at $size, cache on, device: ${device:-?}"
echo "$short
$long" | awk -v tol="$tolerance" -v dir="$out" '
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
        if (growth > tol) { printf "long run: memory grows (more than %s MB)\n", tol; exit 1 }
        printf "long run: memory flat (within %s MB)\n", tol
    }'
