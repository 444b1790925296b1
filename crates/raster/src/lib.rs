//! Images as irsig's stages hand them to each other: a [`Raster`] of named `f32` layers,
//! each with its unit, and the files they live in.
//!
//! - **EXR** ([`write_exr`], [`read_exr`]): every layer is an `f32` channel of one EXR
//!   part, losslessly compressed; the layers' units are stored in the text attribute
//!   `irsig.units`, one `name=unit` line per layer. Files from other programs read too (their channels become
//!   layers, with `f16`/`u32` samples converted to `f32` and unknown units left empty).
//! - **PNG** ([`write_png_gray8`], [`write_png_gray16`], [`write_png_rgb8`],
//!   [`write_png_indexed8`]): 8- and 16-bit previews, digital-count images, and the
//!   legacy interaction map as palette indices ([`read_png_indices`] reads them back).
//!
//! Pixel `(0, 0)` is the top-left corner; `data[row * width + column]`, row 0 at the top,
//! columns left to right, as in EXR and PNG.
//!
//! A raster may say which frame it is part of ([`FramePart`]): the frame's size, where its
//! pixels lie in it and which run made them. irsig-trace writes that on every image, and
//! [`merge`] puts the tiles of a frame back together, byte for byte the frame rendered
//! whole.
//!
//! ```
//! use irsig_raster::{Raster, read_exr, write_exr};
//! let mut r = Raster::new(2, 1);
//! r.push_layer("radiance", "W m^-2 sr^-1", vec![54.93, 60.0]).unwrap();
//! let mut bytes = Vec::new();
//! write_exr(&mut std::io::Cursor::new(&mut bytes), &r).unwrap();
//! let back = read_exr(&bytes).unwrap();
//! assert_eq!(back.layer("radiance").unwrap().data, vec![54.93, 60.0]);
//! assert_eq!(back.layer("radiance").unwrap().unit, "W m^-2 sr^-1");
//! ```

#![deny(clippy::print_stdout, clippy::print_stderr)]

use std::io::{Cursor, Seek, Write};

use exr::prelude::{self as x, ReadChannels, ReadLayers, WritableImage};

mod grey;
mod indexed;
pub mod merge;

pub use grey::{read_png_grey, read_png_samples};
pub use indexed::{read_png_indices, write_png_indexed8};

/// One image plane: a name, its unit and `width × height` samples, row-major from the top.
#[derive(Debug, Clone, PartialEq)]
pub struct Layer {
    /// The layer's name (`radiance`, `range`, `material_primary`).
    pub name: String,
    /// The unit of its samples (`W m^-2 sr^-1`, `m`, `K`, or empty for a pure number).
    pub unit: String,
    /// The samples, `data[row * width + column]`.
    pub data: Vec<f32>,
}

/// An image of one or more layers of the same size.
#[derive(Debug, Clone, PartialEq)]
pub struct Raster {
    /// Columns.
    pub width: usize,
    /// Rows.
    pub height: usize,
    /// The layers, each `width × height` samples.
    pub layers: Vec<Layer>,
    /// The frame these pixels are part of, and the run that made them; `None` for an image
    /// that says nothing of either.
    pub part: Option<FramePart>,
    /// Free text about the image, in the EXR's standard `comments` attribute (UTF-8; what
    /// it says is the writer's business: irsig-trace records the image's provenance there).
    pub comments: Option<String>,
}

/// Where a raster's pixels lie in the frame they belong to, and which run made them: a
/// whole frame is the part at (0, 0) of its own size; a tile is a rectangle of it. In an
/// EXR, the frame is the display window, the part's origin the data window's, and the run
/// the text attribute `irsig.run` (formats/images.md).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct FramePart {
    /// The frame's columns.
    pub frame_width: usize,
    /// The frame's rows.
    pub frame_height: usize,
    /// The column of the raster's first pixel in the frame.
    pub x: usize,
    /// The row of the raster's first pixel in the frame.
    pub y: usize,
    /// What made the pixels, as one line of text: the same for every tile of a frame and
    /// for the frame rendered whole, different for another scene, view or option (irsig-trace
    /// writes a SHA-256 of its inputs and options).
    pub run: String,
}

/// What went wrong reading or writing an image.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum RasterError {
    /// A layer's sample count is not `width × height`.
    #[error("layer `{name}` has {len} samples, expected {width}×{height} = {}", width * height)]
    SizeMismatch {
        /// The layer.
        name: String,
        /// Its sample count.
        len: usize,
        /// The raster's width.
        width: usize,
        /// The raster's height.
        height: usize,
    },
    /// Two layers share a name.
    #[error("duplicate layer `{0}`")]
    DuplicateLayer(String),
    /// A layer's name or unit holds a character the units attribute cannot carry.
    #[error(
        "layer {0:?}: a name or unit with `=` (in a name) or a control character cannot be \
         written to the units attribute (`name=unit` lines) and read back"
    )]
    BadLayerName(String),
    /// The image has no pixels or no layers.
    #[error("the image is empty: {0}")]
    Empty(String),
    /// The EXR could not be read or written.
    #[error("EXR: {0}")]
    Exr(#[from] exr::error::Error),
    /// The PNG could not be written.
    #[error("PNG: {0}")]
    Png(#[from] image::ImageError),
    /// An indexed PNG could not be written, or a PNG's pixels could not be read as stored.
    #[error("PNG: {0}")]
    PngPixels(String),
    /// An I/O error.
    #[error(transparent)]
    Io(#[from] std::io::Error),
    /// A header claims an image larger than the memory budget allows.
    #[error("{0}")]
    TooLarge(String),
    /// The frame a raster says it is part of does not hold it.
    #[error("{0}")]
    Part(String),
    /// The `comments` attribute is not UTF-8 text (where irsig records an image's
    /// provenance: a byte changed there would be read as another record).
    #[error("the `comments` attribute is not UTF-8: a byte that is not one at its byte {0}")]
    Comments(usize),
}

/// The `comments` attribute's text: UTF-8, or refused (a lossy reading would turn a record
/// with a bad byte into another record).
fn comments_text(bytes: &[u8]) -> Result<String, RasterError> {
    String::from_utf8(bytes.to_vec())
        .map_err(|e| RasterError::Comments(e.utf8_error().valid_up_to()))
}

impl Raster {
    /// An image of this size with no layers yet, part of no larger frame.
    #[must_use]
    pub fn new(width: usize, height: usize) -> Self {
        Self {
            width,
            height,
            layers: Vec::new(),
            part: None,
            comments: None,
        }
    }

    /// This raster with `comments`.
    #[must_use]
    pub fn with_comments(mut self, comments: Option<String>) -> Self {
        self.comments = comments;
        self
    }

    /// This raster, as `part` of a frame.
    #[must_use]
    pub fn with_part(mut self, part: FramePart) -> Self {
        self.part = Some(part);
        self
    }

    /// Adds a layer.
    ///
    /// # Errors
    /// When its size does not match the raster or its name is taken.
    pub fn push_layer(
        &mut self,
        name: impl Into<String>,
        unit: impl Into<String>,
        data: Vec<f32>,
    ) -> Result<(), RasterError> {
        let name = name.into();
        if data.len() != self.width * self.height {
            return Err(RasterError::SizeMismatch {
                name,
                len: data.len(),
                width: self.width,
                height: self.height,
            });
        }
        if self.layer(&name).is_some() {
            return Err(RasterError::DuplicateLayer(name));
        }
        let unit = unit.into();
        // The units attribute is `name=unit` lines: a name holding `=` or either holding a
        // line break would read back as another layer's (the EXR fuzz target found a name
        // with a newline that came back in another order, without its unit).
        if name.contains('=') || name.chars().chain(unit.chars()).any(char::is_control) {
            return Err(RasterError::BadLayerName(format!("{name}={unit}")));
        }
        self.layers.push(Layer { name, unit, data });
        Ok(())
    }

    /// The layer with this name.
    #[must_use]
    pub fn layer(&self, name: &str) -> Option<&Layer> {
        self.layers.iter().find(|l| l.name == name)
    }

    /// The layer with this name, mutably.
    pub fn layer_mut(&mut self, name: &str) -> Option<&mut Layer> {
        self.layers.iter_mut().find(|l| l.name == name)
    }

    fn check(&self) -> Result<(), RasterError> {
        if self.width == 0 || self.height == 0 {
            return Err(RasterError::Empty(format!(
                "{}×{} pixels",
                self.width, self.height
            )));
        }
        if self.layers.is_empty() {
            return Err(RasterError::Empty("no layers".into()));
        }
        let mut names = std::collections::HashSet::new();
        for l in &self.layers {
            if l.data.len() != self.width * self.height {
                return Err(RasterError::SizeMismatch {
                    name: l.name.clone(),
                    len: l.data.len(),
                    width: self.width,
                    height: self.height,
                });
            }
            if !names.insert(l.name.as_str()) {
                return Err(RasterError::DuplicateLayer(l.name.clone()));
            }
        }
        if let Some(p) = &self.part {
            p.check(self.width, self.height)?;
        }
        Ok(())
    }
}

impl FramePart {
    /// The whole of a `width × height` frame made by `run`.
    #[must_use]
    pub fn whole(width: usize, height: usize, run: impl Into<String>) -> Self {
        Self {
            frame_width: width,
            frame_height: height,
            x: 0,
            y: 0,
            run: run.into(),
        }
    }

    /// Whether this part is its whole frame (of a raster `width × height`).
    #[must_use]
    pub fn is_whole(&self, width: usize, height: usize) -> bool {
        self.x == 0 && self.y == 0 && self.frame_width == width && self.frame_height == height
    }

    /// Checks that a `width × height` raster at this place lies inside the frame, that
    /// every coordinate fits an EXR's 32-bit window, and that the run is one line.
    pub(crate) fn check(&self, width: usize, height: usize) -> Result<(), RasterError> {
        let inside = |start: usize, len: usize, size: usize| {
            start.checked_add(len).is_some_and(|end| end <= size)
        };
        let fits = |v: usize| i32::try_from(v).is_ok();
        if !inside(self.x, width, self.frame_width) || !inside(self.y, height, self.frame_height) {
            return Err(RasterError::Part(format!(
                "a {width}x{height} part at column {}, row {} does not lie inside its {}x{} frame",
                self.x, self.y, self.frame_width, self.frame_height
            )));
        }
        if !(fits(self.frame_width) && fits(self.frame_height)) {
            return Err(RasterError::Part(format!(
                "a {}x{} frame is too large for an EXR window",
                self.frame_width, self.frame_height
            )));
        }
        if self.run.is_empty() || self.run.contains(['\n', '\r']) {
            return Err(RasterError::Part(format!(
                "the run {:?} must be one line of text",
                self.run
            )));
        }
        Ok(())
    }
}

/// The header attribute holding the layers' units, one `name=unit` line per layer, in the
/// raster's order of layers. One attribute rather than one per layer: exr keeps attributes
/// in a hash map, whose order would make the file's bytes differ from run to run.
const UNITS_ATTRIBUTE: &str = "irsig.units";

/// The header attribute naming the run that made a frame's pixels ([`FramePart::run`]).
/// exr writes the layer's own custom attributes, then the image's: this one is the
/// image's, the units the layer's, so each map holds one and the bytes stay the same.
const RUN_ATTRIBUTE: &str = "irsig.run";

/// Writes the raster as a single-part EXR with one `f32` channel per layer (ZIP
/// compression, lossless, scan lines top to bottom: the bytes depend only on the data).
///
/// # Errors
/// An empty or inconsistent raster, or an I/O error.
pub fn write_exr(out: &mut (impl Write + Seek), raster: &Raster) -> Result<(), RasterError> {
    write_exr_threads(out, raster.clone(), several_threads())
}

/// Whether to compress an EXR's blocks on exr's own threads: only when the caller's rayon
/// pool has more than one, so that a tool run on one thread compresses on one (exr's pool
/// has a thread per CPU whatever the caller's has).
fn several_threads() -> bool {
    rayon::current_num_threads() > 1
}

/// [`write_exr`], its blocks compressed on exr's own threads (`parallel`) or on this one:
/// the bytes are the same either way (a test holds it). Takes the raster, whose layers
/// become the image's channels without a copy.
fn write_exr_threads(
    out: &mut (impl Write + Seek),
    raster: Raster,
    parallel: bool,
) -> Result<(), RasterError> {
    raster.check()?;
    let mut attributes = x::LayerAttributes::named("irsig");
    let units: String = raster
        .layers
        .iter()
        .map(|l| format!("{}={}\n", l.name, l.unit))
        .collect();
    let (width, height) = (raster.width, raster.height);
    let part = raster.part;
    // A typed attribute, written in its fixed place (not the hash map of `other`), as the
    // UTF-8 bytes of the text: exr's `Text` is one byte a character.
    attributes.comments = raster
        .comments
        .as_deref()
        .map(|c| x::Text::from_slice_unchecked(c.as_bytes()));
    let channels: x::SmallVec<[x::AnyChannel<x::FlatSamples>; 4]> = raster
        .layers
        .into_iter()
        .map(|l| x::AnyChannel::new(l.name.as_str(), x::FlatSamples::F32(l.data)))
        .collect();
    attributes.other.insert(
        x::Text::from(UNITS_ATTRIBUTE),
        x::AttributeValue::Text(x::Text::from(units.as_str())),
    );
    let encoding = x::Encoding {
        compression: x::Compression::ZIP16,
        blocks: x::Blocks::ScanLines,
        line_order: x::LineOrder::Increasing,
    };
    let mut image_attributes =
        x::ImageAttributes::new(x::IntegerBounds::from_dimensions((width, height)));
    if let Some(p) = &part {
        // Checked by `check`: every coordinate fits an i32.
        let at = |v: usize| i32::try_from(v).unwrap_or(i32::MAX);
        attributes.layer_position = x::Vec2(at(p.x), at(p.y));
        image_attributes = x::ImageAttributes::new(x::IntegerBounds::from_dimensions((
            p.frame_width,
            p.frame_height,
        )));
        image_attributes.other.insert(
            x::Text::from(RUN_ATTRIBUTE),
            x::AttributeValue::Text(x::Text::from(p.run.as_str())),
        );
    }
    let layer = x::Layer::new(
        (width, height),
        attributes,
        encoding,
        x::AnyChannels::sort(channels),
    );
    // Blocks compressed in parallel are written in increasing line order: the same bytes
    // as one thread writes (cargo bench -p irsig-raster --bench exr: 1.41 s on one thread,
    // 0.73 s on two, for 11 layers of 1024 × 1024).
    let image = x::Image::new(image_attributes, layer);
    if parallel {
        image.write().to_buffered(out)?;
    } else {
        image.write().non_parallel().to_buffered(out)?;
    }
    Ok(())
}

/// Writes the raster as EXR into a byte vector.
///
/// # Errors
/// As [`write_exr`].
pub fn exr_bytes(raster: &Raster) -> Result<Vec<u8>, RasterError> {
    into_exr_bytes(raster.clone())
}

/// [`exr_bytes`] of a raster no longer needed: its layers are encoded where they lie, not
/// copied first (a frame's truth layers are 48 bytes a pixel).
///
/// # Errors
/// As [`write_exr`].
pub fn into_exr_bytes(raster: Raster) -> Result<Vec<u8>, RasterError> {
    let mut bytes = Vec::new();
    write_exr_threads(&mut Cursor::new(&mut bytes), raster, several_threads())?;
    Ok(bytes)
}

/// Reads an EXR: every channel of its first part becomes a layer, in the order of the
/// units attribute (the order the raster had when written, so that a raster read back
/// writes the same bytes), channels it does not list after them in the file's
/// (alphabetical) order. The frame the image is part of ([`Raster::part`]) is read when the
/// file names its run.
///
/// # Errors
/// A malformed or empty EXR, or a part that does not lie inside its frame.
pub fn read_exr(bytes: &[u8]) -> Result<Raster, RasterError> {
    check_claimed_size(bytes)?;
    let image = x::read()
        .no_deep_data()
        .largest_resolution_level()
        .all_channels()
        .all_layers()
        .all_attributes()
        .non_parallel()
        .from_buffered(Cursor::new(bytes))?;
    let display = image.attributes.display_window;
    let Some(part) = image.layer_data.into_iter().next() else {
        return Err(RasterError::Empty("no image parts".into()));
    };
    let (width, height) = (part.size.width(), part.size.height());
    let text = |name: &str| match part.attributes.other.get(&x::Text::from(name)) {
        Some(x::AttributeValue::Text(t)) => Some(t.to_string()),
        _ => None,
    };
    let units = text(UNITS_ATTRIBUTE).unwrap_or_default();
    let frame = text(RUN_ATTRIBUTE)
        .map(|run| frame_part(run, display, part.attributes.layer_position))
        .transpose()?;
    let mut raster = Raster::new(width, height);
    raster.comments = part
        .attributes
        .comments
        .as_ref()
        .map(|t| comments_text(t.bytes()))
        .transpose()?;
    for channel in part.channel_data.list {
        let name = channel.name.to_string();
        let unit = unit_of(&units, &name).unwrap_or_default().to_owned();
        let data: Vec<f32> = channel.sample_data.values_as_f32().collect();
        raster.push_layer(name, unit, data)?;
    }
    // Stable: channels the units do not list keep the file's order, after those it does.
    raster
        .layers
        .sort_by_key(|l| order_of(&units, &l.name).unwrap_or(usize::MAX));
    raster.part = frame;
    raster.check()?;
    Ok(raster)
}

/// Refuses an EXR whose header claims more than an image may hold
/// ([`irsig_model::limits::MAX_IMAGE_PIXELS`], and [`irsig_model::limits::MEMORY_BUDGET_BYTES`]
/// over all its channels), before a pixel is decoded: the header is a few hundred bytes and
/// can claim anything.
fn check_claimed_size(bytes: &[u8]) -> Result<(), RasterError> {
    use irsig_model::limits::{MAX_IMAGE_PIXELS, MEMORY_BUDGET_BYTES};
    let meta = x::MetaData::read_from_buffered(Cursor::new(bytes), false)?;
    let mut total = 0u64;
    for header in &meta.headers {
        let (w, h) = (header.layer_size.width(), header.layer_size.height());
        let pixels = (w as u64).saturating_mul(h as u64);
        if pixels > MAX_IMAGE_PIXELS {
            return Err(RasterError::TooLarge(format!(
                "the header claims {w}x{h} pixels, more than the {MAX_IMAGE_PIXELS} \
                 (8192x8192) one image may have"
            )));
        }
        // Four bytes per sample as read, for every channel of every part.
        total = total.saturating_add(pixels.saturating_mul(4 * header.channels.list.len() as u64));
    }
    if total > MEMORY_BUDGET_BYTES {
        return Err(RasterError::TooLarge(format!(
            "the header claims {total} bytes of samples, more than the {MEMORY_BUDGET_BYTES} \
             bytes (16 GiB) of the memory budget"
        )));
    }
    // Nor more than the file's bytes can hold: a block is inflated into a buffer of the
    // size its header claims before its data is read, so a kilobyte claiming gigabytes
    // would allocate them.
    for header in &meta.headers {
        let (w, h) = (header.layer_size.width(), header.layer_size.height());
        // The bytes the samples take in the file: each channel's own sample size and
        // sampling (a subsampled channel stores one sample per `sampling` pixels).
        let claimed = header
            .channels
            .list
            .iter()
            .map(|c| {
                let (sx, sy) = (c.sampling.x().max(1), c.sampling.y().max(1));
                (w.div_ceil(sx) as u64)
                    .saturating_mul(h.div_ceil(sy) as u64)
                    .saturating_mul(c.sample_type.bytes_per_sample() as u64)
            })
            .fold(0u64, u64::saturating_add);
        let ratio = max_expansion(header.compression);
        let holds = (bytes.len() as u64).saturating_mul(ratio);
        if claimed > holds {
            return Err(RasterError::TooLarge(format!(
                "the header claims {w}x{h} pixels of {} channels ({claimed} bytes of samples), \
                 more than the file's {} bytes can hold {} (at most {ratio} bytes per byte)",
                header.channels.list.len(),
                bytes.len(),
                compression_name(header.compression),
            )));
        }
    }
    Ok(())
}

/// The most one byte of a block compressed with `c` can stand for once decompressed,
/// rounded up: deflate (ZIP, and PXR24 after its 24-bit packing) reaches 1032:1, OpenEXR's
/// run-length code 64:1 (a run of up to 128 bytes in two), uncompressed 1:1. The wavelet and
/// block codes (PIZ, B44, DWA) are given a generous 65 536.
fn max_expansion(c: x::Compression) -> u64 {
    match c {
        x::Compression::Uncompressed => 1,
        x::Compression::RLE => 128,
        x::Compression::ZIP1 | x::Compression::ZIP16 | x::Compression::PXR24 => 2048,
        _ => 65_536,
    }
}

/// `c` as a phrase for an error message.
fn compression_name(c: x::Compression) -> String {
    match c {
        x::Compression::Uncompressed => "uncompressed".to_owned(),
        other => format!("compressed with {other:?}"),
    }
}

/// Where in the bytes of an EXR reading it failed with `error`, as a byte offset, for a
/// message that points into the file (`file.exr:1:OFFSET+1`): the magic number (0) or the
/// version (4) when they are wrong, the end of the file when it is cut short, the
/// `dataWindow` attribute when the header claims too large an image, the start of the
/// header (8) when the header is malformed, and the end of the header (the offset table)
/// when the header reads but the pixel data does not.
#[must_use]
pub fn exr_error_offset(bytes: &[u8], error: &RasterError) -> usize {
    const MAGIC: [u8; 4] = [0x76, 0x2f, 0x31, 0x01];
    if bytes.len() < 4 || bytes[..4] != MAGIC {
        return 0;
    }
    if bytes.len() < 8 {
        return bytes.len();
    }
    if bytes[4] != 2 {
        return 4;
    }
    if let RasterError::TooLarge(_) = error {
        return exr_attribute_offset(bytes, "dataWindow").unwrap_or(8);
    }
    if let RasterError::Comments(at) = error {
        // The value follows the name, the type and the 4-byte size: `comments\0string\0`.
        return exr_attribute_offset(bytes, "comments").map_or(8, |o| o + 20 + at);
    }
    let truncated = matches!(error, RasterError::Exr(e) if e.to_string().contains("missing bytes"));
    let mut cursor = Cursor::new(bytes);
    match x::MetaData::read_from_buffered(&mut cursor, false) {
        Err(_) if truncated => bytes.len(),
        Err(_) => 8,
        Ok(_) => usize::try_from(cursor.position()).unwrap_or(8),
    }
}

/// The byte offset of the header attribute `name` (the first byte of its name) in the bytes
/// of an EXR, if its header has one.
#[must_use]
pub fn exr_attribute_offset(bytes: &[u8], name: &str) -> Option<usize> {
    let key: Vec<u8> = name.bytes().chain([0]).collect();
    bytes
        .get(8..)?
        .windows(key.len())
        .position(|w| w == key.as_slice())
        .map(|i| i + 8)
}

/// What an EXR's header says of its image, without its pixels: size, layers (names and
/// units, in the order [`read_exr`] gives them) and the frame it is part of.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct RasterInfo {
    /// Columns.
    pub width: usize,
    /// Rows.
    pub height: usize,
    /// `(name, unit)` of each layer.
    pub layers: Vec<(String, String)>,
    /// The frame the image is part of, if the file says.
    pub part: Option<FramePart>,
    /// The image's comments ([`Raster::comments`]).
    pub comments: Option<String>,
}

/// Reads an EXR's header only (its first part): what [`read_exr`] would give, without
/// decoding a pixel.
///
/// # Errors
/// A malformed or empty EXR header, or a part that does not lie inside its frame.
pub fn read_exr_info(bytes: &[u8]) -> Result<RasterInfo, RasterError> {
    let meta = x::MetaData::read_from_buffered(Cursor::new(bytes), false)?;
    let Some(header) = meta.headers.first() else {
        return Err(RasterError::Empty("no image parts".into()));
    };
    let text = |name: &str| {
        let key = x::Text::from(name);
        match header
            .own_attributes
            .other
            .get(&key)
            .or_else(|| header.shared_attributes.other.get(&key))
        {
            Some(x::AttributeValue::Text(t)) => Some(t.to_string()),
            _ => None,
        }
    };
    let units = text(UNITS_ATTRIBUTE).unwrap_or_default();
    let (width, height) = (header.layer_size.width(), header.layer_size.height());
    let part = text(RUN_ATTRIBUTE)
        .map(|run| {
            frame_part(
                run,
                header.shared_attributes.display_window,
                header.own_attributes.layer_position,
            )
        })
        .transpose()?;
    let mut layers: Vec<(String, String)> = header
        .channels
        .list
        .iter()
        .map(|c| {
            let name = c.name.to_string();
            let unit = unit_of(&units, &name).unwrap_or_default().to_owned();
            (name, unit)
        })
        .collect();
    layers.sort_by_key(|(name, _)| order_of(&units, name).unwrap_or(usize::MAX));
    if width == 0 || height == 0 {
        return Err(RasterError::Empty(format!("{width}×{height} pixels")));
    }
    if let Some(p) = &part {
        p.check(width, height)?;
    }
    let comments = header
        .own_attributes
        .comments
        .as_ref()
        .map(|t| comments_text(t.bytes()))
        .transpose()?;
    Ok(RasterInfo {
        width,
        height,
        layers,
        part,
        comments,
    })
}

/// The unit the units attribute gives layer `name`.
fn unit_of<'a>(units: &'a str, name: &str) -> Option<&'a str> {
    units
        .lines()
        .find_map(|line| line.strip_prefix(name)?.strip_prefix('='))
}

/// The place of layer `name` in the units attribute.
fn order_of(units: &str, name: &str) -> Option<usize> {
    units.lines().position(|line| {
        line.strip_prefix(name)
            .is_some_and(|rest| rest.starts_with('='))
    })
}

/// The frame part a header describes: display window (the frame, which must start at the
/// origin), data window origin (the part's place) and run.
fn frame_part(
    run: String,
    display: x::IntegerBounds,
    position: x::Vec2<i32>,
) -> Result<FramePart, RasterError> {
    let (Ok(x0), Ok(y0)) = (usize::try_from(position.x()), usize::try_from(position.y())) else {
        return Err(RasterError::Part(format!(
            "the data window starts at column {}, row {}, before its frame",
            position.x(),
            position.y()
        )));
    };
    if display.position != x::Vec2(0, 0) {
        return Err(RasterError::Part(format!(
            "the frame (display window) starts at ({}, {}), not at (0, 0)",
            display.position.x(),
            display.position.y()
        )));
    }
    Ok(FramePart {
        frame_width: display.size.width(),
        frame_height: display.size.height(),
        x: x0,
        y: y0,
        run,
    })
}

/// Writes an 8-bit grey PNG; `data` is row-major from the top.
///
/// # Errors
/// A size mismatch or an encoder error.
pub fn write_png_gray8(
    out: &mut impl Write,
    width: usize,
    height: usize,
    data: &[u8],
) -> Result<(), RasterError> {
    write_png(out, width, height, data.to_vec(), image::ColorType::L8)
}

/// Writes a 16-bit grey PNG; `data` is row-major from the top.
///
/// # Errors
/// A size mismatch or an encoder error.
pub fn write_png_gray16(
    out: &mut impl Write,
    width: usize,
    height: usize,
    data: &[u16],
) -> Result<(), RasterError> {
    let (w, h) = dims(width, height, data.len(), 1)?;
    let img = image::ImageBuffer::<image::Luma<u16>, Vec<u16>>::from_raw(w, h, data.to_vec())
        .ok_or_else(|| mismatch("png", data.len(), width, height))?;
    encode(out, &image::DynamicImage::ImageLuma16(img))
}

/// Digital counts of `bits` bits as a grey PNG: 8-bit up to 8 bits, else 16-bit, counts
/// unscaled (a 12-bit image uses 0..=4095 of the 16-bit range).
///
/// # Errors
/// A size mismatch or an encoder error.
pub fn counts_png(
    counts: &[u16],
    width: usize,
    height: usize,
    bits: u8,
) -> Result<Vec<u8>, RasterError> {
    let mut out = Vec::new();
    if bits <= 8 {
        let bytes: Vec<u8> = counts.iter().map(|&c| c.min(255) as u8).collect();
        write_png_gray8(&mut out, width, height, &bytes)?;
    } else {
        write_png_gray16(&mut out, width, height, counts)?;
    }
    Ok(out)
}

/// Writes an 8-bit RGB PNG; `data` holds `r, g, b` per pixel, row-major from the top.
///
/// # Errors
/// A size mismatch or an encoder error.
pub fn write_png_rgb8(
    out: &mut impl Write,
    width: usize,
    height: usize,
    data: &[u8],
) -> Result<(), RasterError> {
    write_png(out, width, height, data.to_vec(), image::ColorType::Rgb8)
}

fn write_png(
    out: &mut impl Write,
    width: usize,
    height: usize,
    data: Vec<u8>,
    color: image::ColorType,
) -> Result<(), RasterError> {
    let channels = usize::from(color.channel_count());
    let (w, h) = dims(width, height, data.len(), channels)?;
    let len = data.len();
    let img = match color {
        image::ColorType::Rgb8 => {
            image::RgbImage::from_raw(w, h, data).map(image::DynamicImage::ImageRgb8)
        }
        _ => image::GrayImage::from_raw(w, h, data).map(image::DynamicImage::ImageLuma8),
    }
    .ok_or_else(|| mismatch("png", len / channels, width, height))?;
    encode(out, &img)
}

fn encode(out: &mut impl Write, img: &image::DynamicImage) -> Result<(), RasterError> {
    let mut bytes = Vec::new();
    img.write_to(&mut Cursor::new(&mut bytes), image::ImageFormat::Png)?;
    out.write_all(&bytes)?;
    Ok(())
}

fn dims(
    width: usize,
    height: usize,
    len: usize,
    channels: usize,
) -> Result<(u32, u32), RasterError> {
    let (Ok(w), Ok(h)) = (u32::try_from(width), u32::try_from(height)) else {
        return Err(mismatch("png", len / channels.max(1), width, height));
    };
    if width == 0 || height == 0 {
        return Err(RasterError::Empty(format!("{width}×{height} pixels")));
    }
    if width
        .checked_mul(height)
        .and_then(|n| n.checked_mul(channels))
        != Some(len)
    {
        return Err(mismatch("png", len / channels.max(1), width, height));
    }
    Ok((w, h))
}

fn mismatch(name: &str, len: usize, width: usize, height: usize) -> RasterError {
    RasterError::SizeMismatch {
        name: name.into(),
        len,
        width,
        height,
    }
}

#[cfg(test)]
mod tests;
