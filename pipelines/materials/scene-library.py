#!/usr/bin/env python3
"""Rebuilds scene-library.ron, the library of scene materials valid over 3-14 um, each with
its thermal properties, from the source data under sources/ (SOURCES.md says where each
file comes from and under which licence). Standard library only; the Fresnel surfaces are
made by `irsig-material fresnel` (on PATH, or IRSIG_MATERIAL=path/to/irsig-material). Run
from the repository root:

    python3 pipelines/materials/scene-library.py > pipelines/materials/scene-library.ron

tests/tests/scene_library.rs checks that the committed library is what this script makes.

What the script does, per kind of source (each material's `source` says which):

- n, k tables (refractiveindex.info, CC0): the rows are interpolated linearly (as
  irsig-material interpolates them) onto the library's grid (0.30-2.50 um every 0.05 um,
  2.6-15.0 um every 0.1 um; only grid points inside the table, so nothing is extrapolated)
  and given to `irsig-material fresnel --nk-table -`, which computes the opaque surface's
  emissivity: smooth (a mirror, with epsilon(lambda, theta) on a grid of angles) or rough
  (RMS facet slope, Gaussian slopes; the separable form, the angular shape its 8-14 um
  table's).
- DIRSIG .ems curves (emissivity): the mean of a file's curves, interpolated linearly onto
  the library's grid; the angular shape is a rough surface's of irsig-material fresnel
  (the fitted grass of rough-surfaces.ron). The grass curve serves the grass and, as named
  models, two tree canopies.
- Coatings: a paint is the opaque, smooth surface of its binder (PMMA's n, k; pigments
  set only its cited solar absorptance); an anodised sheet is an alumina film on aluminium,
  its multiple reflections summed incoherently (film_on_metal). Both separable.
- Assemblies (a roof, double glazing, a car panel) are thermal records of several layers
  under a surface the library already has.

Every emissivity is written to 6 decimals. Thermal properties are handbook values, each
layer's `source` naming its table.
"""

import math
import os
import re
import subprocess
import sys

HERE = "pipelines/materials"
SRC = HERE + "/sources"
TOOL = os.environ.get("IRSIG_MATERIAL") or "irsig-material"

# The library's wavelength grid, um: every 0.1 um from 0.3 to 15 um. Metals, whose n, k
# change slowly, take every 0.25 um beyond 2.5 um (their epsilon(lambda, theta) grids are
# most of a library's bytes, and a trace reads them all).
GRID = [round(0.3 + 0.1 * i, 1) for i in range(148)]
METAL_GRID = GRID[:23] + [round(2.75 + 0.25 * i, 2) for i in range(50)]
# Angles of a smooth surface's epsilon(lambda, theta) grid: dense towards grazing, where a
# Fresnel surface's emissivity turns fastest (a metal's peaks near 85-88 deg).
SMOOTH_ANGLES = "0,10,20,30,40,50,60,65,70,75,80,84,87,89,90"
ROUGH_ANGLES = "0:90:5"

# ---- citations --------------------------------------------------------------------------

INC = "Incropera & DeWitt, Fundamentals of Heat and Mass Transfer, 6th ed. (2007)"
INC_A1 = INC + ", Table A.1 (300 K)"
INC_A3 = INC + ", Table A.3 (300 K)"
INC_A13 = INC + ", Table A.13"
OKE = "Oke, Boundary Layer Climates, 2nd ed. (1987)"
OKE_21 = OKE + ", Table 2.1"
OKE_11 = OKE + ", Table 1.1"
CC0 = "refractiveindex.info database, CC0 1.0"
# Each refractiveindex.info page as the search tool's stored copy has it: its path in
# github.com/polyanskiy/refractiveindex.info-database (under database/data/) and the commit
# of that copy (sources/SOURCES.md).
RI_PAGES = {
    "water-hale.yml": ("main/H2O/nk/Hale.yml", "37773dce"),
    "ice-warren-2008.yml": ("main/H2O/nk/Warren-2008.yml", "37773dce"),
    "aluminium-rakic.yml": ("main/Al/nk/Rakic.yml", "37773dce"),
    "iron-querry.yml": ("main/Fe/nk/Querry.yml", "c817541a"),
    "hematite-querry-o.yml": ("main/Fe2O3/nk/Querry-o.yml", "37773dce"),
    "zinc-querry.yml": ("main/Zn/nk/Querry.yml", "37773dce"),
    "copper-querry.yml": ("main/Cu/nk/Querry.yml", "37773dce"),
    "titanium-rakic-bb.yml": ("main/Ti/nk/Rakic-BB.yml", "c817541a"),
    "soda-lime-rubin-clear.yml": ("glass/misc/soda-lime/nk/Rubin-clear.yml", "37773dce"),
    "soda-lime-rubin-ir.yml": ("glass/misc/soda-lime/nk/Rubin-IR.yml", "37773dce"),
    "alumina-franta.yml": ("main/Al2O3/nk/Franta.yml", "37773dce"),
    "pmma-zhang-mitsubishi.yml": ("organic/(C5H8O2)n - poly(methyl methacrylate)/nk/Zhang-Mitsubishi.yml", "37773dce"),
}


def ri_origin(*pages):
    """Where refractiveindex.info pages come from, as a material's source says it."""
    parts = [f"{RI_PAGES[p][0]} @ {RI_PAGES[p][1]} (sources/refractiveindex/{p})" for p in pages]
    return f"{CC0}; github.com/polyanskiy/refractiveindex.info-database, database/data/" + " and ".join(parts)

# ---- small numerics ---------------------------------------------------------------------


def fmt(x):
    """A number as the library writes it: 6 decimals, trailing zeros dropped."""
    s = f"{x:.6f}".rstrip("0")
    return s + "0" if s.endswith(".") else s


def interp(xs, ys, x):
    """Linear interpolation in increasing xs; x must lie within them."""
    lo, hi = 0, len(xs) - 1
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if xs[mid] <= x:
            lo = mid
        else:
            hi = mid
    t = (x - xs[lo]) / (xs[hi] - xs[lo])
    return ys[lo] + t * (ys[hi] - ys[lo])


def grid_within(xs, grid=None):
    return [g for g in (grid or GRID) if xs[0] <= g <= xs[-1]]


def planck(lam_um, t_k):
    c1, c2 = 1.191042972e8, 1.438776877e4  # W um^4 m^-2 sr^-1, um K
    return c1 / lam_um**5 / (math.exp(c2 / (lam_um * t_k)) - 1.0)


def planck_mean(xs, ys, lo, hi, t_k, step=0.001):
    """Planck-weighted mean of a linear curve over [lo, hi] (midpoint rule, 1 nm cells)."""
    n = round((hi - lo) / step)
    num = den = 0.0
    for i in range(n):
        lam = lo + (i + 0.5) * step
        w = planck(lam, t_k)
        num += w * interp(xs, ys, lam)
        den += w
    return num / den


# ---- sources ----------------------------------------------------------------------------


def ri_rows(name):
    """The (um, n, k) rows of a refractiveindex.info YAML page: its `tabulated nk` block,
    or a `formula 5` n (n = C1 + C2 l^C3 + C4 l^C5) with a `tabulated k` block."""
    text = open(f"{SRC}/refractiveindex/{name}", encoding="utf-8").read()
    blocks = re.split(r"\n  - type: ", text)[1:]
    rows, formula, k_rows = [], None, []
    for b in blocks:
        kind = b.split("\n", 1)[0].strip()
        data = [l.split() for l in b.split("\n")[1:] if re.match(r"^\s+[0-9.]", l)]
        if kind == "tabulated nk":
            rows += [tuple(float(v) for v in r) for r in data if len(r) == 3]
        elif kind == "tabulated k":
            k_rows += [tuple(float(v) for v in r) for r in data if len(r) == 2]
        elif kind == "formula 5":
            formula = [float(v) for v in re.search(r"coefficients: (.*)", b).group(1).split()]
    if formula:
        c = formula
        rows += [(l, c[0] + c[1] * l ** c[2] + c[3] * l ** c[4], k) for l, k in k_rows]
    return sorted(rows)


def dirsig_mean(name):
    """(um, emissivity) of a DIRSIG .ems: the mean of its curves (rows in wavenumber,
    cm^-1, as irsig-material dirsig reads them), increasing in wavelength."""
    lines = open(f"{SRC}/dirsig/{name}", encoding="utf-8").read().splitlines()
    count = int(lines[0].split()[0])
    curves, cur = [], None
    for l in lines[92:]:
        p = l.split()
        if len(p) == 1:
            cur = []
            curves.append(cur)
        elif len(p) == 2:
            cur.append((float(p[0]), float(p[1])))
    assert len(curves) == count
    mean = [sum(c[i][1] for c in curves) / count for i in range(len(curves[0]))]
    return sorted((1e4 / curves[0][i][0], min(max(e, 0.0), 1.0)) for i, e in enumerate(mean))


# ---- irsig-material and its RON ---------------------------------------------------------


def parse_ron(s):
    """The subset of RON irsig writes: numbers, strings, lists, tuples, structs, Some,
    enum variants."""
    pos = 0

    def ws():
        nonlocal pos
        while pos < len(s) and s[pos] in " \n\r\t,":
            pos += 1

    def value():
        nonlocal pos
        ws()
        c = s[pos]
        if c == '"':
            m = re.compile(r'"((?:[^"\\]|\\.)*)"').match(s, pos)
            pos = m.end()
            return m.group(1).replace("\\'", "'").replace('\\"', '"')
        if s.startswith("Some(", pos):
            pos += 5
            v = value()
            ws()
            pos += 1
            return v
        if s.startswith("None", pos):
            pos += 4
            return None
        if c in "[(":
            close = "]" if c == "[" else ")"
            pos += 1
            items, named = [], {}
            while True:
                ws()
                if s[pos] == close:
                    pos += 1
                    return named if named else items
                m = re.compile(r"([a-z_][a-z0-9_]*):").match(s, pos)
                if m:
                    pos = m.end()
                    named[m.group(1)] = value()
                else:
                    items.append(value())
        m = re.compile(r"[A-Z][A-Za-z]*").match(s, pos)
        if m:  # an enum variant: its name, or its name and fields
            pos = m.end()
            return {m.group(0): value()} if s[pos] == "(" else m.group(0)
        m = re.compile(r"-?[0-9][0-9.eE+-]*").match(s, pos)
        pos = m.end()
        return float(m.group(0))

    return value()


def run_tool(args, stdin=None):
    out = subprocess.run([TOOL, "fresnel"] + args, input=stdin, capture_output=True, text=True)
    if out.returncode != 0:
        sys.exit(f"{TOOL} fresnel {' '.join(args)}: {out.stderr}")
    return parse_ron(out.stdout)["materials"][0]


def fresnel_nk(page, extra_rows=None, *args, grid=None):
    """The tool's material for an n, k table resampled onto the grid."""
    rows = ri_rows(page) if extra_rows is None else extra_rows
    xs = [r[0] for r in rows]
    ns, ks = [r[1] for r in rows], [r[2] for r in rows]
    table = "".join(f"{g} {interp(xs, ns, g):.6g} {interp(xs, ks, g):.6g}\n" for g in grid_within(xs, grid))
    return run_tool(["--nk-table", "-", "--band", "8-14", "--planck-temperature", "300"] + list(args), table)


def shape(*args):
    """A rough surface's angular table from a constant index: the shape of a spectrum."""
    return run_tool(["--angles", ROUGH_ANGLES] + list(args))["emissivity"]


# ---- materials --------------------------------------------------------------------------


def layer(thickness_m, k, rho, c, source):
    return dict(thickness_m=thickness_m, k=k, rho=rho, c=c, source=source)


def thermal(layers, back, source, solar=None, wet=0.0, roughness="MediumRough"):
    return dict(layers=layers, back=back, source=source, solar=solar, wet=wet, roughness=roughness)


ADIABATIC = "Adiabatic"


def held(t_k):
    return f"Temperature(temperature_k: {fmt(t_k)})"


def convective(h, air=None):
    air_text = "Outdoor" if air is None else f"Fixed(temperature_k: {fmt(air)})"
    return f"Convective(h_w_m2_k: {fmt(h)}, air: {air_text})"


# Still air behind a sheet: natural convection from a vertical plate a few kelvin from the
# air, 2-4 W m^-2 K^-1 (Incropera ch. 9, eq. 9.26).
SHEET_BACK = convective(3.0)
SHEET_BACK_WHY = "back: natural convection to the outdoor air behind the sheet, 3 W m-2 K-1 (a vertical plate a few kelvin from the air, Incropera & DeWitt eq. 9.26 gives 2-4)"
# Soils: 1 m deep, adiabatic below. The daily temperature wave falls by e every damping
# depth sqrt(2 kappa / omega), 5-15 cm in soils (Oke 1987, section 2.2), so 1 m is past
# it for a day's run.
SOIL_DEPTH_WHY = "1 m deep, adiabatic below: the daily wave's damping depth sqrt(2 kappa/omega) is 5-15 cm in soils (Oke 1987, sec. 2.2)"

def separable(curve_xs, curve_es, shape_table):
    """The library's angular table of a separable material: the shape scaled to the curve's
    8-14 um Planck mean at 300 K (what a reader that knows no spectrum takes)."""
    mean = planck_mean(curve_xs, curve_es, 8.0, 14.0, 300.0)
    first = shape_table[0][1]
    return [(a, min(1.0, e * mean / first)) for a, e in shape_table]


def spectral_from_tool(m, keep_angular):
    s = m["spectral"]
    out = dict(wavelength_um=s["wavelength_um"], emissivity=s["emissivity"])
    if keep_angular:
        out["angular"] = (s["angular"]["angle_deg"], s["angular"]["emissivity"])
    return out


def add(out, id_, m):
    """Appends material m under its id. Ids are stable: a scene or pipeline names a material
    by id, so a removed material's id is never reused and new materials take new ids."""
    m["id"] = id_
    out.append(m)


def material(name, table, specular, source, spectral, therm, rms=None, band=None):
    return dict(name=name, table=table, specular=specular, source=source, spectral=spectral,
                thermal=therm, rms=rms, band=band)


def nk_material(name, pages, cite, therm, rough=None, specular=None, rows=None, note="", grid=None, shape_only=False):
    """A Fresnel material from n, k pages (the first, unless `rows` joins several): smooth
    (angular grid, or with `shape_only` separable) or rough (separable)."""
    pages = (pages,) if isinstance(pages, str) else pages
    grid_angles = rough is None and not shape_only
    args = ["--angles", SMOOTH_ANGLES if grid_angles else ROUGH_ANGLES]
    if rough is not None:
        args += ["--roughness", str(rough)]
    if specular is not None:
        args += ["--specular-fraction", str(specular)]
    m = fresnel_nk(pages[0], rows, *args, grid=grid)
    kind = "smooth" if rough is None else f"rough (RMS facet slope {rough}{note})"
    tool = m["source"]
    if shape_only:
        kind += ", separable (its 8-14 um angular table as the shape)"
        tool = tool.replace(", at normal incidence and at every angle", ", at normal incidence")
    src = (f"{cite} ({ri_origin(*pages)}), n, k on the library's grid" + ("" if grid is None else " (every 0.25 um beyond 2.5 um)") + "; "
           f"{kind}: {tool}")
    return material(name, m["emissivity"], m["specular_fraction"], src,
                    spectral_from_tool(m, grid_angles), therm, m.get("rms_slope"), m.get("band_um"))


def materials():
    out = []
    water = fresnel_nk("water-hale.yml", None, "--angles", SMOOTH_ANGLES, "--roughness", "0.105",
                       "--specular-fraction", "1")
    water_xs, water_es = water["spectral"]["wavelength_um"], water["spectral"]["emissivity"]
    hale = "Hale & Querry (1973, Appl. Opt. 12, 555) water"
    add(out, 1, material(
        "water", water["emissivity"], 1.0,
        f"{hale} ({ri_origin('water-hale.yml')}), n, k on the library's grid; a lightly rippled surface, RMS slope 0.105 fitted to Sobrino & Cuenca (1999) in rough-surfaces.ron, separable (epsilon(lambda, theta) on a grid differs from it by at most 0.004 in either band): {water['source']}",
        spectral_from_tool(water, False),
        thermal([layer(1.0, 1000.0, 1000.0, 4180.0,
                       "well-mixed layer: density and specific heat of water, " + OKE_21 + "; conductivity 1000 W m-1 K-1 is an effective one that stands for wind and convective mixing (k = rho c d^2 / tau with a mixing time tau of about an hour over d = 1 m), which keeps the 1 m layer within a few 0.01 K of uniform, as a mixed layer is; still water's molecular conductivity is 0.57")],
                ADIABATIC,
                "a pond's well-mixed upper metre, adiabatic below (exchange with the water beneath neglected over a day); solar absorptance 0.94: albedo 0.03-0.10 at small zenith angles, " + OKE_11 + ", all of it absorbed within the mixed layer; open water, wet share 1",
                0.94, 1.0, "VerySmooth"),
        0.105, water.get("band_um")))

    ice_rows = ri_rows("ice-warren-2008.yml")
    warren = "Warren & Brandt (2008, J. Geophys. Res. 113, D14220) ice"
    ice_layer = layer(0.3, 2.24, 920.0, 2100.0, OKE_21 + ", ice at 0 C, pure")
    add(out, 2, nk_material(
        "ice (smooth)", "ice-warren-2008.yml", warren,
        thermal([ice_layer], held(273.15),
                "30 cm of lake ice floating on water at its freezing point, 273.15 K; solar absorptance 0.62: albedo 0.30-0.45 for ice, " + OKE_11 + "; no latent heat (the thermal model's wet film does not freeze)",
                0.62, 0.0, "VerySmooth")))
    add(out, 3, nk_material(
        "ice (rough)", "ice-warren-2008.yml", warren,
        thermal([ice_layer], held(271.35),
                "30 cm of sea ice on sea water at its freezing point, 271.35 K (-1.8 C); solar absorptance 0.62: albedo 0.30-0.45 for sea ice, " + OKE_11,
                0.62, 0.0, "MediumRough"),
        rough=0.3, note=", chosen, not measured: a weathered ice surface"))
    snow_note = ", chosen, not measured: randomly tilted grain facets; no volume scattering, so the 3-5 um reflectance of coarse grains is not modelled"
    ground = layer(0.5, 0.52, 2050.0, 1840.0, INC_A3 + ", soil")
    add(out, 4, nk_material(
        "snow (fresh)", "ice-warren-2008.yml", warren + " as the grains' surface",
        thermal([layer(0.2, 0.08, 100.0, 2090.0, OKE_21 + ", snow, fresh"), ground], held(273.15),
                "20 cm of fresh snow over 50 cm of soil held at 273.15 K (ground under snow cover stays near freezing); solar absorptance 0.13: fine fresh snow, " + INC_A13 + " (albedo 0.75-0.95, " + OKE_11 + "); no latent heat (no sublimation or melt in the thermal model)",
                0.13, 0.0, "MediumSmooth"),
        rough=1.0, note=snow_note))
    add(out, 5, nk_material(
        "snow (old)", "ice-warren-2008.yml", warren + " as the grains' surface",
        thermal([layer(0.3, 0.42, 480.0, 2090.0, OKE_21 + ", snow, old"), ground], held(273.15),
                "30 cm of old, settled snow over 50 cm of soil held at 273.15 K; solar absorptance 0.33: ice granules, " + INC_A13 + " (old snow albedo 0.40, " + OKE_11 + ")",
                0.33, 0.0, "MediumRough"),
        rough=1.0, note=snow_note))

    # Grass: DIRSIG's 43 grass curves, their mean, 0.25-28.6 um.
    gx_all, ge_all = zip(*dirsig_mean("grass_texture.ems"))
    gx = grid_within(list(gx_all))
    ge = [interp(gx_all, ge_all, g) for g in gx]
    grass_shape = shape("--n", "1.20", "--roughness", "1.5", "--diffuse-reflectance", "0.0182")
    add(out, 6, material(
        "grass", separable(gx, ge, grass_shape), 0.0,
        "DIRSIG grass_texture.ems (github.com/Rendered-ai/dirsig-channel @ 135340af, Apache-2.0; sources/dirsig/grass_texture.ems): the mean of its 43 curves, interpolated onto the library's grid; angular shape: the rough-surface grass of rough-surfaces.ron (n 1.20, RMS slope 1.5, diffuse reflectance 0.0182, fitted to Sobrino & Cuenca 1999), separable",
        dict(wavelength_um=gx, emissivity=ge),
        thermal([layer(0.02, 0.06, 300.0, 1920.0, "the grass's thatch and root mat taken as a light organic soil: " + OKE_21 + ", peat soil (80 % pore space), dry"),
                 layer(1.0, 0.52, 2050.0, 1840.0, INC_A3 + ", soil")],
                ADIABATIC,
                "grass as a named model: the leaves' own heat capacity is neglected (a few hundred g of water per m2), the surface is the grass's, on 2 cm of thatch over 1 m of soil, adiabatic below (" + SOIL_DEPTH_WHY + "); wet share 0.3 stands for transpiration at three tenths of a wet surface's evaporation, an assumption (stomatal resistance is not modelled); solar absorptance from the curve",
                None, 0.3, "VeryRough")))

    # Glass: Rubin's clear soda-lime n (formula) and k to 4.6 um, his far-infrared n, k beyond.
    glass_rows = ri_rows("soda-lime-rubin-clear.yml") + ri_rows("soda-lime-rubin-ir.yml")
    add(out, 9, nk_material(
        "glass (window)", ("soda-lime-rubin-clear.yml", "soda-lime-rubin-ir.yml"),
        "Rubin (1985, Sol. Energy Mater. 12, 275) clear soda-lime window glass: n from his dispersion formula and tabulated k over 0.31-4.6 um, tabulated n, k over 5-300 um (4.6-5 um interpolated between them)",
        thermal([layer(0.006, 1.4, 2500.0, 750.0, INC_A3 + ", glass, plate (soda lime)")],
                convective(8.3, 293.15),
                "a 6 mm pane, a room at 293.15 K behind it with a still-air surface coefficient of 8.3 W m-2 K-1 (ASHRAE Handbook - Fundamentals, ch. 26, surface film coefficients, vertical surface); solar absorptance 0.10: a 3-6 mm clear pane absorbs about a tenth of sunlight and transmits most of the rest (ASHRAE Handbook - Fundamentals, ch. 15), which the thermal model, a wall of opaque layers, does not carry; modelled opaque in the infrared too, which holds beyond 4.5 um and at a few mm of thickness",
                0.10, 0.0, "VerySmooth"),
        rows=glass_rows))

    # Metals.
    rakic_al = "Rakic (1995, Appl. Opt. 34, 4755) evaporated aluminium"
    al_sheet = [layer(0.002, 177.0, 2770.0, 875.0, INC_A1 + ", aluminium alloy 2024-T6")]
    add(out, 10, nk_material(
        "aluminium (polished)", "aluminium-rakic.yml", rakic_al,
        thermal(al_sheet, SHEET_BACK, "a 2 mm sheet; " + SHEET_BACK_WHY + "; solar absorptance from the curve (polished aluminium 0.09, " + INC_A13 + ")", None, 0.0, "VerySmooth"),
        grid=METAL_GRID))
    add(out, 11, nk_material(
        "aluminium (matte)", "aluminium-rakic.yml", rakic_al,
        thermal(al_sheet, SHEET_BACK, "a 2 mm sheet; " + SHEET_BACK_WHY + "; solar absorptance from the curve", None, 0.0, "Smooth"),
        rough=0.3, note=", chosen, not measured: a bead-blasted or brushed finish", grid=METAL_GRID))
    querry_fe = "Querry (1985, CRDC-CR-85034) iron"
    steel_sheet = layer(0.001, 63.9, 7832.0, 434.0, INC_A1 + ", plain carbon steel AISI 1010")
    add(out, 12, nk_material(
        "steel (polished)", "iron-querry.yml", querry_fe + " (a steel's surface is its iron's)",
        thermal([steel_sheet], SHEET_BACK, "a 1 mm sheet; " + SHEET_BACK_WHY + "; solar absorptance from the curve", None, 0.0, "VerySmooth"),
        grid=METAL_GRID))
    add(out, 13, nk_material(
        "steel (rusted)", "hematite-querry-o.yml", "Querry (1985, CRDC-CR-85034) hematite (Fe2O3, ordinary ray), the red rust on weathered steel",
        thermal([layer(0.003, 63.9, 7832.0, 434.0, INC_A1 + ", plain carbon steel AISI 1010")], SHEET_BACK,
                "a 3 mm plate (the rust's own layer, tens of um, neglected); " + SHEET_BACK_WHY + "; solar absorptance from the curve", None, 0.0, "Rough"),
        rough=0.65, note=", chosen, not measured", grid=METAL_GRID))
    zinc = "Querry (1987, CRDEC-CR-88009) zinc, 0.36-55.6 um: the clean zinc coat of galvanised steel (a weathered coat's oxide is not in the spectrum: handbook new galvanised sheet is 0.13, " + INC_A13 + ")"
    galv = [layer(0.00002, 116.0, 7140.0, 389.0, INC_A1 + ", zinc (a 20 um hot-dip coat)"),
            layer(0.0007, 63.9, 7832.0, 434.0, INC_A1 + ", plain carbon steel AISI 1010")]
    zn = nk_material("zinc-coated steel (polished)", "zinc-querry.yml", zinc, None, grid=METAL_GRID)
    zx, ze = zn["spectral"]["wavelength_um"], zn["spectral"]["emissivity"]
    zn_solar, zn_why = solar_from_curve(zx, ze, "the table starts at 0.36 um")
    zn["thermal"] = thermal(galv, SHEET_BACK, "a 0.7 mm roofing or cladding sheet with a 20 um zinc coat; " + SHEET_BACK_WHY + "; " + zn_why + " (clean new galvanised sheet: 0.65, " + INC_A13 + ")", zn_solar, 0.0, "Smooth")
    add(out, 14, zn)
    add(out, 15, nk_material(
        "copper (polished)", "copper-querry.yml", "Querry (1985, CRDC-CR-85034) copper",
        thermal([layer(0.001, 401.0, 8933.0, 385.0, INC_A1 + ", copper, pure")], SHEET_BACK,
                "a 1 mm roofing or cladding sheet; " + SHEET_BACK_WHY + "; solar absorptance from the curve", None, 0.0, "VerySmooth"),
        grid=METAL_GRID))
    add(out, 16, nk_material(
        "titanium (polished)", "titanium-rakic-bb.yml", "Rakic et al. (1998, Appl. Opt. 37, 5271) titanium, Brendel-Bormann fit, 0.25-31 um",
        thermal([layer(0.002, 21.9, 4500.0, 522.0, INC_A1 + ", titanium")], SHEET_BACK,
                "a 2 mm sheet; " + SHEET_BACK_WHY + "; solar absorptance from the curve", None, 0.0, "VerySmooth"),
        grid=METAL_GRID))
    coated_metals(out)
    glazing_water_and_canopies(out, glass_rows, dict(xs=gx, es=ge, shape=grass_shape))
    return out


# ---- coatings, assemblies and canopies (ids 17-27) ---------------------------------------

INC_A4_AIR = INC + ", Table A.4, air at 300 K"
ASHRAE = "ASHRAE Handbook - Fundamentals"
# A plane air space between ordinary building surfaces (effective emittance 0.82) holds
# 0.15-0.18 m2 K W-1 whatever its width from 13 to 90 mm and the direction of heat flow
# (ASHRAE Handbook - Fundamentals, ch. 26, Table 3): convection and radiation across it,
# which a layer of still air (0.026 W m-1 K-1) would overstate several times. The layer takes
# 0.16 as an effective conductivity d / 0.16.
AIR_SPACE_R = 0.16


def air_space(thickness_m):
    return layer(thickness_m, thickness_m / AIR_SPACE_R, 1.1614, 1007.0,
                 f"a plane air space, its resistance {fmt(AIR_SPACE_R)} m2 K W-1 ({ASHRAE}, ch. 26, Table 3: 0.15-0.18 for 13-90 mm between surfaces of emittance 0.9, effective emittance 0.82) as an effective conductivity; density and specific heat of air, {INC_A4_AIR}")


def complex_nk(rows, lam):
    xs = [r[0] for r in rows]
    return complex(interp(xs, [r[1] for r in rows], lam), interp(xs, [r[2] for r in rows], lam))


def film_on_metal(film_rows, metal_rows, film_um):
    """(um, epsilon) at normal incidence of a film film_um thick on an opaque metal, on the
    grid points both tables cover: the incoherent sum of the film's multiple reflections (a
    film many wavelengths thick and not even to a fraction of one averages its fringes out),
    R = R01 + (1 - R01)^2 R12 t^2 / (1 - R01 R12 t^2), t = exp(-4 pi k1 d / lambda), with R01
    and R12 the normal-incidence reflectances |(Na - Nb)/(Na + Nb)|^2 of the air-film and
    film-metal interfaces, and epsilon = 1 - R (the net-radiation sum for a semitransparent
    layer on an opaque substrate: Siegel & Howell, Thermal Radiation Heat Transfer)."""
    lo = max(film_rows[0][0], metal_rows[0][0])
    hi = min(film_rows[-1][0], metal_rows[-1][0])
    xs = [g for g in GRID if lo <= g <= hi]
    es = []
    for lam in xs:
        n1, n2 = complex_nk(film_rows, lam), complex_nk(metal_rows, lam)
        r01 = abs((1 - n1) / (1 + n1)) ** 2
        r12 = abs((n1 - n2) / (n1 + n2)) ** 2
        t2 = math.exp(-2.0 * 4.0 * math.pi * n1.imag * film_um / lam)
        es.append(1.0 - (r01 + (1 - r01) ** 2 * r12 * t2 / (1 - r01 * r12 * t2)))
    return xs, es


AL_SHEET = [layer(0.002, 177.0, 2770.0, 875.0, INC_A1 + ", aluminium alloy 2024-T6")]
RAKIC_AL = "Rakic (1995, Appl. Opt. 34, 4755) evaporated aluminium"
# Paint is a pigmented binder tens of um thick; in the thermal infrared its surface is the
# binder's and the pigment loading makes the film opaque, so its emissivity is that of an
# opaque, smooth binder surface. Acrylic binders are poly(methyl methacrylate)'s kin.
PAINT_WHY = ("the paint as an opaque surface of its binder, acrylic taken as poly(methyl methacrylate): "
             "Zhang et al. (2020, Appl. Opt. 59, 2337; J. Quant. Spectrosc. Radiat. Transf. 252, 107063) PMMA, 0.4-19.9 um")
WHITE = (0.26, "white acrylic paint, " + INC_A13)
BLACK = (0.98, "black paint (Parsons), " + INC_A13)


def paint_base():
    """The paint surface every painted entry shares: smooth PMMA, separable."""
    return nk_material(
        "paint", "pmma-zhang-mitsubishi.yml",
        PAINT_WHY + "; pigments and fillers are not in the spectrum: they set the solar absorptance (given, cited) and, "
        "where they scatter, lower the 3-5 um emissivity of real paints below this binder surface's",
        None, shape_only=True)


def painted(base, name, colour, layers, back, why):
    m = dict(base, name=name)
    solar, solar_why = colour
    m["thermal"] = thermal(layers, back, f"{why}; the paint film's own heat capacity neglected (about 0.1 mm); solar absorptance {fmt(solar)}: {solar_why}",
                           solar, 0.0, "Smooth")
    return m


def coated_metals(out):
    """Anodised aluminium and painted steel and aluminium: coatings on the library's metals."""
    film = ri_rows("alumina-franta.yml")
    xs, es = film_on_metal(film, ri_rows("aluminium-rakic.yml"), 15.0)
    dielectric = run_tool(["--angles", ROUGH_ANGLES, "--n", "1.6"])["emissivity"]
    add(out, 17, material(
        "aluminium (anodised)", separable(xs, es, dielectric), 1.0,
        "a 15 um anodic film on aluminium as a named model: the film amorphous alumina, Franta et al. (2015, Proc. SPIE 9628, 96281U) "
        f"Al2O3 ({ri_origin('alumina-franta.yml')}), on {RAKIC_AL} ({ri_origin('aluminium-rakic.yml')}), both on the library's grid; "
        "the film's multiple reflections summed incoherently at normal incidence (Siegel & Howell); 15 um chosen, not measured "
        "(sulfuric-acid anodising makes 5-25 um); angular shape: a smooth dielectric of n 1.6 (irsig-material fresnel --n 1.6), separable; "
        "dense alumina barely absorbs below 8 um, where the sheet shows through; a real anodic film is porous and holds water "
        "and sulfate, which absorb near 3 and 6 um and raise its 3-5 um emissivity above this model's",
        dict(wavelength_um=xs, emissivity=es),
        thermal(AL_SHEET, SHEET_BACK, "a 2 mm sheet (the 15 um film's heat capacity neglected); " + SHEET_BACK_WHY + "; solar absorptance from the curve: the film is clear, the sheet below reflects", None, 0.0, "Smooth")))
    base = paint_base()
    panel = [layer(0.0008, 63.9, 7832.0, 434.0, INC_A1 + ", plain carbon steel AISI 1010")]
    panel_why = ("a car body panel: 0.8 mm of steel under the paint; back: the air inside the body, taken at the outdoor temperature, "
                 "by natural convection, 3 W m-2 K-1 (a vertical plate a few kelvin from the air, Incropera & DeWitt eq. 9.26 gives 2-4)")
    add(out, 18, painted(base, "steel (painted, white)", WHITE, panel, SHEET_BACK, panel_why))
    add(out, 19, painted(base, "steel (painted, black)", BLACK, panel, SHEET_BACK, panel_why))
    roof = [layer(0.0005, 63.9, 7832.0, 434.0, INC_A1 + ", plain carbon steel AISI 1010"), air_space(0.02),
            layer(0.012, 0.12, 545.0, 1215.0, INC_A3 + ", plywood")]
    room_below = convective(6.13, 293.15)
    roof_why = ("a roof: 0.5 mm steel sheet, a 20 mm air space, 12 mm plywood deck, and a room at 293.15 K below "
                f"with a still-air surface coefficient of 6.13 W m-2 K-1 ({ASHRAE}, ch. 26, Table 1, horizontal surface, heat flow downward)")
    add(out, 20, painted(base, "roofing (white-painted steel)", WHITE, roof, room_below, roof_why))
    add(out, 21, painted(base, "roofing (black-painted steel)", BLACK, roof, room_below, roof_why))
    skin_why = "an aluminium skin (a trailer, an aircraft or a sign): a 2 mm sheet; " + SHEET_BACK_WHY
    add(out, 22, painted(base, "aluminium (painted, white)", WHITE, AL_SHEET, SHEET_BACK, skin_why))
    add(out, 23, painted(base, "aluminium (painted, black)", BLACK, AL_SHEET, SHEET_BACK, skin_why))


def glazing_water_and_canopies(out, glass_rows, grass):
    """A double-glazed window and calm water from the library's n, k tables, and two canopies
    as named models on the grass's measured curve."""
    pane = layer(0.004, 1.4, 2500.0, 750.0, INC_A3 + ", glass, plate (soda lime)")
    add(out, 24, nk_material(
        "glass (double-glazed window)", ("soda-lime-rubin-clear.yml", "soda-lime-rubin-ir.yml"),
        "Rubin (1985, Sol. Energy Mater. 12, 275) clear soda-lime window glass, as the window above",
        thermal([pane, air_space(0.012), pane], convective(8.3, 293.15),
                "a double-glazed window: two 4 mm panes around a 12 mm air space, a room at 293.15 K behind with a still-air surface coefficient of 8.3 W m-2 K-1 "
                f"({ASHRAE}, ch. 26, Table 1, vertical surface); solar absorptance 0.10: what the outer pane absorbs, as for the single pane ({ASHRAE}, ch. 15); "
                "the sunlight the outer pane passes, most of it, is lost to this model of opaque layers",
                0.10, 0.0, "VerySmooth"),
        rows=glass_rows))
    add(out, 25, nk_material(
        "water (calm)", "water-hale.yml", "Hale & Querry (1973, Appl. Opt. 12, 555) water, as the water above but without ripples",
        thermal([layer(1.0, 1000.0, 1000.0, 4180.0, "well-mixed layer as for the water above: density and specific heat of water, " + OKE_21 + "; conductivity 1000 W m-1 K-1 an effective one for the mixing")],
                ADIABATIC, "a sheltered pond's well-mixed upper metre, adiabatic below, as for the water above; solar absorptance 0.94: albedo 0.03-0.10, " + OKE_11 + "; open water, wet share 1",
                0.94, 1.0, "VerySmooth"),
        shape_only=True))
    canopy = ("a tree canopy as a named model: its surface is leaves, and no broadleaf or needle spectrum is among the sources, "
              "so DIRSIG's grass blades stand for them: grass_texture.ems (github.com/Rendered-ai/dirsig-channel @ 135340af, Apache-2.0; "
              "sources/dirsig/grass_texture.ems), the mean of its 43 curves on the library's grid; angular shape the grass's "
              "(rough-surfaces.ron: n 1.20, RMS slope 1.5, diffuse reflectance 0.0182, fitted to Sobrino & Cuenca 1999), separable; "
              "the cavities of a deep crown raise its emissivity a little above its leaves', which this curve does not add")
    leaves = layer(0.001, 0.57, 1000.0, 4180.0, "the leaves taken as water, " + OKE_21 + ": 1 mm, a leaf area index of 4 of leaves 0.25 mm thick (an assumption)")
    for id_, name, albedo, solar in ((26, "canopy (deciduous)", "0.15-0.20", 0.825), (27, "canopy (conifer)", "0.05-0.15", 0.90)):
        add(out, id_, material(
            name, separable(grass["xs"], grass["es"], grass["shape"]), 0.0, canopy,
            dict(wavelength_um=grass["xs"], emissivity=grass["es"]),
            thermal([leaves],
                    convective(25.0),
                    "the crown's leaves over the air of the trunk space: no soil under them exchanges with the leaves, whose undersides meet air "
                    "at the outdoor temperature with 25 W m-2 K-1 (a leaf's boundary-layer conductance 1.4 x 0.135 (u/d)^0.5 mol m-2 s-1 at u = 1 m s-1 "
                    f"and d = 5 cm, Campbell & Norman 1998, An Introduction to Environmental Biophysics, ch. 7, times 29.3 J mol-1 K-1); solar absorptance {fmt(solar)}: "
                    f"albedo {albedo}, {OKE_11}; wet share 0.3 stands for transpiration, as for the grass, an assumption",
                    solar, 0.3, "VeryRough")))


def solar_from_curve(xs, es, why_short):
    """The solar absorptance of an opaque curve that starts above 0.3 um: 1 - R weighted by a
    5778 K black body over the part of 0.3-4 um it covers (nothing extrapolated), and the
    sentence that says so."""
    value = round(planck_mean(xs, es, xs[0], 4.0, 5778.0), 3)
    share = solar_share(xs[0])
    return value, (f"solar absorptance {fmt(value)}: the curve over {fmt(xs[0])}-4 um weighted by a "
                   f"5778 K black body, {share:.1%} of the 0.3-4 um weight ({why_short})")


def solar_share(start_um):
    """The share of a 5778 K black body's 0.3-4 um radiance that lies above start_um."""
    def integral(lo, hi):
        return sum(planck(lo + (i + 0.5) * 0.001, 5778.0) for i in range(round((hi - lo) / 0.001)))
    return integral(start_um, 4.0) / integral(0.3, 4.0)


# ---- RON --------------------------------------------------------------------------------


def ron_string(s):
    return '"' + s.replace("\\", "\\\\").replace('"', '\\"') + '"'


def numbers(xs):
    return "[" + ", ".join(fmt(x) for x in xs) + "]"


def write(mats):
    w = sys.stdout.write
    w(HEADER)
    for m in mats:
        w("    (\n")
        w(f"      id: {m['id']},\n")
        w(f"      name: {ron_string(m['name'])},\n")
        w("      emissivity: [" + ", ".join(f"({fmt(a)}, {fmt(e)})" for a, e in m["table"]) + "],\n")
        w(f"      specular_fraction: {fmt(m['specular'])},\n")
        w(f"      source: {ron_string(m['source'])},\n")
        if m["band"] is not None:
            w(f"      band_um: Some(({fmt(m['band'][0])}, {fmt(m['band'][1])})),\n")
        s = m["spectral"]
        text = f"wavelength_um: {numbers(s['wavelength_um'])}, emissivity: {numbers(s['emissivity'])}"
        if "angular" in s:
            angles, rows = s["angular"]
            text += f", angular: Some((angle_deg: {numbers(angles)}, emissivity: [" + ", ".join(numbers(r) for r in rows) + "]))"
        w(f"      spectral: Some(({text})),\n")
        if m["rms"] is not None:
            w(f"      rms_slope: Some({fmt(m['rms'])}),\n")
        t = m["thermal"]
        w("      thermal: Some((\n        layers: [\n")
        for l in t["layers"]:
            w(f"          (thickness_m: {fmt(l['thickness_m'])}, conductivity_w_m_k: {fmt(l['k'])}, "
              f"density_kg_m3: {fmt(l['rho'])}, specific_heat_j_kg_k: {fmt(l['c'])}, source: {ron_string(l['source'])}),\n")
        w("        ],\n")
        w(f"        back: {t['back']},\n")
        if t["solar"] is not None:
            w(f"        solar_absorptance: Some({fmt(t['solar'])}),\n")
        w(f"        wet_fraction: {fmt(t['wet'])},\n")
        w(f"        roughness: {t['roughness']},\n")
        w(f"        source: {ron_string(t['source'])},\n")
        w("      )),\n")
        w("    ),\n")
    w("  ],\n)\n")


HEADER = """// Scene materials valid over 3-14 um (and most over 0.3-15 um), each with its thermal
// properties: made by pipelines/materials/scene-library.py from the source data under
// pipelines/materials/sources/ (SOURCES.md: origin, commit and licence of every file).
// Every "source" says where its numbers come from; README.md lists the materials. Emissivity
// tables are (angle from the surface normal in degrees, emissivity); a tracer averages each
// `spectral` curve over the band it traces, and refuses a band the curve does not cover.
(
  materials: [
"""

if __name__ == "__main__":
    write(materials())
