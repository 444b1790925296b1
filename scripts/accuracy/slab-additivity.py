#!/usr/bin/env python3
"""How far a path that ends above the ground is from the difference of two longer paths,
with LOWTRAN7's own numbers at both ends (docs/accuracy.md, "Scattered sunlight along the
tracer's paths").

irsig builds a view path from an observer at h_o to a facet at h_t out of tabulated paths
that end at the ground (looking down) or in space (looking up), along the same direction:

    L(o -> t) = P(h_o) - tau(o -> t) * P(h_t)

which holds exactly for monochromatic light in a plane-parallel atmosphere. This script
asks LOWTRAN7 for every term at the path's own ends, spectral point by spectral point (no
table interpolation, LOWTRAN's tau of the path itself), and compares the band integral of
the difference with LOWTRAN7's path run directly. What is left is the band model's: a
LOWTRAN7 spectral point is a 20 cm^-1 band-model average, and the light arriving from
beyond the facet is not spread over it as the mean tau assumes. Scattered sunlight has
already lost the line centres on its way down, so the slab passes it better than the mean
tau (the difference is too large); the air's thermal emission is strongest in the line
centres, which the slab absorbs most (the difference is too small).

The setting is tests/tests/scattered_trace.rs's: US Standard 1976 with a rural 10 km
aerosol, 2440-2940 cm^-1 every 10 (3.40-4.10 um), sun 30 deg from the zenith on day 172,
azimuths measured from the sun's. LOWTRAN7 is $IRSIG_LOWTRAN (scripts/atmosphere/
install-lowtran.sh builds it). Run from anywhere:

    IRSIG_LOWTRAN=path/to/lowtran7 python3 scripts/accuracy/slab-additivity.py
"""
import os
import subprocess
import sys
import tempfile

LOWTRAN = os.environ.get("IRSIG_LOWTRAN", "lowtran7")
# Card 2: rural aerosol (IHAZE 1), visibility 10 km.
CARD2 = "    1    0    0    0    0    0    10.000     0.000     0.000     0.000     0.000"
V1, V2, DV = 2440.0, 2940.0, 10.0
SUN_ZENITH_DEG, DAY = 30.0, 172


def run(itype, h1_km, h2_km, zenith_deg, azimuth_deg):
    """LOWTRAN7 with single-scattered sunlight (IEMSCT 2) along one path: rows of
    (wavenumber cm^-1, tau, thermal path radiance, scattered path radiance), radiances in
    W cm^-2 sr^-1 per cm^-1."""
    deck = (
        f"    6{itype:5}    2    0    0    0    0    0    0    0    0    0    0   0.000   0.00\n"
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
        w = [float(x) for x in line.split()]
        # FREQ TRANS THERMAL PATH-SCATTERED ...
        rows.append((w[0], w[1], w[2], w[3]))
    return rows


def band(nu, y):
    """The band integral over wavelength, W m^-2 sr^-1, of a radiance per cm^-1 in
    W cm^-2 sr^-1: per um at the points L_lambda = L_nu nu^2 / 1e4, times 1e4 for m^-2
    (trapezoid in wavelength)."""
    pts = [(1e4 / n, v * n * n) for n, v in zip(nu, y)]
    return sum(0.5 * (a[1] + b[1]) * (a[0] - b[0]) for a, b in zip(pts, pts[1:]))


def main():
    # (observer km, facet km, zenith deg at the observer, azimuth from the sun): the
    # test's paths to facets above the ground.
    print("| path | part | LOWTRAN7 (W m⁻² sr⁻¹) | difference of two paths | error |")
    print("| --- | --- | ---: | ---: | ---: |")
    for h_o, h_t, zenith, az in [
        (0.85, 0.15, 133.0, 100.0),
        (0.85, 0.05, 133.0, 100.0),
        (0.85, 0.40, 145.0, 15.0),
        (0.65, 0.60, 125.0, 165.0),
        (0.15, 0.80, 40.0, 70.0),
    ]:
        path = run(2, h_o, h_t, zenith, az)
        if zenith > 90.0:
            # Down: both ends' paths to the ground (LOWTRAN's lowest path end, 1 m up).
            far, near = run(2, h_o, 0.001, zenith, az), run(2, h_t, 0.001, zenith, az)
        else:
            # Up: both ends' paths to space.
            far, near = run(3, h_o, 0.0, zenith, az), run(3, h_t, 0.0, zenith, az)
        nu = [r[0] for r in path]
        for part, k in (("thermal", 2), ("scattered sunlight", 3)):
            direct = band(nu, [r[k] for r in path])
            diff = band(nu, [a[k] - p[1] * b[k] for p, a, b in zip(path, far, near)])
            print(
                f"| {h_o * 1e3:.0f} m → facet at {h_t * 1e3:.0f} m, zenith {zenith:.0f}°, "
                f"azimuth {az:.0f}° | {part} | {direct:.4g} | {diff:.4g} | "
                f"{100 * (diff - direct) / direct:+.1f} % |"
            )
    return 0


if __name__ == "__main__":
    sys.exit(main())
