#!/usr/bin/env bash
# Regenerates every benchmark: builds, measures each scene (build/benchmark), then writes the
# CSV files, the charts and the tables (bench/report.py). See bench/README.md.
#   bench/run.sh           docs: Cornell box, bunny, Sponza at 512x512 (+ 1280x720 timings of
#                          Sponza), into docs/ (about 55 min on 2 cores)
#   bench/run.sh --quick   quick: the same scenes at 256x256, into out/bench/quick/ (4 min)
#   bench/run.sh --all     every scene (+ Sibenik, Conference Room, Mori knob; about 2 h)
#   bench/run.sh --walkthroughs   the thesis's Tables 4.1-4.4 only: the camera paths of the bunny,
#                          Sponza, Sibenik and the conference room at 512x512, cache off and on,
#                          into docs/bench-walkthroughs.md (about 1 h)
#   bench/run.sh --indirect   the indirect light's methods (off, the thesis's, interleaved, importance, world cache) on
#                          the Cornell box, bunny and Sponza: cost at 256x256, error at 128x128,
#                          into docs/bench-indirect.md (about 3 min)
#   bench/run.sh --cache-fixes   what each of the cache's fixes costs (each undone alone, the
#                          guard band on): the bunny's and Sponza's camera paths and a settled
#                          still camera at 256x256, into docs/bench-cache-fixes.md (about 6 min)
# Options: --scenes "a b"  only these scenes (names of scenes/*.json)
#          --report-only   redraw charts and tables from the last run's JSON
set -euo pipefail
cd "$(dirname "$0")/.."

mode=full scenes="" report_only=0
while [ $# -gt 0 ]; do
  case "$1" in
    --quick) mode=quick ;;
    --all) mode=all ;;
    --walkthroughs) mode=walkthroughs ;;
    --indirect) mode=indirect ;;
    --scenes) scenes="$2"; shift ;;
    --report-only) report_only=1 ;;
    --cache-fixes) mode=cache-fixes ;;
    -h|--help) sed -n '2,20p' "$0"; exit 0 ;;
    *) echo "error: unknown option $1 (see bench/run.sh --help)" >&2; exit 2 ;;
  esac
  shift
done

build=${SSGI_BUILD_DIR:-build}
out=out/bench/$mode
if [ "$mode" = quick ]; then
  scenes=${scenes:-"cornell-box bunny sponza"}
  size=256x256 error=128 frames=2 series=44 series_methods=1 other_sizes=""
  walk_scenes="bunny" path_frames=48 error_frames=2
  images=$out/images doc=""
elif [ "$mode" = walkthroughs ]; then
  scenes=${scenes:-"sponza sibenik conference bunny"}
  size=512x512 error=256 frames=3 walk_scenes=$scenes path_frames=96 error_frames=3
  images=docs/images doc=docs/bench-walkthroughs.md out=out/bench/walk
elif [ "$mode" = cache-fixes ]; then
  scenes=${scenes:-"bunny sponza"}
  size=256x256 error=64 frames=3 walk_scenes=""
  images=docs/images doc=docs/bench-cache-fixes.md out=out/bench/cache-fixes
elif [ "$mode" = indirect ]; then
  scenes=${scenes:-"cornell-box bunny sponza"}
  size=256x256 error=128 frames=7 walk_scenes=""
  images=docs/images doc=docs/bench-indirect.md out=out/bench/indirect
else
  all="cornell-box bunny sponza sibenik conference mori-knob"
  [ "$mode" = all ] || all="cornell-box bunny sponza"
  scenes=${scenes:-$all}
  size=512x512 error=256 frames=3 series=64 series_methods=3 other_sizes="1280x720"
  other_scenes="sponza" other_frames=1
  [ "$mode" = all ] && other_scenes=$scenes other_frames=2
  walk_scenes="bunny" path_frames=96 error_frames=3
  images=docs/images doc=docs/bench.md out=out/bench/full
fi

# matplotlib from Debian (the system Python, whatever python3 is first on PATH).
py=/usr/bin/python3
if ! "$py" -c "import matplotlib" 2>/dev/null; then
  echo "installing python3-matplotlib (apt-get)"
  sudo_=""; [ "$(id -u)" -ne 0 ] && sudo_=sudo
  $sudo_ apt-get update -qq && $sudo_ apt-get install -y -qq python3-matplotlib >/dev/null
fi

start=$(date +%s)
commit=$(git rev-parse --short HEAD 2>/dev/null || echo unknown)
if [ -n "$(git status --porcelain --untracked-files=no 2>/dev/null)" ]; then commit="$commit-dirty"; fi

if [ "$report_only" = 0 ]; then
  echo "building ($build)"
  [ -f "$build/build.ninja" ] || cmake -S . -B "$build" -G Ninja >/dev/null
  ninja -C "$build" -j"$(nproc)" benchmark shaders >/dev/null
  mkdir -p "$out"
  rm -f "$out"/*.json
  # The steps: a sweep per scene and size, a walkthrough per walkthrough scene.
  steps=()
  for s in $scenes; do
    [ "$mode" = walkthroughs ] && continue
    if [ "$mode" = indirect ]; then
      steps+=("indirect $s $size --error-size $error")
      continue
    fi
    if [ "$mode" = cache-fixes ]; then
      steps+=("cache-fixes $s $size --error-size $error --spp 1024 --path-frames 48 \
        --error-frames 4 --still-frames 48")
      continue
    fi
    steps+=("sweep $s $size --error-size $error --series-frames $series --series-methods $series_methods")
    case " ${other_scenes:-} " in *" $s "*)
      for z in $other_sizes; do
        steps+=("sweep $s $z --no-error --no-series --frames ${other_frames:-1}")
      done ;;
    esac
  done
  for s in $walk_scenes; do
    case " $scenes " in *" $s "*) steps+=("walkthrough $s $size --error-size $error \
      --path-frames $path_frames --error-frames $error_frames") ;; esac
  done
  n=${#steps[@]} k=0
  for step in "${steps[@]}"; do
    k=$((k + 1))
    read -r kind scene sz rest <<<"$step"
    # A step's own --frames (the other sizes) comes after the default and wins.
    t0=$(date +%s)
    echo "[$k/$n] $kind $scene $sz ($(( (t0 - start) / 60 )) min so far)"
    # shellcheck disable=SC2086
    "$build/benchmark" "$kind" "scenes/$scene.json" --size "$sz" --frames "$frames" $rest \
      --commit "$commit" --out "$out/$kind-$scene-$sz.json"
    echo "      $(( $(date +%s) - t0 )) s"
  done
fi

seconds=$(( $(date +%s) - start ))
if [ "$report_only" = 0 ]; then
  echo "Mode: $mode; $(echo $scenes | wc -w) scenes measured in $((seconds / 60)) min on" \
    "$(nproc) cores ($(date -u +%Y-%m-%d))." >"$out/run.txt"
fi
note=$(cat "$out/run.txt" 2>/dev/null || echo "Mode: $mode.")
if [ "$mode" = indirect ]; then
  "$py" bench/indirect.py --results "$out" --doc "$doc" --note "$note"
  echo "done in $((seconds / 60)) min $((seconds % 60)) s: results in $out/, table in $doc"
  exit 0
fi
if [ "$mode" = cache-fixes ]; then
  "$py" bench/cache_fixes.py --results "$out" --doc "$doc" --note "$note"
  echo "done in $((seconds / 60)) min $((seconds % 60)) s: results in $out/, tables in $doc"
  exit 0
fi
if [ "$mode" = walkthroughs ]; then
  "$py" bench/walkthroughs.py --results "$out" --images "$images" --doc "$doc" \
    --data docs/data/walkthroughs.json
  echo "done in $((seconds / 60)) min $((seconds % 60)) s: results in $out/, charts in $images/"
  exit 0
fi
"$py" bench/report.py --results "$out" --images "$images" --size "$size" \
  ${doc:+--doc "$doc"} --note "$note"
echo "done in $((seconds / 60)) min $((seconds % 60)) s: results in $out/, charts in $images/"
