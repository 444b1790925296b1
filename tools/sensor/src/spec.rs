//! The command-line syntax of one MTF component (`--mtf KIND:PARAMS`), documented in
//! `formats/sensor.md`.

use irsig_sensor_model::mtf::Mtf;

/// The accepted forms, for error messages and `--help`.
pub const MTF_FORMS: &str = "box:5x5 | gauss:sigma=0.8 | gauss:hp=0.25 | \
ss:across=0.3,along=0.2 | diffraction:lambda-um=10,f=2,pitch-um=25 | footprint:1x1 | \
motion:len=3,angle=30 | jitter:0.3 | jitter:x=0.3,y=0.5";

/// Parses one `--mtf` value.
///
/// # Errors
/// A message naming what was expected.
pub fn parse_mtf(text: &str) -> Result<Mtf, String> {
    let (kind, params) = text.split_once(':').unwrap_or((text, ""));
    let mtf = match kind {
        "box" => {
            let (w, h) = size(params, |v| {
                v.parse::<u32>()
                    .map_err(|_| format!("`{v}` is not a whole number of pixels"))
            })?;
            Mtf::Box {
                width_px: w,
                height_px: h,
            }
        }
        "gauss" | "gaussian" => {
            let kv = pairs(params, &["sigma", "hp"])?;
            match (get(&kv, "sigma"), get(&kv, "hp")) {
                (Some(s), None) => Mtf::Gaussian { sigma_px: s },
                (None, Some(f)) => Mtf::gaussian_half_power(f).map_err(|e| e.to_string())?,
                _ => return Err("give exactly one of sigma=PIXELS or hp=CYCLES_PER_PIXEL".into()),
            }
        }
        "ss" | "schott-salvaggio" => {
            let kv = pairs(params, &["across", "along"])?;
            Mtf::SchottSalvaggio {
                across_track_half_power_cyc_px: need(&kv, "across")?,
                along_track_half_power_cyc_px: need(&kv, "along")?,
            }
        }
        "diffraction" => {
            let kv = pairs(params, &["lambda-um", "f", "pitch-um"])?;
            Mtf::Diffraction {
                wavelength_m: need(&kv, "lambda-um")? * 1e-6,
                f_number: need(&kv, "f")?,
                pixel_pitch_m: need(&kv, "pitch-um")? * 1e-6,
            }
        }
        "footprint" => {
            let (w, h) = size(params, number)?;
            Mtf::Footprint {
                width_px: w,
                height_px: h,
            }
        }
        "motion" => {
            let kv = pairs(params, &["len", "angle"])?;
            Mtf::Motion {
                length_px: need(&kv, "len")?,
                angle_deg: get(&kv, "angle").unwrap_or(0.0),
            }
        }
        "jitter" => {
            if params.contains('=') {
                let kv = pairs(params, &["x", "y"])?;
                Mtf::Jitter {
                    sigma_x_px: need(&kv, "x")?,
                    sigma_y_px: need(&kv, "y")?,
                }
            } else {
                let s = number(params)?;
                Mtf::Jitter {
                    sigma_x_px: s,
                    sigma_y_px: s,
                }
            }
        }
        other => {
            return Err(format!(
                "unknown MTF `{other}`; expected one of {MTF_FORMS}"
            ));
        }
    };
    mtf.validate().map_err(|e| format!("`{text}`: {e}"))?;
    Ok(mtf)
}

fn number(v: &str) -> Result<f64, String> {
    v.trim()
        .parse::<f64>()
        .map_err(|_| format!("`{v}` is not a number"))
}

/// `WxH` or a single `N` meaning `NxN`.
fn size<T: Copy>(
    params: &str,
    parse: impl Fn(&str) -> Result<T, String>,
) -> Result<(T, T), String> {
    match params.split_once('x') {
        Some((w, h)) => Ok((parse(w)?, parse(h)?)),
        None if !params.is_empty() => {
            let n = parse(params)?;
            Ok((n, n))
        }
        None => Err("expected a size WIDTHxHEIGHT in pixels, e.g. 5x5".into()),
    }
}

fn pairs(params: &str, keys: &[&str]) -> Result<Vec<(String, f64)>, String> {
    let mut out = Vec::new();
    for item in params.split(',').filter(|s| !s.trim().is_empty()) {
        let (k, v) = item
            .split_once('=')
            .ok_or_else(|| format!("expected KEY=VALUE, found `{item}`"))?;
        let k = k.trim();
        if !keys.contains(&k) {
            return Err(format!("unknown key `{k}`; expected {}", keys.join(", ")));
        }
        if out.iter().any(|(seen, _)| seen == k) {
            return Err(format!("`{k}` given twice"));
        }
        out.push((k.to_owned(), number(v)?));
    }
    Ok(out)
}

fn get(kv: &[(String, f64)], key: &str) -> Option<f64> {
    kv.iter().find(|(k, _)| k == key).map(|(_, v)| *v)
}

fn need(kv: &[(String, f64)], key: &str) -> Result<f64, String> {
    get(kv, key).ok_or_else(|| format!("missing `{key}=`"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_form_parses() {
        assert_eq!(
            parse_mtf("box:5x5").unwrap(),
            Mtf::Box {
                width_px: 5,
                height_px: 5
            }
        );
        assert_eq!(
            parse_mtf("box:3").unwrap(),
            Mtf::Box {
                width_px: 3,
                height_px: 3
            }
        );
        assert_eq!(
            parse_mtf("gauss:sigma=0.8").unwrap(),
            Mtf::Gaussian { sigma_px: 0.8 }
        );
        assert_eq!(
            parse_mtf("gauss:hp=0.25").unwrap(),
            Mtf::gaussian_half_power(0.25).unwrap()
        );
        assert_eq!(
            parse_mtf("ss:across=0.3,along=0.2").unwrap(),
            Mtf::SchottSalvaggio {
                across_track_half_power_cyc_px: 0.3,
                along_track_half_power_cyc_px: 0.2
            }
        );
        let Mtf::Diffraction {
            wavelength_m,
            f_number,
            pixel_pitch_m,
        } = parse_mtf("diffraction:lambda-um=10,f=2,pitch-um=25").unwrap()
        else {
            panic!("not diffraction");
        };
        assert!((wavelength_m - 1e-5).abs() < 1e-18 && (pixel_pitch_m - 2.5e-5).abs() < 1e-18);
        assert!((f_number - 2.0).abs() < 1e-15);
        assert_eq!(
            parse_mtf("footprint:0.9x1").unwrap(),
            Mtf::Footprint {
                width_px: 0.9,
                height_px: 1.0
            }
        );
        assert_eq!(
            parse_mtf("motion:len=3,angle=30").unwrap(),
            Mtf::Motion {
                length_px: 3.0,
                angle_deg: 30.0
            }
        );
        assert_eq!(
            parse_mtf("jitter:x=0.3,y=0.5").unwrap(),
            Mtf::Jitter {
                sigma_x_px: 0.3,
                sigma_y_px: 0.5
            }
        );
    }

    #[test]
    fn bad_forms_say_what_was_expected() {
        for (bad, says) in [
            ("blur:3", "unknown MTF"),
            ("box:0x5", "out of range"),
            ("box:2.5x2", "whole number"),
            ("gauss:sigma=1,hp=0.2", "exactly one"),
            ("gauss:sigma=-1", "out of range"),
            ("ss:across=0.3", "missing `along=`"),
            ("motion:len=3,speed=2", "unknown key"),
            ("jitter:abc", "not a number"),
            ("diffraction:lambda-um=10,f=NaN,pitch-um=25", "out of range"),
        ] {
            let e = parse_mtf(bad).unwrap_err();
            assert!(e.contains(says), "`{bad}`: {e}");
        }
    }
}
