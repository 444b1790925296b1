//! The sun's day against its solar table's: `irsig-trace --sun-utc` on a date other than
//! the day the atmosphere was built for scales the beam by the two days' Earth–Sun
//! distance factors and says so once; on the table's own day it is the table's beam and
//! says nothing; a pipeline's `At` sun does the same through the tool.
//!
//! One atmosphere is built by LOWTRAN7 for a sun 30° from the zenith on day 286 (13
//! October). The sun is then seen from the equator on the prime meridian at the moment of
//! a morning when it stands 30° from the zenith: on 13 October, and on 1 March (day 60).
//! A grey diffuse plate, horizontal, gains `τ (1 − ε) E cos θ/π` from the sun; the ratio of
//! the two days' gains is the beam's, `(r₀/r)²` of 1 March over 13 October, which
//! Spencer's series (1971) gives by hand as 1.018984 / 1.004745 = 1.014172.
//!
//! LOWTRAN7 is `$IRSIG_LOWTRAN`, else `lowtran7` on PATH: without it this test fails,
//! saying so, and never skips.

use std::path::Path;

use irsig_atmosphere::sun::SunSpec;
use irsig_model::truth::Layer;
use irsig_tests::sunlit_plate::{plan_ron_over, plate};
use irsig_tests::{bin, lowtran};

/// The table's sun and day, and the factor 1 March's beam is of it, by hand (above).
const ZENITH_DEG: f64 = 30.0;
const TABLE_DAY: u32 = 286;
const MARCH_OVER_OCTOBER: f64 = 1.018_984 / 1.004_745;

/// A plan of one view down, 4-5 µm (2000-2500 cm⁻¹, both edges on the grid), and the
/// sun's beam at 0, 300 and 1000 m, on the table's day.
fn plan_ron() -> String {
    plan_ron_over(
        &format!("{ZENITH_DEG:.1}"),
        &TABLE_DAY.to_string(),
        [1980.0, 2520.0, 20.0],
    )
}

/// The sun seen from (0°, 0°) at `utc`, geometric, as `--sun-utc` without the air's flags.
fn seen_at(utc: &str) -> SunSpec {
    SunSpec::At {
        utc: utc.to_owned(),
        latitude_deg: 0.0,
        longitude_deg: 0.0,
        altitude_m: 0.0,
        refraction: None,
        delta_t_s: None,
        delta_ut1_s: None,
    }
}

/// The moment of the morning of `date` (`YYYY-MM-DD`) when the sun seen from (0°, 0°)
/// stands `ZENITH_DEG` from the zenith, to the microsecond: bisection between 06:00 and
/// 12:00 UTC, through which its zenith angle falls there.
fn morning_at_zenith(date: &str) -> String {
    let utc = |us: u64| {
        let (h, rest) = (us / 3_600_000_000, us % 3_600_000_000);
        let (m, rest) = (rest / 60_000_000, rest % 60_000_000);
        format!(
            "{date}T{h:02}:{m:02}:{:02}.{:06}Z",
            rest / 1_000_000,
            rest % 1_000_000
        )
    };
    let zenith = |us: u64| seen_at(&utc(us)).position().unwrap().zenith_deg;
    let (mut lo, mut hi) = (6 * 3_600_000_000_u64, 12 * 3_600_000_000_u64);
    assert!(zenith(lo) > ZENITH_DEG && zenith(hi) < ZENITH_DEG);
    while hi - lo > 1 {
        let mid = lo + (hi - lo) / 2;
        if zenith(mid) > ZENITH_DEG {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let z = zenith(hi);
    assert!((z - ZENITH_DEG).abs() < 1e-5, "{date}: {z}");
    utc(hi)
}

fn layer(path: &Path, name: &str) -> Vec<f32> {
    let r = irsig_raster::read_exr(&std::fs::read(path).unwrap()).unwrap();
    r.layer(name).unwrap().data.clone()
}

/// `irsig-trace` of the plate through `atmosphere` in 4-5 µm, one sub-band, with `extra`
/// flags, into `dir/PREFIX.*`; its stderr.
fn trace(dir: &Path, atmosphere: &Path, prefix: &str, extra: &[&str]) -> String {
    let [scene, materials, view] = plate(dir);
    let out = bin("irsig-trace")
        .arg("--scene")
        .arg(scene)
        .arg("--materials")
        .arg(materials)
        .arg("--view")
        .arg(view)
        .arg("--atmosphere")
        .arg(atmosphere)
        .args(["--band", "4-5", "--sub-bands", "1"])
        .args(extra)
        .arg("-o")
        .arg(dir.join(prefix))
        .assert()
        .success();
    String::from_utf8_lossy(&out.get_output().stderr).into_owned()
}

/// What the sun adds to each pixel of `dir/PREFIX`, over the night's.
fn added(dir: &Path, prefix: &str) -> Vec<f64> {
    let day = layer(&dir.join(format!("{prefix}.radiance.exr")), "radiance");
    let night = layer(&dir.join("night.radiance.exr"), "radiance");
    day.iter()
        .zip(&night)
        .map(|(d, n)| f64::from(*d) - f64::from(*n))
        .collect()
}

#[test]
fn a_sun_seen_on_another_day_than_its_tables_gets_that_days_beam_and_a_note() {
    let dir = tempfile::tempdir().unwrap();
    let plan_dir = dir.path().join("plan");
    std::fs::create_dir(&plan_dir).unwrap();
    std::fs::write(plan_dir.join("plan.ron"), plan_ron()).unwrap();
    let spa = dir.path().join("october.spa");
    bin("irsig-atmos")
        .env("IRSIG_LOWTRAN", lowtran())
        .arg("build")
        .arg(&plan_dir)
        .args(["--atmosphere", "us-std-1976", "-o"])
        .arg(&spa)
        .assert()
        .success();
    let out = dir.path().join("out");
    std::fs::create_dir(&out).unwrap();
    let place = ["--latitude-deg", "0", "--longitude-deg", "0"];
    let october = morning_at_zenith("2026-10-13");
    let march = morning_at_zenith("2026-03-01");
    assert_eq!(seen_at(&march).day_of_year(), Some(60));
    assert_eq!(seen_at(&october).day_of_year(), Some(286));

    trace(&out, &spa, "night", &[]);
    let said_october = trace(
        &out,
        &spa,
        "october",
        &[&["--sun-utc", october.as_str()][..], &place].concat(),
    );
    assert!(!said_october.contains("Earth-Sun"), "{said_october}");
    let said_march = trace(
        &out,
        &spa,
        "march",
        &[&["--sun-utc", march.as_str()][..], &place].concat(),
    );
    // Said once, with both days and the factor.
    assert_eq!(said_march.matches("Earth-Sun").count(), 1, "{said_march}");
    for says in ["day 60", "day 286", "x1.0142", "Spencer 1971"] {
        assert!(said_march.contains(says), "`{says}` not in: {said_march}");
    }

    // Every pixel: 1 March's gain is 13 October's times the factor by hand, and so is
    // the irradiance the truth records.
    let (oct, mar) = (added(&out, "october"), added(&out, "march"));
    let irradiance = |prefix: &str| {
        layer(
            &out.join(format!("{prefix}.truth.exr")),
            Layer::SolarIrradiance.name(),
        )
    };
    let (e_oct, e_mar) = (irradiance("october"), irradiance("march"));
    let mut worst = 0.0_f64;
    for p in 0..oct.len() {
        assert!(oct[p] > 0.0, "pixel {p}: the sun adds {}", oct[p]);
        // f32 images: the gain is a few per cent of the pixel's radiance, whose f32
        // rounding (6e-8 of it) is then under 1e-5 of the gain.
        let ratio = mar[p] / oct[p];
        worst = worst.max((ratio / MARCH_OVER_OCTOBER - 1.0).abs());
        assert!(
            (ratio / MARCH_OVER_OCTOBER - 1.0).abs() < 1e-5,
            "pixel {p}: 1 March adds {} and 13 October {}, ratio {ratio}, by hand \
             {MARCH_OVER_OCTOBER}",
            mar[p],
            oct[p]
        );
        let e_ratio = f64::from(e_mar[p]) / f64::from(e_oct[p]);
        assert!(
            (e_ratio / MARCH_OVER_OCTOBER - 1.0).abs() < 1e-6,
            "pixel {p}: E {} against {}",
            e_mar[p],
            e_oct[p]
        );
    }
    eprintln!(
        "sun 30 deg on {march} and {october}: 1 March's gain / 13 October's = {:.6}, by hand \
         {MARCH_OVER_OCTOBER:.6}; worst relative error {worst:.1e}",
        mar[0] / oct[0]
    );

    // A pipeline's `At` sun on 1 March, run by irsig-run: the flags' pixels and the note.
    let pipe = out.join("pipe");
    std::fs::create_dir(&pipe).unwrap();
    std::fs::copy(&spa, pipe.join("october.spa")).unwrap();
    plate(&pipe);
    std::fs::write(
        pipe.join("lit.ron"),
        format!(
            "(\n  sun: At(utc: \"{march}\", latitude_deg: 0.0, longitude_deg: 0.0),\n  stages: \
             [Stage(tool: \"trace\", inputs: {{\"scene\": \"plate.raw.ron\", \"materials\": \
             \"grey.ron\", \"view\": \"down.ron\", \"atmosphere\": \"october.spa\"}}, params: \
             {{\"band\": \"4-5\", \"sub-bands\": 1}}, outputs: {{\"radiance-exr\": \
             \"piped/frame.radiance.exr\"}})],\n)\n"
        ),
    )
    .unwrap();
    let run = bin("irsig-run")
        .arg("lit.ron")
        .current_dir(&pipe)
        .assert()
        .success();
    let said = String::from_utf8_lossy(&run.get_output().stderr).into_owned();
    assert!(said.contains("x1.0142"), "{said}");
    assert_eq!(
        layer(&pipe.join("piped/frame.radiance.exr"), "radiance"),
        layer(&out.join("march.radiance.exr"), "radiance"),
        "the pipeline's sun differs from the flags'"
    );
}
