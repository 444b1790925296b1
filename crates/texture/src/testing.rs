//! The textures the benchmarks put on every facet, in one place, so that the texture
//! crate's own bench (`benches/field.rs`, per point) and the tracer's `frame_1024` (per
//! frame) measure the same ones.

use irsig_model::image_map::{ImageMap, ImageMaps, MapFilter};
use irsig_model::texture::{
    CorrelationLength, FieldFilter, FieldSpectrum, RandomField, StatisticalTexture,
};

use crate::GreyImage;

/// A temperature field (σ 1.5 K, exponential, 0.5 m) and an emissivity field (σ 2 %,
/// Gaussian, 2 m), drawn from `seed`.
#[must_use]
pub fn statistical(seed: u64) -> StatisticalTexture {
    StatisticalTexture {
        seed,
        temperature_offset_k: Some(RandomField {
            sigma: 1.5,
            spectrum: FieldSpectrum::Exponential {
                correlation_length_m: CorrelationLength::Isotropic(0.5),
            },
        }),
        emissivity_scale: Some(RandomField {
            sigma: 0.02,
            spectrum: FieldSpectrum::Gaussian {
                correlation_length_m: CorrelationLength::Isotropic(2.0),
            },
        }),
        filter: FieldFilter::Point,
    }
}

/// The side of [`maps`]' image, texels.
pub const MAP_SIDE: usize = 256;

/// A temperature map (−2 K at black, +4 K a grey) and an emissivity map (0.98 at black,
/// +0.04 a grey), both read through the footprint filter (`footprint`) or nearest and
/// bilinear, and the one 256 × 256 image both show (greys `(k · 7919 mod 251) / 250`).
#[must_use]
pub fn maps(footprint: bool) -> (ImageMaps, GreyImage) {
    let map = |image: &str, at_black, per_grey, filter| ImageMap {
        image: image.into(),
        at_black,
        per_grey,
        filter,
    };
    let (t_filter, e_filter) = if footprint {
        (MapFilter::Footprint, MapFilter::Footprint)
    } else {
        (MapFilter::Nearest, MapFilter::Bilinear)
    };
    let maps = ImageMaps {
        temperature_offset_k: Some(map("t.png", -2.0, 4.0, t_filter)),
        emissivity_scale: Some(map("e.png", 0.98, 0.04, e_filter)),
        material: None,
    };
    let grey: Vec<f32> = (0..MAP_SIDE * MAP_SIDE)
        .map(|k| ((k * 7919) % 251) as f32 / 250.0)
        .collect();
    let image = GreyImage::new(MAP_SIDE, MAP_SIDE, grey).expect("greys within 0 to 1");
    (maps, image)
}
