"""Error against frame time on the Cornell box with the Pareto front, as in docs/bench.md: each
configuration renders with the cache off; its time is the median host clock of 3 frames after a
warm-up frame, its error the relMSE of its last frame against the path-traced reference.
usage: python3 examples/pareto_sweep.py [SIZE [SPP [CHART.png]]]  (256 4096 pareto.png)"""
import statistics
import sys
from typing import Dict

import matplotlib
import matplotlib.pyplot as plt
import ssgi

matplotlib.use("Agg")
args = (sys.argv[1:] + ["256", "4096", "pareto.png"][len(sys.argv) - 1:])[:3]
size, spp, chart = int(args[0]), int(args[1]), args[2]
scene = ssgi.scene_file("cornell-box")  # the shipped scene, from any folder
# What changes the box's image: the bounce and the shadow (it has no sky: AO changes nothing).
configs = {"defaults": {}, "16 VPLs a cell": {"world_vpls": 16},
           "192 VPLs a cell": {"world_vpls": 192}, "interleaved": {"indirect_method": 1},
           "interleaved, unoccluded": {"indirect_method": 1, "indirect_visibility": 0},
           "VPLs by flux": {"indirect_method": 2}, "hard shadows": {"shadow_taps": 1},
           "512 VPLs, thesis": {"indirect_method": 0, "indirect_vpls": 512},
           "PCF 9": {"shadow_variant": 0, "shadow_taps": 9},
           "direct only": {"indirect": 0}}  # type: Dict[str, Dict[str, float]]
truth = ssgi.reference(ssgi.Scene(scene), size=(size, size), spp=spp, noise=0.02)
points = []  # (ms, relMSE, label)
for label, settings in configs.items():
    with ssgi.Renderer(ssgi.Scene(scene, {"cache": 0, **settings}), (size, size)) as renderer:
        renderer.render()  # the warm-up frame: shader variants compile
        times = [(renderer.render(), renderer.profile()["host_ms"])[1] for _ in range(3)]
        error = ssgi.compare(renderer.render(), truth, maps=False)["relmse"]
    points.append((statistics.median(times), error, label))
points.sort()  # cheapest first: a point is on the front when it beats every cheaper one
front = [p for i, p in enumerate(points) if all(p[1] < q[1] for q in points[:i])]
for ms, error, label in points:
    print(f"{'front' if (ms, error, label) in front else '':5} {ms:8.1f} ms {error:.5f} {label}")
plt.scatter([p[0] for p in points], [p[1] for p in points])
plt.plot([p[0] for p in front], [p[1] for p in front], "r-", label="Pareto front")
for i, (ms, error, label) in enumerate(points):  # labels above and below in turn
    plt.annotate(label, (ms, error), (4, 5 - 14 * (i % 2)), textcoords="offset points", fontsize=7)
plt.xlabel("frame time, ms (host clock)"), plt.ylabel("relMSE against the path tracer")
plt.yscale("log"), plt.legend(), plt.title(f"Cornell box {size}x{size}, cache off")
plt.savefig(chart, dpi=110, bbox_inches="tight"), print("wrote", chart)
