//! [`Band`]: blackbody band radiance `L(T)`, its derivative and its inverse `T(L)`.

pub use irsig_model::limits::{MAX_RESPONSE, RESPONSE_WAVELENGTH_UM};

use irsig_model::interp;

use crate::constants::{C1L_W_M2_SR, C2_M_K};
use crate::error::{RadiometryError, RadiometryErrorKind};
use crate::planck;

const METRES_PER_UM: f64 = 1e-6;

/// A relative spectral response: response (dimensionless, usually 0–1) against wavelength
/// (µm), linearly interpolated between the tabulated points and zero outside them.
#[derive(Debug, Clone, PartialEq)]
pub struct SensorResponse {
    wavelength_um: Vec<f64>,
    response: Vec<f64>,
}

impl SensorResponse {
    /// A response table from matching columns.
    ///
    /// # Errors
    /// [`RadiometryErrorKind::InvalidResponse`] when there are fewer than two points, the
    /// columns differ in length, a wavelength is not finite or outside
    /// [`RESPONSE_WAVELENGTH_UM`] (0.2–1000 µm), the wavelengths do not strictly increase,
    /// a response is negative, not finite or above [`MAX_RESPONSE`] (10⁶), or all responses
    /// are 0.
    pub fn new(wavelength_um: Vec<f64>, response: Vec<f64>) -> Result<Self, RadiometryError> {
        let bad = |m: String| {
            Err(RadiometryError::new(
                RadiometryErrorKind::InvalidResponse,
                m,
            ))
        };
        if wavelength_um.len() != response.len() {
            return bad(format!(
                "{} wavelengths but {} responses",
                wavelength_um.len(),
                response.len()
            ));
        }
        if wavelength_um.len() < 2 {
            return bad(format!(
                "need at least 2 points, found {}",
                wavelength_um.len()
            ));
        }
        let [shortest, longest] = RESPONSE_WAVELENGTH_UM;
        for (i, (&w, &r)) in wavelength_um.iter().zip(&response).enumerate() {
            if !(shortest..=longest).contains(&w) {
                return bad(format!(
                    "point {}: wavelength must be {shortest}–{longest} µm, found {w}",
                    i + 1
                ));
            }
            if !(0.0..=MAX_RESPONSE).contains(&r) {
                return bad(format!(
                    "point {}: response must be 0–{MAX_RESPONSE:e}, found {r}",
                    i + 1
                ));
            }
        }
        for (i, pair) in wavelength_um.windows(2).enumerate() {
            let &[a, b] = pair else { continue };
            if b <= a {
                return bad(format!(
                    "wavelengths must increase: point {} ({b} µm) follows {a} µm",
                    i + 2
                ));
            }
        }
        if response.iter().all(|&r| r == 0.0) {
            return bad("the response is zero everywhere".to_owned());
        }
        Ok(Self {
            wavelength_um,
            response,
        })
    }

    /// The tabulated wavelengths, µm.
    #[must_use]
    pub fn wavelength_um(&self) -> &[f64] {
        &self.wavelength_um
    }

    /// The tabulated responses.
    #[must_use]
    pub fn response(&self) -> &[f64] {
        &self.response
    }

    /// The response at `wavelength_um`, linearly interpolated; 0 outside the table.
    #[must_use]
    pub fn at(&self, wavelength_um: f64) -> f64 {
        interpolate_or_zero(&self.wavelength_um, &self.response, wavelength_um)
    }
}

fn interpolate_or_zero(xs: &[f64], ys: &[f64], x: f64) -> f64 {
    let (Some(&first), Some(&last)) = (xs.first(), xs.last()) else {
        return 0.0;
    };
    if !(x >= first && x <= last) {
        return 0.0;
    }
    let i = interp::interval(xs, x);
    interp::between((xs[i], ys[i]), (xs[i + 1], ys[i + 1]), x)
}

/// How the band integral is done.
#[derive(Debug, Clone, PartialEq)]
enum Kernel {
    /// SRF = 1: closed-form series (see [`crate::planck`]).
    Flat,
    /// Gauss–Legendre quadrature with the SRF folded into the weights.
    Nodes(Vec<Node>),
}

/// One quadrature node: `weight · SRF(λ) · c1L / λ^5` and `c2 / λ`.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Node {
    weight: f64,
    c2_over_lambda: f64,
}

/// A spectral band `[λmin, λmax]` with an optional sensor response: maps a blackbody's
/// kinetic temperature to the radiance a sensor with this band sees, and back.
///
/// Units: temperatures in K, radiance in W m^-2 sr^-1 (band-integrated, response-weighted),
/// wavelengths in µm at this API. Constants are CODATA 2018.
///
/// The default is the thesis's 8–14 µm with a flat response.
///
/// # Accuracy
/// - Flat response: closed-form series, relative error ~1e-15 at any temperature (the test
///   suite checks ≤ 1e-10 against adaptive quadrature from 3 K to 5000 K).
/// - With a response table: Gauss–Legendre quadrature on each linear piece of the table
///   (4 nodes per piece up to 0.1 µm, 8 nodes per 1 µm otherwise), relative error ≤ 1e-10
///   from 50 K up (checked against the flat series with a flat table). Below 50 K the
///   Planck function is so steep across a piece that the relative error can grow (a flat
///   8–14 µm table measured 2.0e-11 at 10 K; docs/accuracy.md); the result stays positive
///   and strictly increasing in T, so [`Band::temperature`] still inverts it exactly.
///
/// # Cost
/// A table of many rows would give as many nodes, and every `L(T)` would cost one
/// exponential per node. The nodes of each stretch of at most 1 µm are therefore replaced,
/// when there are more than 8, by the 8-point Gauss rule of the response-weighted measure
/// they make (positive weights, exact for polynomials of degree 15 against it, the degree
/// the 8-point rule of a flat piece has): at most 8 nodes per 0.5 µm of the band, whatever
/// the rows. Setting a band up costs time linear in the rows inside it.
#[derive(Debug, Clone, PartialEq)]
pub struct Band {
    lambda_min_um: f64,
    lambda_max_um: f64,
    kernel: Kernel,
    /// The response the nodes were made from (kept for band averages of other spectral
    /// quantities, such as Fresnel emissivity).
    response: Option<SensorResponse>,
    /// Mean wavelength (m) and integral of the response over the band (m), for the
    /// first guess of the inverse.
    centre_m: f64,
    width_m: f64,
}

impl Default for Band {
    fn default() -> Self {
        Self::lwir()
    }
}

impl Band {
    /// The thesis band: 8–14 µm, flat response.
    #[must_use]
    pub fn lwir() -> Self {
        Self::flat_unchecked(8.0, 14.0)
    }

    fn flat_unchecked(lambda_min_um: f64, lambda_max_um: f64) -> Self {
        Self {
            lambda_min_um,
            lambda_max_um,
            kernel: Kernel::Flat,
            response: None,
            centre_m: 0.5 * (lambda_min_um + lambda_max_um) * METRES_PER_UM,
            width_m: (lambda_max_um - lambda_min_um) * METRES_PER_UM,
        }
    }

    /// A band from `lambda_min_um` to `lambda_max_um` with a flat response.
    ///
    /// # Errors
    /// [`RadiometryErrorKind::InvalidBand`] unless `0 < lambda_min_um < lambda_max_um` and
    /// both are finite.
    pub fn new(lambda_min_um: f64, lambda_max_um: f64) -> Result<Self, RadiometryError> {
        if !(lambda_min_um.is_finite() && lambda_max_um.is_finite())
            || lambda_min_um <= 0.0
            || lambda_max_um <= lambda_min_um
        {
            return Err(RadiometryError::new(
                RadiometryErrorKind::InvalidBand,
                format!("need 0 < λmin < λmax (µm), found {lambda_min_um} to {lambda_max_um}"),
            ));
        }
        Ok(Self::flat_unchecked(lambda_min_um, lambda_max_um))
    }

    /// This band weighted by a sensor response. The response multiplies the Planck
    /// function inside `[λmin, λmax]`; it is zero outside its own table.
    ///
    /// # Errors
    /// [`RadiometryErrorKind::InvalidResponse`] when the response is zero everywhere
    /// inside the band.
    pub fn with_response(self, srf: &SensorResponse) -> Result<Self, RadiometryError> {
        self.with_response_quadrature(srf, 8, 1.0)
    }

    /// [`Band::with_response`] with a chosen quadrature: `nodes_per_piece` Gauss–Legendre
    /// nodes on each piece, every linear piece of the response cut into pieces of at most
    /// `max_piece_um` µm. `with_response` uses 8 nodes and 1 µm (4 nodes, uncut, for
    /// pieces of 0.1 µm or less); `docs/accuracy.md` tabulates the error against both.
    ///
    /// The pieces are gathered into cells of at most `max_piece_um`; a cell holding more
    /// than `nodes_per_piece` nodes has them replaced by the `nodes_per_piece`-point Gauss
    /// rule of the measure they make (the response times the pieces' weights): the rule has
    /// at most `nodes_per_piece` nodes per cell, whatever the number of rows.
    ///
    /// # Errors
    /// [`RadiometryErrorKind::InvalidResponse`] when the response is zero everywhere
    /// inside the band, or `nodes_per_piece` is 0 or above 64, or `max_piece_um` is not
    /// finite and at least 0.01 µm.
    pub fn with_response_quadrature(
        self,
        srf: &SensorResponse,
        nodes_per_piece: usize,
        max_piece_um: f64,
    ) -> Result<Self, RadiometryError> {
        if !((1..=64).contains(&nodes_per_piece)
            && max_piece_um.is_finite()
            && max_piece_um >= 0.01)
        {
            return Err(RadiometryError::new(
                RadiometryErrorKind::InvalidResponse,
                format!(
                    "quadrature needs 1–64 nodes per piece and pieces of at least 0.01 µm, found {nodes_per_piece} nodes per {max_piece_um} µm"
                ),
            ));
        }
        let lo = self.lambda_min_um;
        let hi = self.lambda_max_um;
        #[allow(clippy::float_cmp)] // the default rule, chosen by its exact parameters
        let default_rule = nodes_per_piece == 8 && max_piece_um == 1.0;
        let long_rule = gauss_legendre(nodes_per_piece);
        let short_rule = gauss_legendre(4);
        let (w, r) = (&srf.wavelength_um, &srf.response);
        let mut cells = Cells::new(nodes_per_piece, max_piece_um);
        let mut width_m = 0.0;
        let mut moment = 0.0;
        // Only the rows that reach into the band are visited.
        let first = w.partition_point(|&x| x <= lo).saturating_sub(1);
        for i in first..w.len().saturating_sub(1) {
            let (w0, w1, r0, r1) = (w[i], w[i + 1], r[i], r[i + 1]);
            if w0 >= hi {
                break;
            }
            let a = w0.max(lo);
            let b = w1.min(hi);
            if b <= a {
                continue;
            }
            let length = b - a;
            let (rule, pieces) = if default_rule && length <= 0.1 {
                (&short_rule, 1)
            } else {
                // At most 1000 µm / 0.01 µm pieces: the table's span is bounded.
                (&long_rule, (length / max_piece_um).ceil().max(1.0) as usize)
            };
            let piece = length / pieces as f64;
            for p in 0..pieces {
                let start = a + piece * p as f64;
                cells.start_piece(start, start + piece);
                for &(t, weight) in rule {
                    let lambda_um = start + 0.5 * piece * (t + 1.0);
                    // The response is linear on this row's interval (`SensorResponse::at`).
                    let response = r0 + (r1 - r0) * (lambda_um - w0) / (w1 - w0);
                    if response <= 0.0 {
                        continue;
                    }
                    let lambda_m = lambda_um * METRES_PER_UM;
                    let dl_m = 0.5 * piece * weight * METRES_PER_UM;
                    width_m += dl_m * response;
                    moment += dl_m * response * lambda_m;
                    cells.push(lambda_um, dl_m * response);
                }
            }
        }
        let nodes = cells.finish();
        if nodes.is_empty() || width_m <= 0.0 {
            return Err(RadiometryError::new(
                RadiometryErrorKind::InvalidResponse,
                format!("the sensor response is zero everywhere inside the band {lo}–{hi} µm"),
            ));
        }
        Ok(Self {
            lambda_min_um: lo,
            lambda_max_um: hi,
            kernel: Kernel::Nodes(nodes),
            response: Some(srf.clone()),
            centre_m: moment / width_m,
            width_m,
        })
    }

    /// Lower band limit, µm.
    #[must_use]
    pub fn lambda_min_um(&self) -> f64 {
        self.lambda_min_um
    }

    /// Upper band limit, µm.
    #[must_use]
    pub fn lambda_max_um(&self) -> f64 {
        self.lambda_max_um
    }

    /// Whether a sensor response weights this band.
    #[must_use]
    pub fn has_response(&self) -> bool {
        matches!(self.kernel, Kernel::Nodes(_))
    }

    /// The sensor response weighting this band, if any.
    #[must_use]
    pub fn response(&self) -> Option<&SensorResponse> {
        self.response.as_ref()
    }

    /// Number of quadrature nodes (0 for a flat band, which uses the closed-form series).
    #[must_use]
    pub fn quadrature_nodes(&self) -> usize {
        match &self.kernel {
            Kernel::Flat => 0,
            Kernel::Nodes(n) => n.len(),
        }
    }

    /// Band radiance of a blackbody at `t_k` kelvin, W m^-2 sr^-1.
    ///
    /// `t_k ≤ 0` gives 0; NaN gives NaN; a radiance beyond `f64::MAX` (only for
    /// temperatures above ~1e306 K) saturates at `f64::MAX`. Never Inf for finite input.
    #[must_use]
    pub fn radiance(&self, t_k: f64) -> f64 {
        self.radiance_and_derivative(t_k).0
    }

    /// `dL/dT` at `t_k`, W m^-2 sr^-1 K^-1. 0 for `t_k ≤ 0`, NaN for NaN.
    #[must_use]
    pub fn radiance_derivative(&self, t_k: f64) -> f64 {
        self.radiance_and_derivative(t_k).1
    }

    /// `(L(T), dL/dT)` in one evaluation (they share all the exponentials).
    #[must_use]
    pub fn radiance_and_derivative(&self, t_k: f64) -> (f64, f64) {
        if t_k.is_nan() {
            return (f64::NAN, f64::NAN);
        }
        if t_k <= 0.0 {
            return (0.0, 0.0);
        }
        let t_k = t_k.min(f64::MAX);
        match &self.kernel {
            Kernel::Flat => planck::flat_band(
                self.lambda_min_um * METRES_PER_UM,
                self.lambda_max_um * METRES_PER_UM,
                t_k,
            ),
            Kernel::Nodes(nodes) => nodes_radiance(nodes, t_k),
        }
    }

    /// The temperature (K) of the blackbody whose band radiance is `radiance_w_m2_sr`: the
    /// apparent (brightness) temperature.
    ///
    /// - `radiance ≤ 0` gives **0 K**: the band radiance tends to 0 as T → 0+, so 0 K is the
    ///   continuous extension, and a negative radiance (a noisy or over-corrected pixel) has
    ///   no blackbody temperature; callers that must distinguish it test the sign first.
    /// - NaN gives NaN; `+∞` gives `f64::MAX`; any finite positive radiance gives a finite
    ///   temperature (saturating at `f64::MAX` if even that is too cold).
    ///
    /// Safeguarded Newton iteration on `ln L` in `1/T` (nearly linear where Wien's law
    /// holds), kept inside a bracket; `|T(L(T)) − T| < 1e-6 K` from 3 K to 5000 K.
    #[must_use]
    pub fn temperature(&self, radiance_w_m2_sr: f64) -> f64 {
        let target = radiance_w_m2_sr;
        if target.is_nan() {
            return f64::NAN;
        }
        if target <= 0.0 {
            return 0.0;
        }
        let ln_target = target.ln();
        // First guess: Planck at the band's mean wavelength times its width.
        let lc = self.centre_m;
        let ratio = C1L_W_M2_SR * self.width_m / (lc * lc * lc * lc * lc * target);
        let mut t = (C2_M_K / lc) / ratio.ln_1p();
        if !(t.is_finite() && t > 0.0) {
            t = if ratio.ln_1p() == 0.0 { f64::MAX } else { 1.0 };
        }
        let (mut lo, mut hi) = (0.0_f64, f64::INFINITY);
        for _ in 0..200 {
            let (l, dl) = self.radiance_and_derivative(t);
            #[allow(clippy::float_cmp)] // an exact hit ends the search
            if l == target {
                return t;
            }
            if l < target {
                lo = t;
            } else {
                hi = t;
            }
            // Newton on g(u) = ln L(1/u) − ln L*, u = 1/T: T_new = T / (1 + δ),
            // δ = (ln L − ln L*) / (d ln L / d ln T).
            let slope = t * dl / l;
            let mut next = f64::NAN;
            if l > 0.0 && slope.is_finite() && slope > 0.0 {
                let delta = (l.ln() - ln_target) / slope;
                if delta > -1.0 {
                    next = t / (1.0 + delta);
                }
            }
            if !(next > lo && next < hi) {
                next = if hi.is_infinite() {
                    (t * 4.0).min(f64::MAX)
                } else if lo == 0.0 {
                    t * 0.25
                } else {
                    (lo.sqrt() * hi.sqrt()).clamp(lo, hi)
                };
            }
            if t >= f64::MAX && next >= t {
                return f64::MAX;
            }
            if (next - t).abs() <= 1e-15 * t || (hi.is_finite() && hi - lo <= 2e-16 * hi) {
                return next;
            }
            t = next;
        }
        t
    }
}

/// The quadrature's nodes, gathered cell by cell: a cell spans at most `max_um` of
/// wavelength; one holding more than `order` nodes is replaced by the `order`-point Gauss
/// rule of the measure its nodes make.
struct Cells {
    order: usize,
    max_um: f64,
    /// Where the open cell starts, µm.
    start_um: f64,
    /// The open cell's nodes: wavelength (µm) and weight (response times length, m).
    open: Vec<(f64, f64)>,
    nodes: Vec<Node>,
}

impl Cells {
    fn new(order: usize, max_um: f64) -> Self {
        Self {
            order,
            max_um,
            start_um: f64::NAN,
            open: Vec::new(),
            nodes: Vec::new(),
        }
    }

    /// A piece `[start, end]` begins: the open cell is closed first when the piece would
    /// take it past its length.
    fn start_piece(&mut self, start_um: f64, end_um: f64) {
        // A NaN start (no cell open yet) closes nothing and opens the first.
        let fits = end_um - self.start_um <= self.max_um * (1.0 + 1e-9);
        if !fits {
            self.close();
            self.start_um = start_um;
        }
    }

    fn push(&mut self, lambda_um: f64, weight_m: f64) {
        self.open.push((lambda_um, weight_m));
    }

    fn close(&mut self) {
        let rule = if self.open.len() > self.order {
            gauss_rule_of_measure(&self.open, self.order)
        } else {
            None
        };
        for &(lambda_um, weight_m) in rule.as_deref().unwrap_or(&self.open) {
            let lambda_m = lambda_um * METRES_PER_UM;
            let l5 = lambda_m * lambda_m * lambda_m * lambda_m * lambda_m;
            self.nodes.push(Node {
                weight: weight_m * C1L_W_M2_SR / l5,
                c2_over_lambda: C2_M_K / lambda_m,
            });
        }
        self.open.clear();
    }

    fn finish(mut self) -> Vec<Node> {
        self.close();
        self.nodes
    }
}

/// The `order`-point Gauss rule of the discrete measure `points` (position, positive
/// weight): `order` positions inside the points' span with positive weights, exact for
/// every polynomial of degree up to `2 order - 1` against the measure. The three-term
/// recurrence of the measure's orthogonal polynomials comes from the discretised Stieltjes
/// procedure (on positions mapped to [-1, 1]); the rule's positions are the zeros of the
/// `order`-th polynomial (the eigenvalues of the Jacobi matrix, found by bisection on its
/// Sturm sequence) and its weights the Christoffel numbers. `None` when the measure holds
/// too few distinct points or rounding spoils the rule: the caller keeps the points.
fn gauss_rule_of_measure(points: &[(f64, f64)], order: usize) -> Option<Vec<(f64, f64)>> {
    let (lo, hi) = points
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &(x, _)| {
            (lo.min(x), hi.max(x))
        });
    let (centre, half) = (0.5 * (lo + hi), 0.5 * (hi - lo));
    if !(half > 0.0 && half.is_finite()) {
        return None;
    }
    let x: Vec<f64> = points.iter().map(|&(p, _)| (p - centre) / half).collect();
    let w: Vec<f64> = points.iter().map(|&(_, w)| w).collect();
    // Stieltjes: p_{k+1} = (x - α_k) p_k - β_k p_{k-1}, α_k = <x p_k, p_k> / <p_k, p_k>,
    // β_k = <p_k, p_k> / <p_{k-1}, p_{k-1}>, β_0 = <1, 1>.
    let mut alpha = Vec::with_capacity(order);
    let mut beta = Vec::with_capacity(order);
    let mut previous = vec![0.0; x.len()];
    let mut current = vec![1.0; x.len()];
    let mut norm: f64 = w.iter().sum();
    beta.push(norm);
    for k in 0..order {
        let xpp: f64 = (0..x.len())
            .map(|i| w[i] * x[i] * current[i] * current[i])
            .sum();
        let a = xpp / norm;
        alpha.push(a);
        if k + 1 == order {
            break;
        }
        let b = if k == 0 { 0.0 } else { beta[k] };
        for i in 0..x.len() {
            let next = (x[i] - a) * current[i] - b * previous[i];
            previous[i] = current[i];
            current[i] = next;
        }
        let next_norm: f64 = (0..x.len()).map(|i| w[i] * current[i] * current[i]).sum();
        let ratio = next_norm / norm;
        if !(ratio.is_finite() && ratio > 1e-30 && a.is_finite()) {
            return None;
        }
        beta.push(ratio);
        norm = next_norm;
    }
    // The zeros of p_order: the eigenvalues of the Jacobi matrix, each by bisection on the
    // count of eigenvalues below a point (negative terms of its Sturm sequence).
    let below = |t: f64| -> usize {
        let mut count = 0;
        let mut q = 1.0;
        for k in 0..order {
            q = (alpha[k] - t) - if k == 0 { 0.0 } else { beta[k] / q };
            if q == 0.0 {
                q = -1e-300;
            }
            if q < 0.0 {
                count += 1;
            }
        }
        count
    };
    let mut rule = Vec::with_capacity(order);
    for j in 0..order {
        let (mut a, mut b) = (-1.0 - 1e-9, 1.0 + 1e-9);
        for _ in 0..200 {
            let mid = 0.5 * (a + b);
            if mid <= a || mid >= b {
                break;
            }
            if below(mid) > j {
                b = mid;
            } else {
                a = mid;
            }
        }
        let t = 0.5 * (a + b);
        // Christoffel number: 1 / Σ p̂_k(t)², p̂ the orthonormal polynomials.
        let mut sum = 0.0;
        let (mut p_prev, mut p) = (0.0, 1.0 / beta[0].sqrt());
        for k in 0..order {
            sum += p * p;
            if k + 1 == order {
                break;
            }
            let next = ((t - alpha[k]) * p - if k == 0 { 0.0 } else { beta[k].sqrt() * p_prev })
                / beta[k + 1].sqrt();
            p_prev = p;
            p = next;
        }
        let weight = 1.0 / sum;
        rule.push((centre + half * t.clamp(-1.0, 1.0), weight));
    }
    // A sound rule has positive weights summing to the measure's mass, and distinct
    // positions inside its span.
    let mass: f64 = rule.iter().map(|&(_, w)| w).sum();
    let sound = rule
        .iter()
        .all(|&(p, w)| w > 0.0 && w.is_finite() && p >= lo && p <= hi)
        && rule.windows(2).all(|r| r[1].0 > r[0].0)
        && (mass / beta[0] - 1.0).abs() <= 1e-9;
    sound.then_some(rule)
}

fn nodes_radiance(nodes: &[Node], t_k: f64) -> (f64, f64) {
    let mut radiance = 0.0;
    let mut derivative = 0.0;
    for node in nodes {
        let y = node.c2_over_lambda / t_k;
        if y > 745.0 {
            // exp(−y) underflows: this node and every one with a shorter wavelength add 0.
            continue;
        }
        // 1/(e^y − 1) = e^{−y} / (1 − e^{−y}); expm1 keeps 1 − e^{−y} exact for small y.
        let em = (-y).exp();
        let one_minus = -(-y).exp_m1();
        radiance += node.weight * (em / one_minus);
        // d/dT 1/(e^y − 1) = (y/T) e^y/(e^y − 1)^2, written so no factor overflows:
        // e^{−y} · (y / (1 − e^{−y})) / (T (1 − e^{−y})).
        derivative += node.weight * em * (y / one_minus) / (t_k * one_minus);
    }
    (radiance.min(f64::MAX), derivative.min(f64::MAX))
}

/// Gauss–Legendre nodes and weights on [−1, 1] (Newton on the Legendre recurrence), as
/// `(node, weight)` pairs.
#[must_use]
pub fn gauss_legendre(order: usize) -> Vec<(f64, f64)> {
    let n = order as f64;
    let mut rule = Vec::with_capacity(order);
    for i in 0..order {
        let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (n + 0.5)).cos();
        let mut derivative = 1.0;
        for _ in 0..100 {
            let (mut p0, mut p1) = (1.0_f64, x);
            for k in 2..=order {
                let k = k as f64;
                let p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
                p0 = p1;
                p1 = p2;
            }
            derivative = n * (x * p1 - p0) / (x * x - 1.0);
            let dx = p1 / derivative;
            x -= dx;
            if dx.abs() < 1e-16 {
                break;
            }
        }
        let w = 2.0 / ((1.0 - x * x) * derivative * derivative);
        rule.push((x, w));
    }
    rule
}

#[cfg(test)]
#[allow(clippy::float_cmp)] // exact values are the point of these checks
mod tests {
    use super::*;

    #[test]
    fn gauss_legendre_integrates_polynomials_of_degree_2n_minus_1_exactly() {
        for order in [4, 8] {
            let rule = gauss_legendre(order);
            let weight_sum: f64 = rule.iter().map(|&(_, w)| w).sum();
            assert!((weight_sum - 2.0).abs() < 1e-14);
            // ∫_{-1}^{1} x^(2n-2) dx = 2/(2n-1).
            let degree = 2 * order - 2;
            let integral: f64 = rule.iter().map(|&(x, w)| w * x.powi(degree as i32)).sum();
            assert!((integral - 2.0 / (degree as f64 + 1.0)).abs() < 1e-14);
        }
    }

    #[test]
    fn interpolation_is_zero_outside_and_linear_inside() {
        let srf = SensorResponse::new(vec![8.0, 10.0, 12.0], vec![0.0, 1.0, 0.5]).unwrap();
        assert_eq!(srf.at(7.9), 0.0);
        assert_eq!(srf.at(12.1), 0.0);
        assert!((srf.at(9.0) - 0.5).abs() < 1e-15);
        assert!((srf.at(11.0) - 0.75).abs() < 1e-15);
        assert!((srf.at(12.0) - 0.5).abs() < 1e-15);
    }
}
