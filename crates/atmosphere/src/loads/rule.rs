//! The hemisphere quadratures of the broadband loads: which lines of sight LOWTRAN7 runs,
//! and with what weights their radiances sum to an irradiance on a horizontal surface,
//! `E = ∫ L cos θ dΩ` over the sky.
//!
//! **Longwave.** The sky's thermal radiance depends on the zenith angle alone and rises
//! smoothly toward the horizon: Gauss–Legendre in `μ = cos θ` on [0, 1],
//! `E = 2π ∫ L μ dμ ≈ Σ 2π wᵢ μᵢ L(θᵢ)`.
//!
//! **Diffuse sunlight.** The scattered sky is bright around the sun (the aerosols' forward
//! peak: LOWTRAN7's rural sky is ten times brighter 0.5° from the sun than 6° away) and
//! toward the horizon. A zenith × azimuth grid samples that peak wherever its nodes happen
//! to fall (a 16 × 19 grid was still 0.9 % off, docs/accuracy.md), so the rule is
//! centred on the sun: rings of scattering angle `Θ` about the sun, and on each ring the
//! azimuth `ψ` about the sun from the sun's vertical plane toward the zenith. The ring's
//! part above the horizon is `ψ ∈ [0, ψ_max(Θ)]`, `cos ψ_max = −cot z cot Θ` (the line of
//! sight's `cos θ = cos z cos Θ + sin z sin Θ cos ψ` falls to 0 there), so the rule covers
//! the upper hemisphere exactly and the integrand is smooth on every ring. The rings are
//! cut at the aureole's edges ([`DiffuseRule::aureole_edges_deg`]), where the ring first
//! touches the horizon (`Θ = 90° − z`) and where it leaves it (`Θ = 90° + z`), with
//! Gauss–Legendre nodes in `Θ` on each piece and in `ψ` on each ring:
//!
//! `DHI = ∫ L cos θ dΩ = 2 ∫₀^{90°+z} sin Θ dΘ ∫₀^{ψ_max(Θ)} L(Θ, ψ) cos θ dψ`,
//!
//! the factor 2 the sky's symmetry about the sun's vertical plane. A node's line of sight is
//! its zenith angle θ and its azimuth from the sun's, `cos φ = (cos Θ − cos z cos θ) /
//! (sin z sin θ)`, what LOWTRAN7's card 3A2 takes (PARM1 = φ, PARM2 = z).

use crate::plan::{gauss_legendre_01, round3};

/// The sun-centred rule of the diffuse sky (see the module's page): how many nodes it puts
/// where.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DiffuseRule {
    /// The aureole's rings end at these scattering angles, degrees from the sun,
    /// increasing: the rings inside each are one piece.
    pub aureole_edges_deg: [f64; 2],
    /// Gauss nodes in scattering angle on each aureole piece.
    pub aureole_nodes: usize,
    /// Gauss nodes in azimuth about the sun on an aureole ring wholly above the horizon.
    pub aureole_azimuth_nodes: usize,
    /// Outside the aureole: one Gauss node in scattering angle per this many degrees of a
    /// piece (at least two per piece).
    pub sky_degrees_per_node: f64,
    /// Gauss nodes in azimuth about the sun on every other ring.
    pub sky_azimuth_nodes: usize,
}

impl DiffuseRule {
    /// The rule a loads plan takes: 9 lines of sight for a sun at the zenith, 40 at 30°,
    /// 52 at 60°, 64 at 80°, at most 66 (89°); within 0.07 % of a rule of 60–950 lines of
    /// sight for the sun at 0–80°, 0.14 % at 88° (docs/accuracy.md, "Broadband loads").
    pub const DEFAULT: Self = Self {
        aureole_edges_deg: [2.0, 15.0],
        aureole_nodes: 2,
        aureole_azimuth_nodes: 3,
        sky_degrees_per_node: 15.0,
        sky_azimuth_nodes: 4,
    };

    /// This rule with `factor` times the nodes in every direction (the test of a rule
    /// against a finer one).
    #[must_use]
    pub fn refined(self, factor: usize) -> Self {
        Self {
            aureole_nodes: self.aureole_nodes * factor,
            aureole_azimuth_nodes: self.aureole_azimuth_nodes * factor,
            sky_degrees_per_node: self.sky_degrees_per_node / factor as f64,
            sky_azimuth_nodes: self.sky_azimuth_nodes * factor,
            ..self
        }
    }
}

/// Gauss–Legendre nodes and weights on `[a, b]`.
fn gauss(a: f64, b: f64, n: usize) -> impl Iterator<Item = (f64, f64)> {
    gauss_legendre_01(n)
        .into_iter()
        .map(move |(x, w)| (a + (b - a) * x, (b - a) * w))
}

/// The longwave rule: `n` Gauss–Legendre nodes in cos θ, as `(zenith_deg, weight_sr)`
/// with `E = Σ weight · L(zenith)`, zenith angles rounded to the 0.001° a deck holds,
/// increasing. The weights sum to π.
#[must_use]
pub fn longwave_nodes(n: usize) -> Vec<(f64, f64)> {
    let mut out: Vec<(f64, f64)> = gauss_legendre_01(n)
        .into_iter()
        .map(|(mu, w)| {
            (
                round3(mu.acos().to_degrees()),
                2.0 * std::f64::consts::PI * w * mu,
            )
        })
        .collect();
    out.sort_by(|a, b| a.0.total_cmp(&b.0));
    out
}

/// The pieces of scattering angle, degrees, for a sun at `zenith_deg`: from 0 to the
/// last ring above the horizon, cut at the aureole's edges and at 90° − z; edges closer
/// than 0.5° are one.
fn pieces(zenith_deg: f64, rule: &DiffuseRule) -> Vec<f64> {
    let top = if zenith_deg > 0.0 {
        90.0 + zenith_deg
    } else {
        90.0
    };
    let mut cuts: Vec<f64> = rule
        .aureole_edges_deg
        .iter()
        .copied()
        .chain([90.0 - zenith_deg])
        .filter(|&x| x > 0.0 && x < top)
        .collect();
    cuts.sort_by(f64::total_cmp);
    let mut edges = vec![0.0];
    for x in cuts {
        if x - edges[edges.len() - 1] >= 0.5 && top - x >= 0.5 {
            edges.push(x);
        }
    }
    edges.push(top);
    edges
}

/// The diffuse rule's lines of sight for a sun at `zenith_deg` (0 to below 90), as
/// `(zenith_deg, azimuth_deg from the sun's, weight_sr)`, angles rounded to the 0.001° a
/// deck holds, by zenith angle then azimuth, with `DHI = Σ weight · L`. The weights sum
/// to π within 2·10⁻⁴ for any sun (the pieces that end where a ring touches the horizon
/// are not quite polynomial).
#[must_use]
pub fn diffuse_nodes(zenith_deg: f64, rule: &DiffuseRule) -> Vec<(f64, f64, f64)> {
    let z = zenith_deg.to_radians();
    let (sin_z, cos_z) = z.sin_cos();
    let horizon = 90.0 - zenith_deg;
    let edges = pieces(zenith_deg, rule);
    let mut out = Vec::new();
    for w in edges.windows(2) {
        let (a, b) = (w[0], w[1]);
        let aureole = b <= rule.aureole_edges_deg[1] + 1e-9;
        let above = b <= horizon + 1e-9;
        let n_theta = if aureole {
            rule.aureole_nodes
        } else {
            // Whole nodes: a piece 40° wide at 15° a node takes 3.
            #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
            let n = ((b - a) / rule.sky_degrees_per_node).ceil() as usize;
            n.max(2)
        };
        let n_psi = if zenith_deg == 0.0 {
            // Every ring about a sun at the zenith is one zenith angle: no azimuth.
            1
        } else if aureole && above {
            rule.aureole_azimuth_nodes
        } else {
            rule.sky_azimuth_nodes
        };
        for (t, wt) in gauss(a.to_radians(), b.to_radians(), n_theta) {
            let (sin_t, cos_t) = t.sin_cos();
            let psi_max = if zenith_deg == 0.0 {
                std::f64::consts::PI
            } else {
                let c = -cos_z * cos_t / (sin_z * sin_t);
                if c <= -1.0 {
                    std::f64::consts::PI
                } else if c >= 1.0 {
                    0.0
                } else {
                    c.acos()
                }
            };
            if psi_max <= 0.0 {
                continue;
            }
            for (p, wp) in gauss(0.0, psi_max, n_psi) {
                let mu = (cos_z * cos_t + sin_z * sin_t * p.cos()).clamp(0.0, 1.0);
                let theta = mu.acos();
                let azimuth = if zenith_deg == 0.0 || theta.sin() < 1e-12 {
                    0.0
                } else {
                    ((cos_t - cos_z * mu) / (sin_z * theta.sin()))
                        .clamp(-1.0, 1.0)
                        .acos()
                };
                let weight = 2.0 * wt * sin_t * wp * mu;
                if weight > 0.0 {
                    out.push((
                        round3(theta.to_degrees()),
                        round3(azimuth.to_degrees()),
                        weight,
                    ));
                }
            }
        }
    }
    out.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn the_longwave_rule_integrates_the_cosine_weighted_hemisphere() {
        let nodes = longwave_nodes(8);
        assert_eq!(nodes.len(), 8);
        let sum: f64 = nodes.iter().map(|n| n.1).sum();
        // A uniform sky L gives π L (to the deck's rounding of the angles: none in the
        // weights).
        assert!((sum / PI - 1.0).abs() < 1e-13, "{sum}");
        // L = cos θ: ∫ μ² dΩ = 2π/3, exact for Gauss (the nodes' 0.001° rounding moves
        // cos θ by at most 9e-6).
        let mu2: f64 = nodes.iter().map(|n| n.1 * n.0.to_radians().cos()).sum();
        assert!((mu2 / (2.0 * PI / 3.0) - 1.0).abs() < 2e-5, "{mu2}");
        assert!(nodes.windows(2).all(|w| w[0].0 < w[1].0));
        assert!(nodes.iter().all(|n| n.0 > 0.0 && n.0 < 90.0));
    }

    /// A sky like LOWTRAN7's: an aureole that falls by ten in a few degrees, a floor that
    /// brightens toward the horizon and, the lower the sun, with the azimuth toward it (a
    /// sun at the zenith has no azimuth).
    fn sky(sun_deg: f64, theta: f64, phi: f64) -> f64 {
        let (z, t, p) = (sun_deg.to_radians(), theta, phi);
        let cos_s = (z.cos() * t.cos() + z.sin() * t.sin() * p.cos()).clamp(-1.0, 1.0);
        let s = cos_s.acos().to_degrees();
        1.0 + 30.0 / (1.0 + s / 0.8) + 2.0 * (-t.cos() / 0.15).exp() + 0.3 * z.sin() * p.cos()
    }

    /// The brute-force integral of `sky` over the upper hemisphere: the midpoint rule on
    /// a zenith × azimuth grid of `n` × `2n` cells, with the sun's cell refined.
    fn brute_force(sun_deg: f64, n: usize) -> f64 {
        let (dt, dp) = (0.5 * PI / n as f64, PI / (2 * n) as f64);
        let mut sum = 0.0;
        for i in 0..n {
            let t = (i as f64 + 0.5) * dt;
            for j in 0..2 * n {
                let p = (j as f64 + 0.5) * dp;
                sum += sky(sun_deg, t, p) * t.cos() * t.sin() * dt * dp;
            }
        }
        2.0 * sum
    }

    fn by_rule(sun_deg: f64, rule: &DiffuseRule) -> f64 {
        diffuse_nodes(sun_deg, rule)
            .iter()
            .map(|&(t, p, w)| w * sky(sun_deg, t.to_radians(), p.to_radians()))
            .sum()
    }

    #[test]
    fn the_diffuse_rule_covers_the_upper_hemisphere_for_any_sun() {
        for z in [
            0.0, 0.4, 5.0, 30.0, 45.0, 60.0, 75.0, 74.8, 80.0, 88.0, 89.5, 89.999,
        ] {
            let nodes = diffuse_nodes(z, &DiffuseRule::DEFAULT);
            let sum: f64 = nodes.iter().map(|n| n.2).sum();
            assert!((sum / PI - 1.0).abs() < 2e-4, "sun at {z}: {sum}");
            for &(t, p, w) in &nodes {
                assert!((0.0..=90.0).contains(&t) && (0.0..=180.0).contains(&p) && w > 0.0);
            }
        }
        // A sun at the zenith needs no azimuth: one line of sight per ring.
        assert_eq!(diffuse_nodes(0.0, &DiffuseRule::DEFAULT).len(), 9);
        assert_eq!(diffuse_nodes(30.0, &DiffuseRule::DEFAULT).len(), 40);
        assert_eq!(diffuse_nodes(60.0, &DiffuseRule::DEFAULT).len(), 52);
        assert_eq!(diffuse_nodes(80.0, &DiffuseRule::DEFAULT).len(), 64);
        // Every sun, 0.1° apart up to the last a deck holds: never more than 66.
        let most = (0..900)
            .map(|k| f64::from(k) * 0.1)
            .chain([89.95, 89.999])
            .map(|z| diffuse_nodes(z, &DiffuseRule::DEFAULT).len())
            .max();
        assert_eq!(most, Some(66));
        // The ring through the sun's azimuth toward it: a node 1° from the sun lies in
        // the sun's vertical plane on the sun's side.
        let near = diffuse_nodes(30.0, &DiffuseRule::DEFAULT)
            .into_iter()
            .find(|n| (n.0 - 30.0).abs() < 1.0 && n.1 < 10.0);
        assert!(near.is_some(), "no node in the aureole toward the sun");
    }

    #[test]
    fn the_diffuse_rule_follows_a_sharp_aureole_to_a_tenth_of_a_percent() {
        for z in [0.0, 30.0, 60.0, 80.0, 88.0] {
            let exact = brute_force(z, 1800);
            let got = by_rule(z, &DiffuseRule::DEFAULT);
            let fine = by_rule(z, &DiffuseRule::DEFAULT.refined(4));
            assert!(
                (got / exact - 1.0).abs() < 2e-3,
                "sun at {z}: rule {got}, brute force {exact}"
            );
            assert!(
                (fine / exact - 1.0).abs() < 3e-4,
                "sun at {z}: fine rule {fine}, brute force {exact}"
            );
        }
    }
}
