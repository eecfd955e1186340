#!/usr/bin/env python3
"""Plots of the stability suite: for each case, the region's error over the frames after the
last change (the tested renderer against a fresh one started there) and the frame-to-frame
flicker along the whole timeline. Reads DIR/stability.json as `build/stability` writes it and
writes DIR/plots/stability-CASE.png and DIR/plots/stability-all.png.

usage: stability_plot.py DIR
"""
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (the backend must be chosen first)


def series(frames, key, since_change=True):
    xs, ys = [], []
    for i, f in enumerate(frames):
        x = f["since_change"] if since_change else i
        y = f[key]
        if (since_change and x < 0) or y is None or (isinstance(y, float) and math.isnan(y)):
            continue
        xs.append(x)
        ys.append(max(y, 1e-7))  # log scale: an exact zero shows at the floor
    return xs, ys


def draw(case, error_axis, flicker_axis):
    frames = case["frames"]
    error_axis.plot(*series(frames, "error"), label=f"{case['region']} (tested)", color="C3")
    error_axis.plot(*series(frames, "fresh_error"), label="same region, fresh start", color="C0",
                    linestyle="--")
    error_axis.plot(*series(frames, "error_rest"), label="elsewhere (tested)", color="C2")
    error_axis.set_yscale("log")
    error_axis.set_xlabel("frames since the last change")
    error_axis.set_ylabel("relMSE to the converged image")
    error_axis.set_title(f"{case['case']}: error", fontsize=10)
    error_axis.legend(fontsize=7)
    xs, ys = series(frames, "flicker", since_change=False)
    flicker_axis.plot(xs, ys, color="C1")
    phases = [f["phase"] for f in frames]
    for name, colour in (("path", "#fde0c5"),):
        inside = [i for i, p in enumerate(phases) if p == name]
        if inside:
            flicker_axis.axvspan(inside[0] - 0.5, inside[-1] + 0.5, color=colour, label="moving")
    flicker_axis.set_yscale("log")
    flicker_axis.set_xlabel("frame (warm-up, path, hold)")
    flicker_axis.set_ylabel("frame-to-frame change")
    flicker_axis.set_title(f"{case['case']}: flicker", fontsize=10)
    flicker_axis.legend(fontsize=7)


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    folder = sys.argv[1]
    with open(os.path.join(folder, "stability.json")) as f:
        cases = json.load(f)["cases"]
    os.makedirs(os.path.join(folder, "plots"), exist_ok=True)
    for case in cases:
        figure, axes = plt.subplots(1, 2, figsize=(8, 3))
        draw(case, *axes)
        figure.tight_layout()
        figure.savefig(os.path.join(folder, "plots", f"stability-{case['case']}.png"), dpi=80)
        plt.close(figure)
    # Every case's error in one figure, for the README.
    columns = 3
    rows = (len(cases) + columns - 1) // columns
    figure, axes = plt.subplots(rows, columns, figsize=(4 * columns, 2.8 * rows), squeeze=False)
    for k, case in enumerate(cases):
        axis = axes[k // columns][k % columns]
        frames = case["frames"]
        axis.plot(*series(frames, "error"), color="C3", label="region, tested")
        axis.plot(*series(frames, "fresh_error"), color="C0", linestyle="--", label="fresh start")
        axis.plot(*series(frames, "error_rest"), color="C2", label="elsewhere")
        axis.set_yscale("log")
        axis.set_title(f"{case['case']} ({case['region']})", fontsize=9)
        axis.tick_params(labelsize=7)
        if k == 0:
            axis.legend(fontsize=7)
    for k in range(len(cases), rows * columns):
        axes[k // columns][k % columns].axis("off")
    figure.supxlabel("frames since the last change", fontsize=9)
    figure.supylabel("relMSE to the converged image", fontsize=9)
    figure.tight_layout()
    figure.savefig(os.path.join(folder, "plots", "stability-all.png"), dpi=70)
    print(f"wrote {folder}/plots/")


if __name__ == "__main__":
    main()
