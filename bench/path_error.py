#!/usr/bin/env python3
"""The error along a scene's camera path, without timing: each configuration renders the path's
frames in order, and at `--error-frames` frames evenly spaced (4 by default, the last among
them, as `benchmark walkthrough --error-frames 4` picks them) its image is compared with the path-traced reference of
that camera (relMSE, `ssgi.compare`); prints each configuration's mean and the four values.
Configurations as NAME=KEY:VALUE,KEY:VALUE (settings as `--set` takes them); the uncached frame
("cache off") is always the first. Where a configuration is worse, `--maps DIR` writes each
measured frame and its error map (|image - reference| / (reference + 0.05), summed over RGB).

    PYTHONPATH=build/python python3 bench/path_error.py scenes/sibenik.json \\
        "default=" "reuse=cache_reuse_moving:1"

Faster than the walkthrough benchmark where only the error is wanted (128x128, no timed run)."""
import argparse
import json
import os
import statistics

import numpy as np
import ssgi


def settings_of(text):
    out = {}
    for item in filter(None, text.split(",")):
        key, value = item.split(":", 1)
        out[key] = float(value)
    return out


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("scene")
    parser.add_argument("configs", nargs="*", metavar="NAME=KEY:VALUE,...")
    parser.add_argument("--frames", type=int, default=96, help="frames along the path")
    parser.add_argument("--size", type=int, default=128, help="image side (pixels)")
    parser.add_argument("--spp", type=int, default=256, help="reference samples per pixel")
    parser.add_argument("--error-frames", type=int, default=4,
                        help="frames measured, evenly spaced along the path (the last among them)")
    parser.add_argument("--maps", help="folder for the measured frames and their error maps")
    args = parser.parse_intermixed_args()
    configs = {"cache off": {"cache": 0}}
    for text in args.configs:
        name, _, values = text.partition("=")
        configs[name] = settings_of(values)
    with open(args.scene) as f:
        keys = json.load(f).get("camera_path", [])
    if not keys:
        raise SystemExit("error: %s: the scene has no camera_path" % args.scene)
    duration = keys[-1]["time"]
    n = args.error_frames
    measured = [(args.frames - 1) * k // n for k in range(1, n + 1)]
    size = (args.size, args.size)
    scene = ssgi.Scene(args.scene)
    renderers = {}
    for name, settings in configs.items():
        s = ssgi.Scene(args.scene)
        s.settings.update({k: type(s.settings[k])(v) for k, v in settings.items()})
        renderers[name] = ssgi.Renderer(s, size=size)
    errors = {name: [] for name in configs}
    if args.maps:
        os.makedirs(args.maps, exist_ok=True)
    for f in range(args.frames):
        t = duration * f / max(args.frames - 1, 1)
        truth = None
        if f in measured:
            truth = ssgi.reference(scene, mode="full", size=size, spp=args.spp, time=t)
        for name, renderer in renderers.items():
            renderer.set_time(t)
            image = renderer.render()
            if truth is None:
                continue
            errors[name].append(ssgi.compare(image, truth)["relmse"])
            if args.maps:
                stem = os.path.join(args.maps, "%s-%03d" % (name.replace(" ", "_"), f))
                ssgi.write_image(stem + ".png", ssgi.tonemap(image))
                error = np.abs(image - truth).sum(-1) / (truth.sum(-1) + 0.05)
                grey = np.repeat(np.clip(error, 0.0, 1.0)[..., None], 3, -1).astype(np.float32)
                ssgi.write_image(stem + "-error.png", grey)
    print("relMSE along %s's path (%d frames, %dx%d, frames %s against %d-spp references):" %
          (args.scene, args.frames, args.size, args.size, measured, args.spp))
    for name, e in errors.items():
        print("  %-24s mean %.4f   %s" % (name, statistics.mean(e), " ".join("%.4f" % x for x in e)))


if __name__ == "__main__":
    main()
