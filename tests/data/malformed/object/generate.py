#!/usr/bin/env python3
"""Writes the binary-object test files from the layout in formats/canonical/object.md,
independently of the Rust encoder, so the tests check the code against the documented
layout. Run from this directory: python3 generate.py"""
import struct

def obj(name=b"tri", source=b"hand-made (generate.py)", positions=None, facets=None,
        magic=b"IRSIGOBJ", version=1, counts=None, uvs=None):
    """uvs: None (no texture-coordinate section), or per facet None or three (u, v)."""
    positions = positions if positions is not None else [
        (0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 2.0)]
    facets = facets if facets is not None else [
        ((0, 1, 2), 1, 300.5), ((0, 3, 1), 2, None)]
    n_p, n_f = counts if counts else (len(positions), len(facets))
    flags = 0 if uvs is None else 1
    out = magic + struct.pack("<IIIIII", version, flags, len(name), len(source), n_p, n_f)
    out += name + source
    for p in positions:
        out += struct.pack("<3d", *p)
    for k, (v, m, t) in enumerate(facets):
        facet_flags = (0 if t is None else 1) | (2 if uvs is not None and uvs[k] else 0)
        out += struct.pack("<3IHHd", *v, m, facet_flags, 0.0 if t is None else t)
    for uv in uvs or []:
        out += struct.pack("<6d", *(c for corner in (uv or [(0.0, 0.0)] * 3) for c in corner))
    return out

good = obj()
open("../../object/tri.bin", "wb").write(good)
# The same triangles, the first with texture coordinates, the second without.
open("../../object/tri-uv.bin", "wb").write(
    obj(uvs=[[(0.0, 0.0), (1.0, 0.0), (0.0, 1.0)], None]))
open("truncated.bin", "wb").write(good[:-5])
open("wrong-magic.bin", "wb").write(obj(magic=b"IRSIGOBX"))
# The header claims 10^9 facets (24 GB) in a 200-byte file: must not allocate.
open("count-lies.bin", "wb").write(obj(counts=(4, 1_000_000_000)))
open("nan.bin", "wb").write(obj(positions=[
    (0.0, 0.0, 0.0), (1.0, float("nan"), 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 2.0)]))
open("index-out-of-range.bin", "wb").write(obj(facets=[((0, 1, 2), 1, None), ((0, 3, 4), 1, None)]))
