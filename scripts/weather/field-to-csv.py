#!/usr/bin/env python3
"""Converts a day of field measurements, surface temperature beside the weather that drove
it, to irsig's weather CSV (formats/weather.md) with the measured surface temperature in an
extra column (`x_surface_temperature[K]`, which the weather reader skips), for comparing
irsig-therm with the ground. Python standard library only.

Two sources, both U.S. Government works (NOAA), in the public domain:

  surfrad  A SURFRAD daily file (NOAA GML, gml.noaa.gov/grad/surfrad; one line a minute,
           UTC). Its air temperature, relative humidity, station pressure, wind, global,
           direct and diffuse solar and downwelling longwave become the weather. The
           surface has no thermometer: its radiometric temperature comes from the
           upwelling longwave of the downward-looking pyrgeometer (10 m up) and the
           downwelling one, for a surface emissivity EPS (--emissivity):
               T_s = ((L_up - (1 - EPS) L_down) / (EPS sigma))^(1/4),
           sigma = 5.670374419e-8 W m^-2 K^-4 (CODATA 2018), the pyrgeometers' broadband
           response taken as the whole longwave. The upwelling longwave is kept too
           (`x_longwave_up[W/m2]`), so that another emissivity can be tried.
  uscrn    A USCRN sub-hourly file (NOAA NCEI, www.ncei.noaa.gov/pub/data/uscrn/products/
           subhourly01; one line per 5 minutes, UTC at the end of the period). Its infrared
           surface temperature (SURFACE_TEMPERATURE, an Apogee radiometer) is the measured
           column; air temperature, relative humidity, the 5-minute mean solar radiation
           and the wind at 1.5 m the weather. USCRN measures no pressure: give the
           station's elevation (--elevation-m) for the ICAO standard atmosphere's pressure
           there, p = 101325 Pa (1 - 2.25577e-5 h/m)^5.25588, or a pressure (--pressure-hpa).

Each file's columns are read as their README (SURFRAD's station README; USCRN's
subhourly01/README.txt) and pvlib's readers (pvlib.iotools.read_surfrad, read_crn) define
them. A value flagged bad or missing is left empty; a row missing a required value (air
temperature, humidity, pressure, wind speed) is left out, and the count is printed on
stderr (irsig refuses the gap a long run of them leaves). --every N keeps one row in N
minutes (SURFRAD's 1-minute rows are more than a thermal run needs).

Usage:
  field-to-csv.py surfrad slv16001.dat --emissivity 0.98 --every 5 > alamosa.csv
  field-to-csv.py uscrn CRNS0101-05-2019-AZ_Tucson_11_W.txt --elevation-m 809 > tucson.csv
"""
import argparse
import sys

SIGMA = 5.670374419e-8  # W m^-2 K^-4, CODATA 2018

# SURFRAD daily file: after two header lines, per line the time fields, then pairs of
# (value, QC flag); flag 0 is good. pvlib.iotools.surfrad.SURFRAD_COLUMNS.
SURFRAD_TIME = ["year", "jday", "month", "day", "hour", "minute", "dt", "zen"]
SURFRAD_PAIRS = [
    "dw_solar", "uw_solar", "direct_n", "diffuse", "dw_ir", "dw_casetemp", "dw_dometemp",
    "uw_ir", "uw_casetemp", "uw_dometemp", "uvb", "par", "netsolar", "netir", "totalnet",
    "temp", "rh", "windspd", "winddir", "pressure",
]

# USCRN sub-hourly, whitespace-separated fields (subhourly01/README.txt; pvlib read_crn).
USCRN_FIELDS = [
    "WBANNO", "UTC_DATE", "UTC_TIME", "LST_DATE", "LST_TIME", "CRX_VN", "LONGITUDE",
    "LATITUDE", "AIR_TEMPERATURE", "PRECIPITATION", "SOLAR_RADIATION", "SR_FLAG",
    "SURFACE_TEMPERATURE", "ST_TYPE", "ST_FLAG", "RELATIVE_HUMIDITY", "RH_FLAG",
    "SOIL_MOISTURE_5", "SOIL_TEMPERATURE_5", "WETNESS", "WET_FLAG", "WIND_1_5", "WIND_FLAG",
]


def fail(message):
    sys.exit(f"field-to-csv: {message}")


def fmt(value, digits=3):
    return "" if value is None else f"{value:.{digits}f}".rstrip("0").rstrip(".")


def surfrad(lines, emissivity, every):
    if not 0.5 <= emissivity <= 1.0:
        fail(f"--emissivity {emissivity}: expected 0.5 to 1")
    if len(lines) < 3:
        fail("a SURFRAD daily file has two header lines and a line a minute")
    station = lines[0].strip()
    place = lines[1].split()
    header = [
        f"# SURFRAD {station}: latitude {place[0]}, longitude {place[1]} (as the file writes "
        f"it; SURFRAD's stations are west of Greenwich), elevation {place[2]} m; NOAA GML, "
        "public domain",
        f"# surface temperature: radiometric, from the upwelling and downwelling longwave "
        f"with emissivity {emissivity}",
        "time,air_temperature[degC],relative_humidity[%],pressure[hPa],wind_speed[m/s],"
        "wind_direction[deg],ghi[W/m2],dni[W/m2],dhi[W/m2],longwave_down[W/m2],"
        "x_longwave_up[W/m2],x_surface_temperature[K]",
    ]
    rows, dropped = [], 0
    for number, line in enumerate(lines[2:], start=3):
        f = line.split()
        if not f:
            continue
        if len(f) != len(SURFRAD_TIME) + 2 * len(SURFRAD_PAIRS):
            fail(f"line {number}: expected {len(SURFRAD_TIME) + 2 * len(SURFRAD_PAIRS)} fields")
        year, _, month, day, hour, minute = (int(x) for x in f[:6])
        if (hour * 60 + minute) % every:
            continue
        values = {}
        for k, name in enumerate(SURFRAD_PAIRS):
            v, flag = float(f[8 + 2 * k]), int(f[9 + 2 * k])
            values[name] = v if flag == 0 and v > -9999 else None
        need = ["temp", "rh", "pressure", "windspd"]
        if any(values[n] is None for n in need):
            dropped += 1
            continue
        up, down = values["uw_ir"], values["dw_ir"]
        surface = None
        if up is not None and down is not None:
            emitted = up - (1 - emissivity) * down
            if emitted > 0:
                surface = (emitted / (emissivity * SIGMA)) ** 0.25
        radiation = [max(values[n], 0.0) if values[n] is not None else None
                     for n in ("dw_solar", "direct_n", "diffuse")]
        rows.append(",".join([
            f"{year:04d}-{month:02d}-{day:02d}T{hour:02d}:{minute:02d}:00Z",
            fmt(values["temp"]), fmt(values["rh"]), fmt(values["pressure"]),
            fmt(values["windspd"]), fmt(values["winddir"]),
            *(fmt(r) for r in radiation), fmt(down), fmt(up), fmt(surface, 2),
        ]))
    return header, rows, dropped


def uscrn(lines, elevation_m, pressure_hpa):
    if (elevation_m is None) == (pressure_hpa is None):
        fail("USCRN measures no pressure: give --elevation-m (the standard atmosphere's "
             "pressure there) or --pressure-hpa")
    if pressure_hpa is None:
        pressure_hpa = 1013.25 * (1 - 2.25577e-5 * elevation_m) ** 5.25588
    header = [
        "# USCRN sub-hourly (NOAA NCEI, public domain); wind at 1.5 m; pressure "
        f"{pressure_hpa:.1f} hPa throughout, not measured",
        "time,air_temperature[degC],relative_humidity[%],pressure[hPa],wind_speed[m/s],"
        "ghi[W/m2 mean 300s],x_surface_temperature[K]",
    ]
    rows, dropped = [], 0
    for number, line in enumerate(lines, start=1):
        f = line.split()
        if not f:
            continue
        if len(f) != len(USCRN_FIELDS):
            fail(f"line {number}: expected {len(USCRN_FIELDS)} fields, found {len(f)}")
        v = dict(zip(USCRN_FIELDS, f))
        def good(name, missing, flag=None):
            x = float(v[name])
            if x <= missing or (flag and v[flag] != "0"):
                return None
            return x
        air = good("AIR_TEMPERATURE", -9999)
        rh = good("RELATIVE_HUMIDITY", -9999, "RH_FLAG")
        wind = good("WIND_1_5", -99, "WIND_FLAG")
        if air is None or rh is None or wind is None:
            dropped += 1
            continue
        ghi = good("SOLAR_RADIATION", -99999, "SR_FLAG")
        surface = good("SURFACE_TEMPERATURE", -9999, "ST_FLAG")
        d, t = v["UTC_DATE"], v["UTC_TIME"]
        rows.append(",".join([
            f"{d[:4]}-{d[4:6]}-{d[6:]}T{t[:2]}:{t[2:]}:00Z",
            fmt(air), fmt(rh), fmt(pressure_hpa, 1), fmt(wind),
            fmt(None if ghi is None else max(ghi, 0.0)),
            fmt(None if surface is None else surface + 273.15, 2),
        ]))
    return header, rows, dropped


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("source", choices=["surfrad", "uscrn"])
    p.add_argument("file")
    p.add_argument("--emissivity", type=float, default=0.98,
                   help="surface emissivity for SURFRAD's radiometric temperature (0.98)")
    p.add_argument("--every", type=int, default=1, help="keep one row in N minutes")
    p.add_argument("--elevation-m", type=float, help="USCRN: the station's elevation")
    p.add_argument("--pressure-hpa", type=float, help="USCRN: a pressure to use throughout")
    a = p.parse_args()
    if a.every < 1:
        fail("--every must be 1 or more")
    with open(a.file, encoding="ascii", errors="strict") as f:
        lines = f.read().splitlines()
    if a.source == "surfrad":
        header, rows, dropped = surfrad(lines, a.emissivity, a.every)
    else:
        header, rows, dropped = uscrn(lines, a.elevation_m, a.pressure_hpa)
    print("\n".join(header + rows))
    print(f"field-to-csv: {len(rows)} rows written, {dropped} left out for a missing "
          "required value", file=sys.stderr)


if __name__ == "__main__":
    main()
