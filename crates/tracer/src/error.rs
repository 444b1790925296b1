use irsig_model::ModelError;

/// Why a scene, view or option set cannot be traced.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{kind}")]
pub struct TraceError {
    /// What is wrong.
    pub kind: TraceErrorKind,
}

impl TraceError {
    pub(crate) fn new(kind: TraceErrorKind) -> Self {
        Self { kind }
    }
}

/// What is wrong with the tracer's input.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum TraceErrorKind {
    /// The raw scene breaks a rule of the data model (empty, bad index, NaN, degenerate
    /// triangle).
    #[error("raw scene: {0}")]
    InvalidScene(ModelError),
    /// The material library breaks a rule of the data model.
    #[error("material library: {0}")]
    InvalidMaterials(ModelError),
    /// A facet names a material the library does not have.
    #[error(
        "raw scene: facets[{facet}] uses material {material}, which the material library does not define"
    )]
    UnknownMaterial {
        /// Index of the facet in the raw scene.
        facet: usize,
        /// The material id it names.
        material: u16,
    },
    /// The terrain names a material the material library does not define.
    #[error(
        "raw scene: the terrain's material is {material}, which the material library does not \
         define"
    )]
    UnknownTerrainMaterial {
        /// The material id it names.
        material: u16,
    },
    /// A material's angular emissivity table is not one irsig-radiometry can interpolate
    /// (the data model's checks should have caught it first).
    #[error("material library: material {material}: {reason}")]
    InvalidEmissivity {
        /// The material's id.
        material: u16,
        /// What is wrong with its table.
        reason: String,
    },
    /// A facet of a material with image maps has no texture coordinates to lay them by.
    #[error(
        "raw scene: facets[{facet}] (object `{object}`) has no texture coordinates, but its \
         material {material} has image maps, which need them"
    )]
    NoTextureCoordinates {
        /// Index of the facet in the raw scene.
        facet: usize,
        /// The name of the placed object it came from.
        object: String,
        /// Its material's id.
        material: u16,
    },
    /// A material's emissivity-scale map would make ε leave 0 to 1 somewhere: the scale is
    /// never clamped, so it is refused.
    #[error(
        "material library: material {material}'s emissivity map scales ε by {scale_lo} to \
         {scale_hi}, which takes ε (up to {max_emissivity} in sub-band {sub_band}, its own or, \
         under a material map, its map's materials') outside 0 to 1"
    )]
    EmissivityScaleOutOfRange {
        /// The material's id.
        material: u16,
        /// The least and greatest scale the map gives anywhere.
        scale_lo: f64,
        /// See `scale_lo`.
        scale_hi: f64,
        /// The greatest ε the map scales in the sub-band: the material's own, or under a
        /// material map its map's materials'.
        max_emissivity: f64,
        /// The sub-band (from 1).
        sub_band: usize,
    },
    /// The view breaks a rule of the data model.
    #[error("view: {0}")]
    InvalidView(ModelError),
    /// A trace option is out of range.
    #[error("trace options: {0}")]
    InvalidOptions(String),
    /// A tolerance the models on offer cannot reach in this frame: why, the reachable
    /// floor, and what it would cost.
    #[error("{0}")]
    Unreachable(String),
    /// A tile asked for is empty or reaches beyond the image.
    #[error("{0}")]
    InvalidTile(crate::tile::TileError),
    /// A pixel asked for lies outside the image.
    #[error("pixel ({column}, {row}) lies outside the {width}x{height} image")]
    PixelOutsideImage {
        /// Column asked for.
        column: u32,
        /// Row asked for.
        row: u32,
        /// Image width.
        width: u32,
        /// Image height.
        height: u32,
    },
}
