//! A band atmosphere from a spectral one: [`collapse`] over `[λ1, λ2]` with a response
//! weight `w(λ)`.
//!
//! τ is the response-weighted mean over wavelength, `∫ w τ dλ / ∫ w dλ`; radiances are the
//! response-weighted integral over wavelength, `∫ w L_λ dλ`, in W m⁻² sr⁻¹. The integrals
//! are the trapezoid rule in wavelength over the grid's points inside the band, closed at
//! each band edge by a point interpolated linearly in the grid's own variable
//! (wavenumber or wavelength) between its two neighbours, with radiances converted to per
//! µm at the grid's points first (`L_λ = L_ν ν² / 10⁴` on a wavenumber grid). That is
//! what `scripts/atmosphere/regen.py` did to make the band built-ins from LOWTRAN7's
//! spectra (read its pitfalls: the band must be closed at exactly 14 µm), so collapsing
//! the spectral built-ins over flat 8–14 µm gives their band tables back
//! (`tests/spectral.rs`).
//!
//! Each integral is a fixed linear combination of the grid's values, so
//! [`BandQuadrature`] computes its coefficients once per band and every spectrum after
//! that costs one short dot product.

use irsig_model::{
    Atmosphere, AtmosphereLevel, SlantTables, SpectralAtmosphere, SpectralAxis, SpectralGrid,
};

use crate::error::{AtmosphereError, AtmosphereErrorKind};

/// The band integrals over one band as coefficients on the grid: `∫ w L_λ dλ = Σ a_i L_i`
/// and `∫ w τ dλ / ∫ w dλ = Σ b_i τ_i` for the grid points `i` from `start`.
#[derive(Debug, Clone, PartialEq)]
pub struct BandQuadrature {
    start: usize,
    radiance: Vec<f64>,
    transmission: Vec<f64>,
    weight_integral_um: f64,
}

/// A grid point as an integration node: its wavelength (µm), and the grid indices and
/// coefficients that give the value there.
struct Node {
    wavelength_um: f64,
    parts: [(usize, f64); 2],
}

impl BandQuadrature {
    /// The coefficients for the band `[lo_um, hi_um]` with response `weight(λ in µm)`.
    ///
    /// # Errors
    /// A band that is not `0 < lo < hi`, one that reaches outside the grid, a grid of
    /// fewer than two points, a weight that is negative or not finite at a node, or zero
    /// at every node.
    pub fn new(
        grid: &SpectralGrid,
        lo_um: f64,
        hi_um: f64,
        weight: impl Fn(f64) -> f64,
    ) -> Result<Self, AtmosphereError> {
        let band_error =
            |message: String| -> AtmosphereError { AtmosphereErrorKind::Band(message).into() };
        if !(lo_um.is_finite() && hi_um.is_finite() && lo_um > 0.0 && hi_um > lo_um) {
            return Err(band_error(format!(
                "the band [{lo_um}, {hi_um}] um must have 0 < lower < upper"
            )));
        }
        let g = &grid.points;
        let n = g.len();
        if n < 2 {
            return Err(band_error(
                "the spectral grid has fewer than 2 points".into(),
            ));
        }
        // The grid's variable of a wavelength, and a grid point's wavelength.
        type Map = fn(f64) -> f64;
        let (to_grid, per_um): (Map, Map) = match grid.axis {
            SpectralAxis::WavenumberPerCm => (|l| 1e4 / l, |nu| nu * nu / 1e4),
            SpectralAxis::WavelengthUm => (|l| l, |_| 1.0),
        };
        let wavelength = |i: usize| match grid.axis {
            SpectralAxis::WavenumberPerCm => 1e4 / g[i],
            SpectralAxis::WavelengthUm => g[i],
        };
        let (lam_min, lam_max) = {
            let (a, b) = (wavelength(0), wavelength(n - 1));
            (a.min(b), a.max(b))
        };
        let slack = 1e-9 * lam_max;
        if lo_um < lam_min - slack || hi_um > lam_max + slack {
            return Err(band_error(format!(
                "the band {lo_um}-{hi_um} um reaches outside the atmosphere's spectral range {lam_min:.6}-{lam_max:.6} um"
            )));
        }
        // A value at wavelength `l` (an edge): linear in the grid variable between the two
        // grid points around it, or the grid point itself.
        let edge = |l: f64| -> Node {
            let x = to_grid(l);
            let k = g.partition_point(|&p| p < x);
            if k < n && (g[k] - x).abs() <= 1e-12 * g[k].abs().max(1.0) {
                return Node {
                    wavelength_um: l,
                    parts: [(k, per_um(g[k])), (k, 0.0)],
                };
            }
            let (a, b) = (
                k.saturating_sub(1).min(n - 2),
                k.saturating_sub(1).min(n - 2) + 1,
            );
            let t = ((x - g[a]) / (g[b] - g[a])).clamp(0.0, 1.0);
            Node {
                wavelength_um: l,
                parts: [(a, (1.0 - t) * per_um(g[a])), (b, t * per_um(g[b]))],
            }
        };
        let mut nodes = vec![edge(lo_um)];
        let mut inner: Vec<Node> = (0..n)
            .filter_map(|i| {
                let l = wavelength(i);
                let tol = 1e-12 * l;
                (l > lo_um + tol && l < hi_um - tol).then(|| Node {
                    wavelength_um: l,
                    parts: [(i, per_um(g[i])), (i, 0.0)],
                })
            })
            .collect();
        inner.sort_by(|a, b| a.wavelength_um.total_cmp(&b.wavelength_um));
        nodes.extend(inner);
        nodes.push(edge(hi_um));
        let weights: Vec<f64> = nodes.iter().map(|nd| weight(nd.wavelength_um)).collect();
        if let Some(k) = weights.iter().position(|w| !(w.is_finite() && *w >= 0.0)) {
            return Err(band_error(format!(
                "the response at {} um is {}: it must be finite and not negative",
                nodes[k].wavelength_um, weights[k]
            )));
        }
        // Trapezoid: node k gets half of each neighbouring interval.
        let start = nodes
            .iter()
            .flat_map(|nd| nd.parts.iter().map(|p| p.0))
            .min()
            .unwrap_or(0);
        let end = nodes
            .iter()
            .flat_map(|nd| nd.parts.iter().map(|p| p.0))
            .max()
            .unwrap_or(0);
        let mut radiance = vec![0.0; end - start + 1];
        let mut mean = vec![0.0; end - start + 1];
        let mut weight_integral_um = 0.0;
        for k in 0..nodes.len() {
            let left = if k > 0 {
                nodes[k].wavelength_um - nodes[k - 1].wavelength_um
            } else {
                0.0
            };
            let right = if k + 1 < nodes.len() {
                nodes[k + 1].wavelength_um - nodes[k].wavelength_um
            } else {
                0.0
            };
            let dl = 0.5 * (left + right) * weights[k];
            weight_integral_um += dl;
            for &(i, c) in &nodes[k].parts {
                radiance[i - start] += dl * c;
                // τ is not a spectral density: the same interpolation without the unit
                // conversion (c / per_um at that point).
                let conv = per_um(g[i]);
                mean[i - start] += dl * c / conv;
            }
        }
        if weight_integral_um <= 0.0 {
            return Err(band_error(format!(
                "the response is 0 everywhere in {lo_um}-{hi_um} um"
            )));
        }
        for m in &mut mean {
            *m /= weight_integral_um;
        }
        Ok(Self {
            start,
            radiance,
            transmission: mean,
            weight_integral_um,
        })
    }

    /// `∫ w(λ) dλ` over the band, µm (6 for a flat 8–14 µm band).
    #[must_use]
    pub fn weight_integral_um(&self) -> f64 {
        self.weight_integral_um
    }

    fn dot(c: &[f64], start: usize, spectrum: &[f32]) -> f64 {
        c.iter()
            .zip(&spectrum[start..start + c.len()])
            .map(|(a, &y)| a * f64::from(y))
            .sum()
    }

    /// The band radiance `∫ w L_λ dλ`, W m⁻² sr⁻¹, of a spectral radiance on the grid
    /// (W m⁻² sr⁻¹ per grid unit).
    ///
    /// # Panics
    /// When `spectrum` is shorter than the grid this was made for.
    #[must_use]
    pub fn radiance(&self, spectrum: &[f32]) -> f64 {
        Self::dot(&self.radiance, self.start, spectrum)
    }

    /// The band integral `∫ w y_λ dλ` of any spectral density `y` on the grid (W m⁻² sr⁻¹
    /// or W m⁻² per grid unit; `value(i)` its value at grid point `i`), by the rule of
    /// [`BandQuadrature::radiance`], in double precision: for products of spectra such as
    /// `E_toa τ_sun`.
    #[must_use]
    pub fn integral(&self, value: impl Fn(usize) -> f64) -> f64 {
        self.radiance
            .iter()
            .enumerate()
            .map(|(k, a)| a * value(self.start + k))
            .sum()
    }

    /// The band-mean transmittance `∫ w τ dλ / ∫ w dλ` of a spectral transmittance.
    ///
    /// # Panics
    /// When `spectrum` is shorter than the grid this was made for.
    #[must_use]
    pub fn transmission(&self, spectrum: &[f32]) -> f64 {
        Self::dot(&self.transmission, self.start, spectrum).clamp(0.0, 1.0)
    }
}

/// How many sub-bands a spectral rendering sums over.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum SubBandCount {
    /// `K` sub-bands (1: the band model over a collapsed atmosphere).
    Count(usize),
    /// One sub-band per interval of the atmosphere's grid inside the band.
    Full,
}

impl SubBandCount {
    /// The band model: one sub-band.
    pub const BAND: Self = Self::Count(1);

    /// Whether this is the band model.
    #[must_use]
    pub fn is_band(self) -> bool {
        self == Self::BAND
    }
}

impl std::fmt::Display for SubBandCount {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Count(k) => write!(f, "{k}"),
            Self::Full => f.write_str("full"),
        }
    }
}

impl std::str::FromStr for SubBandCount {
    type Err = String;

    /// `full`, or a whole number from 1 up.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        if s == "full" {
            return Ok(Self::Full);
        }
        match s.parse::<usize>() {
            Ok(k) if k >= 1 => Ok(Self::Count(k)),
            _ => Err(format!(
                "expected a number of sub-bands (1 or more; 1 is the band model) or `full`, found `{s}`"
            )),
        }
    }
}

/// The edges (µm, increasing, `count + 1` of them from `lo_um` to `hi_um`) of the
/// sub-bands of `[lo_um, hi_um]` on `grid`.
///
/// `Full` gives one sub-band per stretch between neighbouring grid points (the band's ends
/// closing the first and last). `Count(K)` gives K sub-bands that each hold about an equal
/// share of `share(a, b)`, the caller's in-band radiance between `a` and `b` µm (the
/// response-weighted blackbody radiance at a reference temperature): every inner edge is
/// the grid point nearest its equal share, so that the sub-bands' trapezoid integrals add
/// up to the whole band's, and each sub-band spans at least one grid interval. Bright
/// parts of the band get narrow sub-bands, where an error in τ costs the most radiance.
///
/// # Errors
/// As [`BandQuadrature::new`] for the band; a count of 0, or more sub-bands than the grid
/// has intervals in the band; a share that is negative or not finite, or 0 over the band.
pub fn sub_band_edges(
    grid: &SpectralGrid,
    lo_um: f64,
    hi_um: f64,
    count: SubBandCount,
    share: impl Fn(f64, f64) -> f64,
) -> Result<Vec<f64>, AtmosphereError> {
    // Checks the band against the grid.
    BandQuadrature::new(grid, lo_um, hi_um, |_| 1.0)?;
    let band_error =
        |message: String| -> AtmosphereError { AtmosphereErrorKind::Band(message).into() };
    let mut nodes: Vec<f64> = grid
        .points
        .iter()
        .map(|&p| match grid.axis {
            SpectralAxis::WavenumberPerCm => 1e4 / p,
            SpectralAxis::WavelengthUm => p,
        })
        .filter(|&l| l > lo_um * (1.0 + 1e-12) && l < hi_um * (1.0 - 1e-12))
        .collect();
    nodes.sort_by(f64::total_cmp);
    nodes.insert(0, lo_um);
    nodes.push(hi_um);
    let intervals = nodes.len() - 1;
    let k = match count {
        SubBandCount::Full => return Ok(nodes),
        SubBandCount::Count(0) => return Err(band_error("0 sub-bands: expected 1 or more".into())),
        SubBandCount::Count(k) if k > intervals => {
            return Err(band_error(format!(
                "{k} sub-bands: the atmosphere's grid has {intervals} intervals in {lo_um}-{hi_um} um; ask for at most {intervals}, or `full`"
            )));
        }
        SubBandCount::Count(k) => k,
    };
    // The cumulative share at every node.
    let mut cumulative = vec![0.0; nodes.len()];
    for i in 0..intervals {
        let s = share(nodes[i], nodes[i + 1]);
        if !(s.is_finite() && s >= 0.0) {
            return Err(band_error(format!(
                "the in-band radiance between {} and {} um is {s}: expected a finite value of 0 or more",
                nodes[i],
                nodes[i + 1]
            )));
        }
        cumulative[i + 1] = cumulative[i] + s;
    }
    let total = cumulative[intervals];
    if total <= 0.0 {
        return Err(band_error(format!(
            "the in-band radiance is 0 over {lo_um}-{hi_um} um: no share to divide"
        )));
    }
    let mut picked = vec![0_usize];
    for j in 1..k {
        let target = total * j as f64 / k as f64;
        let nearest = cumulative.partition_point(|&c| c < target);
        let nearest = if nearest > 0
            && (nearest == cumulative.len()
                || target - cumulative[nearest - 1] < cumulative[nearest] - target)
        {
            nearest - 1
        } else {
            nearest
        };
        // Strictly after the previous edge, and leaving one interval for each sub-band
        // still to come.
        let last = *picked.last().unwrap_or(&0);
        picked.push(nearest.max(last + 1).min(intervals - (k - j)));
    }
    picked.push(intervals);
    Ok(picked.into_iter().map(|i| nodes[i]).collect())
}

/// Least-squares `r ≈ a1 + a2 sec θ + a3 sec² θ` (thesis eq. 10) by Householder-free
/// modified Gram–Schmidt on the three columns, which is accurate enough for the eight
/// decimals the `.cor` prints.
fn fit_correction(nadir_deg: &[f64], ratio: &[f64]) -> Option<[f64; 3]> {
    let m = nadir_deg.len();
    let sec: Vec<f64> = nadir_deg
        .iter()
        .map(|a| 1.0 / a.to_radians().cos())
        .collect();
    let mut q: Vec<Vec<f64>> = vec![
        vec![1.0; m],
        sec.clone(),
        sec.iter().map(|s| s * s).collect(),
    ];
    let mut r = [[0.0; 3]; 3];
    for j in 0..3 {
        for k in 0..j {
            let d: f64 = q[k].iter().zip(&q[j]).map(|(a, b)| a * b).sum();
            r[k][j] = d;
            let qk = q[k].clone();
            for (x, y) in q[j].iter_mut().zip(&qk) {
                *x -= d * y;
            }
        }
        let norm = q[j].iter().map(|x| x * x).sum::<f64>().sqrt();
        if norm <= 1e-12 {
            return None;
        }
        r[j][j] = norm;
        for x in &mut q[j] {
            *x /= norm;
        }
    }
    let qtb: Vec<f64> = (0..3)
        .map(|k| q[k].iter().zip(ratio).map(|(a, b)| a * b).sum())
        .collect();
    let mut a = [0.0; 3];
    for j in (0..3).rev() {
        let s: f64 = (j + 1..3).map(|k| r[j][k] * a[k]).sum();
        a[j] = (qtb[j] - s) / r[j][j];
    }
    Some(a)
}

fn spectra(values: &[f32], n: usize) -> impl Iterator<Item = &[f32]> {
    values.chunks_exact(n)
}

/// The band atmosphere of `spectral` over `[lo_um, hi_um]` with response `weight(λ in
/// µm)`: every table every model reads (profile, `.cor`, ground sky and its hemispheric
/// value, slant tables), usable by [`crate::AtmosphereModel::new`] with any model. The
/// `.rtt` (`band_radiance`) is left empty: it is the band's Planck integral, which the
/// caller's radiometry computes. `band_um` is the band; `source` says it was collapsed.
///
/// # Errors
/// As [`BandQuadrature::new`]; an invalid spectral atmosphere; a `.cor` fit whose paths
/// have no transmittance at nadir.
pub fn collapse(
    spectral: &SpectralAtmosphere,
    lo_um: f64,
    hi_um: f64,
    weight: impl Fn(f64) -> f64,
) -> Result<Atmosphere, AtmosphereError> {
    Collapser::new(spectral)?.collapse(lo_um, hi_um, weight)
}

/// A spectral atmosphere checked once, for [`collapse`]s over many bands: the sub-bands of
/// a trace (a hundred or more for the full grid) would otherwise check every table of it
/// twice each.
#[derive(Debug, Clone, Copy)]
pub struct Collapser<'a>(&'a SpectralAtmosphere);

impl<'a> Collapser<'a> {
    /// # Errors
    /// An invalid spectral atmosphere.
    pub fn new(spectral: &'a SpectralAtmosphere) -> Result<Self, AtmosphereError> {
        spectral.validate()?;
        Ok(Self(spectral))
    }

    /// The spectral atmosphere it collapses.
    #[must_use]
    pub fn spectral(&self) -> &'a SpectralAtmosphere {
        self.0
    }

    /// [`collapse`] over `[lo_um, hi_um]` with response `weight(λ in µm)`.
    ///
    /// # Errors
    /// As [`collapse`].
    pub fn collapse(
        &self,
        lo_um: f64,
        hi_um: f64,
        weight: impl Fn(f64) -> f64,
    ) -> Result<Atmosphere, AtmosphereError> {
        collapse_valid(self.0, lo_um, hi_um, weight)
    }

    /// The transmittances alone of [`Collapser::collapse`] over `[lo_um, hi_um]` with
    /// `weight`, each the same number: for a collapse whose τ is weighted otherwise than
    /// its radiances (sub-bands weigh τ by the blackbody too), without collapsing every
    /// radiance a second time.
    ///
    /// # Errors
    /// As [`collapse`].
    pub fn transmissions(
        &self,
        lo_um: f64,
        hi_um: f64,
        weight: impl Fn(f64) -> f64,
    ) -> Result<Transmissions, AtmosphereError> {
        transmissions_valid(self.0, lo_um, hi_um, weight)
    }
}

fn collapse_valid(
    spectral: &SpectralAtmosphere,
    lo_um: f64,
    hi_um: f64,
    weight: impl Fn(f64) -> f64,
) -> Result<Atmosphere, AtmosphereError> {
    let q = BandQuadrature::new(&spectral.grid, lo_um, hi_um, weight)?;
    let n = spectral.grid.points.len();
    let levels = spectral
        .levels
        .iter()
        .zip(spectra(&spectral.level_transmission, n))
        .zip(spectra(&spectral.level_path_radiance_w_m2_sr_per_unit, n))
        .map(|((l, tau), lu)| AtmosphereLevel {
            altitude_asl_m: l.altitude_asl_m,
            temperature_k: l.temperature_k,
            altitude_m: l.altitude_m,
            transmission: q.transmission(tau),
            path_radiance_w_m2_sr: q.radiance(lu),
        })
        .collect();
    let transmission_correction = correction(spectral, &q, lo_um, hi_um)?;
    let sky = spectral
        .sky_zenith_deg
        .iter()
        .zip(spectra(&spectral.sky_radiance_w_m2_sr_per_unit, n))
        .map(|(&z, s)| (z, q.radiance(s)))
        .collect();
    let slant = spectral.slant.as_ref().map(|s| {
        let grid =
            |values: &[f32], rows: usize, f: &dyn Fn(&[f32]) -> f64| grid(values, n, rows, f);
        SlantTables {
            altitude_m: s.altitude_m.clone(),
            nadir_deg: s.nadir_deg.clone(),
            ground_m: s.ground_m,
            transmission: grid(&s.transmission, s.altitude_m.len(), &|x| q.transmission(x)),
            path_radiance_w_m2_sr: grid(
                &s.path_radiance_w_m2_sr_per_unit,
                s.altitude_m.len(),
                &|x| q.radiance(x),
            ),
            sky_altitude_m: s.sky_altitude_m.clone(),
            sky_zenith_deg: s.sky_zenith_deg.clone(),
            sky_radiance_w_m2_sr: grid(
                &s.sky_radiance_w_m2_sr_per_unit,
                s.sky_altitude_m.len(),
                &|x| q.radiance(x),
            ),
            interpolation_residual: s.interpolation_residual,
        }
    });
    let atmosphere = Atmosphere {
        name: spectral.name.clone(),
        source: format!(
            "{}; collapsed from its spectral form over {lo_um}-{hi_um} um",
            spectral.source
        ),
        band_um: [lo_um, hi_um],
        levels,
        transmission_correction,
        transmission_correction_altitude_m: spectral
            .transmission_correction
            .as_ref()
            .map(|c| c.altitude_m),
        sky,
        sky_hemispheric_w_m2_sr: spectral
            .sky_hemispheric_w_m2_sr_per_unit
            .as_ref()
            .map(|h| q.radiance(h)),
        radiosonde: spectral.radiosonde.clone(),
        band_radiance: Vec::new(),
        slant,
    };
    atmosphere.validate()?;
    Ok(atmosphere)
}

/// The `.cor` fit of `spectral` collapsed with `q` over `[lo_um, hi_um]`.
fn correction(
    spectral: &SpectralAtmosphere,
    q: &BandQuadrature,
    lo_um: f64,
    hi_um: f64,
) -> Result<Option<[f64; 3]>, AtmosphereError> {
    let Some(c) = &spectral.transmission_correction else {
        return Ok(None);
    };
    let n = spectral.grid.points.len();
    let tau: Vec<f64> = spectra(&c.transmission, n)
        .map(|s| q.transmission(s))
        .collect();
    if tau.iter().all(|&t| t <= 0.0) {
        // Opaque at every angle (the 4.3 µm CO2 band over the 1 km .cor paths, a
        // sub-band of 3-5 µm): τ(θ) = τ(0) = 0 whatever the polynomial, and the
        // identity says so. (Refused, this sub-band stopped every spectral trace
        // of 3-5 µm through a plan's atmosphere.)
        Ok(Some([1.0, 0.0, 0.0]))
    } else if tau[0] <= 0.0 {
        Err(AtmosphereErrorKind::Band(format!(
            "the .cor paths have no transmittance at nadir in {lo_um}-{hi_um} um"
        ))
        .into())
    } else {
        let ratio: Vec<f64> = tau.iter().map(|t| t / tau[0]).collect();
        Ok(fit_correction(&c.nadir_deg, &ratio))
    }
}

/// A table of `rows` rows of spectra (`n` values each) collapsed by `f`.
fn grid(values: &[f32], n: usize, rows: usize, f: &dyn Fn(&[f32]) -> f64) -> Vec<Vec<f64>> {
    let all: Vec<f64> = spectra(values, n).map(f).collect();
    all.chunks(all.len() / rows.max(1))
        .map(<[f64]>::to_vec)
        .collect()
}

/// The transmittances of a spectral atmosphere collapsed over a band, alone: the
/// profile's levels', the `.cor` fit's and the slant tables' ([`Collapser::transmissions`]).
#[derive(Debug, Clone, PartialEq)]
pub struct Transmissions {
    /// Each level's, in the order of the atmosphere's levels.
    pub levels: Vec<f64>,
    /// The `.cor` fit (`None` without `.cor` paths).
    pub correction: Option<[f64; 3]>,
    /// The slant table's, `[altitude][nadir]` (`None` without slant tables).
    pub slant: Option<Vec<Vec<f64>>>,
}

impl Transmissions {
    /// Puts these transmittances into `atmosphere`, a collapse of the same spectral
    /// atmosphere over the same band with another weight.
    pub fn apply_to(&self, atmosphere: &mut Atmosphere) {
        for (level, &t) in atmosphere.levels.iter_mut().zip(&self.levels) {
            level.transmission = t;
        }
        atmosphere.transmission_correction = self.correction;
        if let (Some(slant), Some(t)) = (atmosphere.slant.as_mut(), self.slant.as_ref()) {
            slant.transmission.clone_from(t);
        }
    }
}

fn transmissions_valid(
    spectral: &SpectralAtmosphere,
    lo_um: f64,
    hi_um: f64,
    weight: impl Fn(f64) -> f64,
) -> Result<Transmissions, AtmosphereError> {
    let q = BandQuadrature::new(&spectral.grid, lo_um, hi_um, weight)?;
    let n = spectral.grid.points.len();
    let levels = spectral
        .levels
        .iter()
        .zip(spectra(&spectral.level_transmission, n))
        .map(|(_, tau)| q.transmission(tau))
        .collect();
    let correction = correction(spectral, &q, lo_um, hi_um)?;
    let slant = spectral.slant.as_ref().map(|s| {
        grid(&s.transmission, n, s.altitude_m.len(), &|x| {
            q.transmission(x)
        })
    });
    Ok(Transmissions {
        levels,
        correction,
        slant,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn transmissions_are_those_of_the_collapse_with_the_same_weight() {
        let spectral = crate::builtin_spectral("us-std-1976").unwrap();
        let collapser = Collapser::new(&spectral).unwrap();
        let flat = |_: f64| 1.0;
        let tilted = |l: f64| l * l;
        for (lo, hi) in [(8.0, 14.0), (9.5, 9.7)] {
            let whole = collapser.collapse(lo, hi, tilted).unwrap();
            let alone = collapser.transmissions(lo, hi, tilted).unwrap();
            let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            let levels: Vec<f64> = whole.levels.iter().map(|l| l.transmission).collect();
            assert_eq!(bits(&alone.levels), bits(&levels));
            assert_eq!(alone.correction, whole.transmission_correction);
            let slant = whole.slant.as_ref().unwrap();
            assert_eq!(alone.slant.as_ref(), Some(&slant.transmission));
            // Put into the collapse with another weight, they are all that changes.
            let mut other = collapser.collapse(lo, hi, flat).unwrap();
            assert_ne!(
                other.levels[0].transmission.to_bits(),
                whole.levels[0].transmission.to_bits()
            );
            let radiance = other.levels[0].path_radiance_w_m2_sr;
            alone.apply_to(&mut other);
            let levels: Vec<f64> = other.levels.iter().map(|l| l.transmission).collect();
            assert_eq!(bits(&levels), bits(&alone.levels));
            assert_eq!(other.transmission_correction, alone.correction);
            assert_eq!(
                other.slant.as_ref().map(|s| &s.transmission),
                alone.slant.as_ref()
            );
            assert_eq!(
                other.levels[0].path_radiance_w_m2_sr.to_bits(),
                radiance.to_bits()
            );
        }
    }

    fn grid(axis: SpectralAxis, points: Vec<f64>) -> SpectralGrid {
        SpectralGrid { axis, points }
    }

    #[test]
    fn a_flat_band_on_a_wavelength_grid_integrates_linear_functions_exactly() {
        let g = grid(
            SpectralAxis::WavelengthUm,
            (0..=14).map(|i| 7.5 + 0.5 * f64::from(i)).collect(),
        );
        let q = BandQuadrature::new(&g, 8.0, 14.0, |_| 1.0).unwrap();
        assert!((q.weight_integral_um() - 6.0).abs() < 1e-12);
        // L(λ) = λ W m-2 sr-1 um-1: ∫ λ dλ over 8-14 = (196 - 64) / 2 = 66.
        let l: Vec<f32> = g.points.iter().map(|&x| x as f32).collect();
        assert!((q.radiance(&l) - 66.0).abs() < 1e-9);
        // A constant τ is its own mean.
        assert!((q.transmission(&[0.25_f32; 15]) - 0.25).abs() < 1e-12);
        // Edges between grid points: 8.2-13.7 um of L = 1 is 5.5.
        let q = BandQuadrature::new(&g, 8.2, 13.7, |_| 1.0).unwrap();
        assert!((q.radiance(&[1.0_f32; 15]) - 5.5).abs() < 1e-12);
    }

    #[test]
    fn a_wavenumber_grid_converts_radiance_to_per_micrometre() {
        // A flat L_ν = 1 per cm-1 from 1000 to 1250 cm-1 (8-10 um) integrates to the
        // wavenumber span 250 whichever variable the trapezoid runs in, to the trapezoid's
        // error in λ.
        let g = grid(
            SpectralAxis::WavenumberPerCm,
            (0..=50).map(|i| 1000.0 + 5.0 * f64::from(i)).collect(),
        );
        let q = BandQuadrature::new(&g, 8.0, 10.0, |_| 1.0).unwrap();
        let l = vec![1.0_f32; 51];
        assert!(
            (q.radiance(&l) / 250.0 - 1.0).abs() < 1e-4,
            "{}",
            q.radiance(&l)
        );
    }

    #[test]
    fn bands_outside_the_grid_and_bad_weights_are_refused() {
        let g = grid(SpectralAxis::WavelengthUm, vec![8.0, 10.0, 14.0]);
        assert!(BandQuadrature::new(&g, 7.0, 14.0, |_| 1.0).is_err());
        assert!(BandQuadrature::new(&g, 8.0, 14.5, |_| 1.0).is_err());
        assert!(BandQuadrature::new(&g, 8.0, 14.0, |_| 0.0).is_err());
        assert!(BandQuadrature::new(&g, 8.0, 14.0, |_| f64::NAN).is_err());
        assert!(BandQuadrature::new(&g, 10.0, 9.0, |_| 1.0).is_err());
        let e = BandQuadrature::new(&g, 7.0, 14.0, |_| 1.0)
            .unwrap_err()
            .to_string();
        assert!(e.contains("outside"), "{e}");
    }

    #[test]
    fn sub_bands_hold_equal_shares_on_grid_points() {
        // 8-14 um every 0.5 um; a share proportional to the width: equal shares are equal
        // widths, on grid points.
        let g = grid(
            SpectralAxis::WavelengthUm,
            (0..=14).map(|i| 7.5 + 0.5 * f64::from(i)).collect(),
        );
        let width = |a: f64, b: f64| b - a;
        let e = sub_band_edges(&g, 8.0, 14.0, SubBandCount::Count(4), width).unwrap();
        assert_eq!(e, vec![8.0, 9.5, 11.0, 12.5, 14.0]);
        let one = sub_band_edges(&g, 8.0, 14.0, SubBandCount::BAND, width).unwrap();
        assert_eq!(one, vec![8.0, 14.0]);
        // Full: every grid point inside, closed by the band's ends (not on the grid here).
        let full = sub_band_edges(&g, 8.2, 13.7, SubBandCount::Full, width).unwrap();
        assert_eq!(full.len(), 13, "{full:?}");
        assert_eq!((full[0], full[1], full[12]), (8.2, 8.5, 13.7));
        // A share that is all in the upper half: the edges crowd there, one interval each
        // at least.
        let upper = |a: f64, b: f64| (b.min(14.0) - a.max(11.0)).max(0.0);
        let e = sub_band_edges(&g, 8.0, 14.0, SubBandCount::Count(3), upper).unwrap();
        assert_eq!(e, vec![8.0, 12.0, 13.0, 14.0]);
        // As many sub-bands as intervals is the full grid; more is refused, as is 0.
        let twelve = sub_band_edges(&g, 8.0, 14.0, SubBandCount::Count(12), upper).unwrap();
        assert_eq!(
            twelve,
            sub_band_edges(&g, 8.0, 14.0, SubBandCount::Full, upper).unwrap()
        );
        let e = sub_band_edges(&g, 8.0, 14.0, SubBandCount::Count(13), width).unwrap_err();
        assert!(e.to_string().contains("12 intervals"), "{e}");
        assert!(sub_band_edges(&g, 8.0, 14.0, SubBandCount::Count(0), width).is_err());
        assert!(sub_band_edges(&g, 8.0, 14.0, SubBandCount::Count(2), |_, _| 0.0).is_err());
        assert!(sub_band_edges(&g, 8.0, 14.0, SubBandCount::Count(2), |_, _| f64::NAN).is_err());
        assert!(sub_band_edges(&g, 7.0, 14.0, SubBandCount::Count(2), width).is_err());
        assert_eq!("full".parse(), Ok(SubBandCount::Full));
        assert_eq!("16".parse(), Ok(SubBandCount::Count(16)));
        assert!("0".parse::<SubBandCount>().is_err());
        assert!("-3".parse::<SubBandCount>().is_err());
        assert_eq!(SubBandCount::Count(16).to_string(), "16");
    }

    #[test]
    fn the_correction_fit_recovers_its_polynomial() {
        let nadir: Vec<f64> = (0..=16).map(|i| 5.0 * f64::from(i)).collect();
        let truth = [1.1, -0.11, 0.007];
        let ratio: Vec<f64> = nadir
            .iter()
            .map(|a| {
                let s = 1.0 / a.to_radians().cos();
                truth[0] + truth[1] * s + truth[2] * s * s
            })
            .collect();
        let a = fit_correction(&nadir, &ratio).unwrap();
        for k in 0..3 {
            assert!((a[k] - truth[k]).abs() < 1e-10, "{a:?}");
        }
    }
}
