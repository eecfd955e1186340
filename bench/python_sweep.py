#!/usr/bin/env python3
"""A sweep over one setting through the Python module: six values at 96x96, one frame each, on one
Renderer (each change makes the renderer again from the old one's parts) against a Renderer per
value, in alternating order, the images compared bit for bit. Prints each round's times and the
medians' ratio; --json FILE keeps them in a list of runs, one a setting (the run of the same
setting replaced), which bench/docs_tables.py writes docs/python.md's table from.

    PYTHONPATH=build/python python3 bench/python_sweep.py [--setting NAME --values A,B,...]
"""
import argparse
import json
import pathlib
import statistics
import subprocess
import sys
import time

import numpy as np
import ssgi

ROOT = pathlib.Path(__file__).resolve().parents[1]


def commit():
    try:
        head = subprocess.run(["git", "-C", str(ROOT), "rev-parse", "--short", "HEAD"],
                              capture_output=True, text=True, check=True).stdout.strip()
        dirty = subprocess.run(["git", "-C", str(ROOT), "status", "--porcelain", "-uno"],
                               capture_output=True, text=True, check=True).stdout.strip()
        return head + ("-dirty" if dirty else "")
    except (OSError, subprocess.CalledProcessError):
        return "unknown"


def per_value(scene, size, name, values):
    images = []
    for value in values:
        with ssgi.Renderer(ssgi.Scene(scene, {name: value}), size) as renderer:
            images.append(renderer.render())
    return images


def one_renderer(scene, size, name, values):
    images = []
    with ssgi.Renderer(ssgi.Scene(scene), size) as renderer:
        for value in values:
            renderer.settings[name] = value
            images.append(renderer.render())
    return images


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scene", default=str(ROOT / "scenes" / "cornell-box.json"))
    parser.add_argument("--setting", default="indirect_vpls")
    parser.add_argument("--values", default="8,16,32,64,128,256")
    parser.add_argument("--size", default="96x96")
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--json", help="write the figures to this file")
    args = parser.parse_args()
    values = [float(v) if "." in v else int(v) for v in args.values.split(",")]
    size = tuple(int(n) for n in args.size.split("x"))
    # One warm-up: the process's first renderer opens the device and loads the driver.
    with ssgi.Renderer(ssgi.Scene(args.scene), size) as renderer:
        renderer.render()
    apart, together = [], []
    for round_ in range(args.rounds):
        ways = [(apart, per_value), (together, one_renderer)]
        for times, way in ways if round_ % 2 == 0 else reversed(ways):
            start = time.perf_counter()
            images = way(args.scene, size, args.setting, values)
            times.append(time.perf_counter() - start)
            if way is per_value:
                reference = images
            else:
                swept = images
        if not all(np.array_equal(a, b) for a, b in zip(reference, swept)):
            sys.exit("error: the sweep on one Renderer differs from a Renderer per value")
        print(f"round {round_ + 1}: a Renderer per value {apart[-1]:.2f} s, "
              f"one Renderer {together[-1]:.2f} s", flush=True)
    ratio = statistics.median(apart) / statistics.median(together)
    print(f"{args.setting} {args.values} at {args.size}: one Renderer is {ratio:.2f}x faster "
          f"(medians of {args.rounds}), images identical")
    if args.json:
        path = pathlib.Path(args.json)
        runs = json.loads(path.read_text()) if path.exists() else []
        with ssgi.Renderer(ssgi.Scene(args.scene), (8, 8)) as renderer:
            device, validation = renderer.device, renderer.validation
        run = {"setting": args.setting, "values": values, "scene": pathlib.Path(args.scene).name,
               "size": list(size), "rounds": args.rounds, "per_value_s": apart,
               "one_renderer_s": together, "ratio": ratio, "commit": commit(),
               "date": time.strftime("%Y-%m-%d"), "device": device, "validation": validation,
               "command": "python3 bench/python_sweep.py " + " ".join(sys.argv[1:])}
        runs = [r for r in runs if r["setting"] != args.setting] + [run]
        path.write_text(json.dumps(runs, indent=1) + "\n")

if __name__ == "__main__":
    main()
