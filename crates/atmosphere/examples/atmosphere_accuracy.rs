//! Prints the atmosphere-model accuracy tables of docs/accuracy.md: each model against
//! LOWTRAN7's own slant paths, as apparent-temperature error (K) of a 300 K blackbody.
//!
//! `cargo run -p irsig-atmosphere --example atmosphere_accuracy`

// Truth rows are selected by the exact altitudes and angles written in the CSV.
#![allow(clippy::float_cmp)]

#[path = "../tests/common/lowtran.rs"]
mod lowtran;

use irsig_atmosphere::{AtmosphereModel, ModelKind};
use lowtran::{Rtt, Truth, atmosphere, error_k, truth};

fn main() {
    if std::env::args().any(|a| a == "--summary") {
        summary();
        return;
    }
    for name in ["us-std-1976", "midlat-winter"] {
        let a = atmosphere(name);
        let rtt = Rtt::new(&a);
        let mut legacy = a.clone();
        legacy.transmission_correction_altitude_m = None;
        let layered = AtmosphereModel::new(&a, ModelKind::Layered).unwrap();
        let p = layered.curve_of_growth_exponent().unwrap();
        let models: Vec<(String, AtmosphereModel)> = vec![
            (
                "thesis (1990: .cor at every altitude)".into(),
                AtmosphereModel::new(&legacy, ModelKind::Thesis).unwrap(),
            ),
            (
                "thesis (.cor scaled from its 1 km fit)".into(),
                AtmosphereModel::new(&a, ModelKind::Thesis).unwrap(),
            ),
            (
                "layered, Beer per layer (p = 1)".into(),
                layered
                    .clone()
                    .with_curve_of_growth_exponent(&a, 1.0)
                    .unwrap(),
            ),
            (format!("layered (p = {p:.3} from .cor)"), layered),
            (
                "table".into(),
                AtmosphereModel::new(&a, ModelKind::Table).unwrap(),
            ),
        ];
        let rows = truth(name);
        println!(
            "\n### {name}: slant paths to the ground, error in K (model − LOWTRAN7), 300 K blackbody\n"
        );
        let angles = [
            0.0, 30.0, 45.0, 60.0, 70.0, 75.0, 80.0, 83.0, 85.0, 87.0, 88.0, 89.0,
        ];
        for h in [300.0, 1000.0, 3000.0, 400.0, 2500.0] {
            println!("observer {h} m\n");
            print!("| model |");
            for a in angles {
                print!(" {a}° |");
            }
            println!("\n| --- |{}", " ---: |".repeat(angles.len()));
            for (label, m) in &models {
                print!("| {label} |");
                for ang in angles {
                    match rows
                        .iter()
                        .find(|t| t.kind == "ground" && t.observer_m == h && t.angle_deg == ang)
                    {
                        Some(t) => print!(" {:+.2} |", error_k(m, &rtt, t, 300.0)),
                        None => print!(" – |"),
                    }
                }
                println!();
            }
            println!();
        }
        for kind in ["segment", "horizontal"] {
            println!("{kind} paths\n");
            let sel: Vec<&Truth> = rows.iter().filter(|t| t.kind == kind).collect();
            print!("| model |");
            for t in &sel {
                match t.range_m {
                    Some(r) => print!(" {}→{} m, {r} m |", t.observer_m, t.target_m),
                    None => print!(" {}→{} m {}° |", t.observer_m, t.target_m, t.angle_deg),
                }
            }
            println!("\n| --- |{}", " ---: |".repeat(sel.len()));
            for (label, m) in &models {
                print!("| {label} |");
                for t in &sel {
                    print!(" {:+.2} |", error_k(m, &rtt, t, 300.0));
                }
                println!();
            }
            println!();
        }
        println!("sky radiance from above the ground, W m^-2 sr^-1 (LOWTRAN7 / layered / table)\n");
        println!(
            "| observer | zenith | LOWTRAN7 | thesis | layered | table |\n| ---: | ---: | ---: | ---: | ---: | ---: |"
        );
        for t in rows.iter().filter(|t| t.kind == "sky") {
            print!(
                "| {} m | {}° | {:.3} |",
                t.observer_m, t.angle_deg, t.radiance_w_m2_sr
            );
            for (_, m) in models
                .iter()
                .skip(1)
                .filter(|(l, _)| !l.contains("Beer"))
                .take(3)
            {
                print!(" {:.3} |", m.sky_radiance(t.observer_m, t.angle_deg));
            }
            println!();
        }
    }
}

/// Largest |error| (K) per model over both atmospheres, by kind of path.
fn summary() {
    let cats = lowtran::SUMMARY_CATEGORIES;
    println!(
        "\n| model |{}",
        cats.iter()
            .map(|c| format!(" {} |", c.0))
            .collect::<String>()
    );
    println!("| --- |{}", " ---: |".repeat(cats.len()));
    for (label, k) in [
        ("thesis (1990)", 0),
        ("thesis (scaled)", 1),
        ("layered, p = 1", 2),
        ("layered (fitted p)", 3),
        ("table", 4),
    ] {
        print!("| {label} |");
        for (_, sel) in &cats {
            let mut worst = 0.0_f64;
            for name in ["us-std-1976", "midlat-winter"] {
                let a = atmosphere(name);
                let rtt = Rtt::new(&a);
                let mut legacy = a.clone();
                legacy.transmission_correction_altitude_m = None;
                let m = match k {
                    0 => AtmosphereModel::new(&legacy, ModelKind::Thesis).unwrap(),
                    1 => AtmosphereModel::new(&a, ModelKind::Thesis).unwrap(),
                    2 => AtmosphereModel::new(&a, ModelKind::Layered)
                        .unwrap()
                        .with_curve_of_growth_exponent(&a, 1.0)
                        .unwrap(),
                    3 => AtmosphereModel::new(&a, ModelKind::Layered).unwrap(),
                    _ => AtmosphereModel::new(&a, ModelKind::Table).unwrap(),
                };
                for t in truth(name)
                    .iter()
                    .filter(|t| t.transmission.is_some() && sel(t))
                {
                    worst = worst.max(error_k(&m, &rtt, t, 300.0).abs());
                }
            }
            print!(" {worst:.2} K |");
        }
        println!();
    }
}
