#!/usr/bin/env python3
"""Writes the 1,000,000-triangle UV sphere (500,002 vertices, r = 10 m) that BENCHMARKS.md
("import and flatten", through the tools) measures, as big.obj, big.glb and big.fac, plus
scene.ron placing it once, into the current directory. Then, with a release build:

  irsig-import big.obj --materials formats/canonical/samples/materials.ron \\
    | irsig-flatten scene.ron --object big.ron=- -o out.raw
"""
import json, math, struct

S, R, r = 1000, 501, 10.0
P = [(0.0, 0.0, r)]
for i in range(1, R):
    th = math.pi * i / R
    z, rr = r * math.cos(th), r * math.sin(th)
    for j in range(S):
        ph = 2 * math.pi * j / S
        P.append((round(rr * math.cos(ph), 6), round(rr * math.sin(ph), 6), round(z, 6)))
P.append((0.0, 0.0, -r))
def v(i, j): return 1 + (i - 1) * S + (j % S)
south = 1 + (R - 1) * S
F = [(0, v(1, j), v(1, j + 1)) for j in range(S)]
for i in range(1, R - 1):
    for j in range(S):
        a, b, c, d = v(i, j), v(i + 1, j), v(i + 1, j + 1), v(i, j + 1)
        F += [(a, b, c), (a, c, d)]
F += [(south, v(R - 1, j + 1), v(R - 1, j)) for j in range(S)]
assert len(F) == 1_000_000 and len(P) == 500_002

with open("big.obj", "w") as f:
    f.write("o sphere\nusemtl concrete\n")
    f.writelines(f"v {x:.6f} {y:.6f} {z:.6f}\n" for x, y, z in P)
    f.writelines(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in F)
with open("big.fac", "w") as f:
    f.write(f"{len(F)}\n")
    for t in F:
        f.write("1\n" + "".join("%.6f %.6f %.6f\n" % P[k] for k in t))
pos = b"".join(struct.pack("<3f", *p) for p in P)
idx = b"".join(struct.pack("<3I", *t) for t in F)
js = {"asset": {"version": "2.0"}, "buffers": [{"byteLength": len(pos) + len(idx)}],
      "bufferViews": [{"buffer": 0, "byteLength": len(pos)},
                      {"buffer": 0, "byteOffset": len(pos), "byteLength": len(idx)}],
      "accessors": [{"bufferView": 0, "componentType": 5126, "count": len(P), "type": "VEC3",
                     "min": [-10, -10, -10], "max": [10, 10, 10]},
                    {"bufferView": 1, "componentType": 5125, "count": 3 * len(F), "type": "SCALAR"}],
      "materials": [{"name": "concrete"}],
      "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": 0}]}],
      "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}], "scene": 0}
j = json.dumps(js).encode()
j += b" " * (-len(j) % 4)
body = pos + idx
with open("big.glb", "wb") as f:
    f.write(b"glTF" + struct.pack("<II", 2, 12 + 8 + len(j) + 8 + len(body)))
    f.write(struct.pack("<I", len(j)) + b"JSON" + j + struct.pack("<I", len(body)) + b"BIN\0" + body)
with open("scene.ron", "w") as f:
    f.write('(objects: [(object: "big.ron", rotation_deg: (10.0, 20.0, 30.0), '
            'translation_m: (100.0, 0.0, 5.0), temperature_k: Some(300.0))], '
            'terrain: (temperature_k: 286.0, emissivity: 1.0))\n')
