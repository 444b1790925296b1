#!/usr/bin/env python3
"""LOWTRAN7's own rounding: the usual single-precision build against the same source
built with 64-bit reals (`IRSIG_LOWTRAN_REALS=8 sh scripts/atmosphere/install-lowtran.sh`).

LOWTRAN7 is REAL*4 Fortran and locates its paths on a spherical Earth: radii of about
6371 km carry an altitude to about half a metre, so a path from a few tens of metres is
computed from an observer height known to about 1 %. This script measures what that
costs, as the apparent temperature (K) of 260, 290 and 320 K blackbodies seen through
the path to the ground (1 m up, as the built-ins' paths end), integrated over 8-14 um
(or 3-5 um) in wavenumber from TAPE7:

    python3 scripts/atmosphere/precision.py table [--mwir] [--models 2,6]
        for each model and observer, the largest |single - double| over nadir 0-85
        degrees every 2.5 and the three blackbodies (a markdown table);
    python3 scripts/atmosphere/precision.py scan MODEL H_M FROM TO STEP [--mwir]
        both builds' 260 K apparent temperature along nadir angles from one observer:
        the single-precision build's steps are jagged where the double's are smooth.

The programs are `$IRSIG_LOWTRAN` (else `lowtran7` on PATH) and `$IRSIG_LOWTRAN_R8`
(else `lowtran7-r8` beside it). Standard library only; about 0.15 s per LOWTRAN7 run.
"""

import math
import os
import shutil
import subprocess
import sys
import tempfile

C1 = 1.191042e-8  # 2 h c^2, W m^-2 sr^-1 (cm^-1)^-4 with the wavenumber in cm^-1
C2 = 1.4387752  # h c / k, cm K
BLACKBODIES_K = (260.0, 290.0, 320.0)
BANDS = {
    # (LOWTRAN7's wavenumbers, the band's, cm^-1)
    "lwir": ((710.0, 1350.0), (1e4 / 14.0, 1e4 / 8.0)),
    "mwir": ((2000.0, 3340.0), (1e4 / 5.0, 1e4 / 3.0)),
}
OBSERVERS_M = (2, 5, 10, 20, 50, 100, 200, 450, 1000, 2000)
MODEL_NAMES = {
    1: "tropical",
    2: "midlat-summer",
    3: "midlat-winter",
    4: "subarctic-summer",
    5: "subarctic-winter",
    6: "us-std-1976",
}


def programs():
    single = os.environ.get("IRSIG_LOWTRAN") or shutil.which("lowtran7")
    if not single:
        sys.exit("precision: no LOWTRAN7 (set IRSIG_LOWTRAN or run install-lowtran.sh)")
    double = os.environ.get("IRSIG_LOWTRAN_R8") or os.path.join(
        os.path.dirname(single), "lowtran7-r8"
    )
    if not os.access(double, os.X_OK):
        sys.exit(
            f"precision: no 64-bit build at {double} "
            "(IRSIG_LOWTRAN_REALS=8 sh scripts/atmosphere/install-lowtran.sh)"
        )
    return single, double


def spectrum(program, model, h_km, nadir_deg, wavenumbers):
    """(wavenumber, tau, path radiance in W m^-2 sr^-1 per cm^-1) of the path from h_km
    to 1 m above the ground at nadir_deg, thermal only."""
    v1, v2 = wavenumbers
    deck = (
        f"{model:5d}    2    1    0    0    0    0    0    0    0    0    0    0   0.000   0.00\n"
        "    0    0    0    0    0    0     0.000     0.000     0.000     0.000     0.000\n"
        f"{h_km:10.3f}{0.001:10.3f}{180.0 - nadir_deg:10.3f}     0.000     0.000     0.000    0\n"
        f"{v1:10.3f}{v2:10.3f}     5.000\n    0\n"
    )
    with tempfile.TemporaryDirectory() as d:
        with open(os.path.join(d, "TAPE5"), "w") as f:
            f.write(deck)
        os.mkdir(os.path.join(d, "out"))
        for t in ("TAPE6", "TAPE7", "TAPE8"):
            open(os.path.join(d, "out", t), "w").close()
        subprocess.run([program], cwd=d, stdout=subprocess.DEVNULL, check=True)
        with open(os.path.join(d, "out", "TAPE7")) as f:
            tape7 = f.read()
    rows = []
    for line in tape7.splitlines():
        p = line.split()
        try:
            nu, tau, path = float(p[0]), float(p[1]), float(p[2])
        except (IndexError, ValueError):
            continue
        if v1 <= nu <= v2 and p[0].endswith("."):
            rows.append((nu, tau, path * 1e4))
    return rows


def planck(nu, t):
    return C1 * nu**3 / math.expm1(C2 * nu / t)


def apparent_k(rows, t, band):
    """The band's brightness temperature of a t K blackbody seen through the path: the
    sum over the TAPE7 samples inside the band, inverted by bisection."""
    lo, hi = band
    inside = [r for r in rows if lo <= r[0] <= hi]
    seen = sum(tau * planck(nu, t) + path for nu, tau, path in inside)
    if not math.isfinite(seen):
        return math.nan
    a, b = 100.0, 500.0
    for _ in range(60):
        m = 0.5 * (a + b)
        if sum(planck(nu, m) for nu, _, _ in inside) < seen:
            a = m
        else:
            b = m
    return 0.5 * (a + b)


def temperatures(program, model, h_m, nadir_deg, span):
    wavenumbers, band = BANDS[span]
    rows = spectrum(program, model, h_m / 1e3, nadir_deg, wavenumbers)
    return [apparent_k(rows, t, band) for t in BLACKBODIES_K]


def table(span, models):
    single, double = programs()
    angles = [2.5 * i for i in range(35)]  # 0-85 degrees
    regions = (("nadir 0-80°", 0.0, 80.0), ("nadir 82.5-85°", 82.5, 85.0))
    found = {}
    for model in models:
        for h in OBSERVERS_M:
            for a in angles:
                s = temperatures(single, model, h, a, span)
                d = temperatures(double, model, h, a, span)
                if all(map(math.isfinite, s + d)):
                    found[model, h, a] = max((x - y for x, y in zip(s, d)), key=abs)
                else:
                    found[model, h, a] = None
    for title, lo, hi in regions:
        print(f"\n{title}, single - double, K (the nadir angle of the largest):\n")
        print(f"| model | {' | '.join(f'{h} m' for h in OBSERVERS_M)} |")
        print(f"| --- |{' ---: |' * len(OBSERVERS_M)}")
        for model in models:
            cells = []
            for h in OBSERVERS_M:
                errors = [(found[model, h, a], a) for a in angles if lo <= a <= hi]
                nan = sum(e is None for e, _ in errors)
                worst, at = max(
                    ((e, a) for e, a in errors if e is not None),
                    key=lambda p: abs(p[0]),
                    default=(0.0, 0.0),
                )
                cells.append(f"{worst:+.4f} ({at:g}°)" + (f", {nan} NaN" if nan else ""))
            print(f"| {MODEL_NAMES[model]} | {' | '.join(cells)} |")


def scan(model, h_m, first, last, step, span):
    single, double = programs()
    n = int(round((last - first) / step))
    print("| nadir (°) | single, 260 K | double, 260 K | single - double |")
    print("| ---: | ---: | ---: | ---: |")
    for i in range(n + 1):
        a = first + i * step
        s = temperatures(single, model, h_m, a, span)[0]
        d = temperatures(double, model, h_m, a, span)[0]
        print(f"| {a:.2f} | {s:.4f} | {d:.4f} | {s - d:+.4f} |", flush=True)


def main(argv):
    span = "mwir" if "--mwir" in argv else "lwir"
    args = [a for a in argv if a != "--mwir"]
    models = sorted(MODEL_NAMES)
    if "--models" in args:
        i = args.index("--models")
        models = [int(m) for m in args[i + 1].split(",")]
        del args[i : i + 2]
    if args[:1] == ["table"] and len(args) == 1:
        table(span, models)
    elif args[:1] == ["scan"] and len(args) == 6:
        scan(int(args[1]), float(args[2]), float(args[3]), float(args[4]), float(args[5]), span)
    else:
        sys.exit(__doc__)


if __name__ == "__main__":
    main(sys.argv[1:])
