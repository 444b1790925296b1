#!/usr/bin/env python3
"""Writes pipelines/thermal/ground.ron: the quickstart's ground (a grass field, a pool, a
verge and a road at z = 0, x -120..120 m, y -40..200 m) with the part around the panel and
the car cut into 0.25 m cells, so that a facet's temperature (uniform over it) can show the
thermal shadows they cast; coarse rectangles tile the rest. Every facet faces up
(counter-clockwise seen from above). Materials: 1 grass, 2 water, 3 asphalt, as the
quickstart's ids. Standard library only:

    python3 pipelines/thermal/generate.py > pipelines/thermal/ground.ron

tests/tests/thermal.rs checks that the committed file is what this writes.
"""

# The scene library's ids (pipelines/materials/scene-library.ron).
GRASS, WATER, ROAD = 6, 1, 100
CELL = 0.25
# Around the panel (x -3..3, y 0..0.1) and the car (x 6..8, y 4..8.5), north of the pool,
# where the afternoon sun casts their shadows.
FINE = (-5.0, 10.0, -1.0, 11.0)
# The quickstart's seven rectangles: (x0, x1, y0, y1, material, what).
QUICKSTART = [
    (-120.0, -5.0, -40.0, 200.0, GRASS, "field, west of the pool"),
    (-5.0, 4.0, -40.0, -10.0, GRASS, "field, south of the pool"),
    (-5.0, 4.0, -10.0, -1.0, WATER, "the pool"),
    (-5.0, 4.0, -1.0, 200.0, GRASS, "field, north of the pool"),
    (4.0, 5.0, -40.0, 200.0, GRASS, "verge between the pool and the road"),
    (5.0, 9.0, -40.0, 200.0, ROAD, "the road"),
    (9.0, 120.0, -40.0, 200.0, GRASS, "field, east of the road"),
]


def material(x, y):
    """The quickstart's material at a point."""
    for x0, x1, y0, y1, m, _ in QUICKSTART:
        if x0 <= x < x1 and y0 <= y < y1:
            return m
    raise ValueError((x, y))


positions, facets = [], []


def rect(x0, x1, y0, y1, m, note=None):
    base = len(positions)
    positions.extend([(x0, y0), (x1, y0), (x1, y1), (x0, y1)])
    comment = f"  // {note}" if note else ""
    facets.append(f"(vertices: ({base}, {base + 1}, {base + 2}), material: {m}),{comment}")
    facets.append(f"(vertices: ({base}, {base + 2}, {base + 3}), material: {m}),")


# Each quickstart rectangle less the fine box: what lies south, north, west and east of it.
fx0, fx1, fy0, fy1 = FINE
for x0, x1, y0, y1, m, what in QUICKSTART:
    pieces = [
        (x0, x1, y0, min(y1, fy0)),
        (x0, x1, max(y0, fy1), y1),
        (x0, min(x1, fx0), max(y0, fy0), min(y1, fy1)),
        (max(x0, fx1), x1, max(y0, fy0), min(y1, fy1)),
    ]
    for a0, a1, b0, b1 in pieces:
        if a1 > a0 and b1 > b0:
            rect(a0, a1, b0, b1, m, what)
# The fine box, cell by cell, each cell's material taken at its centre.
nx = round((fx1 - fx0) / CELL)
ny = round((fy1 - fy0) / CELL)
for j in range(ny):
    for i in range(nx):
        xa, ya = fx0 + i * CELL, fy0 + j * CELL
        rect(xa, xa + CELL, ya, ya + CELL, material(xa + CELL / 2, ya + CELL / 2))

print(__doc__.split("\n\n")[0].replace('"""', "").replace("\n", "\n// ").join(["// ", ""]))
print("(")
print('  name: "ground",')
print('  source: "pipelines/thermal/generate.py (metres): the quickstart ground, cut finer around its objects",')
print("  positions_m: [")
for x, y in positions:
    print(f"    ({x!r}, {y!r}, 0.0),")
print("  ],")
print("  facets: [")
for f in facets:
    print(f"    {f}")
print("  ],")
print(")")
