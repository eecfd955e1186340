#!/usr/bin/env bash
# Per-pass GPU milliseconds for every scene, as one CSV (scene,pass,median_ms), from `render
# --profile-json`. On lavapipe every time is a CPU time: compare the ratios within one run.
# Usage: bench/frame_times.sh [WxH] [FRAMES] > out/bench/frame_times.csv
set -euo pipefail
cd "$(dirname "$0")/.."
size=${1:-512x512}
frames=${2:-8}
mkdir -p out/bench
echo "scene,pass,median_ms"
for scene in scenes/*.json; do
  name=$(basename "$scene" .json)
  build/render "$scene" --size "$size" --frames "$frames" \
    --output "out/bench/$name.png" --profile-json "out/bench/$name.json" >/dev/null
  python3 -c '
import json, sys
j = json.load(open(sys.argv[1]))
for p in j["passes"]:
    print("%s,%s,%.3f" % (sys.argv[2], p["name"], p["median_ms"]))
print("%s,total,%.3f" % (sys.argv[2], j["total_median_ms"]))
' "out/bench/$name.json" "$name"
done
