#!/usr/bin/env python3
"""Plot and table of the point-cloud robustness experiment (robustness.cpp; docs/pointclouds.md).

    plot_robustness.py robustness.csv docs/pointclouds_robustness.svg > table.md

One panel per method: the two-sided median distance to the clean mesh's result (% of the
diagonal) against the noise (% of the diagonal), one line per mesh and density; a hollow marker
where the topology (b0, b1) differs from the clean mesh's. Plain SVG (no plotting library).
"""
import csv
import sys

rows = [r for r in csv.DictReader(open(sys.argv[1])) if r["method"] != "all"]
methods = ["voronoi", "dey_zhao", "vmas"]
noises = [0.0, 0.1, 0.5, 1.0, 2.0]
series = sorted({(r["mesh"], r["points"]) for r in rows}, key=lambda s: (s[0], int(s[1])))
colours = ["#1b9e77", "#d95f02", "#7570b3", "#e7298a", "#66a61e", "#e6ab02"]
W, H, M = 300, 240, 45  # panel size and margin


def value(r):
    return float(r["median_pct"]) if r["status"] == "ok" else None


def same_topology(r):
    return r["status"] == "ok" and r["b0"] == r["ref_b0"] and r["b1"] == r["ref_b1"]


ymax = max(v for r in rows if (v := value(r)) is not None and r["hole"] == "0")
out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{3 * W + 160}" height="{H + 40}" font-family="sans-serif" font-size="11">']
for p, method in enumerate(methods):
    x0 = p * W
    out.append(f'<text x="{x0 + W / 2}" y="14" text-anchor="middle" font-size="13">{method}</text>')
    out.append(f'<line x1="{x0 + M}" y1="{H - M + 20}" x2="{x0 + W - 10}" y2="{H - M + 20}" stroke="black"/>')
    out.append(f'<line x1="{x0 + M}" y1="24" x2="{x0 + M}" y2="{H - M + 20}" stroke="black"/>')
    sx = lambda i: x0 + M + i * (W - M - 20) / (len(noises) - 1)
    sy = lambda v: H - M + 20 - v / ymax * (H - M - 4)
    for i, n in enumerate(noises):
        out.append(f'<text x="{sx(i)}" y="{H - M + 34}" text-anchor="middle">{n:g}</text>')
    for k in range(5):
        v = ymax * k / 4
        out.append(f'<text x="{x0 + M - 4}" y="{sy(v) + 4}" text-anchor="end">{v:.2g}</text>')
    out.append(f'<text x="{x0 + W / 2}" y="{H + 30}" text-anchor="middle">noise (% of diagonal)</text>')
    for s, (mesh, points) in enumerate(series):
        pts = []
        for i, n in enumerate(noises):
            match = [r for r in rows if r["method"] == method and r["mesh"] == mesh and r["points"] == points
                     and r["hole"] == "0" and abs(float(r["noise_pct"]) - n) < 1e-9]
            if match and value(match[0]) is not None:
                pts.append((sx(i), sy(value(match[0])), same_topology(match[0])))
        c = colours[s % len(colours)]
        if pts:
            out.append('<polyline fill="none" stroke="%s" points="%s"/>' % (c, " ".join(f"{x:.1f},{y:.1f}" for x, y, _ in pts)))
        for x, y, same in pts:
            out.append(f'<circle cx="{x:.1f}" cy="{y:.1f}" r="3" stroke="{c}" fill="{c if same else "white"}"/>')
out.append(f'<text x="10" y="{H / 2}" transform="rotate(-90 10 {H / 2})" text-anchor="middle">median distance (% of diagonal)</text>')
for s, (mesh, points) in enumerate(series):
    y = 40 + 16 * s
    out.append(f'<line x1="{3 * W + 10}" y1="{y}" x2="{3 * W + 30}" y2="{y}" stroke="{colours[s % len(colours)]}"/>')
    out.append(f'<text x="{3 * W + 34}" y="{y + 4}">{mesh} {points}</text>')
out.append(f'<text x="{3 * W + 10}" y="{40 + 16 * len(series) + 10}">hollow: topology differs</text>')
out.append("</svg>")
open(sys.argv[2], "w").write("\n".join(out) + "\n")

print("| mesh | points | corruption | method | vertices | b0, b1 (clean mesh) | median % | mean % | p95 % |")
print("|---|---:|---|---|---:|---|---:|---:|---:|")
for r in rows:
    corruption = "hole" if r["hole"] == "1" else ("none" if float(r["noise_pct"]) == 0 else f'noise {float(r["noise_pct"]):g} %')
    if r["status"] != "ok":
        print(f'| {r["mesh"]} | {r["points"]} | {corruption} | {r["method"]} | failed: {r["status"][8:]} | | | | |')
        continue
    topo = f'{r["b0"]}, {r["b1"]} ({r["ref_b0"]}, {r["ref_b1"]})'
    print(f'| {r["mesh"]} | {r["points"]} | {corruption} | {r["method"]} | {r["vertices"]} | {topo} | '
          f'{float(r["median_pct"]):.2f} | {float(r["chamfer_pct"]):.2f} | {float(r["p95_pct"]):.2f} |')
