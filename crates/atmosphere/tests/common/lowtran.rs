//! LOWTRAN7 truth (written by scripts/atmosphere/regen.py --truth, kept in
//! data/lowtran/NAME/NAME.truth.csv) and the apparent-temperature error of a model on it.
#![allow(dead_code)]

use std::path::Path;

use irsig_atmosphere::{AtmosphereModel, builtin};
use irsig_model::Atmosphere;

/// One LOWTRAN7 path.
#[derive(Debug, Clone, PartialEq)]
pub struct Truth {
    pub kind: String,
    pub observer_m: f64,
    pub target_m: f64,
    pub angle_deg: f64,
    pub range_m: Option<f64>,
    pub transmission: Option<f64>,
    pub radiance_w_m2_sr: f64,
}

pub fn truth(name: &str) -> Vec<Truth> {
    let path =
        Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("data/lowtran/{name}/{name}.truth.csv"));
    let text = std::fs::read_to_string(path).unwrap();
    text.lines()
        .skip(1)
        .map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            let num = |s: &str| {
                if s.is_empty() {
                    None
                } else {
                    Some(s.parse::<f64>().unwrap())
                }
            };
            Truth {
                kind: f[0].to_owned(),
                observer_m: num(f[1]).unwrap() * 1e3,
                target_m: num(f[2]).unwrap_or(0.0) * 1e3,
                angle_deg: num(f[3]).unwrap(),
                range_m: num(f[4]).map(|r| r * 1e3),
                transmission: num(f[5]),
                radiance_w_m2_sr: num(f[6]).unwrap(),
            }
        })
        .collect()
}

pub fn atmosphere(name: &str) -> Atmosphere {
    builtin(name).unwrap()
}

/// Band radiance of a blackbody and its inverse, by linear interpolation of the
/// atmosphere's own `.rtt` (1 K steps; the interpolation error, < 0.01 K, cancels in a
/// difference of two apparent temperatures).
pub struct Rtt {
    t: Vec<f64>,
    l: Vec<f64>,
}

impl Rtt {
    pub fn new(a: &Atmosphere) -> Self {
        Self {
            t: a.band_radiance.iter().map(|r| r.0).collect(),
            l: a.band_radiance.iter().map(|r| r.1).collect(),
        }
    }
    fn interp(xs: &[f64], ys: &[f64], x: f64) -> f64 {
        let i = xs.partition_point(|&v| v <= x).clamp(1, xs.len() - 1);
        let f = (x - xs[i - 1]) / (xs[i] - xs[i - 1]);
        ys[i - 1] + f * (ys[i] - ys[i - 1])
    }
    pub fn radiance(&self, t_k: f64) -> f64 {
        Self::interp(&self.t, &self.l, t_k)
    }
    pub fn temperature(&self, l: f64) -> f64 {
        Self::interp(&self.l, &self.t, l)
    }
}

/// The geometry of a truth row as `path()` arguments: a plane-parallel slant path of the
/// row's nadir angle, or the horizontal range.
pub fn geometry(t: &Truth) -> (f64, f64, f64) {
    let range = t
        .range_m
        .unwrap_or_else(|| (t.observer_m - t.target_m) / t.angle_deg.to_radians().cos());
    (t.observer_m, t.target_m, range)
}

/// Apparent-temperature error (model − LOWTRAN) in K of a blackbody at `target_k` seen
/// through the row's path.
pub fn error_k(model: &AtmosphereModel, rtt: &Rtt, t: &Truth, target_k: f64) -> f64 {
    let (s, g, r) = geometry(t);
    let p = model.path(s, g, r);
    let lt = rtt.radiance(target_k);
    let truth = t.transmission.unwrap() * lt + t.radiance_w_m2_sr;
    rtt.temperature(p.transmission * lt + p.path_radiance_w_m2_sr) - rtt.temperature(truth)
}

/// A selection of truth paths.
pub type Select = fn(&Truth) -> bool;

/// The path categories of docs/accuracy.md's atmosphere summary table, in its column order
/// (shared by the example that prints it and the test that holds it).
pub const SUMMARY_CATEGORIES: [(&str, Select); 6] = [
    ("0–60°", |t| t.kind == "ground" && t.angle_deg <= 60.0),
    ("60–80°", |t| {
        t.kind == "ground" && t.angle_deg > 60.0 && t.angle_deg <= 80.0
    }),
    ("80–88°", |t| {
        t.kind == "ground" && t.angle_deg > 80.0 && t.angle_deg <= 88.0
    }),
    ("slabs", |t| t.kind == "segment"),
    ("horizontal ≤ 1 km", |t| {
        t.kind == "horizontal" && t.range_m.unwrap() <= 1000.0
    }),
    ("horizontal 5 km", |t| {
        t.kind == "horizontal" && t.range_m.unwrap() > 1000.0
    }),
];
