"""Error against frame time on the Cornell box with the Pareto front, as in docs/bench.md: each
configuration renders with the cache off; its time is the median host clock of 3 frames after a
warm-up frame, its error the relMSE of its last frame against the path-traced reference.
usage: python3 examples/pareto_sweep.py [SIZE [SPP [CHART.png]]]  (256 4096 pareto.png)"""
import statistics
import sys

import matplotlib
import matplotlib.pyplot as plt
import ssgi

matplotlib.use("Agg")
size, spp, chart = (sys.argv[1:] + ["256", "4096", "pareto.png"][len(sys.argv) - 1:])[:3]
size, spp = int(size), int(spp)
configs = {"defaults": {}, "no AO": {"ao": 0}, "AO 4x2": {"ao_directions": 4, "ao_steps": 2},
           "horizon AO 8x4": {"ao_variant": 2}, "SSDO 16": {"ssdo": 1},
           "128 VPLs + vis.": {"indirect_vpls": 128}, "no indirect": {"indirect": 0},
           "512 VPLs + vis., thesis": {"indirect_method": 0, "indirect_vpls": 512},
           "PCF 9": dict(shadow_variant=0, shadow_taps=9), "direct only": dict(ao=0, indirect=0)}
truth = ssgi.reference(ssgi.Scene("scenes/cornell-box.json"), size=(size, size), spp=spp,
                       noise=0.02)
points = []  # (ms, relMSE, label)
for label, settings in configs.items():
    renderer = ssgi.Renderer(ssgi.Scene("scenes/cornell-box.json", {"cache": 0, **settings}),
                             size=(size, size))
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
[plt.annotate(label, (ms, error), fontsize=7) for ms, error, label in points]
plt.xlabel("frame time, ms (host clock)"), plt.ylabel("relMSE against the path tracer")
plt.yscale("log"), plt.legend(), plt.title(f"Cornell box {size}x{size}, cache off")
plt.savefig(chart, dpi=110, bbox_inches="tight"), print("wrote", chart)
