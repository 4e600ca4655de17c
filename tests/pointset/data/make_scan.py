#!/usr/bin/env python3
"""Writes torus_scan.xyz: a scan-like cloud of a torus (core radius 1, tube radius 0.35) with what
a scan brings: no normals, Gaussian noise (0.3 % of the bounding-box diagonal), a hole (the points
within 0.3 of a point on the outer equator removed) and 20 stray points. Seeded: the file is
reproducible. Used by pipelines/pointcloud_*.yaml and tests/pointset."""
import math
import random

R, r, N = 1.0, 0.35, 5000
random.seed(17)
diagonal = math.sqrt(2 * (2 * (R + r)) ** 2 + (2 * r) ** 2)
sigma = 0.003 * diagonal
hole = (R + r, 0.0, 0.0)
points = []
while len(points) < N:
    theta, phi = random.uniform(0, 2 * math.pi), random.uniform(0, 2 * math.pi)
    if random.uniform(0, R + r) > R + r * math.cos(phi):  # uniform in area
        continue
    p = ((R + r * math.cos(phi)) * math.cos(theta), (R + r * math.cos(phi)) * math.sin(theta), r * math.sin(phi))
    if math.dist(p, hole) < 0.3:
        continue
    points.append(tuple(c + random.gauss(0, sigma) for c in p))
for _ in range(20):
    points.append(tuple(random.uniform(-1.6, 1.6) for _ in range(2)) + (random.uniform(-0.8, 0.8),))
with open("torus_scan.xyz", "w") as out:
    out.write("# torus scan: no normals, noise 0.3 % of the diagonal, a hole, 20 stray points (make_scan.py)\n")
    for p in points:
        out.write("%.6f %.6f %.6f\n" % p)
