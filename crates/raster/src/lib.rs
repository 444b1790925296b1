//! Images as irsig's stages hand them to each other: a [`Raster`] of named `f32` layers,
//! each with its unit, and the files they live in.
//!
//! - **EXR** ([`write_exr`], [`read_exr`]): every layer is an `f32` channel of one EXR
//!   part, losslessly compressed; the layers' units are stored in the text attribute
//!   `irsig.units`, one `name=unit` line per layer. Files from other programs read too (their channels become
//!   layers, with `f16`/`u32` samples converted to `f32` and unknown units left empty).
//! - **PNG** ([`write_png_gray8`], [`write_png_gray16`], [`write_png_rgb8`]): 8- and
//!   16-bit previews, digital-count images and the legacy interaction map.
//!
//! Pixel `(0, 0)` is the top-left corner; `data[row * width + column]`, row 0 at the top,
//! columns left to right, as in EXR and PNG.
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

use std::io::{Cursor, Seek, Write};

use exr::prelude::{self as x, ReadChannels, ReadLayers, WritableImage};

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
    /// The image has no pixels or no layers.
    #[error("the image is empty: {0}")]
    Empty(String),
    /// The EXR could not be read or written.
    #[error("EXR: {0}")]
    Exr(#[from] exr::error::Error),
    /// The PNG could not be written.
    #[error("PNG: {0}")]
    Png(#[from] image::ImageError),
    /// An I/O error.
    #[error(transparent)]
    Io(#[from] std::io::Error),
}

impl Raster {
    /// An image of this size with no layers yet.
    #[must_use]
    pub fn new(width: usize, height: usize) -> Self {
        Self {
            width,
            height,
            layers: Vec::new(),
        }
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
        self.layers.push(Layer {
            name,
            unit: unit.into(),
            data,
        });
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
        Ok(())
    }
}

/// The header attribute holding the layers' units, one `name=unit` line per layer. One
/// attribute rather than one per layer: exr keeps attributes in a hash map, whose order
/// would make the file's bytes differ from run to run.
const UNITS_ATTRIBUTE: &str = "irsig.units";

/// Writes the raster as a single-part EXR with one `f32` channel per layer (ZIP
/// compression, lossless, scan lines top to bottom: the bytes depend only on the data).
///
/// # Errors
/// An empty or inconsistent raster, or an I/O error.
pub fn write_exr(out: &mut (impl Write + Seek), raster: &Raster) -> Result<(), RasterError> {
    raster.check()?;
    let channels: x::SmallVec<[x::AnyChannel<x::FlatSamples>; 4]> = raster
        .layers
        .iter()
        .map(|l| x::AnyChannel::new(l.name.as_str(), x::FlatSamples::F32(l.data.clone())))
        .collect();
    let mut attributes = x::LayerAttributes::named("irsig");
    let units: String = raster
        .layers
        .iter()
        .map(|l| format!("{}={}\n", l.name, l.unit))
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
    let layer = x::Layer::new(
        (raster.width, raster.height),
        attributes,
        encoding,
        x::AnyChannels::sort(channels),
    );
    x::Image::from_layer(layer)
        .write()
        .non_parallel()
        .to_buffered(out)?;
    Ok(())
}

/// Writes the raster as EXR into a byte vector.
///
/// # Errors
/// As [`write_exr`].
pub fn exr_bytes(raster: &Raster) -> Result<Vec<u8>, RasterError> {
    let mut bytes = Vec::new();
    write_exr(&mut Cursor::new(&mut bytes), raster)?;
    Ok(bytes)
}

/// Reads an EXR: every channel of its first part becomes a layer, in the file's
/// (alphabetical) channel order.
///
/// # Errors
/// A malformed or empty EXR.
pub fn read_exr(bytes: &[u8]) -> Result<Raster, RasterError> {
    let image = x::read()
        .no_deep_data()
        .largest_resolution_level()
        .all_channels()
        .all_layers()
        .all_attributes()
        .non_parallel()
        .from_buffered(Cursor::new(bytes))?;
    let Some(part) = image.layer_data.into_iter().next() else {
        return Err(RasterError::Empty("no image parts".into()));
    };
    let (width, height) = (part.size.width(), part.size.height());
    let units = match part.attributes.other.get(&x::Text::from(UNITS_ATTRIBUTE)) {
        Some(x::AttributeValue::Text(t)) => t.to_string(),
        _ => String::new(),
    };
    let mut raster = Raster::new(width, height);
    for channel in part.channel_data.list {
        let name = channel.name.to_string();
        let unit = units
            .lines()
            .find_map(|line| line.strip_prefix(name.as_str())?.strip_prefix('='))
            .unwrap_or_default()
            .to_owned();
        let data: Vec<f32> = channel.sample_data.values_as_f32().collect();
        raster.push_layer(name, unit, data)?;
    }
    raster.check()?;
    Ok(raster)
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
mod tests {
    use super::*;

    fn sample() -> Raster {
        let mut r = Raster::new(3, 2);
        r.push_layer(
            "radiance",
            "W m^-2 sr^-1",
            vec![1.0, 2.0, 3.0, 4.0, 5.0, f32::MAX],
        )
        .unwrap();
        r.push_layer("range", "m", vec![0.5, 1e-30, 1e30, 0.0, -0.0, 7.25])
            .unwrap();
        r
    }

    #[test]
    fn exr_round_trip_is_bit_exact_and_keeps_units() {
        let r = sample();
        let back = read_exr(&exr_bytes(&r).unwrap()).unwrap();
        assert_eq!((back.width, back.height), (3, 2));
        for l in &r.layers {
            let b = back.layer(&l.name).unwrap();
            assert_eq!(b.unit, l.unit);
            let bits: Vec<u32> = b.data.iter().map(|v| v.to_bits()).collect();
            let want: Vec<u32> = l.data.iter().map(|v| v.to_bits()).collect();
            assert_eq!(bits, want, "layer {}", l.name);
        }
    }

    #[test]
    fn exr_bytes_are_deterministic() {
        assert_eq!(exr_bytes(&sample()).unwrap(), exr_bytes(&sample()).unwrap());
    }

    #[test]
    fn garbage_and_truncated_exr_are_errors_not_panics() {
        assert!(read_exr(b"not an exr").is_err());
        assert!(read_exr(&[]).is_err());
        let bytes = exr_bytes(&sample()).unwrap();
        for cut in [4, 20, bytes.len() / 2, bytes.len() - 1] {
            assert!(read_exr(&bytes[..cut]).is_err(), "cut at {cut}");
        }
    }

    #[test]
    fn layers_must_fit_the_raster() {
        let mut r = Raster::new(2, 2);
        assert!(matches!(
            r.push_layer("a", "", vec![0.0; 3]),
            Err(RasterError::SizeMismatch { .. })
        ));
        r.push_layer("a", "", vec![0.0; 4]).unwrap();
        assert!(matches!(
            r.push_layer("a", "", vec![0.0; 4]),
            Err(RasterError::DuplicateLayer(_))
        ));
        assert!(matches!(
            exr_bytes(&Raster::new(2, 2)),
            Err(RasterError::Empty(_))
        ));
    }

    #[test]
    fn png_writers_produce_decodable_images_of_the_right_depth() {
        let mut out = Vec::new();
        write_png_gray16(&mut out, 2, 1, &[0, 65535]).unwrap();
        let img = image::load_from_memory(&out).unwrap();
        assert_eq!(img.color(), image::ColorType::L16);
        assert_eq!(img.to_luma16().into_raw(), vec![0, 65535]);

        let mut out = Vec::new();
        write_png_gray8(&mut out, 1, 2, &[7, 200]).unwrap();
        assert_eq!(
            image::load_from_memory(&out).unwrap().to_luma8().into_raw(),
            vec![7, 200]
        );

        let mut out = Vec::new();
        write_png_rgb8(&mut out, 1, 1, &[1, 2, 3]).unwrap();
        assert_eq!(
            image::load_from_memory(&out).unwrap().to_rgb8().into_raw(),
            vec![1, 2, 3]
        );

        assert!(write_png_gray8(&mut Vec::new(), 2, 2, &[0; 3]).is_err());
        assert!(write_png_gray8(&mut Vec::new(), 0, 0, &[]).is_err());
    }
}
