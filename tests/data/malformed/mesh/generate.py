#!/usr/bin/env python3
"""Writes the generated malformed meshes of this folder and the manifest, cases.tsv.

The first rows of the manifest are the hand-made cases described in README.md; the rest
are written here, each a small valid model with one rule broken: OBJ, MTL (an OBJ beside
an MTL of the same stem, where the error lies), glTF and GLB. Run from anywhere:
python3 tests/data/malformed/mesh/generate.py
"""
import base64
import copy
import json
import os
import pathlib
import struct

HERE = pathlib.Path(__file__).resolve().parent
ARGS = "{in} --materials formats/canonical/samples/materials.ron -o {out}/object.bin"
# Zero-area triangles are dropped with a warning unless --strict.
STRICT = "{in} --strict --materials formats/canonical/samples/materials.ron -o {out}/object.bin"

HAND = [
    ("truncated.obj", "z coordinate"),
    ("number-garbled.obj", "`O`"),
    ("nan.obj", "finite"),
    ("inf.obj", "finite"),
    ("non-utf8.obj", "UTF-8"),
    ("empty.obj", "empty mesh"),
    ("degenerate.obj", "degenerate"),
    ("face-out-of-range.obj", "index 7"),
    ("texcoord-before-first.obj", "texture coordinate index -5"),
    ("short-normal.obj", "3 numbers after `vn`"),
    ("truncated.glb", "GLB"),
    ("short-header.glb", "12-byte header"),
    ("short-colour.obj", "three numbers"),
    ("garbled.glb", "GLB"),
    ("position-out-of-range.gltf", "Index out of bounds"),
    ("http-uri.glb", "never fetches"),
    ("unknown-material.obj", "unobtainium"),
]

TRI = "v 0 0 0\nv 1 0 0\nv 0 1 0\n"

# (file, content, fragment); content is str or bytes.
OBJ = [
    ("huge-index.obj", TRI + "f 1 2 99999999999999999999\n", "99999999999999999999"),
    ("negative-out-of-range.obj", TRI + "f -1 -2 -9\n", "vertex index -9"),
    ("zero-index.obj", TRI + "f 0 1 2\n", "vertex index 0"),
    ("face-garbled.obj", TRI + "f 1 2 three\n", "`three`"),
    ("normal-index-zero.obj", TRI + "vn 0 0 1\nf 1//0 2//1 3//1\n", "normal index 0"),
    ("mtllib-parent.obj", "mtllib ../outside.mtl\n" + TRI + "f 1 2 3\n", "`..`"),
    ("mtllib-absolute.obj", "mtllib /etc/passwd\n" + TRI + "f 1 2 3\n", "absolute"),
    ("mtllib-http.obj", "mtllib http://example.invalid/a.mtl\n" + TRI + "f 1 2 3\n", "never fetches"),
    ("usemtl-empty.obj", TRI + "usemtl\nf 1 2 3\n", "material name"),
    ("huge-coordinate.obj", "v 1e999 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "finite"),
    ("short-texcoord.obj", TRI + "vt 0.5\nf 1/1 2/1 3/1\n", "2 numbers after `vt`"),
    ("hex-number.obj", "v 0x10 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "`0x10`"),
    ("only-lines.obj", TRI + "f 1 2\nl 1 2 3\n", "empty mesh"),
    ("empty-file.obj", "", "empty mesh"),
    ("byte-order-mark.obj", "\ufeff" + TRI + "f 1 2 3\n", "does not exist"),
    ("face-before-vertices.obj", "f 1 2 3\n" + TRI, "0 vertices are defined"),
    ("texcoord-garbled.obj", TRI + "vt 0 0\nf 1/a 2/1 3/1\n", "`a`"),
    ("missing-z-crlf.obj", "v 0 0 0\r\nv 1 0\r\nv 0 1 0\r\nf 1 2 3\r\n", "z coordinate"),
]

MTL_OBJ = "mtllib {stem}.mtl\n" + TRI + "usemtl skin\nf 1 2 3\n"
MTL = [
    ("ka-letter", "newmtl skin\nKa 0.1 x 0.3\n", "`x`"),
    ("ks-nan", "newmtl skin\nKs 1 NaN 1\n", "finite"),
    ("ke-inf", "newmtl skin\nKe 0 0 inf\n", "finite"),
    ("kd-huge", "newmtl skin\nKd 1e999 0 0\n", "finite"),
    ("kd-alone", "newmtl skin\nKd\n", "three numbers"),
    ("kd-one", "newmtl skin\nKd 0.5\n", "three numbers"),
    ("ns-missing", "newmtl skin\nNs\n", "a number"),
    ("ns-garbled", "newmtl skin\nNs ten\n", "`ten`"),
    ("ni-comma", "newmtl skin\nNi 1,5\n", "`1,5`"),
    ("d-garbled", "newmtl skin\nd half\n", "`half`"),
    ("d-missing", "newmtl skin\nd\n", "a number"),
    ("illum-float", "newmtl skin\nillum 2.5\n", "0 to 255"),
    ("illum-negative", "newmtl skin\nillum -1\n", "0 to 255"),
    ("illum-huge", "newmtl skin\nillum 300\n", "0 to 255"),
    ("illum-missing", "newmtl skin\nillum\n", "illumination model"),
    ("newmtl-empty", "newmtl\nKd 1 1 1\n", "material name"),
    ("map-kd-empty", "newmtl skin\nmap_Kd   \n", "texture file name"),
    ("bump-empty", "newmtl skin\nbump\n", "texture file name"),
    ("map-d-empty", "newmtl skin\nmap_d\n", "texture file name"),
    ("non-utf8", b"newmtl sk\xefn\nKd 1 1 1\n", "UTF-8"),
]


def f32s(values):
    return b"".join(struct.pack("<f", v) for v in values)


POSITIONS = f32s([0, 0, 0, 1, 0, 0, 0, 1, 0])


def triangle(indices=bytes([0, 1, 2]), positions=POSITIONS):
    """A valid one-triangle glTF (as a dict) and its buffer: positions then u8 indices."""
    data = positions + indices
    doc = {
        "asset": {"version": "2.0"},
        "buffers": [{"byteLength": len(data)}],
        "bufferViews": [
            {"buffer": 0, "byteLength": len(positions)},
            {"buffer": 0, "byteOffset": len(positions), "byteLength": len(indices)},
        ],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": len(positions) // 12,
             "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
            {"bufferView": 1, "componentType": 5121, "count": len(indices), "type": "SCALAR"},
        ],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
        "nodes": [{"mesh": 0}],
        "scenes": [{"nodes": [0]}],
        "scene": 0,
    }
    return doc, data


def data_uri(data):
    return "data:application/octet-stream;base64," + base64.b64encode(data).decode()


def gltf_text(doc, data):
    doc = copy.deepcopy(doc)
    doc["buffers"][0].setdefault("uri", data_uri(data))
    return json.dumps(doc, indent=2) + "\n"


def glb(doc, data, bin_extra=b""):
    j = json.dumps(doc).encode()
    j += b" " * (-len(j) % 4)
    body = data + bin_extra
    body += b"\0" * (-len(body) % 4)
    chunks = struct.pack("<I", len(j)) + b"JSON" + j
    if body:
        chunks += struct.pack("<I", len(body)) + b"BIN\0" + body
    return b"glTF" + struct.pack("<II", 2, 12 + len(chunks)) + chunks


def edit(change, indices=bytes([0, 1, 2]), positions=POSITIONS):
    doc, data = triangle(indices, positions)
    change(doc)
    return doc, data


def set_path(path, value):
    def change(doc):
        node = doc
        for k in path[:-1]:
            node = node[k]
        node[path[-1]] = value
    return change


def sparse(doc):
    doc["accessors"][0]["sparse"] = {
        "count": 1,
        "indices": {"bufferView": 1, "componentType": 5121},
        "values": {"bufferView": 0},
    }


NAN_POSITIONS = f32s([0, 0, 0, 1, float("nan"), 0, 0, 1, 0])

# Both glTF and GLB: (name, doc and data, fragment).
COMMON = [
    ("asset-version-1", edit(set_path(["asset", "version"], "1.0")), "asset.version"),
    ("index-count-4", edit(lambda d: None, indices=bytes([0, 1, 2, 0])), "multiple of 3"),
    ("index-past-vertices", edit(lambda d: None, indices=bytes([0, 1, 7])), "index 2 is 7"),
    ("view-past-buffer", edit(set_path(["bufferViews", 1, "byteLength"], 9)), "bufferViews[1].byteLength"),
    ("accessor-past-view", edit(set_path(["accessors", 0, "count"], 4)), "accessors[0].count"),
    ("sparse", edit(sparse), "sparse"),
    ("position-u16", edit(set_path(["accessors", 0, "componentType"], 5123)), "componentType"),
    ("position-vec2", edit(set_path(["accessors", 0, "type"], "VEC2")), "VEC3"),
    ("indices-float", edit(set_path(["accessors", 1, "componentType"], 5126)), "u8, u16 or u32"),
    ("nan-position", edit(lambda d: None, positions=NAN_POSITIONS), "finite"),
    ("no-position", edit(set_path(["meshes", 0, "primitives", 0, "attributes"], {"NORMAL": 0})), "POSITION"),
    ("empty-mesh", edit(set_path(["meshes", 0, "primitives", 0, "mode"], 1)), "empty mesh"),
    ("stride-short", edit(set_path(["bufferViews", 0, "byteStride"], 4)), "byte stride 4"),
    ("node-cycle", edit(set_path(["nodes", 0, "children"], [0])), "nodes[0]"),
    ("min-version", edit(set_path(["asset", "minVersion"], "2.1")), "asset.minVersion"),
    ("uri-parent", edit(set_path(["buffers", 0, "uri"], "../outside.bin")), "`..`"),
    ("uri-absolute", edit(set_path(["buffers", 0, "uri"], "/etc/passwd")), "absolute"),
    ("uri-missing-file", edit(set_path(["buffers", 0, "uri"], "no-such-buffer.bin")), "cannot read"),
    ("bad-base64", edit(set_path(["buffers", 0, "uri"], "data:application/octet-stream;base64,@@@")), "base64"),
    ("data-uri-not-base64", edit(set_path(["buffers", 0, "uri"], "data:text/plain,abc")), "base64"),
    ("position-accessor-missing", edit(set_path(["meshes", 0, "primitives", 0, "attributes", "POSITION"], 9)), "Index out of bounds"),
]


def gltf_cases():
    cases = []
    for name, (doc, data), frag in COMMON:
        cases.append((name + ".gltf", gltf_text(doc, data), frag))
    doc, data = triangle()
    text = gltf_text(doc, data)
    cases += [
        ("buffer-bytelength-short.gltf",
         gltf_text(*edit(set_path(["buffers", 0, "byteLength"], 36))), "buffers[0].byteLength"),
        ("buffer-bytelength-long.gltf",
         gltf_text(*edit(set_path(["buffers", 0, "byteLength"], 45))), "buffers[0].byteLength"),
        ("syntax-trailing-comma.gltf", text.replace('"scene": 0', '"scene": 0,'), "malformed glTF JSON"),
        ("truncated.gltf", text[: len(text) // 2], "malformed glTF JSON"),
        ("non-utf8.gltf", text.replace('"2.0"', '"2.\udcff"').encode("utf-8", "surrogateescape"), "UTF-8"),
        ("huge-number.gltf", text.replace('"count": 3', '"count": ' + "9" * 400), "malformed glTF JSON"),
        ("count-wrong-type.gltf", text.replace('"count": 3', '"count": "three"'), "malformed glTF JSON"),
        ("symlink-out.gltf", gltf_text(*edit(set_path(["buffers", 0, "uri"], "symlink-out.bin"))), "symbolic link"),
    ]
    return cases


def glb_cases():
    cases = []
    for name, (doc, data), frag in COMMON:
        if "uri" not in doc["buffers"][0]:
            cases.append((name + ".glb", glb(doc, data), frag))
        else:
            cases.append((name + ".glb", glb(doc, b""), frag))
    doc, data = triangle()
    good = glb(doc, data)
    json_len = struct.unpack("<I", good[12:16])[0]
    bin_at = 20 + json_len
    cases += [
        ("length-short.glb", good + b"\0" * 8, "the file has"),
        ("length-long.glb", good[:8] + struct.pack("<I", len(good) + 8) + good[12:], "the file has"),
        ("container-version-1.glb", good[:4] + struct.pack("<I", 1) + good[8:], "version 2"),
        ("first-chunk-not-json.glb", good[:16] + b"JSOX" + good[20:], "`JSON`"),
        ("json-chunk-too-long.glb", good[:12] + struct.pack("<I", json_len + 1000) + good[16:], "JSON chunk states"),
        ("second-chunk-not-bin.glb", good[: bin_at + 4] + b"BIX\0" + good[bin_at + 8:], "`BIN`"),
        ("bin-chunk-too-long.glb", good[:bin_at] + struct.pack("<I", 1000) + good[bin_at + 4:], "BIN chunk states"),
        ("bin-missing.glb", glb(doc, b""), "BIN chunk, but there is none"),
        ("bin-short.glb", glb(*edit(set_path(["buffers", 0, "byteLength"], 48))), "buffers[0].byteLength"),
        ("bin-long.glb", glb(doc, data, bin_extra=b"\0" * 8), "buffers[0].byteLength"),
        ("json-syntax.glb", glb_raw_json(b'{"asset": {"version": "2.0"},, }', data), "malformed glTF JSON"),
        ("json-not-utf8.glb", glb_raw_json(b'{"asset": {"version": "2.\xff"}}', data), "malformed glTF JSON"),
    ]
    return cases


def glb_raw_json(j, data):
    j += b" " * (-len(j) % 4)
    body = data + b"\0" * (-len(data) % 4)
    chunks = struct.pack("<I", len(j)) + b"JSON" + j + struct.pack("<I", len(body)) + b"BIN\0" + body
    return b"glTF" + struct.pack("<II", 2, 12 + len(chunks)) + chunks


def write(name, content):
    path = HERE / name
    if isinstance(content, str):
        content = content.encode("utf-8", "surrogateescape")
    path.write_bytes(content)


def main():
    rows = [(f, frag) for f, frag in HAND]
    args = {"degenerate.obj": STRICT}
    for name, content, frag in OBJ:
        write(name, content)
        rows.append((name, frag))
    for stem, mtl, frag in MTL:
        name = f"mtl-{stem}"
        write(name + ".obj", MTL_OBJ.format(stem=name))
        write(name + ".mtl", mtl)
        rows.append((name + ".obj", frag))
    # A link inside the folder that leads out of it (to the repository's README).
    write("mtl-symlink-out.obj", MTL_OBJ.format(stem="mtl-symlink-out"))
    rows.append(("mtl-symlink-out.obj", "symbolic link"))
    for link in ["mtl-symlink-out.mtl", "symlink-out.bin"]:
        if os.path.lexists(HERE / link):
            os.remove(HERE / link)
        os.symlink("../../../../README.md", HERE / link)
    for name, content, frag in gltf_cases() + glb_cases():
        write(name, content)
        rows.append((name, frag))
    with open(HERE / "cases.tsv", "w") as f:
        f.write("# file\ttool\targuments ({in}: the case, {out}: an empty folder)\tmessage fragment\n")
        f.write("# written by generate.py: hand-made cases first (README.md), then generated ones\n")
        for name, frag in rows:
            f.write(f"{name}\tirsig-import\t{args.get(name, ARGS)}\t{frag}\n")
    for ext in ["obj", "mtl", "gltf", "glb"]:
        n = sum(1 for name, _ in rows if name.endswith("." + ext) and not name.startswith("mtl-"))
        if ext == "mtl":
            n = sum(1 for name, _ in rows if name.startswith("mtl-")) + 1  # + short-colour
        print(ext, n)


main()
