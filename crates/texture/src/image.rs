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
        self.wrapped(wrap(i, self.width), wrap(j, self.height))
    }

    /// The grey of texel `(i, j)` of the image itself: `i < width`, `j < height`.
    fn wrapped(&self, i: usize, j: usize) -> f64 {
        let row = self.height - 1 - j;
        f64::from(self.grey[row * self.width + i])
    }

    /// The grey at texture coordinates `uv` with `filter` (a footprint filter, given no
    /// footprint here, reads the image itself bilinearly: [`MipPyramid::sample`] gives it
    /// its footprint).
    #[must_use]
    pub fn sample(&self, [u, v]: [f64; 2], filter: MapFilter) -> f64 {
        let x = u * self.width as f64;
        let y = v * self.height as f64;
        match filter {
            MapFilter::Nearest => self.texel(floor(x), floor(y)),
            MapFilter::Bilinear | MapFilter::Footprint => {
                // Texel centres are at half-integers: measure from the centre of the
                // texel below and left of the point.
                let (x, y) = (x - 0.5, y - 0.5);
                let (i, j) = (floor(x), floor(y));
                let (fx, fy) = (x - i as f64, y - j as f64);
                // Each coordinate wrapped once, its neighbour from it (an integer
                // division a coordinate, where wrapping each of the four texels took eight).
                let (i0, j0) = (wrap(i, self.width), wrap(j, self.height));
                let (i1, j1) = (next(i0, self.width), next(j0, self.height));
                // The two rows' starts once, each texel an offset from its row's.
                let row = |j: usize| (self.height - 1 - j) * self.width;
                let (r0, r1) = (row(j0), row(j1));
                let g = |k: usize| f64::from(self.grey[k]);
                let bottom = (1.0 - fx) * g(r0 + i0) + fx * g(r0 + i1);
                let top = (1.0 - fx) * g(r1 + i0) + fx * g(r1 + i1);
                (1.0 - fy) * bottom + fy * top
            }
        }
    }
}

/// `x.floor()` as an integer by a conversion and a comparison: the baseline x86-64 has no
/// rounding instruction (SSE4.1's), so `f64::floor` is a call into the C library, two a
/// bilinear read. The same integer as `x.floor() as i64` for every finite `x` (exactly,
/// below 2⁶³; saturated beyond, as the cast saturates), and 0 for NaN.
#[inline]
fn floor(x: f64) -> i64 {
    let i = x as i64;
    i.saturating_sub(i64::from(i as f64 > x))
}

/// `i` repeated into `0..size` (`size` ≥ 1; the sizes are at most the memory budget's
/// pixels, far below `i64::MAX`). A side that is a power of two, as a mip pyramid's are,
/// takes the low bits of `i`'s two's complement, which are its Euclidean remainder,
/// without the integer division.
fn wrap(i: i64, size: usize) -> usize {
    if size.is_power_of_two() {
        i as usize & (size - 1)
    } else {
        i.rem_euclid(size as i64) as usize
    }
}

/// The index after `i` (already in `0..size`), repeated.
fn next(i: usize, size: usize) -> usize {
    if i + 1 == size { 0 } else { i + 1 }
}

/// A box-filtered mip pyramid of a grey image (Williams, "Pyramidal parametrics",
/// SIGGRAPH 1983): level 0 is the image, and each texel of level `k + 1` is the mean of the
/// 2 × 2 texels of level `k` it covers (of those that exist: an odd side's last column or
/// row has only one), down to one texel. For an image whose sides are powers of two, a
/// level-`k` texel is exactly the mean of the `2ᵏ × 2ᵏ` texels below it and the last level
/// the image's mean; for other sizes the last column or row of a level weighs its texels
/// up to twice what the others do.
///
/// [`Self::sample`] reads it with a footprint: the point's value over a pixel's footprint
/// `F` texels across is read at level `L = log₂ F` (between levels `⌊L⌋` and `⌊L⌋ + 1`,
/// each read bilinearly, blended linearly by `L − ⌊L⌋`: "trilinear" filtering), level 0
/// bilinearly where `F ≤ 1` (magnification), the last level beyond it. Its error model:
/// the value is a weighted mean of the texels within about `2F` texels of the point, so
/// it differs from the mean of the texels under the footprint by at most the spread of
/// the level-`⌊L⌋` texel means it blends: nothing for a pattern that repeats within
/// `2^⌊L⌋` texels (a checkerboard of single texels from `F = 2` up), up to the texture's
/// whole range where the footprint straddles a feature that large. The footprint is
/// isotropic: its side is the long axis of the pixel's footprint on the surface, so a
/// grazing view is blurred along the short axis more than its own footprint would (no
/// anisotropic filtering).
#[derive(Debug, Clone, PartialEq)]
pub struct MipPyramid {
    /// Levels 1, 2, …, down to one texel (level 0 is the image itself).
    levels: Vec<GreyImage>,
    /// Level 0's texels a texture-coordinate unit, `√(W·H)`.
    texels_per_uv: f64,
}

impl MipPyramid {
    /// The pyramid of `image` (its levels from 1; a 1 × 1 image has none).
    #[must_use]
    pub fn new(image: &GreyImage) -> Self {
        let mut levels: Vec<GreyImage> = Vec::new();
        loop {
            let finer = levels.last().unwrap_or(image);
            if finer.width == 1 && finer.height == 1 {
                break;
            }
            levels.push(finer.halved());
        }
        Self {
            levels,
            texels_per_uv: ((image.width * image.height) as f64).sqrt(),
        }
    }

    /// How many levels, the image's included.
    #[must_use]
    pub fn len(&self) -> usize {
        self.levels.len() + 1
    }

    /// Always false: a pyramid holds at least its image.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        false
    }

    /// The grey of `image` (the pyramid's level 0) at texture coordinates `uv` over a
    /// footprint `footprint_uv` across, in texture-coordinate units (a texture
    /// coordinate's unit is `√(W·H)` texels of the image: the geometric mean of its
    /// sides). `image` is the image the pyramid was made of.
    #[must_use]
    pub fn sample(&self, image: &GreyImage, uv: [f64; 2], footprint_uv: f64) -> f64 {
        let texels = footprint_uv * self.texels_per_uv;
        // Magnification, and a footprint of 0 or NaN: the image itself, bilinearly.
        if texels.is_nan() || texels <= 1.0 {
            return image.sample(uv, MapFilter::Bilinear);
        }
        let level = log2_above_one(texels).min(self.levels.len() as f64);
        let k = level as usize;
        let at = |k: usize| {
            let img = if k == 0 {
                image
            } else {
                &self.levels[(k - 1).min(self.levels.len() - 1)]
            };
            img.sample(uv, MapFilter::Bilinear)
        };
        let f = level - k as f64;
        if f == 0.0 || k >= self.levels.len() {
            return at(k);
        }
        (1.0 - f) * at(k) + f * at(k + 1)
    }
}

/// `log₂ x` for `x > 1` (infinity included), within 1.7·10⁻⁶ and exact at every power of
/// two, without the C library's call: the exponent's bits give the integer part, and the
/// mantissa `m` in `[1, 2)` the rest by `log₂ m = (2/ln 2)·artanh s`, `s = (m − 1)/(m + 1)`
/// in `[0, ⅓)`, its series to `s⁹` (truncation `(2/ln 2)·s¹¹/11·(1 − s²)⁻¹` < 1.7·10⁻⁶). A
/// mip level's blend weight is off by no more: at a power of two the weight steps by that
/// much at most, 2·10⁻⁶ of the two levels' difference.
#[inline]
fn log2_above_one(x: f64) -> f64 {
    const MANTISSA: u64 = (1 << 52) - 1;
    if x == f64::INFINITY {
        return x;
    }
    let bits = x.to_bits();
    let exponent = ((bits >> 52) & 0x7ff) as i64 - 1023;
    let m = f64::from_bits((bits & MANTISSA) | 1.0f64.to_bits());
    let s = (m - 1.0) / (m + 1.0);
    let s2 = s * s;
    let series = s * (1.0 + s2 * (1.0 / 3.0 + s2 * (1.0 / 5.0 + s2 * (1.0 / 7.0 + s2 / 9.0))));
    exponent as f64 + series * (2.0 / std::f64::consts::LN_2)
}

impl GreyImage {
    /// The next level of a box-filtered pyramid: each texel the mean of the (up to) 2 × 2
    /// texels it covers, in texture coordinates (pairs counted from the bottom-left, as
    /// `u` and `v` run).
    fn halved(&self) -> Self {
        let (w, h) = (self.width.div_ceil(2), self.height.div_ceil(2));
        let mut grey = vec![0.0f32; w * h];
        let mut range = [f64::INFINITY, f64::NEG_INFINITY];
        for j in 0..h {
            for i in 0..w {
                let (mut sum, mut n) = (0.0, 0.0);
                for (ci, cj) in [
                    (2 * i, 2 * j),
                    (2 * i + 1, 2 * j),
                    (2 * i, 2 * j + 1),
                    (2 * i + 1, 2 * j + 1),
                ] {
                    if ci < self.width && cj < self.height {
                        sum += self.wrapped(ci, cj);
                        n += 1.0;
                    }
                }
                let g = sum / n;
                range = [range[0].min(g), range[1].max(g)];
                grey[(h - 1 - j) * w + i] = g as f32;
            }
        }
        Self {
            width: w,
            height: h,
            grey,
            range,
        }
    }
}

/// One map with its image, and its pyramid when its filter is the footprint's.
#[derive(Debug, Clone, PartialEq)]
struct LoadedMap {
    map: ImageMap,
    image: GreyImage,
    pyramid: Option<MipPyramid>,
}

impl LoadedMap {
    fn new(map: ImageMap, image: GreyImage) -> Self {
        let pyramid = (map.filter == MapFilter::Footprint).then(|| MipPyramid::new(&image));
        Self {
            map,
            image,
            pyramid,
        }
    }

    fn at(&self, uv: [f64; 2], footprint_uv: f64) -> f64 {
        let grey = match &self.pyramid {
            Some(p) => p.sample(&self.image, uv, footprint_uv),
            None => self.image.sample(uv, self.map.filter),
        };
        self.map.at(grey)
    }

    /// The least and greatest value the map gives anywhere: at the image's least and
    /// greatest grey (the mapping is linear, and every filter gives a weighted mean of
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
    /// The material map with its image ([`Self::with_material`]).
    material: Option<crate::MixMap>,
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
                .map(|map| Ok::<_, TextureError>(LoadedMap::new(map.clone(), images(name, map)?)))
                .transpose()
        };
        Ok(Self {
            temperature: load("temperature_offset_k", &maps.temperature_offset_k)?,
            emissivity: load("emissivity_scale", &maps.emissivity_scale)?,
            material: None,
        })
    }

    /// These maps with the material map `material` (read by the caller: its image is not
    /// a grey map's).
    #[must_use]
    pub fn with_material(mut self, material: crate::MixMap) -> Self {
        self.material = Some(material);
        self
    }

    /// The material map, if the maps have one.
    #[must_use]
    pub fn material(&self) -> Option<&crate::MixMap> {
        self.material.as_ref()
    }

    /// Whether any of the maps (the material map's included) is read over a ray's
    /// footprint (`MapFilter::Footprint`): only then does a ray's footprint matter to them.
    #[must_use]
    pub fn filters_footprint(&self) -> bool {
        [&self.temperature, &self.emissivity]
            .into_iter()
            .flatten()
            .any(|m| m.pyramid.is_some())
            || self
                .material
                .as_ref()
                .is_some_and(crate::MixMap::filters_footprint)
    }

    /// Whether the maps vary the temperature or the emissivity scale (a material map alone
    /// does neither).
    #[must_use]
    pub fn varies_texel(&self) -> bool {
        self.temperature.is_some() || self.emissivity.is_some()
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

    /// The texel at texture coordinates `uv` (a footprint filter reads the image itself,
    /// as for a footprint under a texel).
    #[must_use]
    pub fn sample(&self, uv: [f64; 2]) -> Texel {
        self.sample_over(uv, 0.0)
    }

    /// The texel at texture coordinates `uv` over a pixel's footprint `footprint_uv`
    /// across, in texture-coordinate units ([`MipPyramid::sample`]): only maps with the
    /// footprint filter read it.
    #[must_use]
    pub fn sample_over(&self, uv: [f64; 2], footprint_uv: f64) -> Texel {
        Texel {
            temperature_offset_k: self
                .temperature
                .as_ref()
                .map_or(0.0, |m| m.at(uv, footprint_uv)),
            emissivity_scale: self
                .emissivity
                .as_ref()
                .map_or(1.0, |m| m.at(uv, footprint_uv)),
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
    fn the_arithmetic_floor_and_logarithm_are_the_libraries() {
        for i in -50_000..50_000 {
            let x = f64::from(i) * 0.013_7 + 0.5e-3;
            assert_eq!(floor(x), x.floor() as i64, "{x}");
        }
        for x in [
            -1.0,
            -0.0,
            0.0,
            3.0,
            -2.5,
            1e17 + 2.0,
            -1e17,
            1e300,
            -1e300,
            f64::NAN,
        ] {
            assert_eq!(floor(x), x.floor() as i64, "{x}");
        }
        let mut worst: f64 = 0.0;
        for i in 1..200_000 {
            let x = 1.0 + f64::from(i) * 1.37e-3;
            worst = worst.max((log2_above_one(x) - x.log2()).abs());
        }
        // The series' truncation at `s = ⅓`, the bound the doc gives.
        let third: f64 = 1.0 / 3.0;
        let bound = 2.0 / std::f64::consts::LN_2 * third.powi(11) / 11.0 / (1.0 - third * third);
        assert!(worst < bound && bound < 1.7e-6, "{worst} {bound}");
        assert!(worst > 0.5 * bound, "{worst}");
        for k in 0..60 {
            let x = 2f64.powi(k);
            assert_eq!(log2_above_one(x).to_bits(), f64::from(k).to_bits());
        }
        assert_eq!(
            log2_above_one(f64::INFINITY).to_bits(),
            f64::INFINITY.to_bits()
        );
    }

    #[test]
    fn wrapping_is_the_euclidean_remainder_at_every_size() {
        for size in [1_usize, 2, 3, 7, 64, 256, 1000, 1 << 20] {
            let near = (-3 * size as i64..3 * size as i64).step_by(size.div_ceil(500));
            let far = [i64::MIN, i64::MIN + 1, -(1 << 40) - 1, 1 << 40, i64::MAX];
            for i in near.chain(far) {
                let expected = i.rem_euclid(size as i64) as usize;
                assert_eq!(wrap(i, size), expected, "{i} in {size}");
                assert_eq!(next(expected, size), (expected + 1) % size);
            }
        }
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

    /// A `side × side` checkerboard of single texels, 0 and 1: white where the column plus
    /// the row from the top is odd (for an even side, the bottom-left texel is white).
    fn checker(side: usize) -> GreyImage {
        let grey = (0..side * side)
            .map(|k| ((k / side + k % side) % 2) as f32)
            .collect();
        GreyImage::new(side, side, grey).unwrap()
    }

    #[allow(clippy::float_cmp)] // ½ of 0 and 1, exact in binary
    #[test]
    fn each_level_is_the_mean_of_the_texels_below_it() {
        // The 2 × 2 quad's one level-1 texel: (0.1 + 0.2 + 0.3 + 0.4)/4.
        let p = MipPyramid::new(&quad());
        assert_eq!(p.len(), 2);
        assert!(close(p.levels[0].grey[0].into(), 0.25));
        assert!(close(p.levels[0].range()[0], 0.25));
        // 256 × 256 single-texel checkerboard: 9 levels, every texel of levels 1 to 8 is
        // exactly ½ (a 2 × 2 block holds two of each).
        let c = checker(256);
        let p = MipPyramid::new(&c);
        assert_eq!(p.len(), 9);
        assert!(p.levels.iter().all(|l| l.grey.iter().all(|&g| g == 0.5)));
        assert_eq!(p.levels[7].width, 1);
        // 3 × 1: level 1 is 2 × 1, (a + b)/2 and c alone; level 2 their mean.
        let odd = GreyImage::new(3, 1, vec![0.2, 0.4, 1.0]).unwrap();
        let p = MipPyramid::new(&odd);
        assert_eq!(p.len(), 3);
        assert!(close(p.levels[0].grey[0].into(), 0.3) && close(p.levels[0].grey[1].into(), 1.0));
        assert!(close(p.levels[1].grey[0].into(), 0.65));
        // A 1 × 1 image is its own pyramid.
        assert_eq!(
            MipPyramid::new(&GreyImage::new(1, 1, vec![0.7]).unwrap()).len(),
            1
        );
    }

    #[test]
    fn the_footprint_picks_the_level_and_blends_between_two() {
        let c = checker(256);
        let p = MipPyramid::new(&c);
        let texel = 1.0 / 256.0;
        // The bottom-left texel's centre: under one texel across (or none, or NaN) the
        // image itself, bilinearly: the texel's own 1.
        let centre = [0.5 * texel, 0.5 * texel];
        for f in [0.0, 0.5 * texel, texel, f64::NAN] {
            assert!(close(p.sample(&c, centre, f), 1.0), "{f}");
        }
        // From 2 texels across up, the mean ½ wherever the point is, out to the whole
        // image and beyond.
        for f in [2.0, 3.0, 7.5, 64.0, 256.0, 1e9, f64::INFINITY] {
            for uv in [centre, [0.3, 0.71], [-2.2, 5.9]] {
                assert!(close(p.sample(&c, uv, f * texel), 0.5), "{f} {uv:?}");
            }
        }
        // Between levels 0 and 1 (√2 texels: L = ½), at the white texel's centre: half the
        // image's 1 and half level 1's ½; at its black neighbour's, half 0 and half ½.
        assert!(close(p.sample(&c, centre, 2f64.sqrt() * texel), 0.75));
        let black = [1.5 * texel, 0.5 * texel];
        assert!(close(p.sample(&c, black, 2f64.sqrt() * texel), 0.25));
        // A ramp of 4 × 1 texels: √(W·H) = 2 texels per unit of texture coordinate, so a
        // footprint of 1 unit is 2 texels, level 1 = (0.125, 0.625); at u = ¼, the centre
        // of level 1's first texel, the mean of the image's first two texels.
        let ramp = GreyImage::new(4, 1, vec![0.0, 0.25, 0.5, 0.75]).unwrap();
        let pr = MipPyramid::new(&ramp);
        assert!(close(pr.sample(&ramp, [0.25, 0.5], 1.0), 0.125));
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
            material: None,
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
        // Only a footprint map reads a ray's footprint.
        assert!(!loaded.filters_footprint());
        let mut footprint = maps.clone();
        if let Some(m) = footprint.emissivity_scale.as_mut() {
            m.filter = MapFilter::Footprint;
        }
        let footprint = MaterialMaps::new(&footprint, |_, _| Ok(quad())).unwrap();
        assert!(footprint.filters_footprint());
        // A NaN in the mapping is refused before any image is asked for.
        let nan = ImageMaps {
            temperature_offset_k: Some(map(f64::NAN, 1.0)),
            emissivity_scale: None,
            material: None,
        };
        let e = MaterialMaps::new(&nan, |_, _| panic!("not asked")).unwrap_err();
        assert!(e.to_string().contains("at_black"), "{e}");
    }
}
