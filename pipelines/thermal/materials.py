#!/usr/bin/env python3
"""Writes pipelines/thermal/materials.ron, the thermal pipeline's material library: the
scene library's grass, water and two painted steel car panels
(pipelines/materials/scene-library.ron, copied as they are, ids kept), and the daylight
pipeline's clay track (pipelines/daylight/materials.ron, its kaolinite spectrum over both
bands) with a thermal record, under id 100. The scene library has no soil or asphalt yet
(pipelines/materials/README.md says why); the clay track's 3-5 um emissivity is an opaque
mineral surface's and reads high for a grain layer (pipelines/daylight/README.md).
Standard library only:

    python3 pipelines/thermal/materials.py > pipelines/thermal/materials.ron

tests/tests/thermal.rs checks that the committed file is what this writes.
"""
import pathlib
import re

ROOT = pathlib.Path(__file__).resolve().parents[1]
SCENE = ["grass", "water", "steel (painted, white)", "steel (painted, black)"]
TRACK_ID = 100
# A dry, compacted clay track over the soil beneath it: Oke, Boundary Layer Climates, 2nd ed.
# (1987), Table 2.1 ("clay soil, dry": k 0.25 W/m/K, heat capacity 1.42 MJ/m3/K, density
# 1600 kg/m3) for the top 0.3 m, Incropera & DeWitt, 6th ed., Table A.3 ("soil": 0.52
# W/m/K, 2050 kg/m3, 1840 J/kg/K) below; Oke Table 1.1 gives dry clay an albedo of 0.20-0.35,
# so it absorbs 0.75 of the sunlight here; adiabatic 1.3 m down.
TRACK_THERMAL = """      thermal: Some((
        layers: [
          (thickness_m: 0.3, conductivity_w_m_k: 0.25, density_kg_m3: 1600.0, specific_heat_j_kg_k: 887.5, source: "dry clay soil: Oke, Boundary Layer Climates, 2nd ed. (1987), Table 2.1 (k 0.25 W/m/K, 1.42 MJ/m3/K, 1600 kg/m3)"),
          (thickness_m: 1.0, conductivity_w_m_k: 0.52, density_kg_m3: 2050.0, specific_heat_j_kg_k: 1840.0, source: "soil: Incropera & DeWitt, Fundamentals of Heat and Mass Transfer, 6th ed. (2007), Table A.3"),
        ],
        back: Adiabatic,
        solar_absorptance: Some(0.75),
        roughness: VeryRough,
        source: "a dry clay track: solar absorptance 0.75 from Oke (1987) Table 1.1's dry clay albedo, 0.20-0.35; dry (no evaporation); the broadband emissivity the angular table's hemispherical mean",
      )),
"""


def entries(path):
    """The library's entries as (name, text), each from its `    (` line to its `    ),`."""
    text = path.read_text()
    out = []
    for m in re.finditer(r"^    \(\n(.*?)^    \),\n", text, re.S | re.M):
        name = re.search(r'^      name: "(.*)",$', m.group(1), re.M).group(1)
        out.append((name, m.group(0)))
    return out


scene = dict(entries(ROOT / "materials/scene-library.ron"))
daylight = dict(entries(ROOT / "daylight/materials.ron"))
track = daylight["clay (kaolinite)"]
track = re.sub(r"^      id: \d+,$", f"      id: {TRACK_ID},", track, count=1, flags=re.M)
track = track.replace('      name: "clay (kaolinite)",', '      name: "clay track",')
track = track[: track.rindex("    ),\n")] + TRACK_THERMAL + "    ),\n"
print("// The thermal pipeline's materials, made by materials.py from the scene library and")
print("// the daylight pipeline's clay track: every one with a thermal record, over 3-14 um.")
print("(")
print("  materials: [")
for name in SCENE:
    print(scene[name], end="")
print(track, end="")
print("  ],")
print(")")
