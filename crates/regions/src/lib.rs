//! irsig-regions: the thesis's local-area analysis (Shor 1990, §4.8–4.9, Tables 5–7): per
//! region of an image (a material id, a pixel box or both, `irsig_model::RegionSet`), the
//! pixel count and the mean, standard deviation, minimum and maximum of its values, beside
//! each reference value and the difference mean − reference. `irsig-stats` prints the
//! table; the run report (`irsig-report`) shows the same numbers from the images it has
//! read. Knows no command line and prints nothing; a region that does not fit the image is
//! an error at its line and column in the regions file.
//!
//! ```
//! use irsig_model::{MaterialId, Region, RegionSet};
//! let set = RegionSet {
//!     references: vec![],
//!     regions: vec![Region {
//!         name: "plate".into(),
//!         material: Some(MaterialId(1)),
//!         pixels: None,
//!         references: vec![],
//!     }],
//! };
//! let table = irsig_regions::tabulate(&irsig_regions::Inputs {
//!     regions_name: "regions.ron",
//!     regions_text: "",
//!     set: &set,
//!     image_name: "truth.exr",
//!     material_ids: &[1.0, 1.0, 2.0, 0.0],
//!     width: 2,
//!     values: &[300.0, 302.0, 400.0, 250.0],
//!     source: "apparent temperature".into(),
//!     unit: "K",
//!     celsius: false,
//! })?;
//! assert_eq!((table.regions[0].pixels, table.regions[0].mean), (2, 301.0));
//! # Ok::<(), miette::Report>(())
//! ```

#![deny(clippy::print_stdout, clippy::print_stderr)]

pub mod stats;
pub mod texture;

use irsig_model::RegionSet;
use serde::Serialize;

use crate::stats::{RegionProblem, RegionStats, region_stats};

/// 0 °C in kelvin.
const ZERO_CELSIUS_K: f64 = 273.15;

/// One region's row of the table.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Row {
    /// The region's name.
    pub region: String,
    /// Pixels selected.
    pub pixels: usize,
    /// Mean, in the table's unit.
    pub mean: f64,
    /// Population standard deviation, K.
    pub std_dev: f64,
    /// Minimum, in the table's unit.
    pub min: f64,
    /// Maximum, in the table's unit.
    pub max: f64,
    /// Per reference column (in the file's order): the reference and mean − reference;
    /// `None` where the region gives no value for that column.
    pub references: Vec<Option<Compared>>,
}

/// A reference value and our mean's difference from it.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Compared {
    /// The reference, in the table's unit.
    pub reference: f64,
    /// Mean − reference, K.
    pub difference: f64,
}

/// Everything the output shows.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Table {
    /// Where the values come from (`apparent_temperature of out/f.truth.exr`).
    pub values: String,
    /// The values' unit: `K` or `degC` for temperatures, else the layer's own
    /// ([`irsig_model::truth::Layer::unit`]: `W m^-2`, `m`, empty for a ratio).
    pub unit: String,
    /// Reference columns: name and source.
    pub references: Vec<(String, String)>,
    /// One row per region, in the regions file's order.
    pub regions: Vec<Row>,
}

/// What [`tabulate`] reads: the regions (their file's name and text, for messages at the
/// offending line), the image's material ids and values, pixel by pixel.
#[derive(Debug)]
pub struct Inputs<'a> {
    /// The regions file's name, for messages.
    pub regions_name: &'a str,
    /// Its text, for the line and column of a region that does not fit the image.
    pub regions_text: &'a str,
    /// The regions, as read from that text.
    pub set: &'a RegionSet,
    /// The image's name, for messages.
    pub image_name: &'a str,
    /// The `material_primary` layer, row by row.
    pub material_ids: &'a [f32],
    /// The image's width, pixels.
    pub width: usize,
    /// The values, in `unit`, one per pixel in the same order.
    pub values: &'a [f32],
    /// Where the values come from, in words (the table's `values`).
    pub source: String,
    /// The values' unit: `K` for temperatures (the only values a regions file's references
    /// are compared with and `celsius` applies to), else the layer's own.
    pub unit: &'a str,
    /// Show temperatures in degC rather than K.
    pub celsius: bool,
}

/// A unit in words, for messages: `a ratio` when it has none.
fn unit_words(unit: &str) -> String {
    if unit.is_empty() {
        "a ratio, no unit".into()
    } else {
        format!("in {unit}")
    }
}

/// The table of per-region statistics of `inputs.values`, from images the caller has read.
///
/// # Errors
/// A region that reaches beyond the image, selects no pixel or meets a non-finite value,
/// at the region's line in the regions file; degC or references for values that are not
/// temperatures.
pub fn tabulate(inputs: &Inputs<'_>) -> miette::Result<Table> {
    let temperature = inputs.unit == "K";
    if !temperature && inputs.celsius {
        miette::bail!(
            "{} is not a temperature ({}): degC applies to temperatures only",
            inputs.source,
            unit_words(inputs.unit)
        );
    }
    if !temperature && !inputs.set.references.is_empty() {
        miette::bail!(
            "{}: the references of {} are temperatures (K) and the values are not ({}): \
             compare a temperature layer, or use a regions file without references",
            inputs.regions_name,
            inputs.source,
            unit_words(inputs.unit)
        );
    }
    let offset = if inputs.celsius { ZERO_CELSIUS_K } else { 0.0 };
    let mut rows = Vec::with_capacity(inputs.set.regions.len());
    for (i, region) in inputs.set.regions.iter().enumerate() {
        let s: RegionStats = region_stats(region, inputs.material_ids, inputs.values, inputs.width)
            .map_err(|p| {
                let (path, message) = match p {
                    RegionProblem::BoxOutside { width, height } => (
                        format!("regions[{i}].pixels"),
                        format!(
                            "region `{}`: the box reaches beyond the image {} ({width} x {height} \
                         pixels: columns 0-{}, rows 0-{})",
                            region.name,
                            inputs.image_name,
                            width.saturating_sub(1),
                            height.saturating_sub(1)
                        ),
                    ),
                    RegionProblem::Empty => (
                        format!("regions[{i}]"),
                        format!(
                            "region `{}` selects no pixel of {}: expected at least one pixel \
                         {}",
                            region.name,
                            inputs.image_name,
                            selection(region)
                        ),
                    ),
                    RegionProblem::NotFinite { column, row } => (
                        format!("regions[{i}]"),
                        format!(
                            "region `{}`: pixel ({column}, {row}) has no finite value ({})",
                            region.name, inputs.source
                        ),
                    ),
                };
                irsig_formats::canonical::error_at_path(
                    inputs.regions_name,
                    inputs.regions_text,
                    &path,
                    message,
                )
            })?;
        let references = inputs
            .set
            .references
            .iter()
            .map(|c| {
                RegionSet::reference(region, &c.name).map(|r| Compared {
                    reference: r - offset,
                    difference: s.mean - r,
                })
            })
            .collect();
        rows.push(Row {
            region: region.name.clone(),
            pixels: s.pixels,
            mean: s.mean - offset,
            std_dev: s.std_dev,
            min: s.min - offset,
            max: s.max - offset,
            references,
        });
    }
    Ok(Table {
        values: inputs.source.clone(),
        unit: if inputs.celsius { "degC" } else { inputs.unit }.into(),
        references: inputs
            .set
            .references
            .iter()
            .map(|c| (c.name.clone(), c.source.clone()))
            .collect(),
        regions: rows,
    })
}

/// What a region asks for, in words.
fn selection(region: &irsig_model::Region) -> String {
    let material = region.material.map(|m| format!("of material {}", m.0));
    let pixels = region.pixels.map(|b| {
        format!(
            "in columns {}-{}, rows {}-{}",
            b.columns.0, b.columns.1, b.rows.0, b.rows.1
        )
    });
    [material, pixels]
        .into_iter()
        .flatten()
        .collect::<Vec<_>>()
        .join(" ")
}
