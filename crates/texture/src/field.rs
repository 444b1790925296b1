//! A random field drawn once from a seed and evaluated anywhere in world space.
//!
//! The field is a sum of [`WAVES`] plane waves, `g(x) = σ·√(2/N)·Σ cos(2π(f_i·x + φ_i))`,
//! the spectral representation of a stationary Gaussian field (Shinozuka & Deodatis 1991):
//! each wave's frequency `f_i` (cycles per metre) drawn from the spectrum, its phase `φ_i`
//! uniform. Its covariance is `σ²·E[cos(2π f·r)] = σ²·C(r)`, its variance over space exactly
//! σ², and by the central limit theorem its values are Gaussian to within `1/N` in the
//! fourth moment. The radial frequencies are stratified (wave `i` takes the spectrum's
//! quantile `(i + ξ)/N`), so that one realisation's spectrum already follows the named one
//! closely; directions are uniform on the sphere. A value is a function of the position
//! alone: the same seed gives the same texture at any thread count, in any tile, in every
//! frame, on any CPU.

use std::sync::OnceLock;

use irsig_model::texture::RandomField;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

use crate::spectrum::Shape;

/// The number of plane waves in a field: enough that a realisation's variance is exact and
/// its one-point distribution Gaussian (excess kurtosis `−1.5/N` = −0.047), and the
/// rendered σ and correlation lengths those asked for over a few seeds (the tracer's
/// `tests/texture.rs`); each wave costs a hit about 0.9 ns with AVX2 and FMA
/// (BENCHMARKS.md, "texture: the point field within the floor"), so 64 cost twice as much
/// for no test that 32 fail.
pub const WAVES: usize = 32;

/// A field's values are held within this many σ of its mean: a sum of cosines is bounded
/// anyway (by `√(2N)` σ = 8 σ), and beyond 8 σ a Gaussian puts one point in 10¹⁵.
pub const CLIP_SIGMAS: f64 = 8.0;

/// One random field, ready to evaluate.
#[derive(Debug, Clone, PartialEq)]
pub struct Field {
    /// Each wave's frequency along x, y and z, cycles per metre.
    fx: [f64; WAVES],
    fy: [f64; WAVES],
    fz: [f64; WAVES],
    /// Each wave's phase, turns.
    phase: [f64; WAVES],
    /// `σ·√(2/N)`.
    amplitude: f64,
    /// σ.
    sigma: f64,
    /// The largest wave's frequency, cycles per metre: what decides whether a footprint
    /// is small enough to read the point.
    fastest_per_m: f64,
}

/// A pixel's cell where it lies on a surface: the parallelogram `p + s·a + t·b`,
/// `s, t` in `[−½, ½]`, about the point `p` a ray hit, given by its two edges `a` and `b`,
/// m. Edges that are not finite (a ray at grazing incidence) cover the whole surface.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Footprint {
    /// The edges `a` and `b`, world metres.
    pub edges_m: [[f64; 3]; 2],
}

impl Footprint {
    /// The longer edge's length, m (infinite where an edge is not finite): the width an
    /// isotropic filter (an image's mip level) reads, which errs toward blur along the
    /// shorter edge.
    #[must_use]
    pub fn width_m(&self) -> f64 {
        let squared = |e: [f64; 3]| e[0] * e[0] + e[1] * e[1] + e[2] * e[2];
        let [a, b] = self.edges_m.map(squared);
        if a.is_finite() && b.is_finite() {
            a.max(b).sqrt()
        } else {
            f64::INFINITY
        }
    }
}

/// Under this many of a field's shortest wavelengths across, a footprint reads the point:
/// the box's mean of a wave is then `1 − (π·x)²/6` of the wave at most `x = 5·10⁻⁴` waves
/// across, within 4.2·10⁻⁷ of its amplitude, below the cosine's own error.
const POINT_REACH: f64 = 5e-4;

impl Field {
    /// The field `spec` drawn from `seed` (its waves from a ChaCha8 stream, the same
    /// numbers on every platform; their frequencies through the standard library's `ln`,
    /// `exp`, `sin` and `cos`). `spec` should be valid (`RandomField::validate`); lengths that are
    /// not finite or not positive give a field of 0.
    #[must_use]
    pub fn new(spec: &RandomField, seed: u64) -> Self {
        let (shape, lengths) = Shape::of(&spec.spectrum);
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let mut field = Self {
            fx: [0.0; WAVES],
            fy: [0.0; WAVES],
            fz: [0.0; WAVES],
            phase: [0.0; WAVES],
            amplitude: spec.sigma * (2.0 / WAVES as f64).sqrt(),
            sigma: spec.sigma,
            fastest_per_m: 0.0,
        };
        let usable = spec.sigma.is_finite()
            && spec.sigma > 0.0
            && lengths.iter().all(|l| l.is_finite() && *l > 0.0);
        if !usable {
            field.amplitude = 0.0;
            field.sigma = 0.0;
            return field;
        }
        for i in 0..WAVES {
            let (xi, mu, azimuth, phase): (f64, f64, f64, f64) =
                (rng.random(), rng.random(), rng.random(), rng.random());
            // ξ in [0, 1): keep the quantile inside (0, 1).
            let u = ((i as f64 + xi) / WAVES as f64).clamp(1e-12, 1.0 - 1e-12);
            let k = shape.radial_quantile(u);
            // Uniform on the sphere: z = cos θ uniform in [−1, 1], azimuth uniform.
            let z = 2.0 * mu - 1.0;
            let s = (1.0 - z * z).max(0.0).sqrt();
            let a = std::f64::consts::TAU * azimuth;
            let dir = [s * a.cos(), s * a.sin(), z];
            let per_turn = k / std::f64::consts::TAU;
            field.fx[i] = per_turn * dir[0] / lengths[0];
            field.fy[i] = per_turn * dir[1] / lengths[1];
            field.fz[i] = per_turn * dir[2] / lengths[2];
            field.phase[i] = phase;
            let f = [field.fx[i], field.fy[i], field.fz[i]];
            let per_m = (f[0] * f[0] + f[1] * f[1] + f[2] * f[2]).sqrt();
            field.fastest_per_m = field.fastest_per_m.max(per_m);
        }
        field
    }

    /// The field's standard deviation.
    #[must_use]
    pub fn sigma(&self) -> f64 {
        self.sigma
    }

    /// The field's value at the world point `p_m`, within ±[`CLIP_SIGMAS`] σ.
    #[must_use]
    pub fn at(&self, p_m: [f64; 3]) -> f64 {
        values([Some(self), None], p_m, None)[0]
    }

    /// The field's mean over the footprint about `p_m` ([`FieldFilter::Footprint`]'s
    /// value): each wave at the point times `sinc(π f·a)·sinc(π f·b)`, the mean of a plane
    /// wave over the parallelogram of edges `a`, `b`, exactly. A footprint under
    /// [`POINT_REACH`] of the shortest wavelength gives [`Field::at`], bit for bit; one
    /// that is not finite, the field's mean, 0.
    ///
    /// [`FieldFilter::Footprint`]: irsig_model::texture::FieldFilter::Footprint
    #[must_use]
    pub fn mean_over(&self, p_m: [f64; 3], footprint: &Footprint) -> f64 {
        values([Some(self), None], p_m, Some(footprint))[0]
    }

    /// [`Field::at`] or [`Field::mean_over`] itself, inlined into whichever vector width
    /// [`values`] runs it at.
    #[inline(always)]
    fn value(&self, p_m: [f64; 3], footprint: Option<&Footprint>) -> f64 {
        if self.amplitude == 0.0 {
            return 0.0;
        }
        // Every phase is within `|f|·|p|₁ + 1` turns of 0; the reduction to a turn is exact
        // under 2⁵¹, so a point beyond (2·10¹⁴ m for a 10 cm wave) or not finite reads the
        // field's mean: one test a point, not one a wave.
        let [x, y, z] = p_m;
        let reach = self.fastest_per_m * (x.abs() + y.abs() + z.abs()) + 1.0;
        if reach.is_nan() || reach >= EXACT_TURNS {
            return 0.0;
        }
        // The cosines first, each independent of the others, so that the loop vectorises.
        let mut waves = [0.0; WAVES];
        for (i, w) in waves.iter_mut().enumerate() {
            let turns = self.fx[i].mul_add(
                x,
                self.fy[i].mul_add(y, self.fz[i].mul_add(z, self.phase[i])),
            );
            *w = cos_turns(turns);
        }
        if let Some(cell) = footprint {
            let [a, b] = cell.edges_m;
            let across = |e: [f64; 3]| e[0].abs() + e[1].abs() + e[2].abs();
            let reach = self.fastest_per_m * (across(a) + across(b));
            if !reach.is_finite() {
                return 0.0;
            }
            if reach >= POINT_REACH {
                for (i, w) in waves.iter_mut().enumerate() {
                    let f = [self.fx[i], self.fy[i], self.fz[i]];
                    let dot = |e: [f64; 3]| f[0] * e[0] + f[1] * e[1] + f[2] * e[2];
                    *w *= box_mean(dot(a)) * box_mean(dot(b));
                }
            }
        }
        // Then their sum, in a fixed order: four running sums over every fourth wave, then
        // the pairs of them. A single running sum would chain all the additions one on
        // the last (f64 addition is not associative, so the compiler keeps the order
        // written); four chains are a quarter as long and are one vector of four.
        let mut sums = [0.0; 4];
        for four in waves.chunks_exact(4) {
            for (s, w) in sums.iter_mut().zip(four) {
                *s += w;
            }
        }
        let sum = (sums[0] + sums[1]) + (sums[2] + sums[3]);
        let limit = CLIP_SIGMAS * self.sigma;
        (self.amplitude * sum).clamp(-limit, limit)
    }
}

/// The values at `p_m` of up to two fields (0 for `None`), in one call compiled for the
/// widest vectors this CPU has: pulp's runtime dispatch picks AVX2 on an x86-64 that has
/// it, and the baseline's SSE2 otherwise. The bits do not depend on which: every path does
/// the same IEEE operations in the same order (Rust fuses a multiplication and an addition
/// only where the code asks, by `mul_add`, whose one rounding is the same in an AVX2
/// instruction and in the C library's `fma` the baseline calls), and the test
/// `every_vector_width_gives_the_same_bits` holds the dispatched path to the scalar one.
/// A CPU without FMA (x86-64 before about 2013) gets the same bits from the library's
/// `fma` in software, a call for each of a wave's seven, which is far slower (not measured:
/// no such CPU here). With a footprint, their means over it ([`Field::mean_over`]).
pub(crate) fn values(
    fields: [Option<&Field>; 2],
    p_m: [f64; 3],
    footprint: Option<&Footprint>,
) -> [f64; 2] {
    static ARCH: OnceLock<pulp::Arch> = OnceLock::new();
    ARCH.get_or_init(pulp::Arch::new).dispatch(Values {
        fields,
        p_m,
        footprint,
    })
}

/// [`values`]' work, for pulp to compile once per vector width.
struct Values<'a> {
    fields: [Option<&'a Field>; 2],
    p_m: [f64; 3],
    footprint: Option<&'a Footprint>,
}

impl pulp::WithSimd for Values<'_> {
    type Output = [f64; 2];

    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _: S) -> [f64; 2] {
        let [a, b] = self.fields;
        [
            a.map_or(0.0, |f| f.value(self.p_m, self.footprint)),
            b.map_or(0.0, |f| f.value(self.p_m, self.footprint)),
        ]
    }
}

/// Phases are reduced to a turn exactly below this many turns (the 1.5·2⁵² rounding).
const EXACT_TURNS: f64 = 2_251_799_813_685_248.0; // 2⁵¹

/// The minimax odd polynomial of degree 7 for `sin y` on `[−π/2, π/2]`, `y·Σ c_k y²ᵏ`
/// (Remez exchange in 40 digits): its error equioscillates at 5.9·10⁻⁷, six times under the
/// Taylor series to `y⁹`, which takes one more term.
const SIN_MINIMAX: [f64; 4] = [
    0.999_996_615_908_008_3,
    -0.166_648_283_819_041_9,
    0.008_306_325_227_265_992,
    -0.000_183_636_539_797_233_8,
];

/// The bound on [`cos_turns`]' error, a wave's amplitude: the polynomial's 5.9·10⁻⁷ and
/// the arithmetic's rounding.
#[cfg(test)]
pub(crate) const COS_ERROR: f64 = 6.0e-7;

/// `cos(2π t)` by arithmetic alone, so that a loop of them vectorises: `t` reduced to
/// `a = |t − round(t)|` in [0, ½] (rounding by the 1.5·2⁵² trick, exact for
/// `|t| <` [`EXACT_TURNS`]; the caller keeps `t` there), then `cos 2πa = sin y`,
/// `y = 2π(¼ − a)` in [−π/2, π/2], by [`SIN_MINIMAX`]. Its error, under [`COS_ERROR`] =
/// 6·10⁻⁷ of a wave's amplitude, is under 10⁻⁵ σ for a field's 32 waves together: far
/// below any texture's σ and its sampling error (the statistics rest on the waves, not on
/// the last digits). Every multiplication that feeds an addition is one fused
/// multiply-add (`mul_add`, one rounding on every CPU, an instruction wherever AVX2 is),
/// which with the degree-7 polynomial halves a wave's operations against the Taylor series
/// to `y⁹` written as products and sums (BENCHMARKS.md, "texture: the point field within
/// the floor").
#[inline(always)]
pub(crate) fn cos_turns(t: f64) -> f64 {
    const ROUND: f64 = 6_755_399_441_055_744.0;
    let a = (t - ((t + ROUND) - ROUND)).abs();
    let y = (-std::f64::consts::TAU).mul_add(a, std::f64::consts::FRAC_PI_2);
    let y2 = y * y;
    let [c0, c1, c2, c3] = SIN_MINIMAX;
    y * c3.mul_add(y2, c2).mul_add(y2, c1).mul_add(y2, c0)
}

/// The mean of `cos 2π(t + s·x)` over `s` in `[−½, ½]`, as a fraction of `cos 2πt`:
/// `sinc(πx) = sin(πx)/(πx)`, by arithmetic alone like [`cos_turns`]. Under half a turn
/// (`y = πx` within ±π/2) its Taylor series to `y¹⁰`, whose truncation is below
/// `(π/2)¹²/13!` = 4·10⁻⁸; beyond, `sin(πx) = cos 2π(x/2 − ¼)` over `πx`, within
/// 6·10⁻⁷/(π/2) = 3.8·10⁻⁷. Both are computed and one kept, so that a loop of them
/// vectorises.
#[inline(always)]
pub(crate) fn box_mean(x: f64) -> f64 {
    let y = std::f64::consts::PI * x;
    let y2 = y * y;
    let series = (-1.0 / 39_916_800.0_f64)
        .mul_add(y2, 1.0 / 362_880.0)
        .mul_add(y2, -1.0 / 5040.0)
        .mul_add(y2, 1.0 / 120.0)
        .mul_add(y2, -1.0 / 6.0)
        .mul_add(y2, 1.0);
    let ratio = cos_turns(0.5 * x - 0.25) / y;
    if x.abs() < 0.5 { series } else { ratio }
}

#[cfg(test)]
mod tests {
    use super::*;
    use irsig_model::texture::{CorrelationLength, FieldSpectrum};

    #[test]
    fn the_arithmetic_cosine_is_the_cosine() {
        let mut worst: f64 = 0.0;
        for i in -200_000..=200_000 {
            let t = f64::from(i) * 1.37e-4 + 0.1234;
            worst = worst.max((cos_turns(t) - (std::f64::consts::TAU * t).cos()).abs());
        }
        // The minimax polynomial's equioscillation, 5.9·10⁻⁷, is met: the bound is not
        // loose by more than the rounding.
        assert!(worst < COS_ERROR, "{worst}");
        assert!(worst > 5.5e-7, "{worst}");
        // Extremes: whole, half and quarter turns (y = π/2, −π/2, 0), far from the origin.
        assert!((cos_turns(0.0) - 1.0).abs() < COS_ERROR);
        assert!((cos_turns(0.5) + 1.0).abs() < COS_ERROR);
        assert!(cos_turns(-1e9 - 0.25).abs() < COS_ERROR);
        assert!((cos_turns(1e14 + 0.5) + 1.0).abs() < COS_ERROR);
    }

    fn spec(sigma: f64) -> RandomField {
        RandomField {
            sigma,
            spectrum: FieldSpectrum::Gaussian {
                correlation_length_m: CorrelationLength::Isotropic(0.5),
            },
        }
    }

    fn spec_gaussian(sigma: f64, length_m: f64) -> RandomField {
        RandomField {
            sigma,
            spectrum: FieldSpectrum::Gaussian {
                correlation_length_m: CorrelationLength::Isotropic(length_m),
            },
        }
    }

    #[test]
    fn a_field_is_its_seed_and_its_position() {
        let a = Field::new(&spec(1.0), 7);
        let b = Field::new(&spec(1.0), 7);
        let c = Field::new(&spec(1.0), 8);
        let p = [1.25, -3.5, 0.0];
        assert_eq!(a.at(p).to_bits(), b.at(p).to_bits());
        assert_ne!(a.at(p).to_bits(), c.at(p).to_bits());
        // σ = 0: nothing anywhere.
        assert!(Field::new(&spec(0.0), 7).at(p).abs() < f64::MIN_POSITIVE);
    }

    #[test]
    fn every_vector_width_gives_the_same_bits() {
        use pulp::WithSimd;
        let t = Field::new(&spec(1.5), 5);
        let e = Field::new(&spec(0.02), 6);
        // A footprint wide enough to filter every wave, and none.
        let cell = Footprint {
            edges_m: [[0.4, 0.1, 0.0], [-0.05, 0.3, 0.2]],
        };
        let at = |p_m, footprint| Values {
            fields: [Some(&t), Some(&e)],
            p_m,
            footprint,
        };
        // Each width this CPU has, called through pulp as `values` calls it.
        let mut widths = vec![("the best", pulp::Arch::new())];
        #[cfg(target_arch = "x86_64")]
        {
            if let Some(v3) = pulp::x86::V3::try_new() {
                widths.push(("AVX2", pulp::Arch::V3(v3)));
            }
            // A machine with AVX2 is checked across widths, not only against itself.
            if std::arch::is_x86_feature_detected!("avx2")
                && std::arch::is_x86_feature_detected!("fma")
            {
                assert!(widths.len() > 1);
            }
        }
        let mut checked = 0;
        for i in -300..300 {
            // From the origin out to 10⁶ m, and both signs.
            let r = f64::from(i).powi(3) * 3.7e-2 + 0.1;
            let p = [r, -0.61 * r + 2.0, 0.013 * r];
            for footprint in [None, Some(&cell)] {
                let scalar = at(p, footprint).with_simd(pulp::Scalar::new());
                for (name, arch) in &widths {
                    let bits = arch.dispatch(at(p, footprint)).map(f64::to_bits);
                    assert_eq!(bits, scalar.map(f64::to_bits), "{name} {p:?}");
                }
                let dispatched = values([Some(&t), Some(&e)], p, footprint);
                assert_eq!(dispatched.map(f64::to_bits), scalar.map(f64::to_bits));
                let one = footprint.map_or_else(|| t.at(p), |c| t.mean_over(p, c));
                assert_eq!(one.to_bits(), scalar[0].to_bits());
                checked += usize::from(scalar[0] != 0.0);
            }
        }
        assert!(checked > 1000, "{checked}");
    }

    #[test]
    fn the_arithmetic_box_mean_is_the_sinc() {
        let mut worst: f64 = 0.0;
        for i in -40_000..=40_000 {
            let x = f64::from(i) * 2.37e-4 + 1e-9;
            let y = std::f64::consts::PI * x;
            worst = worst.max((box_mean(x) - y.sin() / y).abs());
        }
        // The series' bound under half a turn, the cosine's over π/2 beyond.
        assert!(worst < COS_ERROR / std::f64::consts::FRAC_PI_2, "{worst}");
        assert!((box_mean(0.0) - 1.0).abs() < f64::EPSILON);
        assert!(box_mean(1.0).abs() < COS_ERROR);
        assert!(box_mean(-3.0).abs() < COS_ERROR);
    }

    #[test]
    fn a_footprint_mean_is_the_quadrature_of_the_field_over_it() {
        // The field's mean over a tilted parallelogram, by the midpoint rule on 400 × 400
        // points of `at` (its error for the fastest wave, 2.6 cycles over an edge, is
        // about (2π·2.6/400)²/24 = 7·10⁻⁵ of a wave), against the sinc of each wave.
        let f = Field::new(&spec_gaussian(1.0, 0.3), 12);
        let cell = Footprint {
            edges_m: [[0.9, 0.3, 0.1], [-0.2, 0.5, 0.25]],
        };
        let [a, b] = cell.edges_m;
        let n = 400;
        for centre in [[0.0, 0.0, 0.0], [37.5, -12.25, 3.0], [1e5, 2e5, -40.0]] {
            let mut sum = 0.0;
            for i in 0..n {
                for j in 0..n {
                    let s = (f64::from(i) + 0.5) / f64::from(n) - 0.5;
                    let t = (f64::from(j) + 0.5) / f64::from(n) - 0.5;
                    let p = [0, 1, 2].map(|k| centre[k] + s * a[k] + t * b[k]);
                    sum += f.at(p);
                }
            }
            let quadrature = sum / f64::from(n * n);
            let filtered = f.mean_over(centre, &cell);
            assert!(
                (filtered - quadrature).abs() < 2e-4,
                "{filtered} {quadrature}"
            );
            // The filter does something here: the mean is not the point's value.
            assert!((filtered - f.at(centre)).abs() > 1e-2, "{filtered}");
        }
    }

    #[test]
    fn a_footprint_far_below_the_waves_is_the_point_and_an_endless_one_the_mean() {
        let f = Field::new(&spec(2.0), 4);
        let p = [3.0, -1.0, 0.5];
        let tiny = Footprint {
            edges_m: [[1e-7, 0.0, 0.0], [0.0, 1e-7, 0.0]],
        };
        assert_eq!(f.mean_over(p, &tiny).to_bits(), f.at(p).to_bits());
        let grazing = Footprint {
            edges_m: [[f64::INFINITY, 0.0, 0.0], [0.0, 0.1, 0.0]],
        };
        assert!(f.mean_over(p, &grazing).abs() < f64::MIN_POSITIVE);
        assert!(grazing.width_m().is_infinite());
        let nan = Footprint {
            edges_m: [[f64::NAN, 0.0, 0.0], [0.0, 0.1, 0.0]],
        };
        assert!(f.mean_over(p, &nan).abs() < f64::MIN_POSITIVE);
        assert!(nan.width_m().is_infinite());
        assert!((tiny.width_m() - 1e-7).abs() < 1e-22);
    }

    #[test]
    fn the_variance_over_space_is_sigma_squared() {
        // The spatial mean of cos² over a region many wavelengths wide is ½, so the
        // variance of σ√(2/N)Σcos is σ² for one realisation, up to the cross terms'
        // residue over a finite region.
        let f = Field::new(&spec(2.0), 3);
        let n = 400;
        let (mut sum, mut sum2) = (0.0, 0.0);
        for i in 0..n {
            for j in 0..n {
                let v = f.at([f64::from(i) * 0.25, f64::from(j) * 0.25, 0.0]);
                sum += v;
                sum2 += v * v;
            }
        }
        let count = f64::from(n * n);
        let var = sum2 / count - (sum / count).powi(2);
        assert!((var.sqrt() - 2.0).abs() < 0.1, "{}", var.sqrt());
    }
}
