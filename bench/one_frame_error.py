#!/usr/bin/env python3
"""One uncached frame's error against a converged reference, over several draws of the sampling
patterns: frames 0..N-1 of an uncached renderer (`cache=0`, so each frame is one frame's estimate
with that frame's patterns), each compared with the same reference (relMSE, `ssgi.compare`).
Prints each scene's mean, its range and frame 0's (the one `render` draws alone, with its SSIM);
with --converged N also a cached renderer's Nth frame (relMSE / SSIM), the converged figure.

    PYTHONPATH=build/python python3 bench/one_frame_error.py scenes/cornell-box.json --frames 12

With --json FILE (docs/data/one-frame-error.json for the docs) it also writes the figures, with
the command, commit and device, for bench/docs_tables.py; the docs' figures are those of
`scenes/*.json --frames 12 --converged 64 --json docs/data/one-frame-error.json`.

The reference is `reference --spp 16384 --noise 0.01 --seed 1` at the same size, the converged
reference of docs/ground-truth.md (cached after the first run)."""
import argparse
import json
import os
import statistics
import subprocess
import sys

import ssgi


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("scenes", nargs="+")
    parser.add_argument("--frames", type=int, default=12, help="draws of the patterns")
    parser.add_argument("--size", type=int, default=128, help="image side (pixels)")
    parser.add_argument("--converged", type=int, default=0, metavar="N",
                        help="also a cached renderer's Nth frame (0: not measured)")
    parser.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                        help="a setting for the real-time frame (repeatable)")
    parser.add_argument("--json", metavar="FILE",
                        help="also write the figures there (docs/data/one-frame-error.json)")
    args = parser.parse_args()
    data = {"scenes": {}}
    size = (args.size, args.size)
    print("relMSE of one uncached frame against the converged reference (%dx%d, %d draws):" %
          (args.size, args.size, args.frames))
    for path in args.scenes:
        scene = ssgi.Scene(path)
        truth = ssgi.reference(scene, mode="full", size=size, spp=16384, noise=0.01, seed=1)
        for item in args.set:
            key, value = item.split("=", 1)
            scene.settings[key] = type(scene.settings[key])(float(value))
        converged = ""
        entry = {}
        if args.converged > 0:
            figures = ssgi.compare(ssgi.Renderer(scene, size=size).render(args.converged), truth)
            converged = "  %d frames %.5f / SSIM %.3f" % (args.converged, figures["relmse"],
                                                          figures["ssim"])
            entry = {"converged": round(figures["relmse"], 6),
                     "converged_ssim": round(figures["ssim"], 4)}
        data["indirect_method"] = int(scene.settings["indirect_method"])
        scene.settings["cache"] = False
        renderer = ssgi.Renderer(scene, size=size)
        figures = [ssgi.compare(renderer.render(), truth) for _ in range(args.frames)]
        errors = [f["relmse"] for f in figures]
        print("  %-40s mean %.5f  range %.5f-%.5f  frame 0 %.5f / SSIM %.3f%s" %
              (path, statistics.mean(errors), min(errors), max(errors), errors[0],
               figures[0]["ssim"], converged))
        entry.update({"mean": round(statistics.mean(errors), 6), "min": round(min(errors), 6),
                      "max": round(max(errors), 6), "frame0": round(errors[0], 6),
                      "frame0_ssim": round(figures[0]["ssim"], 4)})
        data["scenes"][os.path.splitext(os.path.basename(path))[0]] = entry
    if args.json:
        write_json(args, data)


def write_json(args, data):
    """The figures with what measured them, as bench/docs_tables.py reads them."""
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    git = lambda *a: subprocess.run(["git", "-C", root] + list(a), capture_output=True,
                                    text=True).stdout.strip()
    commit = git("rev-parse", "--short", "HEAD") or "unknown"
    if git("status", "--porcelain", "--untracked-files=no"):
        commit += "-dirty"
    device = ssgi.Renderer(ssgi.Scene(args.scenes[0]), size=(16, 16)).device
    settings = "".join(" --set " + s for s in args.set)
    data.update({
        "what": "one uncached frame and a cached renderer's %dth frame against converged "
                "path-traced references (full mode, to 1%% noise or 16,384 spp, seed 1)%s"
                % (args.converged, ", " + settings.strip() if settings else ", default settings"),
        "command": "PYTHONPATH=build/python python3 bench/one_frame_error.py scenes/*.json "
                   "--frames %d --converged %d%s%s --json %s"
                   % (args.frames, args.converged,
                      "" if args.size == 128 else " --size %d" % args.size, settings, args.json),
        "commit": commit, "device": device, "indirect_method": data.pop("indirect_method"),
        "size": args.size, "frames": args.frames,
        "converged_frames": args.converged})
    with open(args.json, "w") as f:
        json.dump(data, f, indent=2)
        f.write("\n")
    print("figures: %s" % args.json, file=sys.stderr)


if __name__ == "__main__":
    main()
