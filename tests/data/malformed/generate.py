#!/usr/bin/env python3
"""Writes the malformed cases of the text formats, one folder per format, each with its
manifest (cases.tsv, run by tests/tests/malformed_corpus.rs) and a README listing what
each case breaks. (materials/ and mesh/ have their own generators or hand-written files.)

Each case is (file name, contents, message fragment, what is wrong), optionally followed
by its own arguments (None: the folder's) and its expected outcome (`1`, the default: an
error at a line and column; `2`: bad usage; `0`: success, within the time and memory
bounds; `stderr-closed`: exit 1 with the reader of stderr gone). Contents are text
(written as UTF-8) or bytes (written as they are). Run from anywhere:
python3 tests/data/malformed/generate.py
"""
import pathlib
import shutil

HERE = pathlib.Path(__file__).resolve().parent
ROOT = (HERE / "../../..").resolve()
SAMPLES = ROOT / "formats"
MATERIALS = "formats/canonical/samples/materials.ron"
BASE = "tests/data/malformed/base"


def sample(rel):
    return (SAMPLES / rel).read_text()


FOLDERS = []


def folder(name, title, tool, args, cases, extra=None):
    """Registers a folder: its cases run as `tool args` ({in}: the case, {out}: an empty
    folder); `extra` maps helper file names (not cases) to their contents."""
    FOLDERS.append((name, title, tool, args, cases, extra or {}))


def edit(base, old, new):
    assert old in base, (old, base[:200])
    return base.replace(old, new, 1)


# ---------------------------------------------------------------- legacy facet file
FAC = """2
1
0 0 0
1 0 0
0 1 0

2 300.5
0 0 1
1 0 1
0 1 1
"""
folder(
    "legacy-object",
    "Malformed legacy facet files (formats/legacy/object.md), read by `irsig-import`.",
    "irsig-import",
    "{in} --unit km --materials " + MATERIALS + " -o {out}/object.ron",
    [
        ("empty.fac", "", "number of facets", "an empty file"),
        ("blank.fac", "\n\n  \n", "number of facets", "only blank lines"),
        ("count-word.fac", edit(FAC, "2\n1\n", "two\n1\n"), "number of facets", "the count is a word"),
        ("count-negative.fac", edit(FAC, "2\n1\n", "-2\n1\n"), "number of facets", "a negative count"),
        ("count-zero.fac", "0\n", "at least 1", "a count of 0"),
        ("count-huge.fac", edit(FAC, "2\n1\n", "99999999999999999999999\n1\n"), "number of facets", "a count past 64 bits"),
        ("count-too-high.fac", edit(FAC, "2\n1\n", "3\n1\n"), "facet 3 of the 3", "3 facets declared, 2 given"),
        ("count-too-low.fac", edit(FAC, "2\n1\n", "1\n1\n"), "1 facet", "1 facet declared, 2 given"),
        ("count-real.fac", edit(FAC, "2\n1\n", "2.5\n1\n"), "", "a count of 2.5"),
        ("truncated-vertex.fac", FAC[: FAC.rindex("1 1")] + "1", "", "ends inside a vertex"),
        ("nan.fac", edit(FAC, "1 0 0\n", "1 NaN 0\n"), "number", "a NaN coordinate"),
        ("inf.fac", edit(FAC, "1 0 0\n", "inf 0 0\n"), "number", "an infinite coordinate"),
        ("overflow.fac", edit(FAC, "1 0 0\n", "1e400 0 0\n"), "", "a coordinate past the largest f64"),
        ("decimal-comma.fac", edit(FAC, "1 0 0\n", "1,5 0 0\n"), "", "a decimal comma"),
        ("hex.fac", edit(FAC, "1 0 0\n", "0x1 0 0\n"), "", "a hexadecimal number"),
        ("material-zero.fac", edit(FAC, "2\n1\n", "2\n0\n"), "material", "material index 0 (nothing hit)"),
        ("material-huge.fac", edit(FAC, "2\n1\n", "2\n70000\n"), "70000", "material index past 65535"),
        ("material-unknown.fac", edit(FAC, "2\n1\n", "2\n9\n"), "9", "material index not in the library"),
        ("temperature-negative.fac", edit(FAC, "2 300.5", "2 -3"), "temperature", "a negative temperature"),
        ("temperature-zero.fac", edit(FAC, "2 300.5", "2 0"), "temperature", "a temperature of 0 K"),
        ("extra-value.fac", edit(FAC, "1 0 0\n", "1 0 0 7\n"), "", "four values on a vertex line"),
        ("non-utf8.fac", edit(FAC, "2\n1\n", "2\n1 # caf\xe9\n").encode("latin-1"), "UTF-8", "a Latin-1 byte in a comment"),
        ("quad-bent.fac", edit(FAC, "1 0 0\n0 1 0\n\n", "1 0 0\n1 1 0\n0 1 0.5\n\n"), "planar", "a 4-vertex facet (irsig extension) bent: its fourth vertex 0.5 off the plane"),
        ("quad-dart.fac", edit(FAC, "1 0 0\n0 1 0\n\n", "3 1 0\n0 2 0\n1 1 0\n\n"), "convex", "a 4-vertex facet with a reflex corner (a dart)"),
        ("quad-bow-tie.fac", edit(FAC, "1 0 0\n0 1 0\n\n", "2 1 0\n2 0 0\n0 2 0\n\n"), "convex", "a 4-vertex facet whose edges cross (a bow-tie)"),
        ("quad-truncated.fac", edit(FAC, "1 0 0\n0 1 0\n\n", "1 0 0\n1 1 0\n0.5 1.0\n\n"), "vertex 4 of facet 1", "a fourth vertex line with two numbers"),
        ("all-degenerate.fac", edit(edit(FAC, "0 1 0\n\n", "2 0 0\n\n"), "0 1 1\n", "2 0 1\n"), "", "every triangle has zero area: nothing is left"),
    ],
)


# ---------------------------------------------------------------- legacy scene file
SCN = "good.fac\n0 0 0\n0 0 0\n1 1 1\n293.15\n"
folder(
    "legacy-scene",
    "Malformed legacy scene files (formats/legacy/scene.md), read by `irsig-flatten`; "
    "`good.fac` is a valid object they name.",
    "irsig-flatten",
    "{in} --unit km --materials " + MATERIALS + " -o {out}/scene.raw",
    [
        ("empty.scn", "", "object", "an empty file"),
        ("comment-only.scn", "# nothing\n", "object", "only a comment"),
        ("missing-object.scn", edit(SCN, "good.fac", "absent.fac"), "absent.fac", "names an object file that does not exist"),
        ("parent-path.scn", edit(SCN, "good.fac", "../legacy-object/good.fac"), "..", "an object path above the scene's folder"),
        ("absolute-path.scn", edit(SCN, "good.fac", "/nonexistent/good.fac"), "/nonexistent/good.fac", "an absolute object path to nowhere"),
        ("device.scn", edit(SCN, "good.fac", "/dev/zero"), "/dev/zero", "a device as the object"),
        ("directory.scn", edit(SCN, "good.fac", "."), "", "a directory as the object"),
        ("truncated.scn", "good.fac\n0 0 0\n0 0\n", "", "ends after eight of the nine values"),
        ("name-only.scn", "good.fac\n", "", "a name and no values"),
        ("nan.scn", edit(SCN, "0 0 0\n0 0 0", "0 NaN 0\n0 0 0"), "", "a NaN rotation"),
        ("inf.scn", edit(SCN, "0 0 0\n0 0 0", "0 0 0\n0 0 inf"), "", "an infinite translation"),
        ("overflow.scn", edit(SCN, "0 0 0\n0 0 0", "0 0 0\n1e999 0 0"), "", "a translation past the largest f64"),
        ("zero-scale.scn", edit(SCN, "1 1 1", "1 0 1"), "scale", "a zero scale"),
        ("temperature-negative.scn", edit(SCN, "293.15", "-10"), "temperature", "a negative temperature"),
        ("temperature-zero.scn", edit(SCN, "293.15", "0"), "temperature", "a temperature of 0 K"),
        ("two-temperatures.scn", edit(SCN, "293.15\n", "293.15\n294\n"), "", "two temperature lines"),
        ("numeric-name.scn", edit(SCN, "good.fac", "42"), "", "an object name that is a number"),
        ("non-utf8.scn", edit(SCN, "good.fac", "g\xf6od.fac").encode("latin-1"), "UTF-8", "a Latin-1 byte in the name"),
        ("bad-object.scn", edit(SCN, "good.fac", "bad-object.fac"), "nan", "names an object file, `bad-object.fac`, that is malformed (NaN): the error is in that file"),
        ("hex.scn", edit(SCN, "1 1 1", "0x1 1 1"), "", "a hexadecimal scale"),
        ("extra-value.scn", edit(SCN, "293.15\n", "293.15 7\n"), "", "an eleventh value"),
    ],
    extra={
        "good.fac": FAC,
        "bad-object.fac": edit(FAC, "1 0 0\n", "1 nan 0\n"),
    },
)


# ---------------------------------------------------------------- legacy viewing file
VIEW = "0.01 0.0 0.05\n4 4\n0 0 0\n10 10\n2.0\n"
TRACE = "--scene " + BASE + "/scene.raw.ron --materials " + MATERIALS
folder(
    "legacy-view",
    "Malformed 1990 viewing files (formats/legacy/view.md), read by `irsig-trace --view`.",
    "irsig-trace",
    TRACE + " --view {in} --radiance-exr {out}/r.exr --truth-exr {out}/t.exr",
    [
        ("truncated.view", "0.01 0.0 0.05\n4 4\n0 0", "", "ends inside the rotations"),
        ("position-only.view", "0.01 0.0 0.05\n", "", "only the position"),
        ("nan.view", edit(VIEW, "0.01 0.0", "NaN 0.0"), "", "a NaN position"),
        ("inf.view", edit(VIEW, "0 0 0", "0 inf 0"), "", "an infinite rotation"),
        ("zero-pixels.view", edit(VIEW, "4 4", "0 4"), "pixel", "zero columns"),
        ("negative-pixels.view", edit(VIEW, "4 4", "-4 4"), "", "negative columns"),
        ("real-pixels.view", edit(VIEW, "4 4", "4.5 4"), "", "a fractional pixel count"),
        ("huge-pixels.view", edit(VIEW, "4 4", "100000 100000"), "pixels", "10^10 pixels, past the image budget"),
        ("u32-max-pixels.view", edit(VIEW, "4 4", "4294967295 4294967295"), "pixels", "4294967295 × 4294967295 pixels"),
        ("pixels-past-u64.view", edit(VIEW, "4 4", "99999999999999999999999 4"), "", "a pixel count past 64 bits"),
        ("zero-fov.view", edit(VIEW, "10 10", "0 10"), "field of view", "a zero field of view"),
        ("fov-180.view", edit(VIEW, "10 10", "10 180"), "field of view", "a 180° field of view"),
        ("fov-negative.view", edit(VIEW, "10 10", "-10 10"), "field of view", "a negative field of view"),
        ("gain-zero.view", edit(VIEW, "2.0", "0"), "gain", "a gain of 0 DC/K"),
        ("gain-negative.view", edit(VIEW, "2.0", "-2"), "gain", "a negative gain"),
        ("extra-value.view", edit(VIEW, "2.0\n", "2.0 7\n"), "", "a sixth line's worth of values"),
        ("word.view", edit(VIEW, "0 0 0", "0 zero 0"), "", "a word for a rotation"),
        ("non-utf8.view", edit(VIEW, "2.0\n", "2.0 # \xb0\n").encode("latin-1"), "UTF-8", "a Latin-1 degree sign"),
        ("empty.view", "", "", "an empty file"),
        ("decimal-comma.view", edit(VIEW, "2.0", "2,0"), "", "a decimal comma"),
        ("overflow.view", edit(VIEW, "0.01 0.0", "1e400 0.0"), "", "a position past the largest f64"),
    ],
)


# ---------------------------------------------------------------- legacy execute file
EXEC = "good.view\ntwo-patches.scn\nframe1.map\nframe1.img\nframe1.lut\n"
folder(
    "legacy-execute",
    "Malformed 1990 execute files (formats/legacy/execute.md), run by `irsig-trace "
    "--execute`; `good.view` is a valid viewing file they name, `bad.view` a broken one. "
    "The outputs an execute file names are relative to it, so a case that wrongly "
    "succeeded would write into this folder: the test checks that it stays as it is.",
    "irsig-trace",
    TRACE + " --execute {in}",
    [
        ("empty.exec", "", "", "an empty file"),
        ("four-names.exec", "good.view\ntwo-patches.scn\nframe1.map\nframe1.img\n", "LUT", "a frame without its LUT"),
        ("second-incomplete.exec", EXEC + "\ngood.view two-patches.scn f2.map\n", "", "a second frame of three names"),
        ("missing-view.exec", edit(EXEC, "good.view", "absent.view"), "absent.view", "a viewing file that does not exist"),
        ("bad-view.exec", edit(EXEC, "good.view", "bad-view.view"), "field of view", "a malformed viewing file (`bad-view.view`, zero field of view): the error is in that file"),
        ("view-as-lut.exec", edit(EXEC, "frame1.lut", "good.view"), "good.view", "its viewing file named as the LUT output: would overwrite its own input"),
        ("view-as-map.exec", edit(EXEC, "frame1.map", "good.view"), "good.view", "its viewing file named as the map output"),
        ("absolute-output.exec", edit(EXEC, "frame1.img", "/tmp/irsig-frame1.img"), "/tmp/irsig-frame1.img", "an absolute output path"),
        ("parent-output.exec", edit(EXEC, "frame1.img", "../frame1.img"), "..", "an output path above the execute file's folder"),
        ("parent-view.exec", edit(EXEC, "good.view", "../legacy-view/zero-fov.view"), "..", "a viewing file above the execute file's folder"),
        ("absolute-view.exec", edit(EXEC, "good.view", "/etc/hostname"), "/etc/hostname", "an absolute viewing file path"),
        ("duplicate-output.exec", edit(EXEC, "frame1.img", "frame1.map"), "frame1.map", "two outputs of one frame share a name"),
        ("duplicate-across-frames.exec", EXEC + "\ngood.view two-patches.scn frame2.map frame1.img frame2.lut\n", "frame1.img", "frame 2 writes frame 1's image"),
        ("two-scenes.exec", EXEC + "\ngood.view other.scn frame2.map frame2.img frame2.lut\n", "other.scn", "frames name different scene files"),
        ("device-view.exec", edit(EXEC, "good.view", "/dev/zero"), "/dev/zero", "a device as the viewing file"),
        ("directory-output.exec", edit(EXEC, "frame1.img", "."), "", "the folder itself as an output"),
        ("non-utf8.exec", edit(EXEC, "frame1.img", "fr\xe4me1.img").encode("latin-1"), "UTF-8", "a Latin-1 byte in a name"),
        ("view-is-directory.exec", edit(EXEC, "good.view", "subdir-that-is-absent/"), "", "a viewing file name ending in /"),
        ("output-into-missing-dir.exec", edit(EXEC, "frame1.img", "absent/frame1.img"), "", "an output in a folder that does not exist"),
        ("second-frame-bad-view.exec", EXEC + "\nsecond-frame-bad-view.view two-patches.scn frame2.map frame2.img frame2.lut\n", "field of view", "frame 2's viewing file (`second-frame-bad-view.view`) is malformed: frame 1 must not be written either"),
        ("scene-as-output.exec", edit(EXEC, "frame1.map", "two-patches.scn"), "two-patches.scn", "the scene file named as the map output"),
    ],
    extra={
        "good.view": VIEW,
        "bad-view.view": edit(VIEW, "10 10", "0 10"),
        "second-frame-bad-view.view": edit(VIEW, "10 10", "0 10"),
    },
)


# ---------------------------------------------------------------- legacy material index
MAT = "3\n1 concrete good.ems 0\n2 steel good.ems 1\n3 skin\n"
EMS = "0 0.95\n45 0.94\n90 0\n"
folder(
    "legacy-material-index",
    "Malformed material index files (formats/legacy/material-index.md), read by "
    "`irsig-material convert`; `good.ems` is a valid table they name, `bad.ems` a broken one.",
    "irsig-material",
    "convert {in} --default-emissivity 0.9 -o {out}/lib.ron",
    [
        ("empty.mat", "", "", "an empty file"),
        ("count-mismatch.mat", edit(MAT, "3\n", "4\n"), "", "4 declared, 3 given"),
        ("count-huge.mat", edit(MAT, "3\n", "18446744073709551617\n"), "", "a count past 64 bits"),
        ("index-zero.mat", edit(MAT, "1 concrete", "0 concrete"), "", "index 0 (nothing hit)"),
        ("index-huge.mat", edit(MAT, "3 skin", "65536 skin"), "65536", "index past 65535"),
        ("index-negative.mat", edit(MAT, "3 skin", "-3 skin"), "", "a negative index"),
        ("index-real.mat", edit(MAT, "3 skin", "3.5 skin"), "", "a fractional index"),
        ("index-duplicate.mat", edit(MAT, "3 skin", "2 skin"), "2", "index 2 twice"),
        ("name-duplicate.mat", edit(MAT, "3 skin", "3 steel"), "steel", "name steel twice"),
        ("name-numeric.mat", edit(MAT, "3 skin", "3 42"), "", "a name that is a number"),
        ("missing-name.mat", edit(MAT, "3 skin", "3"), "", "an index and no name"),
        ("flag-two.mat", edit(MAT, "good.ems 1", "good.ems 2"), "", "specular flag 2"),
        ("flag-word.mat", edit(MAT, "good.ems 1", "good.ems yes"), "", "specular flag `yes`"),
        ("extra-value.mat", edit(MAT, "good.ems 1", "good.ems 1 7"), "", "a fifth value"),
        ("missing-ems.mat", edit(MAT, "good.ems 0", "absent.ems 0"), "absent.ems", "an .ems file that does not exist"),
        ("bad-ems.mat", edit(MAT, "good.ems 0", "bad-ems.ems 0"), "1.3", "an .ems table (`bad-ems.ems`) with emissivity 1.3: the error is in that file"),
        ("parent-ems.mat", edit(MAT, "good.ems 0", "../absent/parent-ems.ems 0"), "..", "an .ems path above the index's folder, to nowhere"),
        ("absolute-ems.mat", edit(MAT, "good.ems 0", "/nonexistent/good.ems 0"), "/nonexistent/good.ems", "an absolute .ems path to nowhere"),
        ("device-ems.mat", edit(MAT, "good.ems 0", "/dev/zero 0"), "/dev/zero", "a device as the .ems"),
        ("non-utf8.mat", edit(MAT, "3 skin", "3 sk\xefn").encode("latin-1"), "UTF-8", "a Latin-1 byte in a name"),
        ("specular-without-ems.mat", edit(MAT, "3 skin", "3 skin 1"), "", "a specular flag where the .ems name belongs"),
    ],
    extra={"good.ems": EMS, "bad-ems.ems": edit(EMS, "45 0.94", "45 1.3")},
)


# ---------------------------------------------------------------- DIRTRAN tables
ATM = "0.050 287.825 0.050 0.964055 1.519176e-04\n0.100 287.500 0.100 0.945967 2.282051e-04\n0.200 286.850 0.200 0.920004 3.371063e-04\n"
DWR = "0 1.166214e-03\n45 1.378463e-03\n90 4.394162e-03\n-1 1.513059e-03\n"
COR = "1.10293990 -0.11240644 0.00703145\n"
RTT = "200 6.01175039861e-04\n201 6.20761893613e-04\n202 6.40799679463e-04\n"
RSD = "0.000 1013.25 15.00 5.00\n0.500 954.61 11.75 5.00\n1.000 898.76 8.50 5.00\n"
CONVERT = "convert --altitude-unit km --radiance-unit W/cm2/sr --name case -o {out}/a.ron"
D = BASE


def table_cases(ext, base, first_value, row_values):
    """Cases every table shares: (name, contents, fragment, what)."""
    first_line = next(l for l in base.splitlines() if not l.startswith("#"))
    return [
        (f"empty.{ext}", "", "", "an empty file"),
        (f"blank.{ext}", "\n \n\t\n", "", "blank lines only"),
        (f"non-utf8.{ext}", (base + "# \xb5m\n").encode("latin-1"), "UTF-8", "a Latin-1 µ in a comment"),
        (f"nan.{ext}", edit(base, first_value, "NaN"), "", "NaN"),
        (f"inf.{ext}", edit(base, first_value, "inf"), "", "infinity"),
        (f"overflow.{ext}", edit(base, first_value, "1e999"), "", "a literal past the largest f64"),
        (f"word.{ext}", edit(base, first_value, "abc"), "", "a word for a number"),
        (f"decimal-comma.{ext}", edit(base, first_value, first_value.replace(".", ",") if "." in first_value else first_value + ",5"), "", "a decimal comma"),
        (f"hex.{ext}", edit(base, first_value, "0x10"), "", "a hexadecimal number"),
        (f"short-row.{ext}", edit(base, first_line, " ".join(first_line.split()[:-1])), "", "a row one value short"),
        (f"long-row.{ext}", edit(base, first_line, first_line + " 1"), "", "a row with one value too many"),
        (f"truncated.{ext}", base[: base.rindex(" ") + 1], "", "cut inside the last row"),
    ] + row_values


LEGACY_EMS_CASES = table_cases("ems", EMS, "0.94", [
    ("angle-above-90.ems", edit(EMS, "90 0", "95 0"), "", "an angle of 95°"),
    ("angle-negative.ems", edit(EMS, "0 0.95", "-5 0.95"), "", "an angle of −5°"),
    ("angle-falling.ems", edit(EMS, "45 0.94", "0 0.94"), "", "angles repeated"),
    ("emissivity-above-one.ems", edit(EMS, "45 0.94", "45 1.3"), "", "an emissivity of 1.3"),
    ("emissivity-negative.ems", edit(EMS, "45 0.94", "45 -0.1"), "", "a negative emissivity"),
])
folder(
    "legacy-ems",
    "Malformed `.ems` angular emissivity tables (formats/legacy/ems.md), read by "
    "`irsig-material convert` through `NAME.mat`, a valid material index beside each case "
    "naming it.",
    "irsig-material",
    "",
    [
        (name, contents, fragment, what, f"convert tests/data/malformed/legacy-ems/{name[:-4]}.mat -o {{out}}/lib.ron")
        for name, contents, fragment, what in LEGACY_EMS_CASES
    ],
    extra={name[:-4] + ".mat": f"1\n1 concrete {name} 0\n" for name, *_ in LEGACY_EMS_CASES},
)


folder(
    "dirtran-atm",
    "Malformed `.atm` tables (formats/legacy/atm.md), read by `irsig-atmos convert --atm`.",
    "irsig-atmos",
    CONVERT + " --atm {in} --dwr " + D + "/good.dwr",
    table_cases("atm", ATM, "0.050", [
        ("altitude-repeated.atm", edit(ATM, "0.100 287.500 0.100", "0.050 287.500 0.050"), "", "an altitude repeated"),
        ("altitude-decreasing.atm", edit(ATM, "0.200 286.850 0.200", "0.070 286.850 0.070"), "", "altitudes falling"),
        ("transmission-above-one.atm", edit(ATM, "0.945967", "1.2"), "", "τ = 1.2"),
        ("transmission-negative.atm", edit(ATM, "0.945967", "-0.1"), "", "τ < 0"),
        ("radiance-negative.atm", edit(ATM, "2.282051e-04", "-2e-4"), "", "a negative path radiance"),
        ("temperature-zero.atm", edit(ATM, "287.500", "0"), "", "T = 0 K"),
        ("temperature-negative.atm", edit(ATM, "287.500", "-5"), "", "T < 0 K"),
        ("ground-altitude-negative.atm", edit(ATM, "0.050 287.825 0.050", "0.050 287.825 -0.050"), "", "a negative altitude above the ground"),
        ("ground-altitude-repeated.atm", edit(ATM, "0.100 287.500 0.100", "0.100 287.500 0.050"), "above ground", "the altitude above the ground (column 3) repeated, while column 1 increases"),
    ]),
)
folder(
    "dirtran-dwr",
    "Malformed `.dwr` tables (formats/legacy/dwr.md), read by `irsig-atmos convert --dwr`.",
    "irsig-atmos",
    CONVERT + " --atm " + D + "/good.atm --dwr {in}",
    table_cases("dwr", DWR, "1.166214e-03", [
        ("angle-above-90.dwr", edit(DWR, "90 4.39", "95 4.39"), "", "a zenith angle of 95°"),
        ("angle-negative.dwr", edit(DWR, "0 1.16", "-5 1.16"), "", "a zenith angle of −5° (not the −1 row)"),
        ("angle-repeated.dwr", edit(DWR, "45 1.37", "0 1.37"), "", "an angle repeated"),
        ("angle-decreasing.dwr", edit(DWR, "45 1.37", "95 1.37"), "", "angles not increasing"),
        ("radiance-negative.dwr", edit(DWR, "1.378463e-03", "-1e-3"), "", "a negative sky radiance"),
        ("hemi-not-last.dwr", "0 1.166214e-03\n-1 1.513059e-03\n45 1.378463e-03\n90 4.394162e-03\n", "", "the hemispheric row before the last"),
        ("hemi-twice.dwr", DWR + "-1 1.5e-03\n", "", "two hemispheric rows"),
        ("hemi-only.dwr", "-1 1.513059e-03\n", "", "only the hemispheric row"),
    ]),
)
folder(
    "dirtran-cor",
    "Malformed `.cor` files (formats/legacy/cor.md), read by `irsig-atmos convert --cor`.",
    "irsig-atmos",
    CONVERT + " --atm " + D + "/good.atm --dwr " + D + "/good.dwr --cor {in}",
    table_cases("cor", COR, "1.10293990", [
        ("two-rows.cor", COR + COR, "", "the coefficients twice"),
        ("one-value.cor", "1.1\n", "", "one coefficient of three"),
        ("four-on-two-lines.cor", "1.1 -0.1\n0.007 5\n", "", "four values over two lines"),
        ("nan-last.cor", edit(COR, "0.00703145", "nan"), "", "a NaN a3"),
        ("inf-middle.cor", edit(COR, "-0.11240644", "-inf"), "", "an infinite a2"),
        ("two-points.cor", edit(COR, "1.10293990", "1.1.0"), "", "`1.1.0`"),
        ("letter-suffix.cor", edit(COR, "1.10293990", "1.10293990d0"), "", "a Fortran `d0` exponent"),
        ("plus-minus.cor", edit(COR, "1.10293990", "+-1.1"), "", "`+-1.1`"),
    ]),
)
folder(
    "dirtran-rtt",
    "Malformed `.rtt` tables (formats/legacy/rtt.md), read by `irsig-atmos convert --rtt`.",
    "irsig-atmos",
    CONVERT + " --atm " + D + "/good.atm --dwr " + D + "/good.dwr --rtt {in}",
    table_cases("rtt", RTT, "6.01175039861e-04", [
        ("temperature-repeated.rtt", edit(RTT, "201 6.2", "200 6.2"), "", "a temperature repeated"),
        ("temperature-decreasing.rtt", edit(RTT, "202 6.4", "199 6.4"), "", "temperatures falling"),
        ("temperature-zero.rtt", edit(RTT, "200 6.0", "0 6.0"), "", "T = 0 K"),
        ("temperature-negative.rtt", edit(RTT, "200 6.0", "-200 6.0"), "", "T < 0 K"),
        ("radiance-decreasing.rtt", edit(RTT, "6.40799679463e-04", "5e-04"), "", "radiance falling as T rises"),
        ("radiance-negative.rtt", edit(RTT, "6.01175039861e-04", "-6e-04"), "", "a negative radiance"),
        ("temperature-minus-zero.rtt", edit(RTT, "200 6.0", "-0 6.0"), "", "T = −0 K"),
        ("bom-inside.rtt", edit(RTT, "201 6.2", "\ufeff201 6.2"), "", "a byte-order mark at the start of the second line"),
    ]),
)
folder(
    "dirtran-rsd",
    "Malformed `.rsd` radiosondes (formats/legacy/rsd.md), read by `irsig-atmos convert --rsd`.",
    "irsig-atmos",
    CONVERT + " --atm " + D + "/good.atm --dwr " + D + "/good.dwr --rsd {in}",
    table_cases("rsd", RSD, "954.61", [
        ("altitude-repeated.rsd", edit(RSD, "0.500 954", "0.000 954"), "", "an altitude repeated"),
        ("altitude-decreasing.rsd", edit(RSD, "1.000 898", "0.200 898"), "", "altitudes falling"),
        ("pressure-zero.rsd", edit(RSD, "954.61", "0"), "", "p = 0 hPa"),
        ("temperature-absolute-zero.rsd", edit(RSD, "11.75", "-273.15"), "", "T = −273.15 °C exactly"),
        ("temperature-below-zero-k.rsd", edit(RSD, "11.75", "-300"), "", "T below −273.15 °C"),
        ("dewpoint-negative.rsd", edit(RSD, "11.75 5.00", "11.75 -5.00"), "", "a negative dew-point depression"),
        ("pressure-negative.rsd", edit(RSD, "954.61", "-954.61"), "", "a negative pressure"),
        ("altitude-inf.rsd", edit(RSD, "1.000 898", "inf 898"), "", "an infinite altitude"),
        ("dewpoint-below-zero-k.rsd", edit(RSD, "11.75 5.00", "11.75 300.00"), "absolute zero", "a depression of 300 °C at 11.75 °C: a dew point below 0 K (finding 13 of the third hardening pass)"),
    ]),
)



# ---------------------------------------------------------------- canonical RON forms
def ron_cases(base, unknown, numeric, lst, far=False):
    """Cases every canonical RON file shares. `unknown` is (old, new) adding an unknown
    field, `numeric` a number of the base to break, `lst` an opening `[` of a list to nest
    without end; `far` adds a 70 kB one-line file with an error past column 65,535."""
    one_line = " ".join(l.split("//")[0].strip() for l in base.splitlines())
    cases = [
        ("empty.ron", "", "", "an empty file"),
        ("non-utf8.ron", ("// caf\xe9\n" + base).encode("latin-1"), "UTF-8", "a Latin-1 byte in a comment"),
        ("truncated.ron", base[: len(base) // 2], "", "cut in the middle"),
        ("trailing-garbage.ron", base + ")\n", "", "a `)` after the value"),
        ("unknown-field.ron", edit(base, *unknown), "", "an unknown field"),
        ("nan.ron", edit(base, numeric, "NaN"), "", "NaN for a number"),
        ("inf.ron", edit(base, numeric, "inf"), "", "infinity for a number"),
        ("string-for-number.ron", edit(base, numeric, '"1.0"'), "", "a string for a number"),
        ("deep-nesting.ron", edit(base, lst, "[" * 1000), "", "1,000 nested lists where one value belongs (past the RON reader's recursion limit where the type allows nesting)"),
        ("wrong-root.ron", "[1, 2, 3]\n", "", "a list where a struct belongs"),
    ]
    if far:
        cases.append(("far-column.ron", edit(one_line, numeric, " " * 70000 + "oops"), "", "an error at column 70,000 of a one-line file"))
    return cases


OBJ = """(
  name: "tri",
  source: "hand-written",
  positions_m: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0)],
  facets: [(vertices: (0, 1, 2), material: 1, temperature_k: Some(300.0))],
)
"""
SCENE = """(
  objects: [
    (
      object: "tri.ron",
      rotation_deg: (0.0, 0.0, 90.0),
      translation_m: (10.0, 0.0, 0.0),
      scale: (1.0, 1.0, 1.0),
      temperature_k: Some(300.0),
      overrides: [(select: Range(first: 0, last: 0), temperature_k: Some(320.0))],
    ),
  ],
  terrain: (temperature_k: 286.0, emissivity: 1.0),
)
"""
folder(
    "canonical-scene",
    "Malformed canonical scenes (formats/canonical/scene.md), read by `irsig-flatten`; "
    "`tri.ron` is a valid object they place.",
    "irsig-flatten",
    "{in} --materials " + MATERIALS + " -o {out}/scene.raw",
    ron_cases(SCENE, ("      scale:", "      colour: 3,\n      scale:"), "10.0", "[\n    (", far=True)
    + [
        ("no-objects.ron", edit(SCENE, SCENE[SCENE.index("[") : SCENE.rindex("]") + 1], "[]"), "", "no placement"),
        ("missing-object.ron", edit(SCENE, "tri.ron", "absent.ron"), "absent.ron", "an object file that does not exist"),
        ("parent-object.ron", edit(SCENE, "tri.ron", "../canonical-object/good.ron"), "..", "an object path above the scene's folder"),
        ("absolute-object.ron", edit(SCENE, "tri.ron", "/nonexistent/tri.ron"), "/nonexistent/tri.ron", "an absolute object path to nowhere"),
        ("device-object.ron", edit(SCENE, "tri.ron", "/dev/zero"), "/dev/zero", "a device as the object"),
        ("directory-object.ron", edit(SCENE, "tri.ron", "."), "", "the folder as the object"),
        ("zero-scale.ron", edit(SCENE, "(1.0, 1.0, 1.0)", "(1.0, 0.0, 1.0)"), "scale", "a zero scale"),
        ("terrain-emissivity.ron", edit(SCENE, "emissivity: 1.0", "emissivity: 1.5"), "emissivity", "terrain emissivity 1.5"),
        ("terrain-temperature.ron", edit(SCENE, "temperature_k: 286.0", "temperature_k: -1.0"), "temperature", "terrain at −1 K"),
        ("range-past-end.ron", edit(SCENE, "last: 0", "last: 7"), "", "an override range past the object's facets"),
        ("range-reversed.ron", edit(edit(SCENE, "first: 0", "first: 1"), "last: 0", "last: 0"), "", "an override range whose first is after its last"),
        ("override-material-zero.ron", edit(SCENE, "temperature_k: Some(320.0))", "material: Some(0))"), "", "an override to material 0"),
        ("override-material-unknown.ron", edit(SCENE, "temperature_k: Some(320.0))", "material: Some(77))"), "77", "an override to a material not in the library"),
        ("rotation-two-values.ron", edit(SCENE, "(0.0, 0.0, 90.0)", "(0.0, 90.0)"), "", "a rotation of two values"),
        ("translation-huge.ron", edit(SCENE, "(10.0, 0.0, 0.0)", "(1e300, 0.0, 0.0)"), "", "a translation of 10^300 m"),
        ("bad-object.ron", edit(SCENE, "tri.ron", "objects/bad-object.ron"), "out of range", "places an object (`objects/bad-object.ron`) whose index is out of range: the error is in that file"),
    ],
    extra={"tri.ron": OBJ, "objects/bad-object.ron": edit(OBJ, "(0, 1, 2)", "(0, 1, 3)")},
)
folder(
    "canonical-object",
    "Malformed canonical objects (formats/canonical/object.md), read by `irsig-flatten "
    "--object`: `base/scene.ron` places `tri.ron`, taken from the case.",
    "irsig-flatten",
    BASE + "/scene.ron --object tri.ron={in} --materials " + MATERIALS + " -o {out}/scene.raw",
    ron_cases(OBJ, ("  source:", "  colour: 3,\n  source:"), "1.0, 0.0, 0.0", "[(0.0")
    + [
        ("no-facets.ron", edit(OBJ, "[(vertices: (0, 1, 2), material: 1, temperature_k: Some(300.0))]", "[]"), "", "no facet"),
        ("index-out-of-range.ron", edit(OBJ, "(0, 1, 2)", "(0, 1, 3)"), "", "a vertex index past the positions"),
        ("index-negative.ron", edit(OBJ, "(0, 1, 2)", "(0, -1, 2)"), "", "a negative vertex index"),
        ("index-huge.ron", edit(OBJ, "(0, 1, 2)", "(0, 1, 4294967296)"), "", "a vertex index past u32"),
        ("degenerate.ron", edit(OBJ, "(0.0, 1.0, 0.0)", "(2.0, 0.0, 0.0)"), "", "collinear vertices"),
        ("material-zero.ron", edit(OBJ, "material: 1", "material: 0"), "", "material 0"),
        ("material-huge.ron", edit(OBJ, "material: 1", "material: 65536"), "", "material past u16"),
        ("temperature-negative.ron", edit(OBJ, "Some(300.0)", "Some(-1.0)"), "", "a negative temperature"),
        ("coordinate-huge.ron", edit(OBJ, "1.0, 0.0, 0.0", "1e300, 0.0, 0.0"), "", "a coordinate of 10^300 m"),
        ("two-coordinates.ron", edit(OBJ, "(1.0, 0.0, 0.0)", "(1.0, 0.0)"), "", "a position of two numbers"),
        ("missing-name.ron", edit(OBJ, '  name: "tri",\n', ""), "name", "no name"),
    ],
)



VIEWS = """[
  LookAt(
    position_m: (0.0, 0.0, 50.0),
    target_m: (0.0, 0.0, 0.0),
    up: (0.0, 1.0, 0.0),
    pixels: (4, 4),
    fov_deg: (10.0, 10.0),
    gain_dc_per_k: Some(2.0),
  ),
  Legacy(
    position_m: (0.0, 0.0, 50.0),
    pixels: (4, 4),
    omega_phi_kappa_deg: (0.0, 0.0, 0.0),
    fov_deg: (10.0, 10.0),
  ),
]
"""
folder(
    "views",
    "Malformed canonical views (formats/canonical/view.md), read by `irsig-trace --view`.",
    "irsig-trace",
    TRACE + " --view {in} -o {out}/f",
    [c for c in ron_cases(VIEWS, ("    fov_deg: (10.0, 10.0),\n    gain", "    fov_deg: (10.0, 10.0),\n    colour: 3,\n    gain"), "50.0", "[\n  LookAt", far=True) if c[0] != "wrong-root.ron"]
    + [
        ("empty-list.ron", "[]\n", "", "a list of no views"),
        ("misspelt-gain.ron", edit(VIEWS, "gain_dc_per_k", "gain_dc_per_kk"), "gain_dc_per_kk", "`gain_dc_per_kk` for `gain_dc_per_k`"),
        ("misspelt-up.ron", edit(VIEWS, "up:", "upp:"), "upp", "`upp` for `up`"),
        ("unknown-in-legacy.ron", edit(VIEWS, "    omega_phi_kappa_deg", "    roll_deg: 3.0,\n    omega_phi_kappa_deg"), "roll_deg", "an unknown field in `Legacy(…)`"),
        ("unknown-variant.ron", edit(VIEWS, "Legacy(", "Orbit("), "Orbit", "a view kind that does not exist"),
        ("zero-pixels.ron", edit(VIEWS, "pixels: (4, 4)", "pixels: (0, 4)"), "pixel", "zero columns"),
        ("huge-pixels.ron", edit(VIEWS, "pixels: (4, 4)", "pixels: (100000, 100000)"), "pixels", "10^10 pixels, past the image budget"),
        ("u32-max-pixels.ron", edit(VIEWS, "pixels: (4, 4)", "pixels: (4294967295, 4294967295)"), "pixels", "4294967295 × 4294967295 pixels"),
        ("pixels-past-u32.ron", edit(VIEWS, "pixels: (4, 4)", "pixels: (4294967296, 4)"), "", "a pixel count past u32"),
        ("fov-180.ron", edit(VIEWS, "fov_deg: (10.0, 10.0)", "fov_deg: (180.0, 10.0)"), "fov", "a 180° field of view"),
        ("fov-zero.ron", edit(VIEWS, "fov_deg: (10.0, 10.0)", "fov_deg: (10.0, 0.0)"), "fov", "a zero field of view"),
        ("up-parallel.ron", edit(VIEWS, "up: (0.0, 1.0, 0.0)", "up: (0.0, 0.0, 1.0)"), "up", "`up` along the view direction"),
        ("target-is-position.ron", edit(VIEWS, "target_m: (0.0, 0.0, 0.0)", "target_m: (0.0, 0.0, 50.0)"), "target", "the target at the camera"),
        ("gain-zero.ron", edit(VIEWS, "Some(2.0)", "Some(0.0)"), "gain", "a gain of 0"),
        ("gain-negative.ron", edit(VIEWS, "Some(2.0)", "Some(-2.0)"), "gain", "a negative gain"),
        ("position-huge.ron", edit(VIEWS, "(0.0, 0.0, 50.0),\n    target", "(1e300, 0.0, 50.0),\n    target"), "", "a camera 10^300 m away"),
        ("missing-pixels.ron", edit(VIEWS, "    pixels: (4, 4),\n    fov_deg: (10.0, 10.0),\n    gain", "    fov_deg: (10.0, 10.0),\n    gain"), "pixels", "no `pixels`"),
        ("many-views-one-bad.ron", VIEWS.replace("]\n", "  " + "LookAt(position_m: (0.0, 0.0, 50.0), target_m: (0.0, 0.0, 0.0), up: (0.0, 1.0, 0.0), pixels: (4, 4), fov_deg: (10.0, 10.0)),\n  " * 3 + "LookAt(position_m: (0.0, 0.0, 50.0), target_m: (0.0, 0.0, 0.0), up: (0.0, 1.0, 0.0), pixels: (4, 4), fov_deg: (10.0, -1.0)),\n]\n"), "fov", "the sixth view of six has a negative field of view: no frame may be written"),
    ],
)

ATMOS = sample("canonical/samples/atmosphere.ron")
ATMOS_TAIL = "  band_radiance: [(200.0, 6.0), (201.0, 6.2)],\n"
ATMOS_RADIOSONDE = ATMOS_TAIL + """  radiosonde: [
    (altitude_m: 0.0, pressure_hpa: 1013.0, temperature_k: 288.0, dew_point_depression_k: 5.0),
    (altitude_m: 500.0, pressure_hpa: 955.0, temperature_k: 285.0, dew_point_depression_k: 5.0),
  ],
"""
ATMOS_SLANT = ATMOS_TAIL + """  slant: Some((
    altitude_m: [2.0, 1000.0],
    nadir_deg: [0.0, 60.0],
    ground_m: Some(1.0),
    transmission: [[0.95, 0.9], [0.8, 0.7]],
    path_radiance_w_m2_sr: [[0.5, 1.0], [5.0, 7.0]],
    sky_altitude_m: [0.0, 1000.0],
    sky_zenith_deg: [0.0, 90.0],
    sky_radiance_w_m2_sr: [[10.0, 40.0], [8.0, 38.0]],
  )),
"""
folder(
    "atmosphere",
    "Malformed canonical atmospheres (formats/canonical/atmosphere.md), read by "
    "`irsig-trace --atmosphere`.",
    "irsig-trace",
    TRACE + " --view " + BASE + "/view.ron --atmosphere {in} --atmosphere-model thesis -o {out}/f",
    ron_cases(ATMOS, ("  band_um:", "  colour: 3,\n  band_um:"), "287.8", "[\n    (altitude")
    + [
        ("band-reversed.ron", edit(ATMOS, "(8.0, 14.0)", "(14.0, 8.0)"), "band", "a band from 14 to 8 µm"),
        ("band-zero.ron", edit(ATMOS, "(8.0, 14.0)", "(0.0, 14.0)"), "band", "a band from 0 µm"),
        ("transmission-above-one.ron", edit(ATMOS, "transmission: 0.964", "transmission: 1.2"), "transmission", "τ = 1.2"),
        ("transmission-negative.ron", edit(ATMOS, "transmission: 0.964", "transmission: -0.2"), "transmission", "τ < 0"),
        ("path-radiance-negative.ron", edit(ATMOS, "path_radiance_w_m2_sr: 1.519", "path_radiance_w_m2_sr: -1.5"), "radiance", "a negative path radiance"),
        ("levels-decreasing.ron", edit(ATMOS, "altitude_asl_m: 100.0", "altitude_asl_m: 20.0"), "", "level altitudes falling"),
        ("levels-empty.ron", edit(ATMOS, ATMOS[ATMOS.index("levels: [") : ATMOS.index("  transmission_correction")], "levels: [],\n"), "levels", "no level"),
        ("sky-angle-above-90.ron", edit(ATMOS, "(90.0, 43.9)", "(95.0, 43.9)"), "", "a sky zenith angle of 95°"),
        ("sky-not-increasing.ron", edit(ATMOS, "(45.0, 15.2)", "(0.0, 15.2)"), "", "sky angles repeated"),
        ("sky-negative.ron", edit(ATMOS, "(45.0, 15.2)", "(45.0, -15.2)"), "", "a negative sky radiance"),
        ("sky-empty.ron", edit(ATMOS, "sky: [(0.0, 11.66), (45.0, 15.2), (90.0, 43.9)]", "sky: []"), "sky", "no sky"),
        ("hemispheric-negative.ron", edit(ATMOS, "Some(15.13)", "Some(-15.13)"), "", "a negative hemispheric sky"),
        ("band-radiance-decreasing.ron", edit(ATMOS, "(201.0, 6.2)", "(201.0, 5.0)"), "", "band radiance falling as T rises"),
        ("correction-nan.ron", edit(ATMOS, "(1.1, -0.11, 0.007)", "(1.1, NaN, 0.007)"), "", "a NaN `.cor` coefficient"),
        ("missing-levels.ron", edit(ATMOS, ATMOS[ATMOS.index("  levels: [") : ATMOS.index("  transmission_correction")], ""), "levels", "no `levels` field"),
        ("temperature-zero.ron", edit(ATMOS, "temperature_k: 287.8", "temperature_k: 0.0"), "temperature", "a level at 0 K"),
        # The page's radiosonde and slant-table rules, each on a valid table.
        ("radiosonde-dewpoint-below-zero-k.ron", edit(ATMOS, ATMOS_TAIL, ATMOS_RADIOSONDE.replace("dew_point_depression_k: 5.0)", "dew_point_depression_k: 300.0)")), "absolute zero", "a dew-point depression of 300 K at 288 K"),
        ("radiosonde-falling.ron", edit(ATMOS, ATMOS_TAIL, ATMOS_RADIOSONDE.replace("altitude_m: 500.0", "altitude_m: -5.0")), "radiosonde", "radiosonde altitudes falling"),
        ("radiosonde-depression-negative.ron", edit(ATMOS, ATMOS_TAIL, ATMOS_RADIOSONDE.replace("dew_point_depression_k: 5.0)", "dew_point_depression_k: -5.0)")), "radiosonde", "a negative dew-point depression"),
        ("slant-ground-above-observer.ron", edit(ATMOS, ATMOS_TAIL, ATMOS_SLANT.replace("ground_m: Some(1.0)", "ground_m: Some(3000.0)")), "ground_m", "the paths' lower end above the lowest observer"),
        ("slant-nadir-90.ron", edit(ATMOS, ATMOS_TAIL, ATMOS_SLANT.replace("nadir_deg: [0.0, 60.0]", "nadir_deg: [0.0, 90.0]")), "nadir_deg", "a slant path at 90° from nadir (horizontal)"),
        ("slant-transmission-above-one.ron", edit(ATMOS, ATMOS_TAIL, ATMOS_SLANT.replace("[[0.95, 0.9], [0.8, 0.7]]", "[[0.95, 1.5], [0.8, 0.7]]")), "transmission", "a slant τ of 1.5"),
        ("slant-table-short.ron", edit(ATMOS, ATMOS_TAIL, ATMOS_SLANT.replace("[[0.95, 0.9], [0.8, 0.7]]", "[[0.95, 0.9]]")), "transmission", "one row of τ for two altitudes"),
        ("slant-sky-zenith-above-90.ron", edit(ATMOS, ATMOS_TAIL, ATMOS_SLANT.replace("sky_zenith_deg: [0.0, 90.0]", "sky_zenith_deg: [0.0, 95.0]")), "sky_zenith_deg", "a sky zenith angle of 95°"),
    ],
)

UNC = sample("canonical/samples/uncertainties.ron").replace('"panel"', '"patch"')
folder(
    "uncertainties",
    "Malformed uncertainties (formats/canonical/uncertainties.md), read by `irsig-trace "
    "--uncertainties`.",
    "irsig-trace",
    TRACE + " --view " + BASE + "/view.ron --uncertainties {in} -o {out}/f",
    ron_cases(UNC, ("  transmission_relative", "  colour: 3,\n  transmission_relative"), "0.02", "[\n    (facets: All")
    + [
        ("sigma-negative.ron", edit(UNC, "sigma_k: 0.1", "sigma_k: -0.1"), "sigma_k", "a negative σ"),
        ("relative-above-one.ron", edit(UNC, "transmission_relative: 0.02", "transmission_relative: 1.5"), "transmission_relative", "a relative σ of 150 %"),
        ("relative-negative.ron", edit(UNC, "path_radiance_relative: 0.05", "path_radiance_relative: -0.05"), "path_radiance_relative", "a negative relative σ"),
        ("emissivity-leaves-range.ron", edit(UNC, "sigma: 0.01", "sigma: 0.2"), "", "ε ± σ leaves [0, 1] (concrete's 0.95 + 0.2)"),
        ("material-unknown.ron", edit(UNC, "material: 1", "material: 99"), "99", "a material not in the library"),
        ("material-zero.ron", edit(UNC, "material: 1", "material: 0"), "", "material 0"),
        ("unknown-selector.ron", edit(UNC, "facets: All", "facets: Every"), "Every", "a facet selector that does not exist"),
        ("object-unknown.ron", edit(UNC, 'Object("patch")', 'Object("nothing-by-that-name")'), "nothing-by-that-name", "an object not in the raw scene"),
        ("misspelt-field.ron", edit(UNC, "transmission_relative", "transmision_relative"), "transmision_relative", "a misspelt field"),
        ("sigma-inf.ron", edit(UNC, "sigma_k: 0.5", "sigma_k: inf"), "", "an infinite σ"),
    ],
)

REG = """(
  references: [
    (name: "kinetic", source: "the temperature base/scene.raw.ron assigns"),
    (name: "measured", source: "illustrative; not a measurement"),
  ],
  regions: [
    // every concrete pixel of the image
    (name: "all concrete", material: Some(1)),
    (
      name: "concrete, centre",
      material: Some(1),
      pixels: Some((columns: (1, 2), rows: (1, 2))),
      references: [
        (name: "kinetic", temperature_k: 300.0),
        (name: "measured", temperature_k: 297.4),
      ],
    ),
    (
      name: "top left corner",
      pixels: Some((columns: (0, 1), rows: (0, 1))),
      references: [(name: "measured", temperature_k: 250.0)],
    ),
  ],
)
"""
folder(
    "regions",
    "Malformed regions of interest (formats/canonical/regions.md), read by `irsig-stats` "
    "against `base/truth.exr` (a 4 × 4 truth image of `base/scene.raw.ron`, see "
    "`base/README.md`).",
    "irsig-stats",
    BASE + "/truth.exr --regions {in} -o {out}/stats.txt",
    ron_cases(REG, ("  regions: [", "  colour: 3,\n  regions: ["), "300.0", "[\n    // every")
    + [
        ("no-regions.ron", edit(REG, REG[REG.index("  regions: [") : REG.rindex("  ],") + 4], "  regions: [],"), "regions", "no region"),
        ("duplicate-name.ron", edit(REG, '"top left corner"', '"all concrete"'), "all concrete", "a region name twice"),
        ("duplicate-column.ron", edit(REG, '(name: "measured", source', '(name: "kinetic", source'), "kinetic", "a reference column twice"),
        ("selects-nothing.ron", edit(REG, '(name: "all concrete", material: Some(1))', '(name: "all concrete")'), "all concrete", "a region with neither material nor box"),
        ("material-zero.ron", edit(REG, "material: Some(1)", "material: Some(0)"), "", "material 0"),
        ("box-reversed.ron", edit(REG, "columns: (1, 2)", "columns: (2, 1)"), "", "a box whose last column is before its first"),
        ("undeclared-column.ron", edit(REG, '[(name: "measured", temperature_k: 250.0)]', '[(name: "simulated", temperature_k: 250.0)]'), "simulated", "a reference to a column not declared"),
        ("reference-twice.ron", edit(REG, '[(name: "measured", temperature_k: 250.0)]', '[(name: "measured", temperature_k: 250.0), (name: "measured", temperature_k: 251.0)]'), "measured", "a region's reference given twice"),
        ("temperature-negative.ron", edit(REG, "temperature_k: 297.4", "temperature_k: -297.4"), "", "a negative reference temperature"),
        ("box-outside-image.ron", edit(REG, "columns: (0, 1), rows: (0, 1)", "columns: (0, 4), rows: (0, 1)"), "top left", "a box past the 4 × 4 image"),
        ("material-absent.ron", edit(REG, '(name: "all concrete", material: Some(1))', '(name: "no such material here", material: Some(3))'), "no such material here", "a region whose material no pixel shows"),
        ("name-nul.ron", edit(REG, '"top left corner"', '"top left\\u{0}corner"'), "control character", "a NUL inside a region name (finding 13 of the third hardening pass)"),
        ("name-newline.ron", edit(REG, '"top left corner"', '"top left\\ncorner"'), "control character", "a newline inside a region name"),
    ],
)



# ---------------------------------------------------------------- SRF and n, k tables
SRF = "# a response\n8.0 0.5\n10.0 1.0\n12.0 0.5\n"
NK = "# wavelength_um n k\n8.0 1.291 0.0343\n11.0 1.2 0.05\n14.0 1.3 0.4\n"
FRESNEL = "fresnel --planck-temperature 300 --angles 0:90:30 -o {out}/m.ron"
folder(
    "srf",
    "Malformed sensor response files (formats/srf.md), read by `irsig-material fresnel "
    "--band` (every tool that takes a band reads them through the same parser).",
    "irsig-material",
    FRESNEL + " --nk-table formats/samples/water-hale-querry-nk.txt --band {in}",
    table_cases("srf", SRF, "10.0", [
        ("one-sample.srf", "10.0 1.0\n", "", "one sample"),
        ("all-zero.srf", "8.0 0\n10.0 0\n12.0 0\n", "", "every response 0"),
        ("wavelength-repeated.srf", edit(SRF, "10.0 1.0", "8.0 1.0"), "", "a wavelength repeated"),
        ("wavelength-decreasing.srf", edit(SRF, "12.0 0.5", "9.0 0.5"), "", "wavelengths falling"),
        ("wavelength-zero.srf", edit(SRF, "8.0 0.5", "0 0.5"), "", "a wavelength of 0"),
        ("wavelength-negative.srf", edit(SRF, "8.0 0.5", "-8.0 0.5"), "", "a negative wavelength"),
        ("response-negative.srf", edit(SRF, "10.0 1.0", "10.0 -1.0"), "", "a negative response"),
        ("comments-only.srf", "# a response\n# with no samples\n", "", "comments and no sample"),
        ("span-1e-300-1e300.srf", "1e-300 1\n1e300 1\n", "0.2–1000", "wavelengths from 1e-300 to 1e300 µm: the quadrature filled memory (finding 6 of the third hardening pass)"),
        ("span-1e-10-1e10.srf", "1e-10 1\n1e10 1\n", "0.2–1000", "wavelengths from 1e-10 to 1e10 µm"),
        ("wavelength-far.srf", edit(SRF, "12.0 0.5", "1001 0.5"), "0.2–1000", "a wavelength past 1000 µm"),
        ("response-huge.srf", "8.0 1e308\n12.0 1e308\n", "0–1e6", "responses of 1e308: a band radiance of 1.797693e308 (finding 15)"),
        ("many-rows.srf", "# 20,001 rows, 8-12 um every 0.2 nm\n" + "".join(f"{8 + i * 2e-4:.4f} {0.5 + 0.5 * ((i * 37) % 101) / 101:.3f}\n" for i in range(20001)), "", "20,001 rows: the band's quadrature is set up once, in time linear in them, and costs no more nodes than a coarse table (finding 11)", None, "0"),
    ]),
)
folder(
    "nk",
    "Malformed complex refractive index tables (formats/nk.md), read by `irsig-material "
    "fresnel --nk-table`.",
    "irsig-material",
    FRESNEL + " --band 8-14 --nk-table {in}",
    table_cases("nk", NK, "1.2", [
        ("one-row.nk", "10.0 1.2 0.05\n", "", "one row"),
        ("k-negative.nk", edit(NK, "0.05", "-0.2"), "k", "k < 0 (gain)"),
        ("n-zero.nk", edit(NK, "1.2 0.05", "0 0.05"), "n", "n = 0"),
        ("n-negative.nk", edit(NK, "1.2 0.05", "-1.2 0.05"), "n", "n < 0"),
        ("wavelength-repeated.nk", edit(NK, "11.0 1.2", "8.0 1.2"), "", "a wavelength repeated"),
        ("wavelength-decreasing.nk", edit(NK, "14.0 1.3", "10.0 1.3"), "", "wavelengths falling"),
        ("short-of-band.nk", edit(NK, "14.0 1.3", "13.0 1.3"), "", "ends at 13 µm, short of the 8–14 µm band"),
        ("wavelength-negative.nk", edit(NK, "8.0 1.291", "-8.0 1.291"), "", "a negative wavelength"),
    ]),
)


# ---------------------------------------------------------------- EXR into the sensor
import struct


def exr(width, height, channels=("radiance",), value=10.0, claim=None, units=True, extra=b"", cut=None, values=None):
    """A minimal uncompressed scanline OpenEXR of f32 channels, every sample `value`
    (or `values`, a list, for the first channel). `claim` overrides the data window's
    (width, height); `cut` truncates the bytes."""
    def attr(name, kind, data):
        return name.encode() + b"\0" + kind.encode() + b"\0" + struct.pack("<i", len(data)) + data

    chl = b"".join(c.encode() + b"\0" + struct.pack("<iB3xii", 2, 0, 1, 1) for c in sorted(channels)) + b"\0"
    cw, ch = claim or (width, height)
    box = struct.pack("<iiii", 0, 0, cw - 1, ch - 1)
    header = (
        attr("channels", "chlist", chl)
        + attr("compression", "compression", b"\0")
        + attr("dataWindow", "box2i", box)
        + attr("displayWindow", "box2i", box)
        + attr("lineOrder", "lineOrder", b"\0")
        + attr("pixelAspectRatio", "float", struct.pack("<f", 1.0))
        + attr("screenWindowCenter", "v2f", struct.pack("<ff", 0, 0))
        + attr("screenWindowWidth", "float", struct.pack("<f", 1.0))
    )
    if units:
        header += attr("irsig.units", "string", ";".join(f"{c}=W m-2 sr-1" for c in channels).encode())
    header += extra + b"\0"
    start = b"\x76\x2f\x31\x01" + struct.pack("<I", 2) + header
    table_len = 8 * height
    offset = len(start) + table_len
    table = b""
    chunks = b""
    for y in range(height):
        row = b""
        for c in sorted(channels):
            for x in range(width):
                v = value
                if values is not None and c == channels[0]:
                    v = values[y * width + x]
                row += struct.pack("<f", v)
        chunk = struct.pack("<ii", y, len(row)) + row
        table += struct.pack("<Q", offset + len(chunks))
        chunks += chunk
    data = start + table + chunks
    return data[:cut] if cut is not None else data


def zip_exr(width, height, channels=("radiance",), value=10.0):
    """A ZIP-compressed OpenEXR (16 scanlines a block) of f32 channels, every sample
    `value`: an 8,192 × 8,192 image in a few hundred kilobytes."""
    import zlib

    def attr(name, kind, data):
        return name.encode() + b"\0" + kind.encode() + b"\0" + struct.pack("<i", len(data)) + data

    def block(rows):
        raw = b"".join(struct.pack("<f", value) * width for _ in range(rows) for _c in channels)
        half = (len(raw) + 1) // 2
        inter = bytearray(len(raw))
        inter[:half] = raw[0::2]
        inter[half:] = raw[1::2]
        delta = bytearray(inter)
        for i in range(len(delta) - 1, 0, -1):
            delta[i] = (inter[i] - inter[i - 1] + 128 + 256) % 256
        return zlib.compress(bytes(delta), 9)

    chl = b"".join(c.encode() + b"\0" + struct.pack("<iB3xii", 2, 0, 1, 1) for c in sorted(channels)) + b"\0"
    box = struct.pack("<iiii", 0, 0, width - 1, height - 1)
    header = (
        attr("channels", "chlist", chl)
        + attr("compression", "compression", b"\3")
        + attr("dataWindow", "box2i", box)
        + attr("displayWindow", "box2i", box)
        + attr("lineOrder", "lineOrder", b"\0")
        + attr("pixelAspectRatio", "float", struct.pack("<f", 1.0))
        + attr("screenWindowCenter", "v2f", struct.pack("<ff", 0, 0))
        + attr("screenWindowWidth", "float", struct.pack("<f", 1.0))
        + attr("irsig.units", "string", ";".join(f"{c}=W m-2 sr-1" for c in channels).encode())
        + b"\0"
    )
    start = b"\x76\x2f\x31\x01" + struct.pack("<I", 2) + header
    blocks = (height + 15) // 16
    full = block(16)
    offset = len(start) + 8 * blocks
    table = b""
    chunks = b""
    for b in range(blocks):
        rows = min(16, height - 16 * b)
        data = full if rows == 16 else block(rows)
        table += struct.pack("<Q", offset + len(chunks))
        chunks += struct.pack("<ii", 16 * b, len(data)) + data
    return start + table + chunks


GOOD_EXR = exr(4, 4)
folder(
    "exr-sensor",
    "Malformed radiance EXRs (formats/sensor.md, formats/images.md), read by "
    "`irsig-sensor`. Written by `../generate.py` with a small OpenEXR writer of its own "
    "(uncompressed scanlines), each a few hundred bytes.",
    "irsig-sensor",
    "{in} --mtf box:1x1 --dc-per-kelvin 2 -o {out}/s.exr --dc-png {out}/dc.png --lut {out}/lut.txt",
    [
        ("empty.exr", b"", "", "an empty file"),
        ("not-exr.exr", b"P6\n4 4\n255\n" + b"\0" * 48, "", "a PPM image named .exr"),
        ("magic-only.exr", GOOD_EXR[:4], "", "the magic number and nothing else"),
        ("truncated-header.exr", GOOD_EXR[:60], "", "cut inside the header"),
        ("truncated-pixels.exr", GOOD_EXR[:-20], "", "cut inside the last scanline"),
        ("huge-claim.exr", exr(4, 4, claim=(100000, 100000)), "pixels", "a 400-byte file whose header claims 100,000 × 100,000 pixels"),
        ("claim-past-memory.exr", exr(4, 4, channels=tuple(f"c{i:03}" for i in range(70)) + ("radiance",), claim=(8192, 8192), cut=2500), "", "a header claiming 8,192 × 8,192 pixels of 71 channels (18 GB, past the memory budget), cut after 2,500 bytes"),
        ("negative-window.exr", exr(4, 4, claim=(-5, 4)), "", "a data window of negative width"),
        ("no-radiance.exr", exr(4, 4, channels=("temperature",)), "radiance", "no `radiance` layer"),
        ("nan.exr", exr(4, 4, values=[10.0] * 5 + [float("nan")] + [10.0] * 10), "", "a NaN pixel (column 1, row 1)"),
        ("inf.exr", exr(4, 4, values=[10.0] * 15 + [float("inf")]), "", "an infinite pixel"),
        ("nan-second-row.exr", exr(4, 4, values=[10.0] * 4 + [float("nan")] * 4 + [10.0] * 8), "", "a row of NaN"),
        ("bad-version.exr", GOOD_EXR[:4] + struct.pack("<I", 99) + GOOD_EXR[8:], "", "format version 99"),
        ("bad-offset.exr", GOOD_EXR[: len(GOOD_EXR) - 4 * 24 - 8 * 4] + struct.pack("<Q", 1 << 40) + GOOD_EXR[len(GOOD_EXR) - 4 * 24 - 8 * 3 :], "", "a scanline offset past the end of the file"),
        ("garbled-chlist.exr", GOOD_EXR.replace(b"chlist", b"chlizt"), "", "the channel list's type misspelt"),
        ("unknown-compression.exr", GOOD_EXR.replace(b"compression\0compression\0\x01\0\0\0\0", b"compression\0compression\0\x01\0\0\0\x63"), "", "compression method 99"),
        ("zero-height.exr", exr(4, 0, claim=(4, 0)), "", "a data window of no rows"),
        ("wrong-size-chunk.exr", GOOD_EXR.replace(struct.pack("<ii", 2, 16), struct.pack("<ii", 2, 0x7FFFFFF0)), "", "a scanline chunk that claims 2 GB"),
        ("offset-into-header.exr", GOOD_EXR[: len(GOOD_EXR) - 4 * 24 - 8 * 4] + struct.pack("<Q", 10) + GOOD_EXR[len(GOOD_EXR) - 4 * 24 - 8 * 3 :], "", "a scanline offset pointing into the header"),
        ("directory-name.exr", b"\x76\x2f\x31\x01", "", "four bytes: the magic only, version missing"),
        ("half-channel.exr", GOOD_EXR.replace(struct.pack("<iB3xii", 2, 0, 1, 1), struct.pack("<iB3xii", 7, 0, 1, 1)), "", "a channel of pixel type 7 (not half, float or uint)"),
        ("declares-8192-squared.exr", zip_exr(8192, 8192), "", "284 KB that decode to 8,192 × 8,192 pixels: the sensor holds its stated bytes per pixel (it used 2.3 GB; finding 16 of the third hardening pass; tests/tests/memory.rs measures it)", "{in} --mtf box:1x1 -o {out}/s.exr", "0"),
        ("output-is-input.exr", GOOD_EXR, "both an output and an input", "a valid radiance image named as the sensor's output too: it would be replaced (finding 4)", "{in} --mtf box:1x1 -o {in}", "2"),
        ("dc-png-is-input.exr", GOOD_EXR, "both an output and an input", "the input named as the counts PNG", "{in} --mtf box:1x1 --dc-per-kelvin 2 -o {out}/s.exr --dc-png {in}", "2"),
    ],
)



# ---------------------------------------------------------------- pipeline files
PIPE = """Pipeline(
  sweeps: {"views": Frames([{"label": "a"}, {"label": "b"}])},
  stages: [
    Stage(name: "copy", tool: "testcat", args: ["input.txt"], outputs: {"o": "build/copy.txt"}, slurm: (cpus: 1)),
    Stage(
      name: "views",
      tool: "testcat",
      sweep: "views",
      args: ["build/copy.txt"],
      params: {"prefix": "{label} "},
      outputs: {"o": "build/v-{frame}.txt"},
    ),
  ],
)
"""
folder(
    "pipeline",
    "Malformed pipeline files (formats/pipeline.md), run by `irsig-run`; `input.txt` is "
    "the file their first stage reads. The stages would write under `build/` here: the "
    "test checks that nothing is.",
    "irsig-run",
    "{in}",
    ron_cases(PIPE, ("  sweeps:", "  colour: 3,\n  sweeps:"), "cpus: 1", "[\n    Stage(name")
    + [
        ("sweep-not-a-list.ron", edit(PIPE, 'Frames([{"label": "a"}, {"label": "b"}])', 'Frames({"label": "a"})'), "", "a sweep's frames not a list"),
        ("unknown-tool.ron", edit(PIPE, 'tool: "testcat", args', 'tool: "nosuchtool", args'), "nosuchtool", "a tool that does not exist"),
        ("unknown-flag.ron", edit(PIPE, 'Stage(name: "copy", tool: "testcat", args: ["input.txt"]', 'Stage(name: "copy", tool: "flatten", args: ["input.txt"], params: {"unitt": "km"}'), "unitt", "a flag irsig-flatten does not take (checked before anything runs)"),
        ("unknown-sweep.ron", edit(PIPE, 'sweep: "views"', 'sweep: "veiws"'), "veiws", "a sweep that does not exist"),
        ("unknown-variable.ron", edit(PIPE, "{label} ", "{lable} "), "lable", "a template variable no frame defines"),
        ("template-outside-sweep.ron", edit(PIPE, '"build/copy.txt"}, slurm', '"build/copy-{frame}.txt"}, slurm'), "frame", "a template in a stage without a sweep"),
        ("missing-input.ron", edit(PIPE, '["input.txt"]', '["absent.txt"]'), "absent.txt", "an input no stage writes and that does not exist"),
        ("two-writers.ron", edit(PIPE, '"build/v-{frame}.txt"', '"build/copy.txt"'), "build/copy.txt", "two stages write one file"),
        ("cycle.ron", edit(PIPE, '["input.txt"]', '["build/v-1.txt"]'), "cycle", "a dependency cycle"),
        ("dash-output.ron", edit(PIPE, '"build/copy.txt"}, slurm', '"-"}, slurm'), "", "standard output as a stage's output"),
        ("misspelt-stage-field.ron", edit(PIPE, "outputs: {\"o\": \"build/copy.txt\"}", "output: {\"o\": \"build/copy.txt\"}"), "output", "`output` for `outputs`"),
        ("slurm-negative.ron", edit(PIPE, "slurm: (cpus: 1)", "slurm: (cpus: -1)"), "", "a negative Slurm CPU count"),
        ("frames-zero.ron", edit(PIPE, 'Frames([{"label": "a"}, {"label": "b"}])', "FlyBy(frames: 0, path: [(0, 0, 300), (0, 10, 300)], look_at: (0, 0, 0))"), "", "a fly-by of 0 frames"),
        ("output-is-input.ron", edit(edit(PIPE, '"build/copy.txt"}, slurm', '"input.txt"}, slurm'), 'args: ["build/copy.txt"]', 'args: ["input.txt"]'), "input.txt", "a stage writes the file it reads"),
        ("newline-in-parameter.ron", edit(PIPE, '{"prefix": "{label} "}', '{"prefix": "a\\nr.html: ; touch X #"}'), "control character", "a newline in a parameter: a rule make would run (finding 1 of the third hardening pass)", "--emit-makefile {out}/Makefile {in}"),
        ("newline-in-name.ron", edit(PIPE, 'name: "copy"', 'name: "copy\\ntouch X"'), "control character", "a newline in a stage name: a line of the Makefile's comment (finding 1)", "--emit-makefile {out}/Makefile {in}"),
        ("newline-in-name-slurm.ron", edit(PIPE, 'name: "copy"', 'name: "copy\\ntouch X"'), "control character", "a newline in a stage name: a command line of the Slurm script (finding 2)", "--emit-slurm {out}/slurm {in}"),
        ("nul-in-parameter.ron", edit(PIPE, '{"prefix": "{label} "}', '{"prefix": "$(touch X)\\u{0}"}'), "control character", "a NUL in a parameter: printed raw by --dry-run (finding 3)", "--dry-run {in}"),
        ("raw-newline.ron", edit(PIPE, '{"prefix": "{label} "}', '{"prefix": r"a\nb"}'), "control character", "a newline written as it is in a raw string"),
        ("tab-in-path.ron", edit(PIPE, '"build/copy.txt"}, slurm', '"build/co\\tpy.txt"}, slurm'), "control character", "a tab in an output path"),
        ("no-stages.ron", "(stages: [])\n", "no stages", "`(stages: [])`: ran nothing, rc 0 (finding 13)"),
        ("makefile-is-pipeline.ron", PIPE, "both an output and an input", "--emit-makefile over the pipeline file itself (finding 4)", "--emit-makefile {in} {in}", "2"),
    ],
    extra={"input.txt": "a line\n"},
)

DECISION = """(
  tolerance_k: 0.3,
  percentile: 99.0,
  choices: [
    (model: atmosphere, setting: "table", reference: "table", pinned: false,
      error: (percentile_k: 0.0, max_k: 0.0), relative_cost: 1.0, reason: "cheapest"),
    (model: bounces, setting: "1", reference: "1", pinned: false,
      error: (percentile_k: 0.0, max_k: 0.0), relative_cost: 1.0, reason: "cheapest"),
    (model: r#sky-view, setting: "0", reference: "0", pinned: false,
      error: (percentile_k: 0.0, max_k: 0.0), relative_cost: 1.0, reason: "cheapest"),
    (model: supersampling, setting: "1", reference: "1", pinned: false,
      error: (percentile_k: 0.0, max_k: 0.0), relative_cost: 1.0, reason: "cheapest"),
    (model: r#path-terms, setting: "exact", reference: "exact", pinned: false,
      error: (percentile_k: 0.0, max_k: 0.0), relative_cost: 1.0, reason: "cheapest"),
    (model: r#sub-bands, setting: "1", reference: "1", pinned: false,
      error: (percentile_k: 0.0, max_k: 0.0), relative_cost: 1.0, reason: "cheapest"),
  ],
  predicted: (percentile_k: 0.12, max_k: 0.8),
  relative_cost: 0.06,
  pilot_pixels: 16,
)
"""
# The decision's fields after the choices, and its classes (the new fields of the third
# pass): each broken as the page's rules forbid, read by irsig-trace --decision and by
# irsig-report --decision alike.
DECISION_CLASSES = edit(
    DECISION,
    "  pilot_pixels: 16,\n",
    """  pilot_pixels: 16,
  classes: [
    (event: "diffuse", material: 1, name: "concrete", grazing: false, horizon: false,
      sub_pixel: false, share: 1.0, samples: 16,
      error: (percentile_k: 0.1, max_k: 0.2), rms_k: 0.05, residual_k: 0.01,
      guaranteed: true, why: "held"),
  ],
  not_guaranteed_share: 0.0,
  data_error_k: Some(0.004),
""",
)
DECISION_RULES = [
    ("classes-valid.ron", DECISION_CLASSES, "", "a valid decision with a class (success)", None, "0"),
    ("not-guaranteed-half.ron", edit(DECISION_CLASSES, "not_guaranteed_share: 0.0", "not_guaranteed_share: 0.5"), "0.5 is out of range: expected 0 to 0.005", "half the frame not guaranteed: the page allows at most 0.005"),
    ("event-bogus.ron", edit(DECISION_CLASSES, 'event: "diffuse"', 'event: "bogus"'), "`bogus`: expected one of sky, terrain, diffuse", "a class whose event is `bogus`"),
    ("data-error-huge.ron", edit(DECISION_CLASSES, "data_error_k: Some(0.004)", "data_error_k: Some(1e308)"), "1e308 is out of range: expected 0 to 10000", "a data error of 1e308 K"),
    ("class-error-huge.ron", edit(DECISION_CLASSES, "rms_k: 0.05", "rms_k: 1e300"), "`classes[0].rms_k`: 1e300 is out of range", "a class's σ of 1e300 K"),
    ("reference-word.ron", edit(DECISION_CLASSES, 'setting: "exact", reference: "exact"', 'setting: "exact", reference: "exakt"'), "`exakt` is no setting of path-terms", "a reference setting that does not exist"),
]
DECISION_SUN = edit(
    DECISION_CLASSES,
    "  ],\n  predicted:",
    """    (model: sun, setting: "on", reference: "on", pinned: false,
      error: (percentile_k: 0.0, max_k: 0.0), relative_cost: 1.0, reason: "cheapest"),
  ],
  predicted:""",
)
folder(
    "decision",
    "Malformed decisions (formats/canonical/decision.md), read by `irsig-trace --decision`.",
    "irsig-trace",
    TRACE + " --view " + BASE + "/view.ron --atmosphere us-std-1976 --decision {in} -o {out}/f",
    ron_cases(DECISION, ("  predicted:", "  colour: 3,\n  predicted:"), "0.12", "[\n    (model: atmosphere")
    + [
        ("tolerance-zero.ron", edit(DECISION, "tolerance_k: 0.3", "tolerance_k: 0.0"), "tolerance", "a tolerance of 0 K"),
        ("percentile-zero.ron", edit(DECISION, "percentile: 99.0", "percentile: 0.0"), "percentile", "percentile 0"),
        ("percentile-above-100.ron", edit(DECISION, "percentile: 99.0", "percentile: 101.0"), "percentile", "percentile 101"),
        ("unknown-model.ron", edit(DECISION, "model: bounces", "model: bouncez"), "bouncez", "a model that does not exist"),
        ("unknown-setting.ron", edit(DECISION, 'setting: "table"', 'setting: "tabel"'), "tabel", "an atmosphere setting that does not exist"),
        ("bounces-word.ron", edit(DECISION, 'setting: "1", reference: "1", pinned: false,\n      error: (percentile_k: 0.0, max_k: 0.0), relative_cost: 1.0, reason: "cheapest"),\n    (model: r#sky-view', 'setting: "one", reference: "1", pinned: false,\n      error: (percentile_k: 0.0, max_k: 0.0), relative_cost: 1.0, reason: "cheapest"),\n    (model: r#sky-view'), "one", "bounces `one`"),
        ("model-twice.ron", edit(DECISION, "model: r#sky-view", "model: bounces"), "bounces", "a model chosen twice"),
        ("pinned-word.ron", edit(DECISION, "pinned: false", 'pinned: "no"'), "pinned", "`pinned` a string"),
        ("bounces-huge.ron", edit(DECISION, 'setting: "1", reference: "1", pinned: false,\n      error: (percentile_k: 0.0, max_k: 0.0), relative_cost: 1.0, reason: "cheapest"),\n    (model: r#sky-view', 'setting: "4000000000", reference: "1", pinned: false,\n      error: (percentile_k: 0.0, max_k: 0.0), relative_cost: 1.0, reason: "cheapest"),\n    (model: r#sky-view'), "", "4,000,000,000 bounces"),
        # The settings of the entries after `r#sky-view` (line 9), at their own line and
        # column: 11:37, 13:36, 15:35 (finding 14: they were reported at `choices`, 4:12).
        ("supersampling-huge.ron", edit(DECISION, '(model: supersampling, setting: "1"', '(model: supersampling, setting: "100000"'), "supersampling-huge.ron:11:37", "100,000 × 100,000 rays per pixel"),
        ("supersampling-word.ron", edit(DECISION, '(model: supersampling, setting: "1"', '(model: supersampling, setting: "two"'), "supersampling-word.ron:11:37", "supersampling `two`, at its entry's setting (finding 14)"),
        ("supersampling-refine-no-record.ron", edit(DECISION, '(model: supersampling, setting: "1"', '(model: supersampling, setting: "refine-8"'), "supersampling-refine-no-record.ron:11:37", "supersampling `refine-8` without the `sampling` record it needs, at its entry's setting (finding 14)"),
        ("path-terms-unknown.ron", edit(DECISION, '(model: r#path-terms, setting: "exact"', '(model: r#path-terms, setting: "exakt"'), "path-terms-unknown.ron:13:36", "path terms `exakt`, at its entry's setting (finding 14)"),
        ("sub-bands-word.ron", edit(DECISION, '(model: r#sub-bands, setting: "1"', '(model: r#sub-bands, setting: "two"'), "sub-bands-word.ron:15:35", "sub-bands `two`, at its entry's setting (finding 14)"),
        ("error-negative.ron", edit(DECISION, "predicted: (percentile_k: 0.12", "predicted: (percentile_k: -0.12"), "", "a negative error"),
    ]
    + [c for c in DECISION_RULES if c[0] != "classes-valid.ron"],
)



folder(
    "decision-report",
    "Malformed decisions (formats/canonical/decision.md), read by `irsig-report "
    "--decision`: the same rules irsig-trace applies, the settings' spelling included.",
    "irsig-report",
    BASE + "/truth.exr --decision {in} -o {out}/r.html",
    [
        ("sun-maybe.ron", edit(DECISION_SUN, 'model: sun, setting: "on"', 'model: sun, setting: "maybe"'), "`maybe` is no setting of sun: expected on or off", "the sun's setting `maybe`, which irsig-trace refuses"),
        ("sun-on.ron", DECISION_SUN, "", "the sun on (success)", None, "0"),
        ("unknown-setting.ron", edit(DECISION, 'setting: "table"', 'setting: "tabel"'), "`tabel` is no setting of atmosphere", "an atmosphere setting that does not exist"),
    ]
    + DECISION_RULES,
)


# ---------------------------------------------------------------- spectral atmospheres
SPA_TABLES = {
    "level_transmission": [0.95, 0.9, 0.96, 0.9, 0.8, 0.92],
    "level_path_radiance_w_m2_sr_per_unit": [0.1, 0.2, 0.1, 0.5, 0.9, 0.6],
    "sky_radiance_w_m2_sr_per_unit": [1.0, 2.0, 1.5, 1.5, 2.5, 2.0, 3.0, 4.0, 3.5],
}


def spa_ron(tables=None, **edits):
    t = dict(SPA_TABLES, **(tables or {}))
    fmt = lambda v: "[" + ", ".join(repr(x) if isinstance(x, float) else str(x) for x in v) + "]"
    text = f"""(
  name: "case",
  source: "hand-written for the malformed corpus",
  grid: (axis: wavelength_um, points: [8.0, 11.0, 14.0]),
  levels: [
    (altitude_asl_m: 100.0, temperature_k: 288.0, altitude_m: 100.0),
    (altitude_asl_m: 1000.0, temperature_k: 282.0, altitude_m: 1000.0),
  ],
  level_transmission: {fmt(t["level_transmission"])},
  level_path_radiance_w_m2_sr_per_unit: {fmt(t["level_path_radiance_w_m2_sr_per_unit"])},
  sky_zenith_deg: [0.0, 45.0, 90.0],
  sky_radiance_w_m2_sr_per_unit: {fmt(t["sky_radiance_w_m2_sr_per_unit"])},
)
"""
    for old, new in edits.get("replace", []):
        text = edit(text, old, new)
    return text


def spa_bin(header=None, tables=None, magic=b"IRSIGSPA", version=1, counts=None, extra=b"", hlen=None):
    t = dict(SPA_TABLES, **(tables or {}))
    h = header if header is not None else spa_ron({k: [] for k in SPA_TABLES})
    hb = h.encode() if isinstance(h, str) else h
    out = magic + struct.pack("<II", version, len(hb) if hlen is None else hlen) + hb
    for i, k in enumerate(SPA_TABLES):
        vals = t[k]
        n = counts[i] if counts and counts[i] is not None else len(vals)
        out += struct.pack("<I", n) + b"".join(struct.pack("<f", v) for v in vals)
    return out + extra


SPECTRAL = TRACE + " --view " + BASE + "/view.ron --atmosphere {in} --atmosphere-model layered --sub-bands 2 -o {out}/f"
SPA = spa_ron()
folder(
    "spectral-atmosphere",
    "Malformed spectral atmospheres in RON (formats/canonical/spectral-atmosphere.md), read "
    "by `irsig-trace --atmosphere`.",
    "irsig-trace",
    SPECTRAL,
    ron_cases(SPA, ("  grid:", "  colour: 3,\n  grid:"), "288.0", "[\n    (altitude")
    + [
        ("grid-one-point.ron", edit(SPA, "points: [8.0, 11.0, 14.0]", "points: [8.0]"), "points", "a grid of one point"),
        ("grid-repeated.ron", edit(SPA, "points: [8.0, 11.0, 14.0]", "points: [8.0, 8.0, 14.0]"), "points", "a grid point repeated"),
        ("grid-negative.ron", edit(SPA, "points: [8.0, 11.0, 14.0]", "points: [-8.0, 11.0, 14.0]"), "points", "a negative grid point"),
        ("unknown-axis.ron", edit(SPA, "axis: wavelength_um", "axis: frequency_hz"), "frequency_hz", "an axis that does not exist"),
        ("table-short.ron", spa_ron({"level_transmission": [0.95, 0.9, 0.96, 0.9, 0.8]}), "level_transmission", "5 values for 2 levels × 3 points"),
        ("table-long.ron", spa_ron({"sky_radiance_w_m2_sr_per_unit": [1.0] * 10}), "sky_radiance", "10 values for 3 angles × 3 points"),
        ("transmission-above-one.ron", spa_ron({"level_transmission": [0.95, 1.9, 0.96, 0.9, 0.8, 0.92]}), "transmission", "τ = 1.9"),
        ("radiance-negative.ron", spa_ron({"sky_radiance_w_m2_sr_per_unit": [1.0, 2.0, 1.5, 1.5, -2.5, 2.0, 3.0, 4.0, 3.5]}), "sky_radiance", "a negative sky radiance"),
        ("radiance-nan.ron", spa_ron({"level_path_radiance_w_m2_sr_per_unit": [0.1, 0.2, "NaN", 0.5, 0.9, 0.6]}), "", "a NaN path radiance"),
        ("levels-decreasing.ron", edit(SPA, "altitude_asl_m: 1000.0, temperature_k: 282.0, altitude_m: 1000.0", "altitude_asl_m: 50.0, temperature_k: 282.0, altitude_m: 50.0"), "", "levels falling"),
        ("sky-angle-above-90.ron", edit(SPA, "[0.0, 45.0, 90.0]", "[0.0, 45.0, 95.0]"), "", "a sky angle of 95°"),
        ("band-outside-grid.ron", edit(SPA, "points: [8.0, 11.0, 14.0]", "points: [3.0, 4.0, 5.0]"), "", "a 3–5 µm grid for the 8–14 µm band"),
        # The page's `.cor` path rule: from 0°, at least 3 angles.
        ("correction-two-angles.ron", edit(SPA, "  sky_zenith_deg:", "  transmission_correction: Some((altitude_m: 1000.0, nadir_deg: [0.0, 45.0], transmission: [0.9, 0.8, 0.9, 0.8, 0.7, 0.8])),\n  sky_zenith_deg:"), "at least 3", "correction paths at two angles"),
        ("correction-not-from-zero.ron", edit(SPA, "  sky_zenith_deg:", "  transmission_correction: Some((altitude_m: 1000.0, nadir_deg: [5.0, 30.0, 45.0], transmission: [0.9, 0.8, 0.9, 0.8, 0.7, 0.8, 0.7, 0.6, 0.7])),\n  sky_zenith_deg:"), "starting at 0", "correction paths from 5°"),
    ],
)

SPA_GOOD = spa_bin()
header_len = len(spa_ron({k: [] for k in SPA_TABLES}).encode())
folder(
    "spectral-binary",
    "Malformed binary spectral atmospheres (`IRSIGSPA`, formats/canonical/"
    "spectral-atmosphere.md), read by `irsig-trace --atmosphere`.",
    "irsig-trace",
    SPECTRAL,
    [
        ("empty.spa", b"", "", "an empty file"),
        ("magic-only.spa", b"IRSIGSPA", "", "the magic and nothing else"),
        ("wrong-magic.spa", spa_bin(magic=b"IRSIGSPX"), "", "a magic one letter off"),
        ("version-2.spa", spa_bin(version=2), "version", "version 2"),
        ("header-length-huge.spa", spa_bin(hlen=0xFFFFFFFF), "", "a header of 4 GiB claimed"),
        ("header-length-short.spa", spa_bin(hlen=10), "", "a header length that cuts the RON"),
        ("header-not-utf8.spa", spa_bin(header=spa_ron({k: [] for k in SPA_TABLES}).encode().replace(b"hand-written", b"hand-wr\xfftten")), "UTF-8", "a non-UTF-8 byte in the header"),
        ("header-bad-ron.spa", spa_bin(header=spa_ron({k: [] for k in SPA_TABLES}).replace("levels:", "levelz:")), "levelz", "an unknown field in the header"),
        ("header-tables-not-empty.spa", spa_bin(header=spa_ron()), "", "the header's tables not empty"),
        ("count-huge.spa", spa_bin(counts=[0xFFFFFFFF, None, None]), "", "a table count of 4 × 10^9 in a small file"),
        ("count-short.spa", spa_bin(counts=[5, None, None]), "", "a count one short: the tables shift"),
        ("truncated.spa", SPA_GOOD[:-6], "", "cut inside the last table"),
        ("trailing-bytes.spa", SPA_GOOD + b"\0\0\0\0", "", "bytes after the last table"),
        ("nan.spa", spa_bin(tables={"level_transmission": [0.95, float("nan"), 0.96, 0.9, 0.8, 0.92]}), "", "a NaN transmission"),
        ("inf.spa", spa_bin(tables={"sky_radiance_w_m2_sr_per_unit": [1.0, 2.0, float("inf"), 1.5, 2.5, 2.0, 3.0, 4.0, 3.5]}), "", "an infinite sky radiance"),
        ("transmission-above-one.spa", spa_bin(tables={"level_transmission": [0.95, 1.9, 0.96, 0.9, 0.8, 0.92]}), "transmission", "τ = 1.9"),
        ("radiance-negative.spa", spa_bin(tables={"level_path_radiance_w_m2_sr_per_unit": [0.1, -0.2, 0.1, 0.5, 0.9, 0.6]}), "", "a negative path radiance"),
        ("radiance-1e38.spa", spa_bin(tables={"sky_radiance_w_m2_sr_per_unit": [1.0, 2.0, 1e38, 1.5, 2.5, 2.0, 3.0, 4.0, 3.5]}), "radiance from 0 to 1e9", "a sky radiance of 1e38: finite, but no sky's, and infinite once integrated"),
        ("table-short.spa", spa_bin(tables={"level_transmission": [0.95, 0.9, 0.96, 0.9, 0.8]}), "", "5 values for 2 levels × 3 points"),
        ("header-truncated-file.spa", SPA_GOOD[: 16 + header_len // 2], "", "cut inside the header"),
        ("missing-table.spa", SPA_GOOD[: SPA_GOOD.rindex(struct.pack("<I", 9))], "", "the last table missing"),
    ],
)


# ---------------------------------------------------------------- raw scene, binary
def raw(names=(b"patch",), positions=None, facets=None, magic=b"IRSIGRAW", version=1, flags=0,
        terrain=(286.0, 1.0), counts=None, name_bytes=None, reserved=0, extra=b""):
    positions = positions if positions is not None else [(-10.0, -10.0, 0.0), (10.0, -10.0, 0.0), (0.0, 10.0, 0.0)]
    facets = facets if facets is not None else [((0, 1, 2), 1, 0, 300.0)]
    block = name_bytes if name_bytes is not None else b"".join(struct.pack("<I", len(n)) + n for n in names)
    o, p_, f = counts or (len(names), len(positions), len(facets))
    out = magic + struct.pack("<IIddIIII", version, flags, *terrain, o, p_, f, len(block)) + block
    for p in positions:
        out += struct.pack("<3d", *p)
    for v, m, obj, t in facets:
        out += struct.pack("<3IHHId", *v, m, reserved, obj, t)
    return out + extra


RAW_GOOD = raw()
folder(
    "raw-binary",
    "Malformed binary raw scenes (`IRSIGRAW`, formats/canonical/raw-scene.md), read by "
    "`irsig-trace --scene`.",
    "irsig-trace",
    "--scene {in} --materials " + MATERIALS + " --view " + BASE + "/view.ron -o {out}/f",
    [
        ("empty.raw", b"", "", "an empty file"),
        ("magic-only.raw", b"IRSIGRAW", "", "the magic and nothing else"),
        ("wrong-magic.raw", raw(magic=b"IRSIGRAX"), "", "a magic one letter off"),
        ("version-2.raw", raw(version=2), "version", "version 2"),
        ("flags.raw", raw(flags=1), "", "reserved flags not 0"),
        ("truncated.raw", RAW_GOOD[:-5], "", "cut inside the facet"),
        ("trailing-bytes.raw", raw(extra=b"\0"), "", "a byte after the last facet"),
        ("facet-count-huge.raw", raw(counts=(1, 3, 1_000_000_000)), "", "10^9 facets claimed in a 150-byte file"),
        ("position-count-huge.raw", raw(counts=(1, 0xFFFFFFFF, 1)), "", "4 × 10^9 positions claimed"),
        ("name-length-huge.raw", raw(name_bytes=struct.pack("<I", 0xFFFFFFF0) + b"patch"), "", "a name longer than its block"),
        ("name-not-utf8.raw", raw(names=(b"p\xffatch",)), "UTF-8", "a non-UTF-8 object name"),
        ("nan.raw", raw(positions=[(-10.0, float("nan"), 0.0), (10.0, -10.0, 0.0), (0.0, 10.0, 0.0)]), "", "a NaN coordinate"),
        ("inf.raw", raw(positions=[(-10.0, -10.0, 0.0), (float("inf"), -10.0, 0.0), (0.0, 10.0, 0.0)]), "", "an infinite coordinate"),
        ("index-out-of-range.raw", raw(facets=[((0, 1, 3), 1, 0, 300.0)]), "", "a vertex index past the positions"),
        ("object-out-of-range.raw", raw(facets=[((0, 1, 2), 1, 5, 300.0)]), "", "an object index past the names"),
        ("material-zero.raw", raw(facets=[((0, 1, 2), 0, 0, 300.0)]), "", "material 0"),
        ("material-unknown.raw", raw(facets=[((0, 1, 2), 9, 0, 300.0)]), "9", "a material not in the library"),
        ("temperature-negative.raw", raw(facets=[((0, 1, 2), 1, 0, -300.0)]), "", "a negative temperature"),
        ("degenerate.raw", raw(positions=[(-10.0, -10.0, 0.0), (10.0, -10.0, 0.0), (0.0, -10.0, 0.0)]), "", "collinear vertices"),
        ("terrain-emissivity.raw", raw(terrain=(286.0, 1.5)), "", "terrain emissivity 1.5"),
        ("reserved.raw", raw(reserved=7), "", "a facet's reserved u16 not 0"),
        ("no-facets.raw", raw(facets=[]), "", "no facet"),
    ],
)





RAWRON = (HERE / "base/scene.raw.ron").read_text()
folder(
    "raw-scene",
    "Malformed raw scenes in RON (formats/canonical/raw-scene.md), read by `irsig-trace "
    "--scene`.",
    "irsig-trace",
    "--scene {in} --materials " + MATERIALS + " --view " + BASE + "/view.ron -o {out}/f",
    ron_cases(RAWRON, ("  objects:", "  colour: 3,\n  objects:"), "10.0, 0.0", "[(-10.0")
    + [
        ("no-facets.ron", edit(RAWRON, "facets: [(vertices: (0, 1, 2), material: 1, temperature_k: 300.0, object: 0)]", "facets: []"), "", "no facet"),
        ("index-out-of-range.ron", edit(RAWRON, "(0, 1, 2)", "(0, 1, 3)"), "", "a vertex index past the positions"),
        ("object-out-of-range.ron", edit(RAWRON, "object: 0", "object: 1"), "", "an object index past the names"),
        ("material-zero.ron", edit(RAWRON, "material: 1", "material: 0"), "", "material 0"),
        ("material-unknown.ron", edit(RAWRON, "material: 1", "material: 77"), "77", "a material not in the library"),
        ("temperature-negative.ron", edit(RAWRON, "temperature_k: 300.0", "temperature_k: -300.0"), "", "a negative temperature"),
        ("degenerate.ron", edit(RAWRON, "(0.0, 10.0, 0.0)", "(0.0, -10.0, 0.0)"), "", "collinear vertices"),
        ("terrain-emissivity.ron", edit(RAWRON, "emissivity: 1.0", "emissivity: 1.5"), "emissivity", "terrain emissivity 1.5"),
        ("coordinate-huge.ron", edit(RAWRON, "(10.0, -10.0, 0.0)", "(1e300, -10.0, 0.0)"), "", "a coordinate of 10^300 m"),
        ("terrain-temperature-nan.ron", edit(RAWRON, "temperature_k: 286.0", "temperature_k: NaN"), "", "a NaN terrain temperature"),
    ],
)

# ---------------------------------------------------------------- object, binary
def bobj(name=b"tri", source=b"hand-made", positions=None, facets=None, magic=b"IRSIGOBJ",
         version=1, flags=0, counts=None, extra=b""):
    """The binary object of formats/canonical/object.md (as ../object/generate.py)."""
    positions = positions if positions is not None else [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0)]
    facets = facets if facets is not None else [((0, 1, 2), 1, 300.0)]
    n_p, n_f = counts if counts else (len(positions), len(facets))
    out = magic + struct.pack("<IIIIII", version, flags, len(name), len(source), n_p, n_f) + name + source
    for p in positions:
        out += struct.pack("<3d", *p)
    for v, m, t in facets:
        flag = t if isinstance(t, tuple) else (0 if t is None else 1, 0.0 if t is None else t)
        out += struct.pack("<3IHHd", *v, m, *flag)
    return out + extra


BOBJ = bobj()
folder(
    "object-binary",
    "Malformed binary objects (`IRSIGOBJ`, formats/canonical/object.md), read by "
    "`irsig-flatten --object`: `base/scene.ron` places `tri.ron`, taken from the case.",
    "irsig-flatten",
    BASE + "/scene.ron --object tri.ron={in} --materials " + MATERIALS + " -o {out}/scene.raw",
    [
        ("empty.bin", b"", "", "an empty file"),
        ("magic-only.bin", b"IRSIGOBJ", "", "the magic and nothing else"),
        ("wrong-magic.bin", bobj(magic=b"IRSIGRAW"), "IRSIGOBJ", "a raw scene's magic"),
        ("version-2.bin", bobj(version=2), "version", "version 2"),
        ("flags.bin", bobj(flags=1), "", "reserved flags not 0"),
        ("truncated.bin", BOBJ[:-3], "", "cut inside the facet"),
        ("trailing-bytes.bin", bobj(extra=b"\0\0"), "", "bytes after the last facet"),
        ("facet-count-huge.bin", bobj(counts=(3, 0xFFFFFFFF)), "", "4 × 10^9 facets claimed"),
        ("position-count-huge.bin", bobj(counts=(0xFFFFFFFF, 1)), "", "4 × 10^9 positions claimed"),
        ("name-not-utf8.bin", bobj(name=b"tr\xffi"), "UTF-8", "a non-UTF-8 name"),
        ("source-not-utf8.bin", bobj(source=b"hand\xc0made"), "UTF-8", "a non-UTF-8 source"),
        ("nan.bin", bobj(positions=[(0.0, 0.0, 0.0), (float("nan"), 0.0, 0.0), (0.0, 1.0, 0.0)]), "", "a NaN coordinate"),
        ("inf.bin", bobj(positions=[(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, float("-inf"), 0.0)]), "", "an infinite coordinate"),
        ("coordinate-huge.bin", bobj(positions=[(0.0, 0.0, 0.0), (1e300, 0.0, 0.0), (0.0, 1.0, 0.0)]), "", "a coordinate of 10^300 m"),
        ("index-out-of-range.bin", bobj(facets=[((0, 1, 3), 1, 300.0)]), "", "a vertex index past the positions"),
        ("material-zero.bin", bobj(facets=[((0, 1, 2), 0, 300.0)]), "", "material 0"),
        ("material-unknown.bin", bobj(facets=[((0, 1, 2), 77, 300.0)]), "77", "a material not in the library"),
        ("temperature-flag-2.bin", bobj(facets=[((0, 1, 2), 1, (2, 300.0))]), "", "a temperature flag of 2"),
        ("temperature-negative.bin", bobj(facets=[((0, 1, 2), 1, -5.0)]), "", "a negative temperature"),
        ("temperature-nan.bin", bobj(facets=[((0, 1, 2), 1, float("nan"))]), "", "a NaN temperature"),
        ("degenerate.bin", bobj(positions=[(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (2.0, 0.0, 0.0)]), "", "collinear vertices"),
        ("no-facets.bin", bobj(facets=[]), "", "no facet"),
    ],
)

# ---------------------------------------------------------------- radiative-transfer files
# Each case is a copy of base/plan (a valid plan whose four runs all have their TAPE7, so
# that LOWTRAN7 never runs) with one file replaced; irsig-atmos build reads the plan folder.
PLAN = HERE / "base/plan"
T5 = (PLAN / "runs/0000.tape5").read_text()
T6 = (PLAN / "runs/0000.tape6").read_text()
T7 = (PLAN / "runs/0000.tape7").read_text()
MODTRAN = (ROOT / "tests/data/malformed/radtran/modtran-column-count/runs/0000.tape7").read_bytes().decode()


def plan_cases(folder_name, target, cases):
    """(case, contents of runs/`target`, fragment, what) -> cases whose file is
    `case/runs/target` and whose arguments name the case's plan folder."""
    out = []
    for case, contents, fragment, what in cases:
        files = {f"{case}/plan.ron": (PLAN / "plan.ron").read_text()}
        for f in sorted((PLAN / "runs").iterdir()):
            if f.suffix != ".tape6":
                files[f"{case}/runs/{f.name}"] = f.read_text()
        if target.endswith(".tape5"):
            # A deck that fails must not be run: no TAPE7 for it.
            del files[f"{case}/runs/0000.tape7"]
        if target.endswith(".tape7"):
            # The profile comes from a TAPE6: beside another run's TAPE7.
            files[f"{case}/runs/0001.tape6"] = T6
        files[f"{case}/runs/{target}"] = contents
        args = f"build tests/data/malformed/{folder_name}/{case} -o {{out}}/a.spa"
        out.append((f"{case}/runs/{target}", files, fragment, what, args))
    return out


def columns(line, start, width, value):
    """`line` with columns start..start+width (1-based) set to `value`, right-aligned."""
    line = line.ljust(start - 1 + width)
    return line[: start - 1] + value.rjust(width)[:width] + line[start - 1 + width :]


T5_LINES = T5.splitlines()


def t5_with(card, start, width, value):
    lines = list(T5_LINES)
    lines[card] = columns(lines[card], start, width, value)
    return "\n".join(lines) + "\n"


def swap_v1_v2():
    """The base deck with card 4's V1 and V2 (F10.3 each, columns 1-20) swapped."""
    lines = list(T5_LINES)
    card4 = lines[3]
    lines[3] = card4[10:20] + card4[0:10] + card4[20:]
    return "\n".join(lines) + "\n"


def deck_beside_its_tape7(case, contents, fragment, what):
    """A deck off the plan with the good deck's TAPE7 still beside it: build reads that
    TAPE7 instead of running LOWTRAN7, so the deck's own check is all that refuses it."""
    ((file, files, fragment, what, args),) = plan_cases("tape5", "0000.tape5", [(case, contents, fragment, what)])
    files[f"{case}/runs/0000.tape7"] = (PLAN / "runs/0000.tape7").read_text()
    return (file, files, fragment, what, args)


folder(
    "tape5",
    "Malformed LOWTRAN7 card decks (formats/radtran/tape5.md), read by `irsig-atmos build` "
    "from a plan folder (each case is a copy of `base/plan` with `runs/0000.tape5` broken "
    "and no TAPE7 for it).",
    "irsig-atmos",
    "",
    plan_cases("tape5", "0000.tape5", [
        ("empty", "", "", "an empty deck"),
        ("card1-only", T5_LINES[0] + "\n", "", "only card 1"),
        ("model-letter", t5_with(0, 1, 5, "x"), "", "MODEL is `x`"),
        ("model-8", t5_with(0, 1, 5, "8"), "MODEL", "MODEL 8 (0-7)"),
        ("itype-4", t5_with(0, 6, 5, "4"), "ITYPE", "ITYPE 4 (1-3)"),
        ("iemsct-9", t5_with(0, 11, 5, "9"), "IEMSCT", "IEMSCT 9 (0-3)"),
        ("tbound-letters", t5_with(0, 66, 8, "abc"), "", "TBOUND is letters"),
        ("non-ascii", edit(T5, "0.000   0.00", "0.000   0.0\u00e9"), "", "an é in card 1"),
        ("control-char", edit(T5, "0.000   0.00", "0.000   0.0\x07"), "", "a BEL character in card 1"),
        ("dv-zero", t5_with(3, 21, 10, "0.000"), "DV", "DV = 0"),
        ("dv-negative", t5_with(3, 21, 10, "-90.000"), "DV", "DV < 0"),
        ("h1-letters", t5_with(2, 1, 10, "one"), "", "H1 is a word"),
        ("angle-other-path", t5_with(2, 21, 10, "170.000"), "path 0", "a deck whose path is not the plan's"),
        ("no-card4", "\n".join(T5_LINES[:3]) + "\n", "", "ends before card 4"),
        ("no-card5", "\n".join(T5_LINES[:4]) + "\n", "", "ends before card 5"),
        ("two-calculations", "\n".join(T5_LINES[:4]) + "\n    3\n" + T5_LINES[2] + "\n    0\n", "", "IRPT 3 chains a second path"),
        ("model-negative", t5_with(0, 1, 5, "-1"), "MODEL", "MODEL −1"),
        ("nan", t5_with(2, 1, 10, "NaN"), "", "H1 is NaN"),
        ("binary", b"\x00\x01\x02\xff" * 20, "", "bytes that are not text"),
        ("crlf-truncated", T5.replace("\n", "\r\n")[:150], "", "a CRLF deck cut inside card 3"),
    ]) + [
        deck_beside_its_tape7("v1-above-v2-given-tape7", swap_v1_v2(), "card 4", "V1 and V2 swapped, with LOWTRAN7's TAPE7 of the good deck given beside it"),
        deck_beside_its_tape7("dv-other-given-tape7", t5_with(3, 21, 10, "10.000"), "card 4", "DV 10 where the plan has 90, with the good deck's TAPE7 given beside it"),
    ],
)

T7_LINES = T7.splitlines()
T7_ROW = T7_LINES[11]
folder(
    "lowtran-tape7",
    "Malformed LOWTRAN7 TAPE7 files (formats/radtran/lowtran-tape7.md), read by `irsig-atmos "
    "build` from a plan folder (each case is a copy of `base/plan` with `runs/0000.tape7` "
    "broken).",
    "irsig-atmos",
    "",
    plan_cases("lowtran-tape7", "0000.tape7", [
        ("empty", "", "", "an empty file"),
        ("no-end", T7.replace(" -9999.\n", ""), "", "no ` -9999.` line"),
        ("header-only", "\n".join(T7_LINES[:11]) + "\n -9999.\n", "", "the column header and no row"),
        ("short-row", edit(T7, T7_ROW, T7_ROW[:23]), "", "a row of two numbers"),
        ("extra-row-value", edit(T7, T7_ROW, T7_ROW + " 5.0"), "", "a row with one number too many"),
        ("nan", edit(T7, "0.4790", "   NaN"), "", "τ is NaN"),
        ("asterisks", edit(T7, "0.4790", "******"), "", "τ printed as asterisks"),
        ("transmission-above", edit(T7, "0.4790", "1.4790"), "", "τ = 1.479"),
        ("transmission-negative", edit(T7, "0.4790", "-.4790"), "", "τ < 0"),
        ("radiance-negative", edit(T7, "6.71E-06", "-6.7E-06"), "", "a negative radiance"),
        ("repeated-wavenumber", edit(T7, "   800.", "   710."), "", "710 cm⁻¹ twice"),
        ("falling-wavenumber", edit(T7, "   890.", "   750."), "", "the wavenumber falls"),
        ("wrong-header", edit(T7, "  FREQ   TRANS     ATMOS", "  FREQ   TRANS     SOLAR"), "", "a column header LOWTRAN never writes"),
        ("iemsct-0", edit(T7, T7_LINES[0], columns(T7_LINES[0], 11, 5, "0")), "", "card 1 says IEMSCT 0 but the rows are radiance rows"),
        ("modtran-like", "T" + T7, "columns", "starts with a letter, so is read as MODTRAN, which it is not"),
        ("non-utf8", edit(T7, "TROPICAL", "TROP\xccCAL").encode("latin-1"), "UTF-8", "a Latin-1 byte in the model name"),
        ("truncated-row", T7[: T7.index(T7_ROW) + 20], "", "cut inside the first row"),
        ("word-in-row", edit(T7, "0.7023", "abcdef"), "", "a word for τ"),
        ("grid-differs", edit(T7, "  1250.  0.3573", "  1240.  0.3573"), "", "a grid that is not the other runs' (ends at 1240 cm⁻¹)"),
        ("inf", edit(T7, "3.38E-06", "Infinity"), "", "an infinite radiance"),
        ("misspelt-header", edit(T7, "ATMOS   PATH", "ATMOS   PAHT"), "column headers LOWTRAN7 writes", "`PAHT` for `PATH`: a header LOWTRAN never writes, word for word"),
        ("header-extra-column", edit(T7, "TOTAL RAD", "TOTAL RAD   EXTRA"), "column headers LOWTRAN7 writes", "a column added to LOWTRAN's header"),
    ]),
)

M_LINES = MODTRAN.split("\r\n")
M_HEADER = next(i for i, l in enumerate(M_LINES) if l.split()[:1] == ["FREQ"])
# The header of pyradi's tape7-05 and its first row, repeated on the plan's grid
# (710-1250 cm-1 every 90), so that the base builds with the other runs' TAPE7s.
M_ROW = M_LINES[M_HEADER + 1]
GOOD_M = "\r\n".join(
    M_LINES[: M_HEADER + 1]
    + [M_ROW.replace(" 2050.00", f"{w:8.2f}", 1) for w in range(710, 1251, 90)]
    + [" -9999."]
) + "\r\n"
M_ROW = GOOD_M.split("\r\n")[M_HEADER + 1]
folder(
    "modtran-tape7",
    "Malformed MODTRAN tape7 files (formats/radtran/modtran-tape7.md), read by `irsig-atmos "
    "build` from a plan folder (each case is a copy of `base/plan` with `runs/0000.tape7` "
    "replaced by a broken cut of pyradi's `tape7-05`, radiance mode, CRLF).",
    "irsig-atmos",
    "",
    plan_cases("modtran-tape7", "0000.tape7", [
        ("no-end", GOOD_M.replace(" -9999.\r\n", ""), "", "no ` -9999.` line"),
        ("no-header", "\r\n".join(M_LINES[:M_HEADER]) + "\r\n -9999.\r\n", "", "no FREQ header"),
        ("no-rows", "\r\n".join(M_LINES[: M_HEADER + 1]) + "\r\n -9999.\r\n", "", "a header and no row"),
        ("short-row", edit(GOOD_M, M_ROW, M_ROW[:40]), "", "a row short of columns"),
        ("long-row", edit(GOOD_M, M_ROW, M_ROW + " 1.0"), "", "a row with one number too many"),
        ("nan", edit(GOOD_M, "0.74772996", "       NaN"), "", "τ is NaN"),
        ("transmission-above", edit(GOOD_M, "0.74772996", "1.74772996"), "", "τ = 1.75"),
        ("radiance-negative", edit(GOOD_M, "5.6037E-08", "-5.604E-08"), "", "a negative path radiance"),
        ("repeated-frequency", GOOD_M.replace("  800.00", "  710.00"), "", "710 cm⁻¹ twice"),
        ("falling-frequency", GOOD_M.replace("  890.00", "  750.00"), "", "the frequency falls"),
        ("transmittance-mode", edit(GOOD_M, "TOT_TRANS", "TOT_TRANZ"), "", "no τ column name irsig knows"),
        ("no-path-radiance", edit(GOOD_M, "PTH_THRML", "PTH_THRMX"), "", "no `PTH_THRML` column"),
        ("word-in-row", edit(GOOD_M, "0.74772996", "abcdefghij"), "", "a word for τ"),
        ("non-utf8", edit(GOOD_M, "U S STANDARD", "U S ST\xc4NDARD").encode("latin-1"), "UTF-8", "a Latin-1 byte in the model name"),
        ("truncated", GOOD_M[: GOOD_M.index(M_ROW) + 30], "", "cut inside the first row"),
        ("lf-mixed-repeated", GOOD_M.replace("\r\n", "\n", 5).replace("  980.00", "  890.00"), "", "LF and CRLF mixed, and a repeated frequency"),
        ("header-only-letters", "T F\r\n FREQ\r\n -9999.\r\n", "", "a letter, a FREQ header of one column, nothing else"),
        ("asterisks", edit(GOOD_M, "5.6037E-08", "**********"), "", "a radiance printed as asterisks"),
        ("inf", edit(GOOD_M, "5.6037E-08", "  Infinity"), "", "an infinite radiance"),
        ("grid-differs", "\r\n".join(M_LINES[: M_HEADER + 3] + [" -9999."]) + "\r\n", "grid", "pyradi's first two rows, on 2050-2051 cm⁻¹, unlike the other runs' 710-1250 cm⁻¹"),
    ]),
)

T6_LINES = T6.splitlines()
folder(
    "lowtran-tape6",
    "Malformed LOWTRAN7 TAPE6 listings (formats/radtran/lowtran-tape6.md), read by "
    "`irsig-atmos build` beside a run's given TAPE7 (each case is a copy of `base/plan` "
    "with `runs/0000.tape6` broken; `base/plan/runs/0000.tape6` is LOWTRAN7's own, cut "
    "down to its first profile table and its spectral table).",
    "irsig-atmos",
    "",
    plan_cases("lowtran-tape6", "0000.tape6", [
        ("empty", "", "", "an empty file"),
        ("no-banner", "\n".join(T6_LINES[1:]) + "\n", "", "no `***** LOWTRAN 7 *****` banner"),
        ("profile-row-short", edit(T6, next(l for l in T6_LINES if l.startswith("   2     1.00")), "   2     1.00  904.000"), "", "a profile row of three numbers (no T)"),
        ("profile-nan", edit(T6, "293.7", "  NaN"), "", "a NaN temperature in the profile"),
        ("profile-asterisks", edit(T6, "293.7", "*****"), "", "a temperature printed as asterisks"),
        ("profile-word", edit(T6, "904.000", "pascal!"), "", "a word for a pressure"),
        ("spectral-row-short", edit(T6, "    800.  12.500  6.71E-06  4.29E-04  1.21E-03   0.4790", "    800.  12.500  6.71E-06"), "", "a spectral row short of numbers"),
        ("spectral-repeated", edit(T6, "    800.  12.500", "    710.  12.500"), "", "a wavenumber repeated"),
        ("spectral-falling", edit(T6, "    890.  11.236", "    750.  11.236"), "", "a wavenumber falling"),
        ("spectral-infinity", edit(T6, "6.71E-06", "Infinity"), "", "an infinite radiance"),
        ("integral-word", edit(T6, "2.200E-03 WATTS", "lots      WATTS"), "", "an integral that is not a number"),
        ("average-word", edit(T6, "=0.6093", "=abcdef"), "", "an average transmittance that is not a number"),
        ("non-utf8", edit(T6, "ATMOSPHERIC PROFILES", "ATMOSPH\xc9RIC PROFILES").encode("latin-1"), "UTF-8", "a Latin-1 byte"),
        ("truncated", T6[: T6.index("   3     2.00")], "", "cut inside the profile"),
        ("banner-only", T6_LINES[0] + "\n", "", "the banner and nothing else"),
        ("binary", b"\x00" * 64, "", "zero bytes"),
        ("profile-only-one-level", "\n".join(l for l in T6_LINES if not l.startswith(("   2 ", "   3 ", "   4 ", "   5 ", "   6 ", "  30 ", "  31 ", "  32 ", "  33 "))) + "\n", "", "a profile of one level"),
        ("spectral-nan", edit(T6, "0.7023", "   NaN"), "", "τ is NaN"),
        ("spectral-word", edit(T6, "6.71E-06", "lots-of-"), "", "a word for a radiance"),
        ("crlf-truncated", T6.replace("\n", "\r\n")[:400], "", "CRLF, cut after the card echoes"),
        ("profile-z-blank", edit(T6, next(l for l in T6_LINES if l.startswith("   2     1.00")), "   2         " + next(l for l in T6_LINES if l.startswith("   2     1.00"))[13:]), "blank field", "row 2's Z left blank: read by words, P became Z and T became P (finding 7 of the third hardening pass)"),
        ("profile-shifted", edit(T6, next(l for l in T6_LINES if l.startswith("   2     1.00")), "   2  1.00   " + next(l for l in T6_LINES if l.startswith("   2     1.00"))[13:]), "right-aligned", "row 2's Z out of its columns (F9.2, 5-13)"),
        ("spectral-extra-field", edit(T6, "    800.  12.500  6.71E-06  4.29E-04  1.21E-03   0.4790", "    800.  12.500  6.71E-06  4.29E-04  1.21E-03   0.4790 7"), "end of", "a seventh number after a row's last column"),
        ("card1-iemsct-blank", edit(T6, "0 CARD 1  *****    1    2    1", "0 CARD 1  *****    1    2     "), "IEMSCT", "the echo of card 1 without its IEMSCT"),
        ("header-renamed", edit(T6, "ATMOS RADIANCE       INTEGRAL", "ATMOS RADIANZE       INTEGRAL"), "column headers LOWTRAN7 prints", "a column of the table's header renamed"),
        ("spectral-negative", edit(T6, "6.71E-06", "-6.7E-06"), "from 0", "a negative radiance"),
        ("spectral-huge", edit(T6, "6.71E-06", "1.00E+99"), "from 0", "a radiance of 1e99 W cm-2 sr-1 per cm-1: finite, and no atmosphere's"),
        ("transmittance-above", edit(T6, "0.4790", "1.4790"), "transmittance", "τ = 1.479"),
        ("table-empty", "\n".join(l for l in T6_LINES if not l.startswith(("    710.", "    800.", "    890.", "    980.", "   1070.", "   1160.", "   1250."))) + "\n", "found none", "a column header and no rows under it"),
        ("table-cut", T6[: T6.index("    890.  11.236")], "cut", "cut inside the spectral table, before its INTEGRATED line"),
    ]),
)


PLAN_RON = (PLAN / "plan.ron").read_text()


def plan_ron_cases(folder_name, cases):
    """(case, contents of plan.ron, fragment, what) -> cases whose file is `case/plan.ron`
    beside the base plan's runs."""
    out = []
    for case, contents, fragment, what in cases:
        files = {f"{case}/plan.ron": contents}
        for f in sorted((PLAN / "runs").iterdir()):
            files[f"{case}/runs/{f.name}"] = f.read_text()
        args = f"build tests/data/malformed/{folder_name}/{case} -o {{out}}/a.spa"
        out.append((f"{case}/plan.ron", files, fragment, what, args))
    return out


folder(
    "atmosphere-plan",
    "Atmosphere plans (formats/canonical/atmosphere-plan.md) that break a rule of their page, "
    "read by `irsig-atmos build` (each case is a copy of `base/plan` with its `plan.ron` "
    "broken).",
    "irsig-atmos",
    "",
    plan_ron_cases("atmosphere-plan", [
        ("observer-below-path-end", edit(PLAN_RON, "observers_m: [1000.0]", "observers_m: [0.5]"), "paths' end", "an observer below the paths' end (1 m), which the page refuses and build used to accept (finding 8 of the third hardening pass)"),
        ("observer-at-path-end", edit(PLAN_RON, "observers_m: [1000.0]", "observers_m: [1.0]"), "paths' end", "an observer at the paths' end"),
        ("altitude-not-whole", edit(PLAN_RON, "slant_altitude_m: [1000.0]", "slant_altitude_m: [1000.5]"), "whole number of metres", "an altitude of 1000.5 m: its deck's F10.3 km runs 1001 m"),
        ("angle-not-thousandths", edit(PLAN_RON, "correction_nadir_deg: [0.0, 5.0, 10.0]", "correction_nadir_deg: [0.0, 5.0, 10.0005]"), "0.001", "a nadir angle of 10.0005°: its deck's F10.3 runs 10.001°"),
        ("sun-on-the-horizon", edit(PLAN_RON, "  sky_zenith_deg: [0.0],\n", "  sky_zenith_deg: [0.0],\n  sun: Some((zenith_deg: 90.0, day_of_year: 172, altitude_m: [0.0])),\n"), "horizon", "a sun 90° from the zenith: on the horizon, no direct light (issue 30)"),
        ("sun-day-zero", edit(PLAN_RON, "  sky_zenith_deg: [0.0],\n", "  sky_zenith_deg: [0.0],\n  sun: Some((zenith_deg: 30.0, day_of_year: 0, altitude_m: [0.0])),\n"), "day of the year", "a sun on day 0: days run 1-366"),
    ]),
)

DIRSIG_MAT = """MATERIAL_ENTRY {
    ID = 4
    NAME = water
    SURFACE_PROPERTIES {
        EMISSIVITY_PROP_NAME = ClassicEmissivity
        EMISSIVITY_PROP {
            FILENAME = good.ems
            SPECULAR_FRACTION = 0.9
        }
    }
}
"""
# A THERM temperature solver (formats/dirsig.md): water, 1 m deep, in DIRSIG's units.
DIRSIG_THERM = edit(DIRSIG_MAT, "    NAME = water\n", """    NAME = water
    TEMP_SOLVER_NAME = Therm
    TEMP_SOLVER {
        SPECIFIC_HEAT        = 1
        MASS_DENSITY         = 1
        THERMAL_CONDUCTIVITY = 0.6
        SOLAR_ABSORPTION     = 0.5
        THERMAL_EMISSIVITY   = 0.96
        EXPOSED_AREA         = 0.4
        THICKNESS            = 100
    }
""")
THERM_ARGS = "dirsig {in} --default-emissivity 0.9 --thermal-back adiabatic -o {out}/lib.ron"
folder(
    "dirsig-mat",
    "Malformed DIRSIG `.mat` files (formats/dirsig.md), read by `irsig-material dirsig`; "
    "`good.ems` is a valid curve file they name (DIRSIG's `muddy_water.ems`, see "
    "`../../third-party/dirsig-channel`).",
    "irsig-material",
    "dirsig {in} --default-emissivity 0.9 -o {out}/lib.ron",
    [
        ("filename-device.mat", edit(DIRSIG_MAT, "good.ems", "/dev/zero"), "not a regular file", "`FILENAME = /dev/zero`: read until memory ran out (2.1 GB; finding 5 of the third hardening pass)"),
        ("filename-twice.mat", edit(DIRSIG_MAT, "            SPECULAR_FRACTION", "            FILENAME = other.ems\n            SPECULAR_FRACTION"), "given twice", "a second FILENAME, which won silently (finding 13)"),
        ("name-empty.mat", edit(DIRSIG_MAT, "NAME = water", "NAME ="), "material name", "an empty NAME (finding 13)"),
        ("empty.mat", "", "MATERIAL_ENTRY", "an empty file: an empty library, rc 0 (finding 13)"),
        ("comment-only.mat", "# no entry here\n", "MATERIAL_ENTRY", "only a comment"),
        ("id-twice.mat", edit(DIRSIG_MAT, "    ID = 4\n", "    ID = 4\n    ID = 5\n"), "given twice", "ID twice in one entry"),
        ("output-is-ems.mat", DIRSIG_MAT, "both an output and an input", "the .ems it names given as the output (finding 4)", "dirsig {in} --default-emissivity 0.9 -o tests/data/malformed/dirsig-mat/good.ems", "2"),
        ("therm-no-back.mat", DIRSIG_THERM, "--thermal-back", "a THERM block without `--thermal-back`: DIRSIG does not say what lies behind the slab"),
        ("therm-thickness-zero.mat", edit(DIRSIG_THERM, "= 100\n", "= 0\n"), "THICKNESS 0", "`THICKNESS = 0`, which DIRSIG gives a meaning of its own", THERM_ARGS),
        ("therm-no-thickness.mat", edit(DIRSIG_THERM, "        THICKNESS            = 100\n", ""), "no THICKNESS", "no `THICKNESS`", THERM_ARGS),
        ("therm-exposed-negative.mat", edit(DIRSIG_THERM, "= 0.4\n", "= -0.4\n"), "negative", "a negative `EXPOSED_AREA`, which DIRSIG gives a meaning of its own", THERM_ARGS),
        ("therm-conductivity-zero.mat", edit(DIRSIG_THERM, "= 0.6\n", "= 0\n"), "out of range", "a slab that conducts no heat", THERM_ARGS),
        ("therm-nan.mat", edit(DIRSIG_THERM, "= 0.5\n", "= NaN\n"), "finite", "a NaN solar absorption", THERM_ARGS),
        ("therm-unknown-key.mat", edit(DIRSIG_THERM, "        THICKNESS", "        HEAT_SOURCE          = 5\n        THICKNESS"), "does not know", "a THERM key irsig does not know", THERM_ARGS),
        ("therm-key-twice.mat", edit(DIRSIG_THERM, "        THICKNESS", "        THICKNESS            = 50\n        THICKNESS"), "given twice", "`THICKNESS` twice", THERM_ARGS),
        ("therm-back-negative.mat", DIRSIG_THERM, "--thermal-back", "a back boundary that makes no sense (a negative convective coefficient)", "dirsig {in} --default-emissivity 0.9 --thermal-back convective:-3 -o {out}/lib.ron", "2"),
        ("therm-back-and-none.mat", DIRSIG_THERM, "cannot be used with", "`--thermal-back` and `--no-thermal` together", "dirsig {in} --default-emissivity 0.9 --thermal-back adiabatic --no-thermal -o {out}/lib.ron", "2"),
    ],
    extra={"good.ems": (ROOT / "tests/data/third-party/dirsig-channel/emissivity/muddy_water.ems").read_bytes()},
)

LUT = "# dc radiance_w_m2_sr temperature_k temperature_c\n0 4.77201355e1 288.4512 15.3012\n1 4.78439209e1 288.6163 15.4663\n2 4.79678955e1 288.7813 15.6313\n"
folder(
    "lut",
    "Malformed LUTs (formats/sensor.md), read by `irsig-report --lut` beside `base/truth.exr`.",
    "irsig-report",
    BASE + "/truth.exr --lut {in} -o {out}/r.html",
    [
        ("empty.lut", "", "none", "an empty file"),
        ("header-only.lut", "# dc radiance_w_m2_sr temperature_k temperature_c\n", "none", "the header and no row"),
        ("count-skips.lut", edit(LUT, "\n2 4.79", "\n3 4.79"), "digital count 2", "count 3 after 1"),
        ("count-from-one.lut", edit(edit(edit(LUT, "\n2 4.79", "\n3 4.79"), "\n1 4.78", "\n2 4.78"), "\n0 4.77", "\n1 4.77"), "digital count 0", "counts from 1"),
        ("three-columns.lut", edit(LUT, "288.6163 15.4663", "288.6163"), "4 columns", "a row of three fields"),
        ("nan.lut", edit(LUT, "288.6163", "NaN"), "temperature in K", "a NaN temperature"),
        ("word.lut", edit(LUT, "4.78439209e1", "lots"), "radiance", "a word for a radiance"),
        ("past-16-bits.lut", "# dc radiance_w_m2_sr temperature_k temperature_c\n" + "".join(f"{dc} 1 2 3\n" for dc in range(65537)), "65536 rows", "65,537 rows: counts of more than 16 bits"),
        ("non-utf8.lut", (LUT + "# \xb5\n").encode("latin-1"), "UTF-8", "a Latin-1 byte in a comment"),
    ],
)

folder(
    "report",
    "Inputs `irsig-report` refuses (formats/report.md, \"Inputs\"), beside `base/truth.exr`.",
    "irsig-report",
    BASE + "/truth.exr --colour-preview {in} -o {out}/r.html",
    [
        ("not-png.png", "P6\n4 4\n255\n", "PNG", "a PPM image named .png as the colour preview"),
        ("empty.png", b"", "PNG", "an empty colour preview"),
        ("profile-outside.png", b"\x89PNG\r\n\x1a\n", "outside the image", "a profile ending at pixel (4, 0) of the 4 × 4 image (bad usage)", BASE + "/truth.exr --colour-preview {in} --profile 0,0:4,0 -o {out}/r.html", "2"),
        ("report-is-preview.png", b"\x89PNG\r\n\x1a\n", "both an output and an input", "the colour preview named as the report too (finding 4)", BASE + "/truth.exr --colour-preview {in} -o {in}", "2"),
    ],
)

DIRSIG_EMS = "1\n" + "1.0\n" * 91 + "CURVE_BEGIN\n8.0 0.95\n11.0 0.96\n14.0 0.97\nCURVE_END\n"
DIRSIG_EMS_INDEX = "1\n" + "1.0\n" * 91 + "0\n1250 0.97\n909 0.96\n714 0.95\n"
EMS_CASES = [
    ("count-zero.ems", edit(DIRSIG_EMS, "1\n1.0\n", "0\n1.0\n"), "", "a count of 0 curves"),
    ("count-word.ems", edit(DIRSIG_EMS, "1\n1.0\n", "one\n1.0\n"), "", "the count a word"),
    ("count-above-curves.ems", edit(DIRSIG_EMS, "1\n1.0\n", "2\n1.0\n"), "", "2 curves declared, 1 given"),
    ("factors-short.ems", "1\n" + "1.0\n" * 90 + "CURVE_BEGIN\n8.0 0.95\n14.0 0.97\nCURVE_END\n", "", "90 angular factors of 91"),
    ("factor-above-one.ems", "1\n1.2\n" + "1.0\n" * 90 + "CURVE_BEGIN\n8.0 0.95\n14.0 0.97\nCURVE_END\n", "", "an angular factor of 1.2"),
    ("emissivity-above-one.ems", edit(DIRSIG_EMS, "11.0 0.96", "11.0 1.5"), "", "an emissivity of 1.5"),
    ("wavelengths-falling.ems", edit(DIRSIG_EMS, "11.0 0.96", "7.0 0.96"), "", "wavelengths falling in a CURVE_BEGIN curve"),
    ("wavenumbers-rising.ems", edit(DIRSIG_EMS_INDEX, "909 0.96", "1300 0.96"), "", "wavenumbers rising in an indexed curve (they decrease)"),
    ("index-wrong.ems", edit(DIRSIG_EMS_INDEX, "\n0\n1250", "\n1\n1250"), "", "a first curve indexed 1"),
    ("curve-one-row.ems", "1\n" + "1.0\n" * 91 + "CURVE_BEGIN\n8.0 0.95\nCURVE_END\n", "", "a curve of one row"),
    ("row-three-values.ems", edit(DIRSIG_EMS, "11.0 0.96", "11.0 0.96 3"), "", "a row of three numbers"),
    ("nan.ems", edit(DIRSIG_EMS, "11.0 0.96", "11.0 NaN"), "", "a NaN emissivity"),
    ("curves-other-wavelengths.ems", "2\n" + "1.0\n" * 91 + "CURVE_BEGIN\n8.0 0.95\n11.0 0.96\n14.0 0.97\nCURVE_END\nCURVE_BEGIN\n8.0 0.95\n12.0 0.96\n14.0 0.97\nCURVE_END\n", "share their wavelengths", "a second curve on other wavelengths: the curves of a file are averaged point by point"),
    ("non-utf8.ems", edit(DIRSIG_EMS, "CURVE_BEGIN", "CURVE_BEGIN # caf\xe9").encode("latin-1"), "UTF-8", "a Latin-1 byte"),
]
folder(
    "dirsig-ems",
    "Malformed DIRSIG `.ems` curve files (formats/dirsig.md), read by `irsig-material dirsig` "
    "through `NAME.mat`, a valid `.mat` beside each case naming it.",
    "irsig-material",
    "",
    [
        (name, contents, fragment, what, f"dirsig tests/data/malformed/dirsig-ems/{name[:-4]}.mat -o {{out}}/lib.ron")
        for name, contents, fragment, what in EMS_CASES
    ],
    extra={name[:-4] + ".mat": edit(DIRSIG_MAT, "good.ems", name) for name, *_ in EMS_CASES},
)

folder(
    "stderr-closed",
    "Errors reported to a stderr whose reader is gone (`tool 2>&1 | head -c1`): the tool "
    "exits with its own status, 1, never a panic (101; finding 9 of the third hardening "
    "pass). Run with stderr closed, so no message is checked.",
    "irsig-flatten",
    "{in} --materials " + MATERIALS + " -o {out}/scene.raw",
    [
        ("unknown-field.ron", "(objects: [Objekt()])\n", "", "an unknown struct name", None, "stderr-closed"),
        ("missing-object.ron", "(objects: [(object: \"absent.ron\")])\n", "", "an object that does not exist", None, "stderr-closed"),
    ],
)


# ---------------------------------------------------------------- banded EXRs
def with_comments(exr_bytes, comments):
    """`exr_bytes` (a scanline EXR) with a `comments` string attribute, where irsig records
    an image's provenance: added at the header's end, the offset table moved along."""
    i = 8
    count = None
    while exr_bytes[i] != 0:
        j = exr_bytes.index(b"\0", i)
        name = exr_bytes[i:j]
        k = exr_bytes.index(b"\0", j + 1)
        (n,) = struct.unpack("<i", exr_bytes[k + 1 : k + 5])
        if name == b"chunkCount":
            (count,) = struct.unpack("<i", exr_bytes[k + 5 : k + 9])
        i = k + 5 + n
    attr = b"comments\0string\0" + struct.pack("<i", len(comments)) + comments
    head, rest = exr_bytes[:i], exr_bytes[i + 1 :]
    table = [struct.unpack("<Q", rest[8 * c : 8 * c + 8])[0] + len(attr) for c in range(count)]
    return head + attr + b"\0" + b"".join(struct.pack("<Q", t) for t in table) + rest[8 * count :]


TRUTH_EXR = (HERE / "base/truth.exr").read_bytes()
SHA = "sha256:" + "ab" * 32
RECORD = """irsig provenance (canonical RON)
(
    band: BAND,
    sub_bands: "1",
    atmosphere: "none",
    atmosphere_model: "none",
    inputs: [(stage: "trace", role: "scene", sha256: "SHA")],
)
"""


def banded(band, record=RECORD):
    return with_comments(TRUTH_EXR, record.replace("BAND", band).replace("SHA", SHA).encode())


FLAT_8_14 = "Flat(min_um: 8.0, max_um: 14.0)"
BANDED_CASES = [
    ("band-reversed.exr", banded("Flat(min_um: 14.0, max_um: 8.0)"), "max_um", "a band from 14 to 8 µm"),
    ("band-nan.exr", banded("Flat(min_um: NaN, max_um: 14.0)"), "min_um", "a band from NaN µm"),
    ("band-missing.exr", with_comments(TRUTH_EXR, RECORD.replace("    band: BAND,\n", "").replace("SHA", SHA).encode()), "band", "no band in the record"),
    ("comments-not-utf8.exr", with_comments(TRUTH_EXR, RECORD.replace("BAND", FLAT_8_14).replace("SHA", SHA).encode().replace(b"scene", b"sc\xe9ne")), "", "a Latin-1 byte in the record"),
    ("response-hash-short.exr", banded('Response(sha256: "sha256:00", wavelength_um: [8.0, 10.0, 12.0], response: [0.0, 1.0, 0.0])'), "sha256", "a response band whose hash is `sha256:00`"),
    ("input-hash-short.exr", with_comments(TRUTH_EXR, RECORD.replace("BAND", FLAT_8_14).replace("SHA", "sha256:0").encode()), "sha256", "an input whose hash is `sha256:0`"),
    ("response-decreasing.exr", banded(f'Response(sha256: "{SHA}", wavelength_um: [8.0, 12.0, 10.0], response: [0.0, 1.0, 0.0])'), "wavelength_um", "a response whose wavelengths fall"),
]
ALL_REGION = '(regions: [(name: "all", pixels: Some((columns: (0, 3), rows: (0, 3))))])\n'
BANDED_TITLE = (
    "Truth EXRs whose provenance (formats/images.md, the `comments` attribute) is "
    "malformed, read at the record's line and column by `{tool}` as by every stage that "
    "reads an image; and a `--band` that is not the band an image records, refused "
    "(exit 2) whether or not a radiance image is converted."
)
folder(
    "banded-exr",
    BANDED_TITLE.format(tool="irsig-stats"),
    "irsig-stats",
    "{in} --regions tests/data/malformed/banded-exr/all.ron -o {out}/stats.txt",
    BANDED_CASES
    + [
        ("records-8-14-band-8-12.exr", banded(FLAT_8_14), "is not the band", "an 8-14 µm image, `--band 8-12`, no radiance image", "{in} --regions tests/data/malformed/banded-exr/all.ron --band 8-12 -o {out}/stats.txt", "2"),
        ("records-8-14-band-8-14.exr", banded(FLAT_8_14), "", "an 8-14 µm image with its own band given", "{in} --regions tests/data/malformed/banded-exr/all.ron --band 8-14 -o {out}/stats.txt", "0"),
    ],
    extra={"all.ron": ALL_REGION},
)
folder(
    "banded-exr-report",
    BANDED_TITLE.format(tool="irsig-report"),
    "irsig-report",
    "{in} -o {out}/r.html",
    BANDED_CASES
    + [
        ("records-8-14-band-8-12.exr", banded(FLAT_8_14), "is not the band", "an 8-14 µm image, `--band 8-12`, no radiance image", "{in} --band 8-12 -o {out}/r.html", "2"),
    ],
)
folder(
    "banded-exr-sensor",
    BANDED_TITLE.format(tool="irsig-sensor"),
    "irsig-sensor",
    "{in} --mtf box:1x1 -o {out}/s.exr",
    BANDED_CASES,
)


def write(path, contents):
    path.parent.mkdir(parents=True, exist_ok=True)
    if isinstance(contents, str):
        contents = contents.encode()
    path.write_bytes(contents)


def main():
    write(HERE / "base/scene.ron", "// A valid scene placing tri.ron (given with --object NAME=PATH by the cases).\n" + SCENE)
    for name, title, tool, args, cases, extra in FOLDERS:
        d = HERE / name
        if d.exists():
            shutil.rmtree(d)
        d.mkdir()
        seen = set()
        lines = ["# file\ttool\targuments ({in}: the case, {out}: an empty folder)\tmessage fragment\t[expected: 1 by default, 2, 0 or stderr-closed]"]
        table = ["| file | what is wrong |", "| --- | --- |"]
        for file, contents, fragment, what, *case_args in cases:
            assert file not in seen, file
            seen.add(file)
            if isinstance(contents, dict):
                for f, c in contents.items():
                    write(d / f, c)
            else:
                write(d / file, contents)
            case_args = list(case_args) + [None, None]
            expect = case_args[1] or "1"
            line = f"{file}\t{tool}\t{case_args[0] or args}\t{fragment}"
            if expect != "1":
                line += f"\t{expect}"
            lines.append(line)
            outcome = {"1": "", "2": " (expected: bad usage, exit 2)", "0": " (expected: success, exit 0)", "stderr-closed": " (expected: exit 1 with stderr closed)"}[expect]
            table.append(f"| `{file}` | {what}{outcome} |")
        for file, contents in extra.items():
            write(d / file, contents)
        write(d / "cases.tsv", "\n".join(lines) + "\n")
        readme = [
            f"# {name}",
            "",
            title,
            "",
            "Written by `../generate.py`, which also writes `cases.tsv`, the manifest that",
            "`tests/tests/malformed_corpus.rs` runs: exit 1, the file named with a line and",
            "column, the fragment in the message, nothing written (unless a case says",
            "otherwise: bad usage, exit 2, nothing written; success, exit 0; or exit 1 with",
            "stderr closed), and the case's own file as it was.",
            "",
        ] + table
        write(d / "README.md", "\n".join(readme) + "\n")


if __name__ == "__main__":
    main()
