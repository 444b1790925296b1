//! A facet under a material map (asphalt and grass), solved by per-material walls through a
//! clear summer day at Golden, Colorado (formats/samples/golden-tmy3-aug.epw), against
//! plates of plain asphalt and plain grass beside it under the same sky: each part of the
//! mixed facet takes exactly its plain plate's temperature (same wall, same loads), the
//! facet's own temperature is their emission-weighted radiative mean over the area
//! fractions the map gives its triangle (by hand: 1/4 and 3/4), and the one-wall
//! approximation puts the whole facet at the host's wall. The 8–14 µm apparent temperature
//! of the mixed facet's emission under both models is printed: their difference is the
//! one-wall approximation's error (docs/accuracy.md, "The thermal model").

use std::path::Path;
use std::process::Command;

use irsig_model::RawScene;
use irsig_radiometry::Band;
use sha2::Digest;

/// Broadband emissivities of the materials below.
const EPS_ASPHALT: f64 = 0.95;
const EPS_GRASS: f64 = 0.97;

fn write(dir: &Path, name: &str, text: &str) -> String {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p.to_string_lossy().into_owned()
}

/// Three 2 m squares on the ground facing up, 10 m apart: `lot` (material 3, mapped; texture
/// coordinates (0, 0) to (1, 1) over the square), `asphalt` (1) and `grass` (2). Nothing
/// stands above any of them: each sees the whole sky.
fn scene(dir: &Path) -> String {
    let mut positions = Vec::new();
    let mut facets = Vec::new();
    for (k, material) in [3, 1, 2].into_iter().enumerate() {
        let x = 10.0 * k as f64;
        let base = positions.len();
        for (dx, dy) in [(0.0, 0.0), (2.0, 0.0), (2.0, 2.0), (0.0, 2.0)] {
            positions.push(format!("({}, {dy}, 0.0)", x + dx));
        }
        let uv = |c: [usize; 3]| {
            let corner = |i: usize| ["(0.0, 0.0)", "(1.0, 0.0)", "(1.0, 1.0)", "(0.0, 1.0)"][i];
            format!(
                ", uv: Some(({}, {}, {}))",
                corner(c[0]),
                corner(c[1]),
                corner(c[2])
            )
        };
        for c in [[0, 1, 2], [0, 2, 3]] {
            facets.push(format!(
                "(vertices: ({}, {}, {}), material: {material}, temperature_k: 300.0, \
                 object: {k}{})",
                base + c[0],
                base + c[1],
                base + c[2],
                if material == 3 { uv(c) } else { String::new() }
            ));
        }
    }
    write(
        dir,
        "scene.ron",
        &format!(
            "(objects: [\"lot\", \"asphalt\", \"grass\"], positions_m: [{}], facets: [{}])",
            positions.join(", "),
            facets.join(", ")
        ),
    )
}

/// Asphalt over soil and grass over soil, and `lot`, whose 2 × 1 index map is asphalt on
/// the left half and grass on the right; `lot`'s own thermal record is the asphalt's (the
/// pavement the grass islands lie in), what the one-wall approximation solves it with.
/// With `grass_thermal` false grass has no thermal record.
fn materials(dir: &Path, grass_thermal: bool) -> String {
    let mut png = Vec::new();
    irsig_raster::write_png_gray8(&mut png, 2, 1, &[0, 255]).unwrap();
    std::fs::write(dir.join("lot.png"), &png).unwrap();
    let soil = "(thickness_m: 1.0, conductivity_w_m_k: 0.52, density_kg_m3: 2050.0, \
                specific_heat_j_kg_k: 1840.0, source: \"soil\")";
    let asphalt = format!(
        "Some((layers: [(thickness_m: 0.1, conductivity_w_m_k: 0.75, density_kg_m3: 2110.0, \
         specific_heat_j_kg_k: 920.0, source: \"asphalt\"), {soil}], back: Adiabatic, \
         solar_absorptance: Some(0.9), thermal_emissivity: Some({EPS_ASPHALT}), source: \
         \"asphalt\"))"
    );
    let grass = if grass_thermal {
        format!(
            ", thermal: Some((layers: [(thickness_m: 0.02, conductivity_w_m_k: 0.06, \
             density_kg_m3: 300.0, specific_heat_j_kg_k: 1920.0, source: \"thatch\"), {soil}], \
             back: Adiabatic, solar_absorptance: Some(0.8), thermal_emissivity: \
             Some({EPS_GRASS}), wet_fraction: 0.3, roughness: VeryRough, source: \"grass\"))"
        )
    } else {
        String::new()
    };
    write(
        dir,
        "mats.ron",
        &format!(
            "(materials: [
               (id: 1, name: \"asphalt\", emissivity: [(0.0, {EPS_ASPHALT})], \
                specular_fraction: 0.0, source: \"t\", thermal: {asphalt}),
               (id: 2, name: \"grass\", emissivity: [(0.0, {EPS_GRASS})], specular_fraction: \
                0.0, source: \"t\"{grass}),
               (id: 3, name: \"lot\", emissivity: [(0.0, 0.9)], specular_fraction: 0.0, \
                source: \"t\", thermal: {asphalt}, maps: Some((material: Some((image: \
                \"lot.png\", form: Index(table: [(grey: 0, material: \"asphalt\"), (grey: 255, \
                material: \"grass\")]), filter: Nearest)))))])"
        ),
    )
}

fn weather() -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../formats/samples/golden-tmy3-aug.epw")
        .to_string_lossy()
        .into_owned()
}

/// Pre-dawn and solar noon on 7 August at Golden (105.2° W: noon near 19:00 UTC).
const MOMENTS: [&str; 2] = ["2001-08-07T11:00Z", "2001-08-07T19:00Z"];

/// Runs irsig-therm with `extra` flags, giving each moment's scene.
fn run(dir: &Path, materials: &str, extra: &[&str]) -> Result<Vec<RawScene>, String> {
    let scene = scene(dir);
    let raws: Vec<_> = (0..MOMENTS.len())
        .map(|k| dir.join(format!("m{k}.raw")))
        .collect();
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_irsig-therm"));
    cmd.args([&scene, "--materials", materials, "--weather", &weather()]);
    for (at, raw) in MOMENTS.iter().zip(&raws) {
        cmd.args(["--at", at, "--raw"]).arg(raw);
    }
    cmd.args(["--spin-up-h", "48", "--hemisphere-rays", "16"]);
    let out = cmd.args(extra).output().unwrap();
    if !out.status.success() {
        return Err(String::from_utf8_lossy(&out.stderr).into_owned());
    }
    Ok(raws
        .iter()
        .map(|p| {
            let bytes = std::fs::read(p).unwrap();
            irsig_formats::canonical::read_raw_scene("m.raw", &bytes).unwrap()
        })
        .collect())
}

/// `(Σ fᵢ εᵢ Tᵢ⁴ / Σ fᵢ εᵢ)^¼` of asphalt at `ta` and grass at `tg`, asphalt's share `fa`.
fn radiative_mean(fa: f64, ta: f64, tg: f64) -> f64 {
    let (wa, wg) = (fa * EPS_ASPHALT, (1.0 - fa) * EPS_GRASS);
    ((wa * ta.powi(4) + wg * tg.powi(4)) / (wa + wg)).powf(0.25)
}

/// The 8–14 µm brightness temperature of the mixed facet's emission `Σ fᵢ εᵢ L(Tᵢ)`.
fn apparent_k(band: &Band, fa: f64, ta: f64, tg: f64) -> f64 {
    band.temperature(
        fa * EPS_ASPHALT * band.radiance(ta) + (1.0 - fa) * EPS_GRASS * band.radiance(tg),
    )
}

#[test]
fn each_material_of_a_mapped_facet_takes_its_own_walls_temperature() {
    let dir = tempfile::tempdir().unwrap();
    let mats = materials(dir.path(), true);
    let per = run(dir.path(), &mats, &[]).unwrap();
    let one = run(dir.path(), &mats, &["--mixture", "one-wall"]).unwrap();
    let band = Band::new(8.0, 14.0).unwrap();
    for (k, (p, o)) in per.iter().zip(&one).enumerate() {
        // The plain plates: facets 2, 3 asphalt, 4, 5 grass.
        let (ta, tg) = (p.facets[2].temperature_k, p.facets[4].temperature_k);
        assert_eq!(p.mix_temperatures.len(), 2, "{:?}", p.mix_temperatures);
        // Facet 0 ((0,0), (1,0), (1,1) in u, v) is 1/4 asphalt (u < 1/2), facet 1 3/4.
        for (facet, fa) in [(0usize, 0.25), (1, 0.75)] {
            let t = p.mix_temperatures_of(facet).unwrap();
            assert!((t[0] - ta).abs() < 1e-9, "{k}: {t:?} against asphalt {ta}");
            assert!((t[1] - tg).abs() < 1e-9, "{k}: {t:?} against grass {tg}");
            let mean = radiative_mean(fa, ta, tg);
            let got = p.facets[facet].temperature_k;
            assert!(
                (got - mean).abs() < 1e-9,
                "{k}: facet {facet}: {got}, by hand {mean}"
            );
        }
        // One wall: the host's record (the asphalt's) for the whole facet, no entries.
        assert!(o.mix_temperatures.is_empty());
        let t_one = o.facets[0].temperature_k;
        assert!((t_one - o.facets[2].temperature_k).abs() < 1e-9);
        let per_k = apparent_k(&band, 0.5, ta, tg);
        let one_k = apparent_k(&band, 0.5, t_one, t_one);
        println!(
            "{}: asphalt {ta:.2} K, grass {tg:.2} K; a 50/50 facet's 8-14 um apparent \
             temperature of its emission: per-material {per_k:.2} K, one-wall {one_k:.2} K, \
             error {:+.2} K",
            MOMENTS[k],
            one_k - per_k
        );
    }
    // At noon the asphalt is tens of kelvin above the grass; before dawn the two are within
    // a few kelvin of each other, asphalt the warmer (it stored the day's heat).
    let noon = &per[1];
    let (ta, tg) = (noon.facets[2].temperature_k, noon.facets[4].temperature_k);
    assert!(ta - tg > 10.0, "noon: asphalt {ta}, grass {tg}");
    let night = &per[0];
    let (ta, tg) = (night.facets[2].temperature_k, night.facets[4].temperature_k);
    assert!(ta > tg, "night: asphalt {ta}, grass {tg}");
}

#[test]
fn a_map_material_without_a_thermal_record_is_refused_naming_host_map_and_material() {
    let dir = tempfile::tempdir().unwrap();
    let mats = materials(dir.path(), false);
    let e = run(dir.path(), &mats, &[]).unwrap_err();
    assert!(
        e.contains("material `grass` (id 2) has no thermal properties")
            && e.contains("the material map `lot.png` of material `lot` (id 3)")
            && e.contains("--mixture one-wall"),
        "{e}"
    );
    assert!(!dir.path().join("m0.raw").exists() && !dir.path().join("m1.raw").exists());
    // The host's one wall needs no record of grass (grass's plate has none either: held).
    let held = run(
        dir.path(),
        &mats,
        &["--mixture", "one-wall", "--hold", "grass=300"],
    )
    .unwrap();
    assert!(held[0].mix_temperatures.is_empty());
}

#[test]
fn the_map_image_the_parts_were_read_from_is_in_the_history_provenance() {
    let dir = tempfile::tempdir().unwrap();
    let mats = materials(dir.path(), true);
    let history = |mixture: &str| {
        let h = dir.path().join(format!("{mixture}.thm"));
        let h_arg = h.to_string_lossy().into_owned();
        run(
            dir.path(),
            &mats,
            &["--mixture", mixture, "--history", &h_arg],
        )
        .unwrap();
        irsig_formats::canonical::binary_history::decode("h.thm", &std::fs::read(&h).unwrap())
            .unwrap()
            .provenance
            .inputs
    };
    // The image's digest, by sha2 over the file's bytes, as every input record writes it.
    let png = std::fs::read(dir.path().join("lot.png")).unwrap();
    let hex: String = sha2::Sha256::digest(&png)
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect();
    let digest = format!("sha256:{hex}");
    let per = history("per-material");
    let maps: Vec<_> = per.iter().filter(|r| r.role == "map image").collect();
    assert_eq!(maps.len(), 1, "{per:?}");
    assert_eq!(maps[0].sha256, digest);
    assert_eq!(maps[0].stage, "therm");
    // One wall never reads the image: nothing of it decided the temperatures.
    let one = history("one-wall");
    assert!(one.iter().all(|r| r.role != "map image"), "{one:?}");
}
