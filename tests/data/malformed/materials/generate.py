#!/usr/bin/env python3
"""Writes the malformed material libraries of this folder and their manifest, cases.tsv.

Each case is the sample library (formats/canonical/samples/materials.ron) with one edit:
(name, text to replace, replacement, a fragment the error message must hold). Run from
anywhere: python3 tests/data/malformed/materials/generate.py
"""
import pathlib

HERE = pathlib.Path(__file__).resolve().parent
SAMPLE = (HERE / "../../../../formats/canonical/samples/materials.ron").resolve().read_text()

# The sample's skin, and the same with a spectral curve (a valid one; the cases break it).
SKIN = """      name: "skin",
      emissivity: [(0.0, 0.98), (90.0, 0.0)],
      specular_fraction: 0.0,"""
SKIN_SPECTRAL = """      name: "skin",
      emissivity: [(0.0, 0.98), (90.0, 0.0)],
      specular_fraction: 0.0,
      spectral: Some((wavelength_um: [8.0, 14.0], emissivity: [0.97, 0.98], angular: None)),"""

CASES = [
    ("emissivity-above-one", "(40.0, 0.95)", "(40.0, 1.3)", "out of range"),
    ("emissivity-negative", "(60.0, 0.93)", "(60.0, -0.1)", "out of range"),
    ("emissivity-nan", "(60.0, 0.93)", "(60.0, NaN)", "emissivity"),
    ("angle-above-90", "(80.0, 0.8)", "(91.0, 0.8)", "angle"),
    ("angles-not-increasing", "(60.0, 0.28)", "(0.0, 0.28)", "increas"),
    ("specular-above-one", "specular_fraction: 1.0", "specular_fraction: 1.5", "out of range"),
    ("specular-inf", "specular_fraction: 1.0", "specular_fraction: inf", "specular_fraction"),
    ("id-zero", "id: 2,", "id: 0,", "id"),
    ("id-duplicate", "id: 3,", "id: 2,", "id"),
    ("id-too-large", "id: 3,", "id: 70000,", "70000"),
    ("id-negative", "id: 3,", "id: -3,", "id"),
    ("name-duplicate", 'name: "skin"', 'name: "steel"', "steel"),
    ("angle-negative", "(0.0, 0.3)", "(-10.0, 0.3)", "angle"),
    ("unknown-field", "specular_fraction: 0.0,\n      source: \"illustrative values for the sample; not a measurement\",\n    ),\n  ],",
     "specular_fraction: 0.0,\n      colour: 3,\n      source: \"illustrative values for the sample; not a measurement\",\n    ),\n  ],", "colour"),
    ("misspelt-field", "specular_fraction: 0.0,\n      source", "specular_fractoin: 0.0,\n      source", "specular_fractoin"),
    ("missing-field", "      specular_fraction: 1.0,\n", "", "specular_fraction"),
    ("wrong-type", "id: 1,", 'id: "one",', "id"),
    ("unclosed-string", 'name: "steel"', 'name: "steel', "string"),
    ("unclosed-list", "  ],\n)", "\n)", ""),
    ("truncated", "    (\n      id: 3,", "    (\n      id: ", ""),
    ("empty-emissivity", "[(0.0, 0.98), (90.0, 0.0)]", "[]", "emissivity"),
    ("specular-negative", "specular_fraction: 1.0", "specular_fraction: -0.5", "out of range"),
    ("trailing-garbage", "  ],\n)", "  ],\n) )", ""),
    # Spectral materials (the page's `.spectral` rules): skin given a curve.
    ("spectral-one-sample", SKIN, SKIN_SPECTRAL.replace("[8.0, 14.0]", "[8.0]").replace("[0.97, 0.98]", "[0.97]"), "at least two"),
    ("spectral-not-increasing", SKIN, SKIN_SPECTRAL.replace("[8.0, 14.0]", "[14.0, 8.0]"), "increas"),
    ("spectral-above-one", SKIN, SKIN_SPECTRAL.replace("[0.97, 0.98]", "[0.97, 1.2]"), "out of range"),
    ("spectral-wavelength-nan", SKIN, SKIN_SPECTRAL.replace("[8.0, 14.0]", "[8.0, NaN]"), "wavelength"),
    ("spectral-shape-zero-at-normal", SKIN, SKIN_SPECTRAL.replace("emissivity: [(0.0, 0.98), (90.0, 0.0)]", "emissivity: [(0.0, 0.0), (90.0, 0.0)]"), "0°"),
    ("spectral-grid-short", SKIN, SKIN_SPECTRAL.replace("angular: None", "angular: Some((angle_deg: [0.0, 90.0], emissivity: [[0.97, 0.0]]))"), "emissivity"),
    ("spectral-grid-angles-falling", SKIN, SKIN_SPECTRAL.replace("angular: None", "angular: Some((angle_deg: [90.0, 0.0], emissivity: [[0.0, 0.97], [0.0, 0.98]]))"), "increas"),
    ("non-utf8", "illustrative values for the sample; not a measurement\",\n    ),\n  ],",
     "illustrative values for the sample; not a measurement\xff\",\n    ),\n  ],", "UTF-8"),
]


def main():
    lines = [
        "# file\ttool\targuments ({in}: the case, {out}: an empty folder)\tmessage fragment",
    ]
    args = "formats/canonical/samples/scene.ron --materials {in} -o {out}/scene.raw"
    for name, old, new, fragment in CASES:
        assert old in SAMPLE, name
        text = SAMPLE.replace(old, new, 1)
        data = text.encode("latin-1") if name == "non-utf8" else text.encode()
        (HERE / f"{name}.ron").write_bytes(data)
        lines.append(f"{name}.ron\tirsig-flatten\t{args}\t{fragment}")
    (HERE / "cases.tsv").write_text("\n".join(lines) + "\n")


main()
