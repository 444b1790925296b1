//! The interpolation error of a spectral atmosphere's `table` model between its rows,
//! against the atmospheric model's own spectra at paths that are not rows: what
//! `scripts/atmosphere/regen.py` asks while it places rows by error.
//!
//! ```text
//! cargo run --release -p irsig-atmosphere --example row_residual -- CANDIDATE.bin PATHS.csv [LO-HI]
//! ```
//!
//! `CANDIDATE.bin` is a binary spectral atmosphere with slant tables; `PATHS.csv` has a
//! header line and one path per line, `kind,observer_m,angle_deg,tau,radiance`: `kind`
//! `slant` (observer → the tables' lower end at `angle_deg` from nadir) or `sky`
//! (observer → space at `angle_deg` from zenith), `tau` and `radiance` the path's spectra
//! on the atmosphere's grid, `;`-separated (radiance per grid unit; `tau` empty for the
//! sky). For every path it prints `kind,observer_m,angle_deg,error_k`: the largest
//! apparent-temperature error (model − spectra, K) over blackbody targets of 260, 290 and
//! 320 K seen through the path (slant) or the brightness-temperature error of the sky,
//! both summed over 16 sub-bands of flat 8–14 µm, or of `LO-HI` µm when given (`3-5` for the
//! 3–5 µm built-ins; equal shares of the 300 K radiance, as
//! `irsig-trace --sub-bands 16` makes them), each sub-band's truth the same quadrature of
//! the given spectra: what is left is the interpolation between rows.

use irsig_atmosphere::{
    AtmosphereModel, BandQuadrature, Collapser, ModelKind, SubBandCount, sub_band_edges,
};
use irsig_radiometry::Band;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let (Some(bin), Some(paths)) = (args.get(1), args.get(2)) else {
        eprintln!("usage: row_residual CANDIDATE.bin PATHS.csv [LO-HI]");
        std::process::exit(2);
    };
    let [lo, hi] = match args.get(3) {
        None => [8.0, 14.0],
        Some(b) => {
            let limits: Vec<f64> = b.split('-').filter_map(|x| x.parse().ok()).collect();
            let [lo, hi] = limits[..] else {
                eprintln!("row_residual: the band `{b}` is not LO-HI in um (such as 3-5)");
                std::process::exit(2);
            };
            [lo, hi]
        }
    };
    let bytes = std::fs::read(bin).expect("the candidate atmosphere");
    let spectral = irsig_formats::canonical::binary_spectral::decode(bin, &bytes)
        .expect("a spectral atmosphere");
    let ground_m = spectral
        .slant
        .as_ref()
        .and_then(|s| s.ground_m)
        .unwrap_or(0.0);
    let share = |a: f64, b: f64| Band::new(a, b).map_or(0.0, |band| band.radiance(300.0));
    let edges = sub_band_edges(&spectral.grid, lo, hi, SubBandCount::Count(16), share)
        .expect("16 sub-bands");
    let collapser = Collapser::new(&spectral).expect("a valid atmosphere");
    let bands: Vec<(AtmosphereModel, BandQuadrature, Band)> = edges
        .windows(2)
        .map(|e| {
            let atm = collapser.collapse(e[0], e[1], |_| 1.0).expect("a sub-band");
            (
                AtmosphereModel::new(&atm, ModelKind::Table).expect("slant tables"),
                BandQuadrature::new(&spectral.grid, e[0], e[1], |_| 1.0).expect("a quadrature"),
                Band::new(e[0], e[1]).expect("a band"),
            )
        })
        .collect();
    let whole = Band::new(lo, hi).expect("the band");
    let text = std::fs::read_to_string(paths).expect("the paths");
    for line in text.lines().skip(1).filter(|l| !l.trim().is_empty()) {
        let f: Vec<&str> = line.split(',').collect();
        let (kind, h, angle) = (
            f[0],
            f[1].parse::<f64>().unwrap(),
            f[2].parse::<f64>().unwrap(),
        );
        let spectrum = |s: &str| -> Vec<f32> {
            s.split(';')
                .filter(|x| !x.is_empty())
                .map(|x| x.parse().unwrap())
                .collect()
        };
        let (tau, radiance) = (spectrum(f[3]), spectrum(f[4]));
        let error = match kind {
            "slant" => {
                let range = (h - ground_m) / angle.to_radians().cos();
                [260.0, 290.0, 320.0]
                    .iter()
                    .map(|&t| {
                        let (mut model, mut truth) = (0.0, 0.0);
                        for (m, q, b) in &bands {
                            let p = m.path(h, ground_m, range);
                            let bt = b.radiance(t);
                            model += p.transmission * bt + p.path_radiance_w_m2_sr;
                            truth += q.transmission(&tau) * bt + q.radiance(&radiance);
                        }
                        whole.temperature(model) - whole.temperature(truth)
                    })
                    .fold(0.0_f64, |a, e| if e.abs() > a.abs() { e } else { a })
            }
            "sky" => {
                let (mut model, mut truth) = (0.0, 0.0);
                for (m, q, _) in &bands {
                    model += m.sky_radiance(h, angle);
                    truth += q.radiance(&radiance);
                }
                whole.temperature(model) - whole.temperature(truth)
            }
            other => panic!("unknown path kind {other}"),
        };
        println!("{kind},{h},{angle},{error:.6}");
    }
}
