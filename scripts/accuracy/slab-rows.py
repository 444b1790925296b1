#!/usr/bin/env python3
"""The slab tables on `irsig-atmos plan --slabs`'s own rows (docs/accuracy.md, "Slab
tables"): a day plan with slabs from observers at 150 and 650 m to the default target rows
up to 900 m (2, 5, 10, 25 m, 25 m apart to 100 m, 50 m apart above) at the default angles
(0-60 deg every 10, 65-80 every 5), built with `irsig-atmos build`, then six view paths
between rows in every coordinate traced with `irsig-trace --probe` (by day and without
the sun) and compared with LOWTRAN7 run for each path (IEMSCT 2).

The setting is tests/tests/slab_trace.rs's (US Standard 1976, rural 10 km, 2440-2940
cm^-1 every 10, sun 30 deg from the zenith on day 172, its azimuth 120 deg). The build
runs 5461 LOWTRAN7 decks (about a minute on 2 cores). LOWTRAN7 is $IRSIG_LOWTRAN; the
tools are $IRSIG_BIN/irsig-atmos and $IRSIG_BIN/irsig-trace (default target/release, where
the first command builds them).

    IRSIG_LOWTRAN=path/to/lowtran7 python3 scripts/accuracy/slab-rows.py
"""
import math
import os
import subprocess
import tempfile

LOWTRAN = os.environ.get("IRSIG_LOWTRAN", "lowtran7")
BIN = os.environ.get("IRSIG_BIN", "target/release")
CARD2 = "    1    0    0    0    0    0    10.000     0.000     0.000     0.000     0.000"
V1, V2, DV = 2440.0, 2940.0, 10.0
SUN_ZENITH_DEG, SUN_AZIMUTH_DEG, DAY = 30.0, 120.0, 172
AZIMUTHS = [0, 10, 20, 30, 45, 60, 90, 120, 150, 180]
TARGETS = [2, 5, 10, 25, 50, 75, 100] + list(range(150, 901, 50))
ANGLES = [0, 10, 20, 30, 40, 50, 60, 65, 70, 75, 80]
# (observer m, facet m, zenith angle at the observer, azimuth from the sun)
PATHS = [
    (650, 575, 125, 165),
    (650, 630, 125, 165),
    (650, 12, 133, 100),
    (150, 825, 45, 70),
    (150, 120, 145, 100),
    (150, 7, 117.5, 52.5),
]


def floats(xs):
    return ", ".join(f"{float(x):.1f}" for x in xs)


PLAN = f"""(
  name: "slab-rows",
  model: Standard(6),
  wavenumber_per_cm: ({V1}, {V2}, {DV}),
  path_end_m: 1.0,
  observers_m: [150.0, 650.0],
  levels_m: [50.0, 1000.0],
  correction_altitude_m: 1000.0,
  correction_nadir_deg: [0.0, 20.0, 40.0],
  ground_sky_zenith_deg: [0.0, 45.0, 90.0],
  hemispheric: [],
  slant_altitude_m: [100.0, 1000.0],
  slant_nadir_deg: [0.0, 30.0, 60.0],
  sky_altitude_m: [0.0, 1000.0],
  sky_zenith_deg: [0.0, 45.0, 90.0],
  sun: Some((zenith_deg: {SUN_ZENITH_DEG}, day_of_year: {DAY}, altitude_m: [0.0, 1000.0],
             relative_azimuth_deg: [{floats(AZIMUTHS)}])),
  aerosol: Some((model: Rural, visibility_m: 10000.0)),
  slabs: Some((target_m: [{floats(TARGETS)}], nadir_deg: [{floats(ANGLES)}],
               zenith_deg: [{floats(ANGLES)}])),
)
"""


def lowtran(h1_km, h2_km, zenith_deg, azimuth_deg):
    """LOWTRAN7's band integrals (trapezoid in wavelength, W m^-2 sr^-1) of the thermal,
    scattered and total path radiance from h1 to h2 (ITYPE 2, IEMSCT 2)."""
    deck = (
        "    6    2    2    0    0    0    0    0    0    0    0    0    0   0.000   0.00\n"
        f"{CARD2}\n"
        f"{h1_km:10.3f}{h2_km:10.3f}{zenith_deg:10.3f}{0:10.3f}{0:10.3f}{0:10.3f}{0:5d}\n"
        f"    2    2{DAY:5d}    0\n"
        f"{azimuth_deg:10.3f}{SUN_ZENITH_DEG:10.3f}" + f"{0:10.3f}" * 6 + "\n"
        f"{V1:10.3f}{V2:10.3f}{DV:10.3f}\n    0\n"
    )
    with tempfile.TemporaryDirectory() as d:
        with open(os.path.join(d, "TAPE5"), "w") as f:
            f.write(deck)
        os.mkdir(os.path.join(d, "out"))
        for t in ("TAPE6", "TAPE7", "TAPE8"):
            open(os.path.join(d, "out", t), "w").close()
        subprocess.run([LOWTRAN], cwd=d, stdout=subprocess.DEVNULL, check=True)
        with open(os.path.join(d, "out", "TAPE7")) as f:
            lines = f.read().splitlines()
    start = next(i for i, l in enumerate(lines) if l.strip().startswith("FREQ"))
    rows = []
    for line in lines[start + 1:]:
        if line.strip() == "-9999.":
            break
        rows.append([float(x) for x in line.split()])

    def band(col):
        # L_lambda = L_nu nu^2 / 1e4 per um; x 1e4 for m^-2: L_nu nu^2.
        nodes = [(1e4 / r[0], r[col] * r[0] * r[0]) for r in rows]
        return sum(0.5 * (a[1] + b[1]) * (a[0] - b[0]) for a, b in zip(nodes, nodes[1:]))

    # FREQ TRANS THERMAL PATH-SCATTERED SINGLE GROUND GROUND-SINGLE TOTAL
    return band(2), band(3), band(7)


def direction(zenith_deg, azimuth_deg):
    sz, cz = math.sin(math.radians(zenith_deg)), math.cos(math.radians(zenith_deg))
    a = math.radians(SUN_AZIMUTH_DEG + azimuth_deg)
    return [sz * math.sin(a), sz * math.cos(a), cz]


def probe(d, spa, facet, observer, look, sun):
    """The probe's path radiance L_u, W m^-2 sr^-1, of a 1-pixel view onto a grey plate."""
    with open(os.path.join(d, "scene.raw.ron"), "w") as f:
        f.write(
            f'(objects: ["plate"], positions_m: [(-2e3, -2e3, {facet}), (2e3, -2e3, {facet}), '
            f"(2e3, 2e3, {facet}), (-2e3, 2e3, {facet})], facets: [(vertices: (0, 1, 2), "
            "material: 1, temperature_k: 300.0, object: 0), (vertices: (0, 2, 3), "
            "material: 1, temperature_k: 300.0, object: 0)])"
        )
    t = [look[0] * 100, look[1] * 100, observer + look[2] * 100]
    with open(os.path.join(d, "view.ron"), "w") as f:
        f.write(
            f"LookAt(position_m: (0.0, 0.0, {float(observer)}), target_m: ({t[0]!r}, {t[1]!r}, "
            f"{t[2]!r}), up: (0.0, 0.0, 1.0), pixels: (1, 1), fov_deg: (0.01, 0.01))"
        )
    with open(os.path.join(d, "materials.ron"), "w") as f:
        f.write(
            '(materials: [(id: 1, name: "grey", emissivity: [(0.0, 0.2), (90.0, 0.2)], '
            'specular_fraction: 0.0, source: "slab-rows.py")])'
        )
    cmd = [os.path.join(BIN, "irsig-trace"), "--band", "3.40137-4.09836", "--probe", "0,0"]
    for flag, name in (("--scene", "scene.raw.ron"), ("--materials", "materials.ron"),
                       ("--view", "view.ron")):
        cmd += [flag, os.path.join(d, name)]
    cmd += ["--atmosphere", spa]
    if sun:
        cmd += ["--sun-zenith-deg", str(SUN_ZENITH_DEG), "--sun-azimuth-deg", str(SUN_AZIMUTH_DEG)]
    out = subprocess.run(cmd, capture_output=True, text=True, check=True).stdout
    return next(float(l.split()[-1]) for l in out.splitlines() if l.startswith("L_u (W m-2 sr-1)"))


def main():
    with tempfile.TemporaryDirectory() as d:
        os.mkdir(os.path.join(d, "plan"))
        with open(os.path.join(d, "plan", "plan.ron"), "w") as f:
            f.write(PLAN)
        spa = os.path.join(d, "rows.spa")
        subprocess.run(
            [os.path.join(BIN, "irsig-atmos"), "build", os.path.join(d, "plan"),
             "--atmosphere", "us-std-1976", "-o", spa],
            check=True, env=dict(os.environ, IRSIG_LOWTRAN=LOWTRAN),
        )
        print(f"{spa}: {os.path.getsize(spa)} bytes")
        for observer, facet, zenith, az in PATHS:
            look = direction(zenith, az)
            lit = probe(d, spa, facet, observer, look, True)
            dark = probe(d, spa, facet, observer, look, False)
            thermal, scattered, total = lowtran(observer / 1000, facet / 1000, zenith, az)
            print(
                f"{observer} m -> {facet} m, zenith {zenith}, azimuth {az}: LOWTRAN7 "
                f"{total:.4e} W/m2/sr ({100 * scattered / total:.1f} % scattered); traced: "
                f"whole {100 * (lit - total) / total:+.2f} %, scattered part "
                f"{100 * (lit - dark - scattered) / total:+.2f} % of the path radiance "
                f"({100 * (lit - dark - scattered) / scattered:+.1f} % of itself), thermal "
                f"{100 * (dark - thermal) / thermal:+.2f} %"
            )


if __name__ == "__main__":
    main()
