#!/usr/bin/env python3
"""Writes the scene of scripts/bench/thrend.sh into the current directory, in irsig's input
and in ThRend's: a bumpy terrain of 2 x 707^2 = 999,698 triangles (800 m x 800 m, 708^2
vertices) and a 12-triangle box standing on it, seen by one pinhole camera.

  thrend-scene.py PIXELS

irsig: terrain.obj and box.obj (Wavefront OBJ, material names of materials.ron), scene.ron
(both placed as they are: terrain at 290 K, box at 330 K), materials.ron (soil: emissivity
0.95, 10 % specular, so every hit sends one mirror ray as the box's do; mirror: emissivity
0.3, all specular) and view.ron (LookAt).

ThRend: scene.inp (AVS UCD: nodes, triangle cells with a material id, one node datum, the
temperature in kelvin), settings (its view-settings keywords), materials, tsky (ten sky
temperatures, K) and colormap (256 grey levels): the same camera with one primary ray per
pixel (aa 1), one reflection ray per hit (reflSamples 1, which samples the mirror
direction, and MAX_BOUNCES 1), surface temperatures mapped to grey over 0-100 degC so the
terrain (16.85 degC) and the box (56.85 degC) are told apart in its real.png.

Both cameras: at (-300, 0, 40) m towards (150, 0, -40) m, 40 degree square field. ThRend's
`cameraUp` is given orthogonal to the view direction, since it spans its image plane with it.
"""
import math
import sys

pixels = int(sys.argv[1])
N, L = 707, 800.0  # cells per side, side in metres
T_TERRAIN, T_BOX = 290.0, 330.0
CAM, TARGET, FOV = (-300.0, 0.0, 40.0), (150.0, 0.0, -40.0), 40.0


def height(x, y):
    """Bumps of 1-6 m over a 5 m base, so the terrain stays above z = 0."""
    return 5.0 + 3.0 * math.sin(x / 23.0) * math.cos(y / 17.0) + 1.5 * math.sin((x + y) / 7.0)


step = L / N
verts = []
for i in range(N + 1):
    y = -L / 2 + i * step
    for j in range(N + 1):
        x = -L / 2 + j * step
        verts.append((x, y, height(x, y)))
tris = []
for i in range(N):
    for j in range(N):
        a = i * (N + 1) + j
        b, c, d = a + 1, a + N + 2, a + N + 1
        tris += [(a, b, c), (a, c, d)]  # counter-clockwise seen from above
assert len(tris) == 999_698

# The box: 40 x 40 x 30 m, its base at z = 0 (below the terrain), outward-facing triangles.
x0, x1, y0, y1, z0, z1 = 30.0, 70.0, -20.0, 20.0, 0.0, 30.0
box_v = [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0),
         (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)]
box_f = [(0, 2, 1), (0, 3, 2), (4, 5, 6), (4, 6, 7), (0, 1, 5), (0, 5, 4),
         (1, 2, 6), (1, 6, 5), (2, 3, 7), (2, 7, 6), (3, 0, 4), (3, 4, 7)]

with open("terrain.obj", "w") as f:
    f.write("o terrain\nusemtl soil\n")
    f.writelines("v %.4f %.4f %.4f\n" % v for v in verts)
    f.writelines("f %d %d %d\n" % (a + 1, b + 1, c + 1) for a, b, c in tris)
with open("box.obj", "w") as f:
    f.write("o box\nusemtl mirror\n")
    f.writelines("v %.4f %.4f %.4f\n" % v for v in box_v)
    f.writelines("f %d %d %d\n" % (a + 1, b + 1, c + 1) for a, b, c in box_f)
with open("scene.ron", "w") as f:
    f.write('(objects: [(object: "terrain.ron", temperature_k: Some(%.1f)),\n'
            '  (object: "box.ron", temperature_k: Some(%.1f))])\n' % (T_TERRAIN, T_BOX))
with open("materials.ron", "w") as f:
    f.write('(materials: [\n'
            '  (id: 1, name: "soil", emissivity: [(0.0, 0.95), (90.0, 0.95)], specular_fraction: 0.1,\n'
            '   source: "illustrative values for a benchmark"),\n'
            '  (id: 2, name: "mirror", emissivity: [(0.0, 0.3), (90.0, 0.3)], specular_fraction: 1.0,\n'
            '   source: "illustrative values for a benchmark"),\n'
            '])\n')
with open("view.ron", "w") as f:
    f.write("LookAt(position_m: (%.1f, %.1f, %.1f), target_m: (%.1f, %.1f, %.1f), "
            "pixels: (%d, %d), fov_deg: (%.1f, %.1f))\n" % (CAM + TARGET + (pixels, pixels, FOV, FOV)))

# ThRend: one node list (terrain, then box), cells numbered from 1, material ids 1 and 2.
nv = len(verts)
with open("scene.inp", "w") as f:
    f.write("%d %d 1 0 0\n" % (nv + len(box_v), len(tris) + len(box_f)))
    f.writelines("%d %.4f %.4f %.4f\n" % (k + 1, *v) for k, v in enumerate(verts + box_v))
    f.writelines("%d 1 tri %d %d %d\n" % (k + 1, a + 1, b + 1, c + 1) for k, (a, b, c) in enumerate(tris))
    f.writelines("%d 2 tri %d %d %d\n" % (len(tris) + k + 1, a + nv + 1, b + nv + 1, c + nv + 1)
                 for k, (a, b, c) in enumerate(box_f))
    f.write("1 1\ntemperature, K\n")
    f.writelines("%d %.2f\n" % (k + 1, T_TERRAIN) for k in range(nv))
    f.writelines("%d %.2f\n" % (nv + k + 1, T_BOX) for k in range(len(box_v)))
d = [t - c for t, c in zip(TARGET, CAM)]
n = math.sqrt(sum(x * x for x in d))
d = [x / n for x in d]
up = [-d[0] * d[2], -d[1] * d[2], 1.0 - d[2] * d[2]]  # z minus its part along d
n = math.sqrt(sum(x * x for x in up))
up = [x / n for x in up]
with open("settings", "w") as f:
    f.write("sceneFile scene.inp\nskyTempsFile tsky\ncolormapFile colormap\n"
            "cameraCenter %.6f %.6f %.6f\n" % CAM +
            "cameraDirection %.9f %.9f %.9f\n" % tuple(d) +
            "cameraUp %.9f %.9f %.9f\n" % tuple(up) +
            "fovVertical %.1f\nimageWidth %d\nimageHeight %d\n" % (FOV, pixels, pixels) +
            "aa 1\nreflSamples 1\nMAX_BOUNCES 1\n"
            "tmin 0\ntmax 100\ntmin_reflected 0\ntmax_reflected 100\n")
with open("materials", "w") as f:
    f.write("name soil\nUCD_id 1\nnormal_emissivity 0.95\ndiffuse_fraction 0.9\nroughness 0.01\n\n"
            "name mirror\nUCD_id 2\nnormal_emissivity 0.3\ndiffuse_fraction 0\nroughness 0.01\n")
with open("tsky", "w") as f:
    f.write("250 252 254 256 258 260 262 264 266 268\n")
with open("colormap", "w") as f:
    f.writelines("%.6f %.6f %.6f\n" % ((k / 255.0,) * 3) for k in range(256))
