#!/usr/bin/env bash
# Renders a fixed set of images that between them run every pass and every cache path, so that a
# refactor can be shown to change nothing: run it before and after, then compare the two folders.
#   tools/render_set.sh OUT_DIR [RENDER]      # RENDER: the render program (default build/render)
#   tools/render_set.sh --compare DIR_A DIR_B # every EXR of A against B's: exit 1 unless identical
# About a minute and a half on two cores. The EXRs' values are compared (build/compare's MAE is 0 only
# where every value is the same; the files' headers carry the program's build).
set -euo pipefail
cd "$(dirname "$0")/.."

if [ "${1:-}" = "--compare" ]; then
  a=$2 b=$3 differ=0
  for f in "$a"/*.exr; do
    name=$(basename "$f")
    # The image row's MAE is 0 only where every value is the same (the files' headers differ).
    row=$(build/compare "$f" "$b/$name" 2>&1 | grep -m1 '^image') || row="unreadable"
    if [ "$(echo "$row" | awk '{print $5}')" = "0.0000e+00" ]; then
      echo "identical: $name"
    else
      echo "differs: $name: $row"
      differ=1
    fi
  done
  exit $differ
fi

out=${1:?usage: tools/render_set.sh OUT_DIR [RENDER]}
render=${2:-build/render}
mkdir -p "$out"
run() { # name, then render's arguments
  local name=$1
  shift
  "$render" "$@" --output "$out/$name.png" >/dev/null
}
run cornell "scenes/cornell-box.json" --size 128x128
run cornell-thesis "scenes/cornell-box.json" --size 128x128 --set indirect_method=0
run cornell-uncached "scenes/cornell-box.json" --size 128x128 --set cache=0
run cornell-settled "scenes/cornell-box.json" --size 96x96 --frames 40
run bunny-frames "scenes/bunny.json" --size 128x96 --frames 4
run bunny-mean "scenes/bunny.json" --size 128x96 --frames 4 --set cache_method=1
run bunny-ssdo "scenes/bunny.json" --size 128x96 --frames 3 \
  --set ssdo=1 --set depth_peeling=1 --set contact_shadows=1
run bunny-band "scenes/bunny.json" --size 112x80 --frames 2 --set guard_band=8
run sponza "scenes/sponza.json" --size 128x96 --frames 2
run pine "scenes/scrub-pine.json" --size 96x96 --frames 2
run bare-bunny "scenes/models/bunny.glb" --size 96x96
run bare-knob-ground "scenes/models/mori-knob.glb" --size 96x96 --set ground_plane=0
run sponza-path "scenes/sponza.json" --size 96x72 --frames 3 --time 1.5
# Every debug view once: Sponza has a sky (sky-visibility), the bunny with SSDO the rest.
for view in albedo normal depth direct rsm-flux rsm-normal shadow ao indirect sky-visibility; do
  run "view-$view" "scenes/sponza.json" --size 64x48 --frames 2 --view "$view"
done
for view in ssdo contact peel; do
  run "view-$view" "scenes/bunny.json" --size 64x48 --frames 2 --view "$view" \
    --set ssdo=1 --set depth_peeling=1 --set contact_shadows=1
done
