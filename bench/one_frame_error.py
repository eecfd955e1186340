#!/usr/bin/env python3
"""One uncached frame's error against a converged reference, over several draws of the sampling
patterns: frames 0..N-1 of an uncached renderer (`cache=0`, so each frame is one frame's estimate
with that frame's patterns), each compared with the same reference (relMSE, `ssgi.compare`).
Prints each scene's mean, its range and frame 0's (the one `render` draws alone, with its SSIM);
with --converged N also a cached renderer's Nth frame (relMSE / SSIM), the converged figure.

    PYTHONPATH=build/python python3 bench/one_frame_error.py scenes/cornell-box.json --frames 12

The reference is `reference --spp 16384 --noise 0.01 --seed 1` at the same size, the converged
reference of docs/ground-truth.md (cached after the first run)."""
import argparse
import statistics

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
    args = parser.parse_args()
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
        if args.converged > 0:
            figures = ssgi.compare(ssgi.Renderer(scene, size=size).render(args.converged), truth)
            converged = "  %d frames %.5f / SSIM %.3f" % (args.converged, figures["relmse"],
                                                          figures["ssim"])
        scene.settings["cache"] = False
        renderer = ssgi.Renderer(scene, size=size)
        figures = [ssgi.compare(renderer.render(), truth) for _ in range(args.frames)]
        errors = [f["relmse"] for f in figures]
        print("  %-40s mean %.5f  range %.5f-%.5f  frame 0 %.5f / SSIM %.3f%s" %
              (path, statistics.mean(errors), min(errors), max(errors), errors[0],
               figures[0]["ssim"], converged))


if __name__ == "__main__":
    main()
