//! Material maps, read: each material's area fraction as an image of its own, sampled with
//! the map's filter ([`MixMap`]).
//!
//! An index map becomes one indicator image per material (1 where a texel is that
//! material, 0 elsewhere); a weights map one image per channel, each texel's weights
//! divided by their sum once that sum is found within the map's tolerance of 1. Every
//! filter is a weighted mean of texels with weights that sum to 1, so the fractions it
//! gives sum to 1 too (to rounding): Nearest gives the one texel's, Bilinear the area
//! fractions of the four texels around the point, Footprint those of the texels under a
//! pixel's footprint ([`MipPyramid`]).

use irsig_model::image_map::MapFilter;
use irsig_model::material_map::MAX_MAP_MATERIALS;

use crate::{GreyImage, MipPyramid, TextureError, TextureErrorKind};

/// A material map with its image, ready to sample.
#[derive(Debug, Clone, PartialEq)]
pub struct MixMap {
    filter: MapFilter,
    /// Per material of the map, in its order: the fraction image and, for the footprint
    /// filter, its pyramid.
    fractions: Vec<(GreyImage, Option<MipPyramid>)>,
}

fn bad(why: String) -> TextureError {
    TextureError {
        kind: TextureErrorKind::BadImage(why),
    }
}

impl MixMap {
    fn from_fractions(filter: MapFilter, images: Vec<GreyImage>) -> Self {
        let fractions = images
            .into_iter()
            .map(|image| {
                let pyramid = (filter == MapFilter::Footprint).then(|| MipPyramid::new(&image));
                (image, pyramid)
            })
            .collect();
        Self { filter, fractions }
    }

    /// Whether the map is read over a ray's footprint (`MapFilter::Footprint`).
    #[must_use]
    pub fn filters_footprint(&self) -> bool {
        self.filter == MapFilter::Footprint
    }

    /// An index map: `values` the image's stored integers row after row from the top,
    /// `table` each listed value with the index (from 0, below `materials`) of the
    /// material it names.
    ///
    /// # Errors
    /// More than [`MAX_MAP_MATERIALS`] materials, a value count that is not
    /// `width × height`, or a value the table does not list: the first such texel, by its
    /// column and row (from the top-left) and the values the table lists.
    pub fn from_index(
        width: usize,
        height: usize,
        values: &[u16],
        table: &[(u16, usize)],
        materials: usize,
        filter: MapFilter,
    ) -> Result<Self, TextureError> {
        if materials == 0 || materials > MAX_MAP_MATERIALS {
            return Err(bad(format!(
                "{materials} materials: expected 1 to {MAX_MAP_MATERIALS}"
            )));
        }
        if width == 0 || width.checked_mul(height) != Some(values.len()) {
            return Err(bad(format!(
                "{} values for an image of {width} × {height} texels",
                values.len()
            )));
        }
        let mut of_value = vec![u8::MAX; usize::from(u16::MAX) + 1];
        for &(v, m) in table {
            if m >= materials {
                return Err(bad(format!("value {v} names material {m} of {materials}")));
            }
            of_value[usize::from(v)] = m as u8;
        }
        let mut grey = vec![vec![0.0f32; values.len()]; materials];
        for (k, &v) in values.iter().enumerate() {
            let m = of_value[usize::from(v)];
            if m == u8::MAX {
                let mut listed: Vec<u16> = table.iter().map(|e| e.0).collect();
                listed.sort_unstable();
                return Err(bad(format!(
                    "texel at column {}, row {} (from the top-left) holds value {v}, which \
                     the table does not list: expected one of {listed:?}",
                    k % width,
                    k / width
                )));
            }
            grey[usize::from(m)][k] = 1.0;
        }
        let images = grey
            .into_iter()
            .map(|g| GreyImage::new(width, height, g))
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Self::from_fractions(filter, images))
    }

    /// A weights map: `samples` the image's channels interleaved, texel after texel row
    /// after row from the top, each 0 to 1, one channel per material.
    ///
    /// # Errors
    /// No channel or more than [`MAX_MAP_MATERIALS`], a sample count that is not
    /// `width × height × channels`, a sample outside 0 to 1 or NaN, or a texel whose
    /// weights sum further than `tolerance` from 1: the first such texel, by its column and
    /// row and its sum.
    pub fn from_weights(
        width: usize,
        height: usize,
        channels: usize,
        samples: &[f32],
        tolerance: f64,
        filter: MapFilter,
    ) -> Result<Self, TextureError> {
        if channels == 0 || channels > MAX_MAP_MATERIALS {
            return Err(bad(format!(
                "{channels} channels: expected 1 to {MAX_MAP_MATERIALS}"
            )));
        }
        if width == 0
            || width
                .checked_mul(height)
                .and_then(|n| n.checked_mul(channels))
                != Some(samples.len())
        {
            return Err(bad(format!(
                "{} samples for an image of {width} × {height} texels of {channels} channels",
                samples.len()
            )));
        }
        let n = width * height;
        let mut grey = vec![vec![0.0f32; n]; channels];
        for (k, texel) in samples.chunks_exact(channels).enumerate() {
            let at = || {
                format!(
                    "texel at column {}, row {} (from the top-left)",
                    k % width,
                    k / width
                )
            };
            if let Some(s) = texel.iter().find(|s| !(0.0..=1.0).contains(*s)) {
                return Err(bad(format!("{} has weight {s}: expected 0 to 1", at())));
            }
            let sum: f64 = texel.iter().map(|&s| f64::from(s)).sum();
            if sum.is_nan() || (sum - 1.0).abs() > tolerance {
                return Err(bad(format!(
                    "{}: its weights sum to {sum}, expected 1 within {tolerance}",
                    at()
                )));
            }
            for (c, &s) in texel.iter().enumerate() {
                grey[c][k] = (f64::from(s) / sum) as f32;
            }
        }
        let images = grey
            .into_iter()
            .map(|g| GreyImage::new(width, height, g))
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Self::from_fractions(filter, images))
    }

    /// How many materials the map mixes.
    #[must_use]
    pub fn materials(&self) -> usize {
        self.fractions.len()
    }

    /// Each material's area fraction at texture coordinates `uv` over a pixel's footprint
    /// `footprint_uv` across (only the footprint filter reads it), in the map's order; 0
    /// past the map's materials.
    #[must_use]
    pub fn sample(&self, uv: [f64; 2], footprint_uv: f64) -> [f64; MAX_MAP_MATERIALS] {
        let mut w = [0.0; MAX_MAP_MATERIALS];
        for (slot, (image, pyramid)) in w.iter_mut().zip(&self.fractions) {
            *slot = match pyramid {
                Some(p) => p.sample(image, uv, footprint_uv),
                None => image.sample(uv, self.filter),
            };
        }
        w
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// 2 × 2 texels, row 0 at the top: values 10, 20 over 20, 10; 10 is material 0, 20
    /// material 1.
    fn checker(filter: MapFilter) -> MixMap {
        MixMap::from_index(2, 2, &[10, 20, 20, 10], &[(10, 0), (20, 1)], 2, filter).unwrap()
    }

    fn bits(w: [f64; MAX_MAP_MATERIALS]) -> [u64; MAX_MAP_MATERIALS] {
        w.map(f64::to_bits)
    }

    #[test]
    fn nearest_takes_the_texels_material() {
        let m = checker(MapFilter::Nearest);
        // The bottom-left texel (row 1 from the top) holds 20: material 1.
        assert_eq!(
            bits(m.sample([0.25, 0.25], 0.0)),
            bits([0.0, 1.0, 0.0, 0.0])
        );
        assert_eq!(
            bits(m.sample([0.75, 0.25], 0.0)),
            bits([1.0, 0.0, 0.0, 0.0])
        );
        assert_eq!(
            bits(m.sample([0.25, 0.75], 0.0)),
            bits([1.0, 0.0, 0.0, 0.0])
        );
        // Repeated outside 0 to 1.
        assert_eq!(
            bits(m.sample([1.25, -0.75], 0.0)),
            bits([0.0, 1.0, 0.0, 0.0])
        );
    }

    #[test]
    fn bilinear_gives_the_area_fractions_of_the_texels_around_the_point() {
        let m = checker(MapFilter::Bilinear);
        // At a texel's centre, its material alone.
        assert_eq!(
            bits(m.sample([0.25, 0.25], 0.0)),
            bits([0.0, 1.0, 0.0, 0.0])
        );
        // Halfway between the bottom two texels' centres (u = 0.5, v = 0.25): half each.
        let w = m.sample([0.5, 0.25], 0.0);
        assert!(
            (w[0] - 0.5).abs() < 1e-15 && (w[1] - 0.5).abs() < 1e-15,
            "{w:?}"
        );
        // A quarter of the way from the bottom-left centre towards the right: 3/4 of it.
        let w = m.sample([0.375, 0.25], 0.0);
        assert!(
            (w[1] - 0.75).abs() < 1e-12 && (w[0] - 0.25).abs() < 1e-12,
            "{w:?}"
        );
        // The footprint filter far away: each material's share of the image.
        let far = checker(MapFilter::Footprint).sample([0.3, 0.6], 100.0);
        assert!(
            (far[0] - 0.5).abs() < 1e-7 && (far[1] - 0.5).abs() < 1e-7,
            "{far:?}"
        );
    }

    #[test]
    fn a_value_the_table_does_not_list_is_refused_at_its_texel() {
        let e = MixMap::from_index(2, 1, &[10, 30], &[(10, 0), (20, 1)], 2, MapFilter::Nearest)
            .unwrap_err();
        let text = e.to_string();
        assert!(
            text.contains("column 1, row 0") && text.contains("value 30"),
            "{text}"
        );
        assert!(text.contains("[10, 20]"), "{text}");
        assert!(
            MixMap::from_index(1, 1, &[0], &[(0, 0)], 5, MapFilter::Nearest).is_err(),
            "five materials"
        );
    }

    #[test]
    fn weights_are_checked_against_their_tolerance_and_divided_by_their_sum() {
        // Two texels of two channels: (0.5, 0.51) sums to 1.01.
        let m = MixMap::from_weights(2, 1, 2, &[0.5, 0.51, 1.0, 0.0], 0.02, MapFilter::Nearest)
            .unwrap();
        let w = m.sample([0.25, 0.5], 0.0);
        assert!((w[0] - 0.5 / 1.01).abs() < 1e-7 && (w[0] + w[1] - 1.0).abs() < 1e-7);
        let e = MixMap::from_weights(2, 1, 2, &[0.5, 0.51, 1.0, 0.0], 0.005, MapFilter::Nearest)
            .unwrap_err();
        assert!(e.to_string().contains("sum to 1.0099"), "{e}");
        let e =
            MixMap::from_weights(1, 1, 2, &[f32::NAN, 1.0], 0.01, MapFilter::Nearest).unwrap_err();
        assert!(e.to_string().contains("NaN"), "{e}");
        assert!(MixMap::from_weights(1, 1, 2, &[0.5], 0.01, MapFilter::Nearest).is_err());
    }
}
