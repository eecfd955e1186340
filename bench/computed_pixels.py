#!/usr/bin/env python3
"""Which passes run on a moving frame, and how much of each cached effect they compute: along a
scene's camera path, the share of the covered pixels each cached effect computed (its raw image's
alpha is 1 there, 0 where it reused its cache) and every pass's GPU milliseconds and the compute
invocations it dispatched (what a GPU pays for, skipped pixels' lanes included), as means over
the frames after the first four. Settings as `--set` takes them.

    PYTHONPATH=build/python python3 bench/computed_pixels.py scenes/bunny.json --frames 48 \\
        --set cache_reuse_moving=1 --set cache_blur_indirect=4

On lavapipe a pass's time is a CPU time: compare runs of one machine, one after the other."""
import argparse
import json
import statistics

import ssgi

EFFECTS = ["shadow", "ao", "ssdo", "indirect", "sky_visibility"]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("scene")
    parser.add_argument("--frames", type=int, default=48)
    parser.add_argument("--size", default="256x256")
    parser.add_argument("--set", action="append", default=[], metavar="KEY=VALUE")
    args = parser.parse_args()
    scene = ssgi.Scene(args.scene)
    for item in args.set:
        key, value = item.split("=", 1)
        kind = type(scene.settings[key])
        scene.settings[key] = kind(float(value)) if kind is not bool else value not in ("0", "false")
    with open(args.scene) as f:
        path = json.load(f).get("camera_path", [])
    duration = path[-1]["time"] if path else 0.0
    width, height = (int(v) for v in args.size.split("x"))
    # The effects this frame caches: those with a history (SSDO only where it replaces the AO).
    names = ssgi.Renderer(scene, size=(8, 8)).images()
    effects = [e for e in EFFECTS if e + ".history" in names]
    renderer = ssgi.Renderer(scene, size=(width, height), keep=effects)
    computed = {e: [] for e in effects}
    passes, invocations = {}, {}
    for f in range(args.frames):
        renderer.set_time(duration * f / max(args.frames - 1, 1))
        renderer.render(1)
        if f < 4:
            continue
        covered = renderer.read("gbuffer.position")[..., 3] != 0
        for e in effects:
            raw = renderer.read(e)[..., 3]
            computed[e].append(float(((raw > 0.5) & covered).sum()) / max(int(covered.sum()), 1))
        profile = renderer.profile()
        for name, ms in profile["passes"].items():
            passes.setdefault(name, []).append(ms)
        for name, count in profile["invocations"].items():
            invocations.setdefault(name, []).append(count)
    print("computed share of the covered pixels (mean over frames 4-%d):" % (args.frames - 1))
    for e, shares in computed.items():
        if shares:
            print("  %-16s %5.1f%%" % (e, 100.0 * statistics.mean(shares)))
    print("GPU ms and compute invocations per pass (means; a pass that ran in none of the frames "
          "is left out):")
    for name, ms in passes.items():
        print("  %-24s %7.2f %10.0f" % (name, statistics.mean(ms),
                                        statistics.mean(invocations[name])))
    print("  %-24s %7.2f %10.0f" % ("sum", sum(statistics.mean(ms) for ms in passes.values()),
                                    sum(statistics.mean(n) for n in invocations.values())))


if __name__ == "__main__":
    main()
