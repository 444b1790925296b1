//! One implicit time step of a facet's wall.
//!
//! Each node `i` balances `C_i dT_i/dt = Σ_j g_ij (T_j − T_i) + boundary terms`, advanced
//! by the θ-method: the right-hand side is weighted `θ` at the step's end and `1 − θ` at
//! its start, with the loads of each end. Backward Euler (`θ = 1`) is first-order in the
//! step and L-stable: it damps every mode, however stiff. Crank–Nicolson (`θ = ½`) is
//! second-order and A-stable but not L-stable: modes much faster than the step (a thin
//! paint layer's, a thin skin's over an insulator) are not damped but flip sign each step,
//! so such a wall carries a step-to-step ripple at its surface as large as the mismatch a
//! start or a sudden change of load left in that mode: millikelvin for paint over
//! concrete, tens of kelvin for a micron of metal over an insulator, whose surface is all
//! but algebraic (Patankar 1980, §4.3; Hensen & Nakhi 1994, "Fourier and Biot numbers and
//! the accuracy of conduction modelling"; `tests/extremes.rs` has the second). Its
//! explicit half can also overshoot: a surface whose emission or convection changes
//! steeply over a long step (a hot skin of little heat capacity) can be driven below 1 K,
//! which [`step`] refuses rather than returns. Spinning up by Backward Euler and then
//! switching to Crank–Nicolson damps what the start excites; the tests do so. TR-BDF2
//! ([`Scheme::TrBdf2`]) is second-order and L-stable, at two surface solves a step: the
//! choice where thin skins over insulators meet long steps.
//!
//! The interior is linear with coefficients fixed by the wall, the step length and θ, so
//! the tridiagonal elimination from the back node toward the surface is computed once per
//! (wall, step, scheme) and kept in a [`Scratch`]. What remains at the surface node is one
//! scalar equation, nonlinear through `ε σ T⁴`, a temperature-dependent `h` and the latent
//! heat; it is solved exactly by Newton's method on its analytic derivative, safeguarded by
//! bisection (the equation is increasing in the surface temperature, so a bracket always
//! holds the root), to 1e-9 K. The other nodes follow by back-substitution. A step
//! allocates nothing once its (wall, step, scheme) has been seen.

use std::ops::AddAssign;

use irsig_model::thermal::{BackAir, BackBoundary};

use crate::convection::{ForcedCache, Orientation};
use crate::error::{ThermalError, ThermalErrorKind};
use crate::surface::{Loads, Surface, SurfaceAt, SurfaceParts};
use crate::wall::Wall;
use crate::{MAX_TEMPERATURE_K, MIN_TEMPERATURE_K};

/// The surface balance is converged when Newton's step is this small, K.
pub const SURFACE_TOLERANCE_K: f64 = 1e-9;
/// The most iterations of the surface balance (bisection from 1–5000 K alone would need 43).
const MAX_ITERATIONS: usize = 200;
/// How many (wall, step, scheme) eliminations a [`Scratch`] keeps.
const CACHE_CAPACITY: usize = 16;

/// The time-stepping scheme.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Scheme {
    /// Fully implicit, the θ-method with `θ = 1`: first-order in the step, L-stable. One
    /// surface solve per step.
    BackwardEuler,
    /// Trapezoidal, the θ-method with `θ = ½`: second-order in the step, A-stable, not
    /// L-stable (see the module's notes). One surface solve and one evaluation per step.
    CrankNicolson,
    /// TR-BDF2 (Bank et al. 1985, IEEE Trans. Electron Devices 32, 1992–2007; Hosea &
    /// Shampine 1996, Appl. Numer. Math. 20, 21–37): a trapezoidal stage to `t + γΔt`, then
    /// a second-order backward-difference stage to `t + Δt`, `γ = 2 − √2`, so that both
    /// stages share one matrix. Second-order and L-stable: it damps the stiff modes
    /// Crank–Nicolson leaves ringing (a thin skin over an insulator, whose surface is all
    /// but algebraic). Two surface solves per step; the loads at `t + γΔt` are interpolated
    /// linearly between `before` and `after`.
    TrBdf2,
}

impl Scheme {
    /// The weight `θ` of a θ-method stage's end.
    pub(crate) fn theta(self) -> f64 {
        match self {
            Self::BackwardEuler | Self::TrBdf2 => 1.0,
            Self::CrankNicolson => 0.5,
        }
    }
}

/// TR-BDF2's `γ = 2 − √2`: its trapezoidal stage's share of the step.
const GAMMA: f64 = 2.0 - std::f64::consts::SQRT_2;

/// The length and scheme of a step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TimeStep {
    /// The step's length, s, above 0.
    pub dt_s: f64,
    /// The scheme.
    pub scheme: Scheme,
}

/// One facet as the solver sees it: its wall (shared by a material's facets), its surface
/// and its orientation.
#[derive(Debug, Clone, Copy)]
pub struct Facet<'a> {
    /// The discretised wall.
    pub wall: &'a Wall,
    /// The exposed surface's properties.
    pub surface: &'a Surface,
    /// How the facet faces the sky and the wind.
    pub orientation: Orientation,
}

/// The energy of one step, J m⁻², each term weighted as the scheme weights it, so that
/// `stored_change_j_m2` equals the sum of the others (signed as named) to round-off and the
/// surface tolerance: see [`StepFluxes::imbalance_j_m2`]. Add steps with `+=`.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct StepFluxes {
    /// Shortwave absorbed at the surface, ≥ 0.
    pub absorbed_shortwave_j_m2: f64,
    /// Longwave absorbed at the surface, ≥ 0.
    pub absorbed_longwave_j_m2: f64,
    /// Emitted by the surface, `ε σ T⁴`, ≥ 0.
    pub emitted_j_m2: f64,
    /// Convected from the surface to the air (negative when the air warms it).
    pub convected_j_m2: f64,
    /// Carried away by evaporation (negative when water condenses on the surface).
    pub latent_j_m2: f64,
    /// Into the wall through its back (negative when it loses heat there; for a held back,
    /// whatever holds it takes or gives, the source included).
    pub back_j_m2: f64,
    /// Deposited by the source at the back node.
    pub source_j_m2: f64,
    /// Into the wall through a held surface ([`step_held`]; 0 for a balanced one).
    pub held_surface_j_m2: f64,
    /// The change of `Σ C_i T_i`.
    pub stored_change_j_m2: f64,
}

impl StepFluxes {
    /// What the stored change lacks of the sum of the flows: 0 to round-off and the
    /// surface tolerance.
    #[must_use]
    pub fn imbalance_j_m2(&self) -> f64 {
        self.stored_change_j_m2
            - (self.absorbed_shortwave_j_m2 + self.absorbed_longwave_j_m2
                - self.emitted_j_m2
                - self.convected_j_m2
                - self.latent_j_m2
                + self.back_j_m2
                + self.source_j_m2
                + self.held_surface_j_m2)
    }
}

impl StepFluxes {
    /// Every term times `k`.
    fn scaled(self, k: f64) -> Self {
        Self {
            absorbed_shortwave_j_m2: k * self.absorbed_shortwave_j_m2,
            absorbed_longwave_j_m2: k * self.absorbed_longwave_j_m2,
            emitted_j_m2: k * self.emitted_j_m2,
            convected_j_m2: k * self.convected_j_m2,
            latent_j_m2: k * self.latent_j_m2,
            back_j_m2: k * self.back_j_m2,
            source_j_m2: k * self.source_j_m2,
            held_surface_j_m2: k * self.held_surface_j_m2,
            stored_change_j_m2: k * self.stored_change_j_m2,
        }
    }

    /// The sum of two steps' terms.
    fn plus(mut self, o: &Self) -> Self {
        self += *o;
        self
    }
}

impl AddAssign for StepFluxes {
    fn add_assign(&mut self, o: Self) {
        self.absorbed_shortwave_j_m2 += o.absorbed_shortwave_j_m2;
        self.absorbed_longwave_j_m2 += o.absorbed_longwave_j_m2;
        self.emitted_j_m2 += o.emitted_j_m2;
        self.convected_j_m2 += o.convected_j_m2;
        self.latent_j_m2 += o.latent_j_m2;
        self.back_j_m2 += o.back_j_m2;
        self.source_j_m2 += o.source_j_m2;
        self.held_surface_j_m2 += o.held_surface_j_m2;
        self.stored_change_j_m2 += o.stored_change_j_m2;
    }
}

/// The elimination of one (wall, step, scheme): rows `i ≥ 1` give
/// `T_i = P_i − Q_i T_{i−1}`, where `Q_i` and `1/β_i` are fixed and `P_i` follows the
/// right-hand side.
#[derive(Debug, Clone)]
struct Elimination {
    wall_id: u64,
    dt_bits: u64,
    scheme: Scheme,
    /// `Q_i`.
    q: Vec<f64>,
    /// `1/β_i`.
    inv_beta: Vec<f64>,
    /// `C_i / (Δt β_i)`: what `T_i` at the step's start adds to `P_i`.
    own: Vec<f64>,
    /// `θ g_i / β_i`: what `P_{i+1}` adds to `P_i`, so that the recurrence is one fused
    /// multiply-add per node.
    coupling: Vec<f64>,
    /// The surface row's coefficient of `T_0` once `T_1` is eliminated.
    d0: f64,
}

/// Working memory for [`step`]: the eliminations of the last walls, steps and schemes seen,
/// and per-node buffers. One per thread; reuse it across facets and steps.
#[derive(Debug, Clone, Default)]
pub struct Scratch {
    cache: Vec<Elimination>,
    next_victim: usize,
    last: usize,
    p: Vec<f64>,
    /// TR-BDF2's copy of the step's starting temperatures.
    start: Vec<f64>,
    forced: ForcedCache,
}

impl Scratch {
    /// Empty working memory.
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }

    /// The index of the elimination for this wall, step and scheme, made if not kept.
    fn elimination(&mut self, wall: &Wall, dt_s: f64, scheme: Scheme) -> usize {
        let key = (wall.id(), dt_s.to_bits(), scheme);
        let hit = |e: &Elimination| (e.wall_id, e.dt_bits, e.scheme) == key;
        if self.cache.get(self.last).is_some_and(hit) {
            return self.last;
        }
        if let Some(i) = self.cache.iter().position(hit) {
            self.last = i;
            return i;
        }
        let i = if self.cache.len() < CACHE_CAPACITY {
            self.cache.push(Elimination {
                wall_id: 0,
                dt_bits: 0,
                scheme,
                q: Vec::new(),
                inv_beta: Vec::new(),
                own: Vec::new(),
                coupling: Vec::new(),
                d0: 0.0,
            });
            self.cache.len() - 1
        } else {
            let i = self.next_victim;
            self.next_victim = (self.next_victim + 1) % CACHE_CAPACITY;
            i
        };
        eliminate(&mut self.cache[i], wall, dt_s, scheme);
        self.last = i;
        i
    }
}

/// Fills `e` with the elimination of `wall` for a step `dt_s` under `scheme`.
fn eliminate(e: &mut Elimination, wall: &Wall, dt_s: f64, scheme: Scheme) {
    let theta = scheme.theta();
    let c = wall.capacities_j_m2_k();
    let g = wall.conductances_w_m2_k();
    let n = c.len();
    let last = n - 1;
    e.wall_id = wall.id();
    e.dt_bits = dt_s.to_bits();
    e.scheme = scheme;
    for v in [&mut e.q, &mut e.inv_beta, &mut e.own, &mut e.coupling] {
        v.clear();
        v.resize(n, 0.0);
    }
    // Each row's pivot is `β_i = σ_i + θ g_{i−1}`, with `σ_i = C_i/Δt + θ g_i s_{i+1}` and
    // `s_i = 1 + Q_i = σ_i / β_i`: sums of positive terms only, so that a wall whose
    // conductances span many orders (a micron of metal over a thick insulator) loses no
    // digits to cancellation in `1 + Q_i`, nor the surface row's `d0 = C_0/Δt + θ g_0 s_1`.
    let sigma_last = match wall.back() {
        BackBoundary::Temperature { .. } => None,
        BackBoundary::Adiabatic => Some(c[last] / dt_s),
        BackBoundary::Convective { h_w_m2_k, .. } => Some(c[last] / dt_s + theta * h_w_m2_k),
    };
    let mut s_next = match sigma_last {
        // A held back node: `T_N` is given, `Q_N = 0`.
        None => {
            e.inv_beta[last] = 1.0;
            e.q[last] = 0.0;
            1.0
        }
        Some(sigma) => {
            let beta = sigma + theta * g[last - 1];
            e.inv_beta[last] = 1.0 / beta;
            e.q[last] = -theta * g[last - 1] / beta;
            sigma / beta
        }
    };
    for i in (1..last).rev() {
        let sigma = c[i] / dt_s + theta * g[i] * s_next;
        let beta = sigma + theta * g[i - 1];
        e.inv_beta[i] = 1.0 / beta;
        e.q[i] = -theta * g[i - 1] / beta;
        e.own[i] = c[i] / dt_s / beta;
        e.coupling[i] = theta * g[i] / beta;
        s_next = sigma / beta;
    }
    e.d0 = c[0] / dt_s + theta * g[0] * s_next;
}

/// How the surface node is closed.
#[derive(Debug, Clone, Copy)]
enum SurfaceMode<'a> {
    /// By its energy balance.
    Balance(&'a Surface, Orientation),
    /// Held at a temperature at the step's end, K.
    Held(f64),
}

/// Advances a facet's node temperatures by one step.
///
/// `temps` holds the wall's node temperatures (K, surface first, [`Wall::nodes`] of them) at
/// the step's start and is overwritten with those at its end; `before` and `after` are the
/// loads at the step's start and end. On an error `temps` is left as it was.
///
/// # Errors
/// [`ThermalErrorKind::InvalidInput`] for a load or surface property out of range, a step
/// that is not positive and finite, or `temps` of the wrong length;
/// [`ThermalErrorKind::NotConverged`] if the surface balance does not converge (with the
/// facet's numbers); [`ThermalErrorKind::OutOfRange`] if a temperature would leave 1–5000 K.
pub fn step(
    facet: &Facet<'_>,
    temps: &mut [f64],
    before: &Loads,
    after: &Loads,
    time_step: TimeStep,
    scratch: &mut Scratch,
) -> Result<StepFluxes, ThermalError> {
    facet.surface.validate()?;
    advance_scheme(
        facet.wall,
        SurfaceMode::Balance(facet.surface, facet.orientation),
        temps,
        [before, after],
        time_step,
        scratch,
    )
}

/// Advances a wall whose surface is held at a given temperature: a blackbody held at a
/// temperature, or a Dirichlet condition for tests. The surface node ends the step at
/// `held_surface_k` (it starts at `temps[0]`, the last step's held value). The loads supply
/// the back air and the source; their radiation and convection do not act on a held
/// surface. The energy that holding the surface takes is
/// [`StepFluxes::held_surface_j_m2`].
///
/// # Errors
/// As [`step`]; a held temperature outside 1–5000 K is [`ThermalErrorKind::InvalidInput`].
pub fn step_held(
    wall: &Wall,
    temps: &mut [f64],
    held_surface_k: f64,
    before: &Loads,
    after: &Loads,
    time_step: TimeStep,
    scratch: &mut Scratch,
) -> Result<StepFluxes, ThermalError> {
    if !(MIN_TEMPERATURE_K..=MAX_TEMPERATURE_K).contains(&held_surface_k) {
        return Err(ThermalError::input(format!(
            "held surface temperature {held_surface_k} K must lie between \
             {MIN_TEMPERATURE_K} and {MAX_TEMPERATURE_K} K"
        )));
    }
    advance_scheme(
        wall,
        SurfaceMode::Held(held_surface_k),
        temps,
        [before, after],
        time_step,
        scratch,
    )
}

/// What the back boundary sees at one instant: its conductance and the temperature behind
/// it (0 and 0 for an adiabatic back).
fn back_at(back: BackBoundary, loads: &Loads) -> (f64, f64) {
    match back {
        BackBoundary::Adiabatic => (0.0, 0.0),
        BackBoundary::Temperature { temperature_k } => (0.0, temperature_k),
        BackBoundary::Convective { h_w_m2_k, air } => (
            h_w_m2_k,
            match air {
                BackAir::Outdoor => loads.air_temperature_k,
                BackAir::Fixed { temperature_k } => temperature_k,
            },
        ),
    }
}

/// The back boundary over a step: held, or its conductance and the temperature behind it
/// at the step's start (`0`) and end (`1`), and the scheme-weighted source.
#[derive(Debug, Clone, Copy)]
struct BackTerms {
    held: bool,
    h0: f64,
    t0: f64,
    h1: f64,
    t1: f64,
    source_w_m2: f64,
}

impl BackTerms {
    fn new(back: BackBoundary, before: &Loads, after: &Loads, theta: f64) -> Self {
        let (h0, t0) = back_at(back, before);
        let (h1, t1) = back_at(back, after);
        Self {
            held: matches!(back, BackBoundary::Temperature { .. }),
            h0,
            t0,
            h1,
            t1,
            source_w_m2: theta * after.source_w_m2 + (1.0 - theta) * before.source_w_m2,
        }
    }
}

/// Fills `p` from the back row to row 1 with the right-hand side of the step's start, and
/// returns the surface row's right-hand side with `T_1` eliminated (its surface flux
/// terms still to come).
fn sweep_to_surface(
    e: &Elimination,
    wall: &Wall,
    temps: &[f64],
    p: &mut [f64],
    back: &BackTerms,
    dt_s: f64,
    theta: f64,
) -> f64 {
    let explicit = 1.0 - theta;
    let c = wall.capacities_j_m2_k();
    let g = wall.conductances_w_m2_k();
    let last = c.len() - 1;
    let r_last = if back.held {
        back.t1
    } else {
        let mut r = c[last] / dt_s * temps[last] + theta * back.h1 * back.t1 + back.source_w_m2;
        if explicit != 0.0 {
            r += explicit
                * (g[last - 1] * (temps[last - 1] - temps[last])
                    + back.h0 * (back.t0 - temps[last]));
        }
        r
    };
    p[last] = r_last * e.inv_beta[last];
    // Interior rows, back to front: `P_i = (r_i + θ g_i P_{i+1}) / β_i`, over slices of
    // one length so that the loop carries no bounds checks.
    let mut next = p[last];
    let rows = 1..last;
    let (own, coupling) = (&e.own[rows.clone()], &e.coupling[rows.clone()]);
    let (p_rows, t_rows) = (&mut p[rows.clone()], &temps[rows]);
    if explicit == 0.0 {
        for (((pi, &ti), &own), &coupling) in
            p_rows.iter_mut().zip(t_rows).zip(own).zip(coupling).rev()
        {
            next = own * ti + coupling * next;
            *pi = next;
        }
    } else {
        for i in (1..last).rev() {
            let exchange = g[i - 1] * (temps[i - 1] - temps[i]) + g[i] * (temps[i + 1] - temps[i]);
            next = e.own[i] * temps[i] + explicit * exchange * e.inv_beta[i] + e.coupling[i] * next;
            p[i] = next;
        }
    }
    // The surface row: `d0 T_0 − θ q(T_0) = r`.
    let mut r0 = c[0] / dt_s * temps[0] + theta * g[0] * p[1];
    if explicit != 0.0 {
        r0 += explicit * g[0] * (temps[1] - temps[0]);
    }
    r0
}

/// [`advance`] for a θ-method; TR-BDF2 as its two stages.
fn advance_scheme(
    wall: &Wall,
    mode: SurfaceMode<'_>,
    temps: &mut [f64],
    loads: [&Loads; 2],
    time_step: TimeStep,
    scratch: &mut Scratch,
) -> Result<StepFluxes, ThermalError> {
    if time_step.scheme == Scheme::TrBdf2 {
        tr_bdf2(wall, mode, temps, loads, time_step.dt_s, scratch)
    } else {
        advance(wall, mode, temps, loads, time_step, scratch)
    }
}

/// TR-BDF2 as a Crank–Nicolson step of `γΔt` to `T_γ`, then a Backward Euler step of
/// `wΔt`, `w = (1 − γ)/(2 − γ)` (= γ/2, so both stages share one matrix up to scale), from
/// `T̃ = T_n + (T_γ − T_n)/(γ(2 − γ))`: the BDF2 stage
/// `T_{n+1} = (T_γ − (1 − γ)² T_n)/(γ(2 − γ)) + w Δt F(T_{n+1})` rewritten. The step's
/// energy terms weight the start and `T_γ` by `Δt/(2(2 − γ))` each and the end by `wΔt`,
/// which is the first stage's terms times `1/(γ(2 − γ))` plus the second's; the stored
/// change scales the same way, so the sum still closes.
fn tr_bdf2(
    wall: &Wall,
    mode: SurfaceMode<'_>,
    temps: &mut [f64],
    [before, after]: [&Loads; 2],
    dt_s: f64,
    scratch: &mut Scratch,
) -> Result<StepFluxes, ThermalError> {
    let k = 1.0 / (GAMMA * (2.0 - GAMMA));
    let mid = before.lerp(after, GAMMA);
    let first_mode = match mode {
        SurfaceMode::Held(held) => {
            SurfaceMode::Held(temps.first().map_or(held, |&t0| t0 + GAMMA * (held - t0)))
        }
        balance @ SurfaceMode::Balance(..) => balance,
    };
    let mut start = std::mem::take(&mut scratch.start);
    start.clear();
    start.extend_from_slice(temps);
    let in_stage = |stage: &'static str| {
        move |mut e: ThermalError| {
            let hint = if e.kind == ThermalErrorKind::OutOfRange {
                " (TR-BDF2 extrapolates from its trapezoidal stage, which overshoots when the \
                 surface's fluxes change this steeply over a step this long; Backward Euler \
                 or a shorter step keeps the temperature physical)"
            } else {
                ""
            };
            e.message = format!(
                "TR-BDF2 step of {dt_s} s, {stage} stage{hint}: {}",
                e.message
            );
            e
        }
    };
    let result = advance(
        wall,
        first_mode,
        temps,
        [before, &mid],
        TimeStep {
            dt_s: GAMMA * dt_s,
            scheme: Scheme::CrankNicolson,
        },
        scratch,
    )
    .map_err(in_stage("trapezoidal"))
    .and_then(|first| {
        for (t, &t0) in temps.iter_mut().zip(&start) {
            *t = t0 + (*t - t0) * k;
        }
        let second = advance(
            wall,
            mode,
            temps,
            [&mid, after],
            TimeStep {
                dt_s: (1.0 - GAMMA) / (2.0 - GAMMA) * dt_s,
                scheme: Scheme::BackwardEuler,
            },
            scratch,
        );
        if second.is_err() {
            temps.copy_from_slice(&start);
        }
        Ok(first
            .scaled(k)
            .plus(&second.map_err(in_stage("backward-difference"))?))
    });
    scratch.start = start;
    result
}

/// The shared body of [`step`] and [`step_held`] for one θ-method step.
fn advance(
    wall: &Wall,
    mode: SurfaceMode<'_>,
    temps: &mut [f64],
    [before, after]: [&Loads; 2],
    time_step: TimeStep,
    scratch: &mut Scratch,
) -> Result<StepFluxes, ThermalError> {
    let TimeStep { dt_s, scheme } = time_step;
    if !(dt_s.is_finite() && dt_s > 0.0) {
        return Err(ThermalError::input(format!(
            "time step {dt_s} s must be positive and finite"
        )));
    }
    if temps.len() != wall.nodes() {
        return Err(ThermalError::input(format!(
            "{} temperatures for a wall of {} nodes",
            temps.len(),
            wall.nodes()
        )));
    }
    before.validate()?;
    after.validate()?;
    let theta = scheme.theta();
    let explicit = 1.0 - theta;
    let c = wall.capacities_j_m2_k();
    let g = wall.conductances_w_m2_k();
    let n = c.len();
    let last = n - 1;
    let index = scratch.elimination(wall, dt_s, scheme);
    let e = &scratch.cache[index];
    let p = &mut scratch.p;
    // Every entry is written before it is read: no clearing.
    p.resize(n, 0.0);

    let back = BackTerms::new(wall.back(), before, after, theta);
    let mut r0 = sweep_to_surface(e, wall, temps, p, &back, dt_s, theta);
    let mut fluxes = StepFluxes::default();
    let t0_new = match mode {
        SurfaceMode::Held(held) => held,
        SurfaceMode::Balance(surface, orientation) => {
            let at1 = SurfaceAt::new(surface, orientation, after, &mut scratch.forced);
            // The step's start, for Crank–Nicolson's explicit half.
            let start = (explicit != 0.0).then(|| {
                let at0 = SurfaceAt::new(surface, orientation, before, &mut scratch.forced);
                let parts = at0.parts(temps[0]);
                r0 += explicit * (at0.absorbed_w_m2() - parts.leaving());
                (at0, parts)
            });
            let (t0, end) = solve_surface(e.d0, theta, r0, &at1, temps[0]).map_err(|kind| {
                surface_error(kind, surface, orientation, temps, after, time_step)
            })?;
            account_surface(&mut fluxes, (&at1, &end), start.as_ref(), theta, dt_s);
            t0
        }
    };
    // Back-substitution into `p`, so that `temps` is untouched until all is checked, with
    // the stored change on the way.
    p[0] = t0_new;
    let range = MIN_TEMPERATURE_K..=MAX_TEMPERATURE_K;
    let mut in_range = range.contains(&t0_new);
    let mut stored = c[0] * (t0_new - temps[0]);
    let mut previous = t0_new;
    for (((pi, &qi), &ci), &ti) in p[1..n]
        .iter_mut()
        .zip(&e.q[1..n])
        .zip(&c[1..n])
        .zip(&temps[1..n])
    {
        previous = *pi - qi * previous;
        *pi = previous;
        in_range &= range.contains(&previous);
        stored += ci * (previous - ti);
    }
    if !in_range {
        return Err(out_of_range(p, temps, after));
    }
    // The flows through the back and a held surface, and the stored change.
    fluxes.source_j_m2 = back.source_w_m2 * dt_s;
    let conduction = |i: usize, t: &[f64]| g[i] * (t[i + 1] - t[i]);
    let weighted = |i: usize, new: &[f64], old: &[f64]| {
        dt_s * (theta * conduction(i, new) + explicit * conduction(i, old))
    };
    fluxes.back_j_m2 = if back.held {
        c[last] * (p[last] - temps[last]) + weighted(last - 1, p, temps) - fluxes.source_j_m2
    } else {
        dt_s * (theta * back.h1 * (back.t1 - p[last])
            + explicit * back.h0 * (back.t0 - temps[last]))
    };
    if let SurfaceMode::Held(_) = mode {
        fluxes.held_surface_j_m2 = c[0] * (p[0] - temps[0]) - weighted(0, p, temps);
    }
    fluxes.stored_change_j_m2 = stored;
    temps.copy_from_slice(p);
    Ok(fluxes)
}

/// The surface terms of a step, weighted by the scheme, from the surface's loads and what
/// leaves it at the step's end and (Crank–Nicolson) start.
fn account_surface(
    fluxes: &mut StepFluxes,
    (at1, end): (&SurfaceAt, &SurfaceParts),
    start: Option<&(SurfaceAt, SurfaceParts)>,
    theta: f64,
    dt_s: f64,
) {
    let w = dt_s * theta;
    fluxes.absorbed_shortwave_j_m2 = w * at1.absorbed_shortwave_w_m2();
    fluxes.absorbed_longwave_j_m2 = w * at1.absorbed_longwave_w_m2();
    fluxes.emitted_j_m2 = w * end.emitted;
    fluxes.convected_j_m2 = w * end.convected;
    fluxes.latent_j_m2 = w * end.latent;
    if let Some((at0, start)) = start {
        let w = dt_s * (1.0 - theta);
        fluxes.absorbed_shortwave_j_m2 += w * at0.absorbed_shortwave_w_m2();
        fluxes.absorbed_longwave_j_m2 += w * at0.absorbed_longwave_w_m2();
        fluxes.emitted_j_m2 += w * start.emitted;
        fluxes.convected_j_m2 += w * start.convected;
        fluxes.latent_j_m2 += w * start.latent;
    }
}

/// Solves `d0 T − θ q(T) = r` for the surface temperature, from `guess`; returns it with
/// what leaves the surface there.
///
/// `f(T) = d0 T − θ q(T) − r` increases with `T` (`d0 > 0`, and every term of `−q` does
/// not decrease), so its root is bracketed by 1 K and 5000 K whenever it is physical. Each
/// evaluation narrows the bracket by the sign of `f`; a Newton step that leaves the bracket
/// (or a derivative that is not positive, possible only within a hair of `T_air` under
/// DOE-2 with condensation) is replaced by bisection. Newton's method stops once its step
/// is below [`SURFACE_TOLERANCE_K`], or once the error left after its step, estimated from
/// the quadratic convergence of the last two steps (`e ≈ δ_k³ / δ_{k−1}²`, trusted only
/// when the steps shrink at least tenfold), is a hundred times below it. The parts
/// returned are those at the last evaluation carried to the root by their derivatives:
/// exactly what the last Newton step solved, so the step's energy closes to round-off;
/// they differ from a fresh evaluation by `O(δ²)`.
fn solve_surface(
    d0: f64,
    theta: f64,
    r: f64,
    at: &SurfaceAt,
    guess: f64,
) -> Result<(f64, SurfaceParts), ThermalErrorKind> {
    let mut lo = MIN_TEMPERATURE_K;
    let mut hi = MAX_TEMPERATURE_K;
    let mut t = if guess.is_finite() {
        guess.clamp(lo, hi)
    } else {
        300.0
    };
    let absorbed = at.absorbed_w_m2();
    let mut previous_step = f64::INFINITY;
    for _ in 0..MAX_ITERATIONS {
        let parts = at.parts(t);
        let f = d0 * t - theta * (absorbed - parts.leaving()) - r;
        if f < 0.0 {
            lo = t;
        } else if f > 0.0 {
            hi = t;
        } else if f == 0.0 {
            return check_bracket(t).map(|t| (t, parts));
        } else {
            return Err(ThermalErrorKind::NotConverged);
        }
        let slope = d0 + theta * parts.d_leaving();
        let delta = -f / slope;
        let newton = t + delta;
        if slope > 0.0 && newton > lo && newton < hi {
            let size = delta.abs();
            let quadratic = previous_step.is_finite()
                && size < 0.1 * previous_step
                && size * size * size <= 0.01 * SURFACE_TOLERANCE_K * previous_step * previous_step;
            if size <= SURFACE_TOLERANCE_K || quadratic {
                return check_bracket(newton).map(|t| (t, parts.extrapolated(delta)));
            }
            previous_step = size;
            t = newton;
        } else {
            let mid = 0.5 * (lo + hi);
            if hi - lo <= 2.0 * SURFACE_TOLERANCE_K {
                return check_bracket(mid).map(|m| (m, parts.extrapolated(m - t)));
            }
            previous_step = f64::INFINITY;
            t = mid;
        }
    }
    Err(ThermalErrorKind::NotConverged)
}

/// A root pinned against the bracket's ends is not a root: the balance lies outside
/// 1–5000 K.
fn check_bracket(t: f64) -> Result<f64, ThermalErrorKind> {
    if t - MIN_TEMPERATURE_K < 1e-6 || MAX_TEMPERATURE_K - t < 1e-6 {
        Err(ThermalErrorKind::OutOfRange)
    } else {
        Ok(t)
    }
}

fn surface_error(
    kind: ThermalErrorKind,
    surface: &Surface,
    orientation: Orientation,
    temps: &[f64],
    after: &Loads,
    time_step: TimeStep,
) -> ThermalError {
    let what = match kind {
        ThermalErrorKind::OutOfRange if time_step.scheme == Scheme::CrankNicolson => format!(
            "the surface balance has no root between {MIN_TEMPERATURE_K} and \
             {MAX_TEMPERATURE_K} K (the trapezoidal rule's explicit half, Crank–Nicolson's \
             or TR-BDF2's first stage's, overshoots when the surface's fluxes change this \
             steeply over a step this long; Backward Euler or a shorter step keeps the \
             temperature physical)"
        ),
        ThermalErrorKind::OutOfRange => format!(
            "the surface balance has no root between {MIN_TEMPERATURE_K} and \
             {MAX_TEMPERATURE_K} K"
        ),
        _ => format!("the surface balance did not converge in {MAX_ITERATIONS} iterations"),
    };
    ThermalError::new(
        kind,
        format!(
            "{what}: surface {surface:?}, {orientation:?}, loads at the step's end {after:?}, \
             {time_step:?}, surface at the step's start {} K, back node {} K",
            temps[0],
            temps[temps.len() - 1]
        ),
    )
}

fn out_of_range(new: &[f64], old: &[f64], after: &Loads) -> ThermalError {
    let (i, t) = new
        .iter()
        .copied()
        .enumerate()
        .find(|(_, t)| !(MIN_TEMPERATURE_K..=MAX_TEMPERATURE_K).contains(t))
        .unwrap_or((0, f64::NAN));
    ThermalError::new(
        ThermalErrorKind::OutOfRange,
        format!(
            "node {i} would reach {t} K (from {} K), outside {MIN_TEMPERATURE_K}–\
             {MAX_TEMPERATURE_K} K; loads at the step's end {after:?}",
            old.get(i).copied().unwrap_or(f64::NAN)
        ),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Convection, Discretisation};
    use irsig_model::thermal::{Roughness, ThermalLayer, ThermalProperties};

    fn wall(thickness_m: f64) -> Wall {
        let props = ThermalProperties {
            layers: vec![ThermalLayer {
                thickness_m,
                conductivity_w_m_k: 1.4,
                density_kg_m3: 2300.0,
                specific_heat_j_kg_k: 880.0,
                source: "test".into(),
            }],
            back: BackBoundary::Adiabatic,
            solar_absorptance: None,
            thermal_emissivity: None,
            wet_fraction: 0.0,
            roughness: Roughness::Rough,
            source: "test".into(),
        };
        Wall::new(&props, &Discretisation::cells_per_layer(4)).unwrap()
    }

    /// One scratch shared by more walls, steps and schemes than it keeps gives bit for bit
    /// what a fresh scratch per facet gives.
    #[test]
    fn a_shared_scratch_evicts_and_recomputes_correctly() {
        let walls: Vec<Wall> = (1..=20).map(|i| wall(0.01 * f64::from(i))).collect();
        let surface = Surface {
            solar_absorptance: 0.7,
            thermal_emissivity: 0.9,
            wet_fraction: 0.0,
            roughness: Roughness::Rough,
            convection: Convection::Doe2,
        };
        let loads = Loads {
            shortwave_w_m2: 700.0,
            longwave_w_m2: 340.0,
            air_temperature_k: 300.0,
            dew_point_k: 285.0,
            pressure_pa: 101_325.0,
            wind_speed_m_s: 2.0,
            source_w_m2: 0.0,
        };
        let mut shared = Scratch::new();
        let mut temps_shared: Vec<Vec<f64>> =
            walls.iter().map(|w| w.uniform_state(290.0)).collect();
        let mut temps_fresh = temps_shared.clone();
        for round in 0..3 {
            for (i, w) in walls.iter().enumerate() {
                let time_step = TimeStep {
                    dt_s: [60.0, 300.0][(i + round) % 2],
                    scheme: [Scheme::BackwardEuler, Scheme::CrankNicolson][i % 2],
                };
                let facet = Facet {
                    wall: w,
                    surface: &surface,
                    orientation: Orientation {
                        cos_tilt: 0.5,
                        windward: i % 3 == 0,
                    },
                };
                let a = step(
                    &facet,
                    &mut temps_shared[i],
                    &loads,
                    &loads,
                    time_step,
                    &mut shared,
                )
                .unwrap();
                let b = step(
                    &facet,
                    &mut temps_fresh[i],
                    &loads,
                    &loads,
                    time_step,
                    &mut Scratch::new(),
                )
                .unwrap();
                assert_eq!(a, b);
                assert!(
                    temps_shared[i]
                        .iter()
                        .zip(&temps_fresh[i])
                        .all(|(x, y)| x.to_bits() == y.to_bits())
                );
            }
        }
        assert_eq!(shared.cache.len(), CACHE_CAPACITY);
    }
}
