#!/usr/bin/env python3
"""Writes the thermal model's benchmark scene into the current directory: a UV sphere of
about N triangles (radius 10 m, centred 12 m up, a painted steel shell) over a 100 m x 100 m
ground of 2 m cells (asphalt over soil, 5,000 cells, 10,000 triangles), as a binary raw scene
(formats/canonical/raw-scene.md) `scene.raw`, and its material library `materials.ron`
with thermal records. N defaults to 1,000,000 (the tracer's benchmark sphere's size).

    python3 scripts/bench/therm-scene.py 1000000

scripts/bench/therm.sh runs irsig-therm on it for a day; BENCHMARKS.md gives the figures.
"""
import math, struct, sys

n = int(sys.argv[1]) if len(sys.argv) > 1 else 1_000_000
# rings x segments x 2 triangles: segments = 2 rings.
rings = max(3, round(math.sqrt(n / 4)))
segs = 2 * rings
P, F = [], []
def ring(i, j): return 1 + (i - 1) * segs + (j % segs)
P.append((0.0, 0.0, 22.0))
for i in range(1, rings):
    th = math.pi * i / rings
    for j in range(segs):
        ph = 2 * math.pi * j / segs
        P.append((10 * math.sin(th) * math.cos(ph), 10 * math.sin(th) * math.sin(ph), 12 + 10 * math.cos(th)))
P.append((0.0, 0.0, 2.0))
south = len(P) - 1
for j in range(segs):
    F.append((0, ring(1, j), ring(1, j + 1), 1))
for i in range(1, rings - 1):
    for j in range(segs):
        a, b, c, d = ring(i, j), ring(i + 1, j), ring(i + 1, j + 1), ring(i, j + 1)
        F += [(a, b, c, 1), (a, c, d, 1)]
for j in range(segs):
    F.append((south, ring(rings - 1, j + 1), ring(rings - 1, j), 1))
base = len(P)
cells = 50
for i in range(cells + 1):
    for j in range(cells + 1):
        P.append((-50.0 + 2.0 * j, -50.0 + 2.0 * i, 0.0))
def g(i, j): return base + i * (cells + 1) + j
for i in range(cells):
    for j in range(cells):
        F += [(g(i, j), g(i, j + 1), g(i + 1, j + 1), 2), (g(i, j), g(i + 1, j + 1), g(i + 1, j), 2)]
names = [b"sphere", b"ground"]
name_block = b"".join(struct.pack("<I", len(s)) + s for s in names)
with open("scene.raw", "wb") as f:
    f.write(b"IRSIGRAW" + struct.pack("<II", 1, 0) + struct.pack("<dd", 300.0, 1.0))
    f.write(struct.pack("<IIII", len(names), len(P), len(F), len(name_block)) + name_block)
    f.write(b"".join(struct.pack("<3d", *p) for p in P))
    f.write(b"".join(struct.pack("<3IHHId", a, b, c, m, 0, 0 if m == 1 else 1, 300.0) for a, b, c, m in F))
layer = "(thickness_m: {t}, conductivity_w_m_k: {k}, density_kg_m3: {r}, specific_heat_j_kg_k: {c}, source: \"{s}\")"
with open("materials.ron", "w") as f:
    f.write("""// The thermal benchmark's materials: values typical of the materials named, from
// Incropera & DeWitt, Fundamentals of Heat and Mass Transfer, 6th ed., Tables A.1 and A.3.
(materials: [
  (id: 1, name: "painted steel", emissivity: [(0.0, 0.9), (90.0, 0.9)], specular_fraction: 0.0,
   source: "benchmark", thermal: Some((layers: [%s], back: Convective(h_w_m2_k: 3.0, air: Outdoor),
   solar_absorptance: Some(0.6), thermal_emissivity: Some(0.9), source: "benchmark"))),
  (id: 2, name: "asphalt", emissivity: [(0.0, 0.95), (90.0, 0.95)], specular_fraction: 0.0,
   source: "benchmark", thermal: Some((layers: [%s, %s], back: Temperature(temperature_k: 290.0),
   solar_absorptance: Some(0.9), thermal_emissivity: Some(0.95), source: "benchmark"))),
])
""" % (layer.format(t=0.002, k=60.5, r=7854.0, c=434.0, s="plain carbon steel, Table A.1"),
       layer.format(t=0.1, k=0.062, r=2115.0, c=920.0, s="asphalt, Table A.3"),
       layer.format(t=1.0, k=0.52, r=2050.0, c=1840.0, s="soil, Table A.3")))
print(f"{len(F)} triangles ({len(F) - 2 * cells * cells} in the sphere), {len(P)} vertices")
