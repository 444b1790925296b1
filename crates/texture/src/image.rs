//! Image maps: a grey image laid on facets by their texture coordinates, read with a named
//! filter, and what a material's maps give at a point ([`MaterialMaps`]).
//!
//! Texture coordinates follow `irsig_model::FacetUv`: `(0, 0)` is the image's bottom-left
//! corner, `(1, 1)` its top-right, and the image repeats outside 0 to 1. Texel `(i, j)`
//! (column `i` from the left, row `j` from the bottom) covers `u ∈ [i/W, (i+1)/W)` and
//! `v ∈ [j/H, (j+1)/H)`; its centre is at `((i + ½)/W, (j + ½)/H)`.

use irsig_model::image_map::{ImageMap, ImageMaps, MapFilter};

use crate::{Texel, TextureError, TextureErrorKind};

/// A grey image as a map reads it: its texels' grey values, 0 (black) to 1 (white), row 0
/// at the top as images are stored.
#[derive(Debug, Clone, PartialEq)]
pub struct GreyImage {
    width: usize,
    height: usize,
    grey: Vec<f32>,
    /// The least and the greatest grey of the image.
    range: [f64; 2],
}

impl GreyImage {
    /// An image of `width × height` texels, `grey` row after row from the top.
    ///
    /// # Errors
    /// No texel, a grey count that is not `width × height`, or a grey outside 0 to 1
    /// (NaN included).
    pub fn new(width: usize, height: usize, grey: Vec<f32>) -> Result<Self, TextureError> {
        let bad = |why: String| TextureError {
            kind: TextureErrorKind::BadImage(why),
        };
        if width == 0 || height == 0 || width.checked_mul(height) != Some(grey.len()) {
            return Err(bad(format!(
                "{} grey values for an image of {width} × {height} texels",
                grey.len()
            )));
        }
        let mut range = [f64::INFINITY, f64::NEG_INFINITY];
        for (k, &g) in grey.iter().enumerate() {
            if !(0.0..=1.0).contains(&g) {
                return Err(bad(format!("texel {k} has grey {g}, outside 0 to 1")));
            }
            range = [range[0].min(f64::from(g)), range[1].max(f64::from(g))];
        }
        Ok(Self {
            width,
            height,
            grey,
            range,
        })
    }

    /// The least and the greatest grey of the image.
    #[must_use]
    pub fn range(&self) -> [f64; 2] {
        self.range
    }

    /// The grey of texel `(i, j)`, column `i` from the left and row `j` from the bottom,
    /// both repeated (any integer).
    fn texel(&self, i: i64, j: i64) -> f64 {
        // The sizes are at most the memory budget's pixels, far below i64::MAX.
        let i = i.rem_euclid(self.width as i64) as usize;
        let j = j.rem_euclid(self.height as i64) as usize;
        let row = self.height - 1 - j;
        f64::from(self.grey[row * self.width + i])
    }

    /// The grey at texture coordinates `uv` with `filter`.
    #[must_use]
    pub fn sample(&self, [u, v]: [f64; 2], filter: MapFilter) -> f64 {
        let x = u * self.width as f64;
        let y = v * self.height as f64;
        match filter {
            MapFilter::Nearest => self.texel(x.floor() as i64, y.floor() as i64),
            MapFilter::Bilinear => {
                // Texel centres are at half-integers: measure from the centre of the
                // texel below and left of the point.
                let (x, y) = (x - 0.5, y - 0.5);
                let (i, j) = (x.floor(), y.floor());
                let (fx, fy) = (x - i, y - j);
                let (i, j) = (i as i64, j as i64);
                let bottom = (1.0 - fx) * self.texel(i, j) + fx * self.texel(i + 1, j);
                let top = (1.0 - fx) * self.texel(i, j + 1) + fx * self.texel(i + 1, j + 1);
                (1.0 - fy) * bottom + fy * top
            }
        }
    }
}

/// One map with its image.
#[derive(Debug, Clone, PartialEq)]
struct LoadedMap {
    map: ImageMap,
    image: GreyImage,
}

impl LoadedMap {
    fn at(&self, uv: [f64; 2]) -> f64 {
        self.map.at(self.image.sample(uv, self.map.filter))
    }

    /// The least and greatest value the map gives anywhere: at the image's least and
    /// greatest grey (the mapping is linear, and both filters are weighted means of
    /// texels, so no point lies outside its texels' range).
    fn range(&self) -> [f64; 2] {
        let [lo, hi] = self.image.range().map(|g| self.map.at(g));
        [lo.min(hi), lo.max(hi)]
    }
}

/// A material's image maps, with their images, ready to sample.
#[derive(Debug, Clone, PartialEq)]
pub struct MaterialMaps {
    temperature: Option<LoadedMap>,
    emissivity: Option<LoadedMap>,
}

impl MaterialMaps {
    /// The maps of `maps` with their images: `images(name, map)` gives the image of the
    /// map called `name` (`temperature_offset_k`, `emissivity_scale`).
    ///
    /// # Errors
    /// The maps break a rule of their declaration, or `images` fails.
    pub fn new(
        maps: &ImageMaps,
        mut images: impl FnMut(&str, &ImageMap) -> Result<GreyImage, TextureError>,
    ) -> Result<Self, TextureError> {
        maps.validate("maps").map_err(|e| TextureError {
            kind: TextureErrorKind::Invalid(e),
        })?;
        let mut load = |name: &str, m: &Option<ImageMap>| {
            m.as_ref()
                .map(|map| {
                    Ok::<_, TextureError>(LoadedMap {
                        image: images(name, map)?,
                        map: map.clone(),
                    })
                })
                .transpose()
        };
        Ok(Self {
            temperature: load("temperature_offset_k", &maps.temperature_offset_k)?,
            emissivity: load("emissivity_scale", &maps.emissivity_scale)?,
        })
    }

    /// The largest temperature offset the maps give anywhere, in magnitude, K.
    #[must_use]
    pub fn max_temperature_offset_k(&self) -> f64 {
        self.temperature.as_ref().map_or(0.0, |m| {
            m.range().into_iter().fold(0.0, |a, x| a.max(x.abs()))
        })
    }

    /// The least and the greatest emissivity scale the maps give anywhere (`[1, 1]`
    /// without an emissivity map): the tracer refuses a material whose ε times the
    /// greatest exceeds 1 anywhere in the band, or whose least is below 0.
    #[must_use]
    pub fn emissivity_scale_range(&self) -> [f64; 2] {
        self.emissivity
            .as_ref()
            .map_or([1.0, 1.0], LoadedMap::range)
    }

    /// The texel at texture coordinates `uv`.
    #[must_use]
    pub fn sample(&self, uv: [f64; 2]) -> Texel {
        Texel {
            temperature_offset_k: self.temperature.as_ref().map_or(0.0, |m| m.at(uv)),
            emissivity_scale: self.emissivity.as_ref().map_or(1.0, |m| m.at(uv)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// 2 × 2 texels, row 0 at the top: top-left 0.1, top-right 0.2, bottom-left 0.3,
    /// bottom-right 0.4.
    fn quad() -> GreyImage {
        GreyImage::new(2, 2, vec![0.1, 0.2, 0.3, 0.4]).unwrap()
    }

    /// Within what an `f32` grey keeps (6·10⁻⁸ of it), times a mapping's gain of 10.
    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() < 1e-6
    }

    #[test]
    fn nearest_takes_the_texel_the_point_falls_in_with_v_up() {
        let q = quad();
        let at = |u, v| q.sample([u, v], MapFilter::Nearest);
        // u, v from the bottom-left corner: (0.25, 0.25) is in the bottom-left texel.
        assert!(close(at(0.25, 0.25), 0.3));
        assert!(close(at(0.75, 0.25), 0.4));
        assert!(close(at(0.25, 0.75), 0.1));
        assert!(close(at(0.75, 0.75), 0.2));
        // Repeated: one image to the left and two up is the same texel, as is -0.75.
        assert!(close(at(-0.75, 2.25), 0.3));
        assert!(close(at(1e6 + 0.75, -1e6 + 0.75), 0.2));
    }

    #[test]
    fn bilinear_is_the_texel_at_its_centre_and_the_mean_halfway() {
        let q = quad();
        let at = |u, v| q.sample([u, v], MapFilter::Bilinear);
        // Texel centres: the texel's own grey.
        assert!(close(at(0.25, 0.25), 0.3));
        assert!(close(at(0.75, 0.75), 0.2));
        // Halfway between the bottom two centres: (0.3 + 0.4)/2.
        assert!(close(at(0.5, 0.25), 0.35));
        // Halfway between the left two: (0.3 + 0.1)/2; the middle of all four: 0.25.
        assert!(close(at(0.25, 0.5), 0.2));
        assert!(close(at(0.5, 0.5), 0.25));
        // At the image's left edge, halfway to the repeated right column: (0.3 + 0.4)/2.
        assert!(close(at(0.0, 0.25), 0.35));
    }

    #[allow(clippy::float_cmp)] // coordinates and greys written exactly, read back exactly
    #[test]
    fn bad_images_are_refused() {
        assert!(GreyImage::new(0, 1, vec![]).is_err());
        assert!(GreyImage::new(2, 2, vec![0.0; 3]).is_err());
        assert!(GreyImage::new(1, 1, vec![f32::NAN]).is_err());
        assert!(GreyImage::new(1, 1, vec![1.5]).is_err());
        assert_eq!(quad().range(), [f64::from(0.1f32), f64::from(0.4f32)]);
    }

    #[test]
    fn the_maps_map_grey_linearly_and_know_their_ranges() {
        let map = |at_black, per_grey| ImageMap {
            image: "g.png".into(),
            at_black,
            per_grey,
            filter: MapFilter::Nearest,
        };
        let maps = ImageMaps {
            temperature_offset_k: Some(map(-5.0, 10.0)),
            emissivity_scale: Some(map(1.0, -0.5)),
        };
        let loaded = MaterialMaps::new(&maps, |_, _| Ok(quad())).unwrap();
        let t = loaded.sample([0.25, 0.25]);
        // Grey 0.3: -5 + 10·0.3 = -2 K and 1 − 0.5·0.3 = 0.85.
        assert!(close(t.temperature_offset_k, -2.0));
        assert!(close(t.emissivity_scale, 0.85));
        // Offsets from -5 + 1 = -4 to -5 + 4 = -1: the largest magnitude is 4.
        assert!(close(loaded.max_temperature_offset_k(), 4.0));
        let [lo, hi] = loaded.emissivity_scale_range();
        assert!(close(lo, 0.8) && close(hi, 0.95));
        // A NaN in the mapping is refused before any image is asked for.
        let nan = ImageMaps {
            temperature_offset_k: Some(map(f64::NAN, 1.0)),
            emissivity_scale: None,
        };
        let e = MaterialMaps::new(&nan, |_, _| panic!("not asked")).unwrap_err();
        assert!(e.to_string().contains("at_black"), "{e}");
    }
}
