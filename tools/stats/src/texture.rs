//! `--texture REGION`: a region's texture statistics (σ, the autocorrelation and the
//! correlation lengths, `irsig_regions::texture`) written as a texture description a
//! material can carry (`formats/canonical/material-library.md`, "Statistical texture").

use std::fmt::Write as _;
use std::path::PathBuf;

use irsig_model::RegionSet;
use irsig_regions::texture::{TextureEstimate, estimate, region_plane};
use miette::miette;

/// The texture estimate's flags.
#[derive(Debug, Clone, clap::Args)]
pub struct TextureArgs {
    /// Estimate the texture of this region of the regions file (its name): the standard
    /// deviation of its temperatures and their correlation lengths along the image's rows
    /// (x, east) and columns (y, north), fitted by a Gaussian or an exponential
    /// correlation, written to --texture-out as a material's `texture`
    #[arg(long, value_name = "REGION", requires_all = ["pixel_m", "texture_out"])]
    pub texture: Option<String>,
    /// The ground length of one pixel, m: one for both axes or `X,Y` (a nadir view's
    /// footprint: 2·height·tan(fov/2)/pixels)
    #[arg(long = "pixel-m", value_name = "M[,M]", value_parser = parse_pixel_m, requires = "texture")]
    pub pixel_m: Option<[f64; 2]>,
    /// Where the texture description goes (RON; written atomically)
    #[arg(long = "texture-out", value_name = "FILE", requires = "texture")]
    pub texture_out: Option<PathBuf>,
    /// The seed the description gives its field
    #[arg(
        long = "texture-seed",
        value_name = "N",
        default_value_t = 1,
        requires = "texture"
    )]
    pub texture_seed: u64,
}

/// `M` or `X,Y`, each finite and above 0.
fn parse_pixel_m(text: &str) -> Result<[f64; 2], String> {
    let parse = |s: &str| -> Result<f64, String> {
        match s.trim().parse::<f64>() {
            Ok(v) if v.is_finite() && v > 0.0 => Ok(v),
            _ => Err(format!("`{s}`: expected a length in metres above 0")),
        }
    };
    match text.split_once(',') {
        None => parse(text).map(|v| [v, v]),
        Some((x, y)) => Ok([parse(x)?, parse(y)?]),
    }
}

/// What [`describe`] reads.
#[derive(Debug)]
pub(crate) struct Request<'a> {
    pub(crate) region: &'a str,
    pub(crate) pixel_m: [f64; 2],
    pub(crate) seed: u64,
    pub(crate) set: &'a RegionSet,
    pub(crate) ids: &'a [f32],
    pub(crate) values: &'a [f32],
    pub(crate) width: usize,
    pub(crate) unit: &'a str,
    pub(crate) source: &'a str,
    pub(crate) regions_name: &'a str,
}

/// The texture description of the region, as the text of its file: the estimate's
/// figures as comments, then the `texture` value.
///
/// # Errors
/// No region of that name, values that are not temperatures, or a region whose texture
/// cannot be estimated (too small, uniform).
pub(crate) fn describe(r: &Request<'_>) -> miette::Result<String> {
    let Some(region) = r.set.regions.iter().find(|g| g.name == r.region) else {
        let names: Vec<&str> = r.set.regions.iter().map(|g| g.name.as_str()).collect();
        return Err(irsig_cli::usage_error(format!(
            "--texture {}: {} has no region of that name (it has: {})",
            r.region,
            r.regions_name,
            names.join(", ")
        )));
    };
    if r.unit != "K" {
        return Err(irsig_cli::usage_error(format!(
            "--texture {}: the values ({}) are not temperatures: expected a temperature \
             layer, whose texture a material's temperature offset takes",
            r.region, r.source
        )));
    }
    let (plane, width) = region_plane(region, r.ids, r.values, r.width).map_err(|p| {
        miette!(
            "--texture {}: the region has no values to estimate ({p:?})",
            r.region
        )
    })?;
    let e = estimate(&plane, width, r.pixel_m).map_err(|p| {
        miette!(
            "--texture {}: the texture of {} cannot be estimated: {p}",
            r.region,
            r.source
        )
    })?;
    let ron = irsig_formats::canonical::to_ron_pretty(&e.temperature_texture(r.seed))
        .map_err(|err| miette!("the texture description could not be written: {err}"))?;
    Ok(format!("{}{ron}\n", header(r, &e)))
}

/// The estimate's figures as RON comment lines.
fn header(r: &Request<'_>, e: &TextureEstimate) -> String {
    let mut h = String::new();
    let _ = writeln!(
        h,
        "// The texture of region `{}` of the {}: {} pixels of {} x {} m.",
        r.region, r.source, e.pixels, r.pixel_m[0], r.pixel_m[1]
    );
    let _ = writeln!(
        h,
        "// mean {:.4} K, sigma {:.4} K (standard error {:.4} K)",
        e.mean, e.sigma, e.sigma_standard_error
    );
    let _ = writeln!(
        h,
        "// correlation length along x {:.4} m, along y {:.4} m; RMS residual of the fit {:.4} \
         (the other spectrum's {:.4})",
        e.correlation_length_m[0], e.correlation_length_m[1], e.residual[0], e.residual[1]
    );
    for (axis, c) in ["x", "y"].iter().zip(&e.autocorrelation) {
        let values: Vec<String> = c.iter().map(|v| format!("{v:.3}")).collect();
        let _ = writeln!(
            h,
            "// autocorrelation along {axis} at 0, 1, 2, ... pixels: {}",
            values.join(" ")
        );
    }
    h.push_str("// Paste as a material's `texture: Some(...)`.\n");
    h
}

#[cfg(test)]
mod tests {
    use super::*;

    use irsig_model::{MaterialId, Region};

    /// A 64 × 64 image of material 1 whose temperatures alternate in 4-pixel stripes
    /// along x, 300 ± 1 K (σ 1 K exactly), and a region over it.
    fn request<'a>(set: &'a RegionSet, ids: &'a [f32], values: &'a [f32]) -> Request<'a> {
        Request {
            region: "plate",
            pixel_m: [0.1, 0.1],
            seed: 5,
            set,
            ids,
            values,
            width: 64,
            unit: "K",
            source: "test image",
            regions_name: "regions.ron",
        }
    }

    fn set() -> RegionSet {
        RegionSet {
            references: vec![],
            regions: vec![Region {
                name: "plate".into(),
                material: Some(MaterialId(1)),
                pixels: None,
                references: vec![],
            }],
        }
    }

    #[test]
    fn a_region_becomes_a_texture_description_a_material_reads() {
        let ids = vec![1.0f32; 64 * 64];
        let values: Vec<f32> = (0..64 * 64)
            .map(|i| if (i % 64) / 4 % 2 == 0 { 301.0 } else { 299.0 })
            .collect();
        let set = set();
        let text = describe(&request(&set, &ids, &values)).unwrap();
        // The comments are RON comments: the file reads as it is.
        let texture: irsig_model::texture::StatisticalTexture =
            irsig_formats::canonical::from_ron_as("t.ron", &text, "a texture").unwrap();
        assert!(texture.validate("texture").is_ok());
        assert_eq!(texture.seed, 5);
        let field = texture.temperature_offset_k.unwrap();
        assert!((field.sigma - 1.0).abs() < 1e-9, "{}", field.sigma);
        assert!(text.contains("sigma 1.0000 K"), "{text}");
    }

    #[test]
    fn what_cannot_be_described_is_refused_with_the_reason() {
        let ids = vec![1.0f32; 64 * 64];
        let uniform = vec![300.0f32; 64 * 64];
        let set = set();
        let e = describe(&request(&set, &ids, &uniform)).unwrap_err();
        assert!(e.to_string().contains("do not vary"), "{e}");
        let mut r = request(&set, &ids, &uniform);
        r.region = "road";
        assert!(
            describe(&r)
                .unwrap_err()
                .to_string()
                .contains("(it has: plate)")
        );
        let mut r = request(&set, &ids, &uniform);
        r.unit = "W m^-2";
        assert!(
            describe(&r)
                .unwrap_err()
                .to_string()
                .contains("not temperatures")
        );
    }

    #[test]
    fn pixel_lengths_are_one_or_two_positive_numbers() {
        assert_eq!(parse_pixel_m("0.1"), Ok([0.1, 0.1]));
        assert_eq!(parse_pixel_m("0.1,0.2"), Ok([0.1, 0.2]));
        for bad in ["0", "-1", "NaN", "inf", "x", "0.1,", "0.1,0"] {
            assert!(parse_pixel_m(bad).is_err(), "{bad}");
        }
    }
}
