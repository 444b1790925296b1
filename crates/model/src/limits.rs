//! The memory budget every reader checks a size against before it allocates.
//!
//! Sizes read from a file (an image's pixel count, a header's claimed dimensions, a file's
//! length) are taken on trust by nothing: a 400-byte EXR that claims 100,000 × 100,000
//! pixels, or a view of 4,294,967,295 columns, is refused with a location instead of
//! aborting on an allocation of tens of gigabytes.

/// The most pixels one image may have: 2²⁶ = 67,108,864 (8,192 × 8,192). This holds for a
/// view, for every frame a tracer renders and for an EXR read back. The tracer keeps about
/// 150 bytes per pixel of a frame with every truth layer, so one frame stays within
/// [`MEMORY_BUDGET_BYTES`].
pub const MAX_IMAGE_PIXELS: u64 = 1 << 26;

/// The most bytes a reader allocates for one file's content or one decoded image: 16 GiB.
pub const MEMORY_BUDGET_BYTES: u64 = 16 << 30;

/// The longest input file a tool reads whole: 4 GiB. Longer inputs, and endless ones such
/// as a device, are refused before they are read.
pub const MAX_INPUT_BYTES: u64 = 4 << 30;

/// The largest coordinate a scene or object may have, metres: 10⁹ m, more than twice the
/// Moon's distance. Beyond it a triangle's area overflows and it could not be told from a
/// degenerate one.
pub const MAX_COORDINATE_M: f64 = 1e9;

/// The wavelengths a sensor response table may hold, µm: from 0.2 (the ultraviolet edge of
/// what reaches the ground) to 1000 (the far infrared's end). A wider table is no sensor's;
/// the quadrature of a band is then bounded by the table's rows, not by its span.
pub const RESPONSE_WAVELENGTH_UM: [f64; 2] = [0.2, 1000.0];

/// The largest value a sensor response table may hold: 10⁶ (relative responses, per cents
/// and counts all fit). A band radiance weighted by it stays finite at any temperature a
/// scene holds.
pub const MAX_RESPONSE: f64 = 1e6;

/// The temperatures a band average may be Planck-weighted at, kelvin: from 1 K (below it
/// no thermal-infrared source is left to weight by) to 10,000 K (above the Sun's
/// photosphere, 5,778 K, the hottest source a scene's light comes from, whose weighting
/// gives a material's solar absorptance). A temperature outside them is a mistake, not a
/// weighting.
pub const PLANCK_WEIGHTING_K: [f64; 2] = [1.0, 10_000.0];

/// The largest RMS facet slope a rough surface may have (dimensionless: `σ² = ⟨z_x² +
/// z_y²⟩`, the tangent of the facets' tilt): 10, a mean facet tilt of 84°. A material's
/// `rms_slope` and the rough-surface emissivity (`irsig_radiometry::fresnel`) share it.
pub const MAX_RMS_SLOPE: f64 = 10.0;
