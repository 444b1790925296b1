//! The error budget (thesis §5.1): each declared uncertainty of the inputs propagated to
//! the apparent temperature, pixel by pixel, through the radiance equation's partial
//! derivatives, and the residual of the models the tolerance pilot chose
//! ([`crate::guarantee`]).
//!
//! Each declaration is one input, fully correlated over the facets it governs (every
//! facet of a material, of an object or of the scene off by the same error): a pixel's
//! σ is `σ_pixel² = Σ_inputs (Σ_rays ∂L/∂x_input / n)²·σ_input²` (GUM §5.2, the law of
//! propagation with correlated inputs kept together), its partials charged by the tracer
//! to the facets each ray's events met ([`irsig_tracer::charge`]).

use std::collections::HashMap;

use irsig_model::RawScene;
use irsig_model::truth::Layer;
use irsig_model::uncertainty::Uncertainties;
use irsig_radiometry::BandModel;
use irsig_tracer::{Charge, Frame, NO_GROUP};
use rayon::prelude::*;

/// The error budget of a run: the declared uncertainties and the scene they name facets
/// of.
#[derive(Debug)]
pub struct Budget<'a> {
    /// The declared uncertainties.
    pub uncertainties: &'a Uncertainties,
    /// The scene whose facets they name.
    pub scene: &'a RawScene,
}

/// The inputs a group of facets answers to: the index of the temperature entry and of the
/// emissivity entry that govern it.
type Inputs = (Option<usize>, Option<usize>);

impl Budget<'_> {
    /// Each facet's group and each group's inputs: facets governed by the same temperature
    /// entry and the same emissivity entry share a group, numbered in the order of their
    /// first facet; a facet governed by neither is in [`NO_GROUP`].
    fn grouping(&self) -> (Vec<u32>, Vec<Inputs>) {
        let u = self.uncertainties;
        let mut inputs: Vec<Inputs> = Vec::new();
        let mut index: HashMap<Inputs, u32> = HashMap::new();
        let groups = self
            .scene
            .facets
            .iter()
            .map(|facet| {
                let object = self
                    .scene
                    .objects
                    .get(facet.object as usize)
                    .map_or("", String::as_str);
                let key = (
                    u.temperature_entry(facet.material, object),
                    u.emissivity_entry(facet.material),
                );
                if key == (None, None) {
                    return NO_GROUP;
                }
                *index.entry(key).or_insert_with(|| {
                    inputs.push(key);
                    (inputs.len() - 1) as u32
                })
            })
            .collect();
        (groups, inputs)
    }

    /// Each raw-scene facet's input group, for [`irsig_tracer::Tracer::with_budget_groups`]:
    /// what the tracer charges each ray's partials to.
    #[must_use]
    pub fn groups(&self) -> Vec<u32> {
        self.grouping().0
    }

    /// The σ layers ([`Layer::BUDGET`]), K: each declared uncertainty propagated to the
    /// apparent temperature through the radiance equation's partial derivatives at the
    /// pixel (`∂L/∂T = Σ τ·ε·dL_T/dT`, `∂L/∂ε = Σ τ·(L_T − L_reflected)` over the events of
    /// the facets the declaration governs, `∂L/∂τ = L − L_u` for a relative σ of τ, `L_u`
    /// for a relative σ of the path radiance), over the band's dL/dT at the pixel's
    /// apparent temperature; the models' σ at each pixel, `model_k` (0 without a
    /// tolerance); and their root-sum-square, with the atmosphere data's error of the
    /// pixel ([`Frame::data_error_k`], a bound, as σ = bound/√3) where the frame holds it.
    /// The partials are the means over the pixel's rays ([`Frame::charges`], which the tracer keeps when given [`Self::groups`]);
    /// without them, the centre ray's facet answers for the whole pixel.
    #[must_use]
    pub fn layers<R: BandModel + Sync>(
        &self,
        band: &R,
        frame: &Frame,
        apparent: &[f64],
        model_k: Option<&[f64]>,
    ) -> Vec<(Layer, Vec<f32>)> {
        let u = self.uncertainties;
        let inputs = if frame.charges.is_empty() {
            Vec::new()
        } else {
            self.grouping().1
        };
        let per_pixel: Vec<[f64; 5]> = frame
            .truth
            .par_iter()
            .zip(&frame.radiance_w_m2_sr)
            .zip(apparent)
            .enumerate()
            .map(|(i, ((p, &l), &t))| {
                let slope = band.radiance_derivative(t);
                let in_k = |sigma_l: f64| {
                    if slope > 0.0 && sigma_l.is_finite() {
                        sigma_l.abs() / slope
                    } else {
                        0.0
                    }
                };
                let (temperature, emissivity) = if frame.charges.is_empty() {
                    self.centre_sigmas_w_m2_sr(p.facet, p)
                } else {
                    let charges = frame.charges.pixel(i);
                    let input = |c: &Charge| inputs.get(c.group as usize).copied();
                    (
                        correlated_sigma(
                            charges,
                            |c| input(c).and_then(|k| k.0),
                            |c| c.temperature_sensitivity,
                            |e| u.temperature.get(e).map_or(0.0, |d| d.sigma_k),
                        ),
                        correlated_sigma(
                            charges,
                            |c| input(c).and_then(|k| k.1),
                            |c| c.emissivity_sensitivity,
                            |e| u.emissivity.get(e).map_or(0.0, |d| d.sigma),
                        ),
                    )
                };
                // A refined pixel's path radiance is its rays' mean.
                let path = match frame.sampling.get(i) {
                    Some(s) if s.rays > 1 => s.path_radiance_w_m2_sr,
                    _ => p.path_radiance_w_m2_sr,
                };
                let path = f64::from(path);
                let path = if path.is_finite() { path } else { 0.0 };
                [
                    in_k(temperature),
                    in_k(emissivity),
                    in_k(u.transmission_relative * (l - path)),
                    in_k(u.path_radiance_relative * path),
                    model_k.and_then(|m| m.get(i)).copied().unwrap_or(0.0),
                ]
            })
            .collect();
        let mut out: Vec<(Layer, Vec<f32>)> = Layer::BUDGET[..5]
            .iter()
            .enumerate()
            .map(|(k, &layer)| (layer, per_pixel.iter().map(|s| s[k] as f32).collect()))
            .collect();
        // The atmosphere data's error is a bound (the largest error measured), not a σ:
        // taken as the half-width of a uniform distribution, its σ is bound/√3 (GUM
        // §4.3.7). A pixel without a number adds nothing (the frame says why).
        let data_sigma = |i: usize| {
            frame
                .data_error_k
                .get(i)
                .map(|&b| f64::from(b))
                .filter(|b| b.is_finite())
                .map_or(0.0, |b| b / 3.0_f64.sqrt())
        };
        out.push((
            Layer::SigmaTotal,
            per_pixel
                .iter()
                .enumerate()
                .map(|(i, s)| {
                    let data = data_sigma(i);
                    (s.iter().map(|v| v * v).sum::<f64>() + data * data).sqrt() as f32
                })
                .collect(),
        ));
        out
    }

    /// The temperature and emissivity σ of radiance, W m⁻² sr⁻¹, of a pixel from its
    /// centre ray alone (a frame traced without charges): its facet's σ times its partials.
    fn centre_sigmas_w_m2_sr(&self, facet: u32, p: &irsig_tracer::TruthPixel) -> (f64, f64) {
        let u = self.uncertainties;
        let Some(facet) = self.scene.facets.get(facet as usize) else {
            return (0.0, 0.0);
        };
        let object = self
            .scene
            .objects
            .get(facet.object as usize)
            .map_or("", String::as_str);
        (
            f64::from(p.temperature_sensitivity) * u.temperature_sigma_k(facet.material, object),
            f64::from(p.emissivity_sensitivity) * u.emissivity_sigma(facet.material),
        )
    }
}

/// `sqrt(Σ_inputs (Σ_charges of the input ∂L/∂x)²·σ²)`: the charges of one pixel summed per
/// input (`input` of a charge; `None`: answers to no declaration of this kind) before
/// squaring, since the facets of one declaration are off together. A pixel meets few
/// groups, so the quadratic scan costs less than a map.
fn correlated_sigma(
    charges: &[Charge],
    input: impl Fn(&Charge) -> Option<usize>,
    sensitivity: impl Fn(&Charge) -> f32,
    sigma: impl Fn(usize) -> f64,
) -> f64 {
    let mut variance = 0.0;
    for (k, c) in charges.iter().enumerate() {
        let Some(key) = input(c) else { continue };
        // Each input once, at its first charge.
        if charges[..k].iter().any(|d| input(d) == Some(key)) {
            continue;
        }
        let sum: f64 = charges[k..]
            .iter()
            .filter(|d| input(d) == Some(key))
            .map(|d| f64::from(sensitivity(d)))
            .sum();
        variance += (sum * sigma(key)).powi(2);
    }
    variance.sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;
    use irsig_model::uncertainty::{EmissivityUncertainty, Facets, TemperatureUncertainty};
    use irsig_model::{MaterialId, RawFacet};
    use irsig_radiometry::Band;
    use irsig_tracer::{Charges, Event, TruthPixel};

    fn facet(material: u16, object: u32) -> RawFacet {
        RawFacet {
            vertices: [0, 1, 2],
            material: MaterialId(material),
            temperature_k: 300.0,
            object,
            uv: None,
        }
    }

    /// One pixel of apparent temperature 300 K whose centre met facet 0, with `charges`.
    fn layers(u: &Uncertainties, scene: &RawScene, charges: &[Charge]) -> Vec<f64> {
        layers_with_data(u, scene, charges, Vec::new())
    }

    /// [`layers`] with the frame's atmosphere-data layer `data_error_k`.
    fn layers_with_data(
        u: &Uncertainties,
        scene: &RawScene,
        charges: &[Charge],
        data_error_k: Vec<f32>,
    ) -> Vec<f64> {
        let truth = TruthPixel {
            event: Event::Diffuse,
            primary_material: 1,
            secondary_material: 0,
            range_m: 10.0,
            cos_incidence: 1.0,
            temperature_k: 300.0,
            emissivity: 0.9,
            transmission: 1.0,
            path_radiance_w_m2_sr: 0.0,
            sky_view_factor: 1.0,
            facet: 0,
            temperature_sensitivity: 1.0,
            emissivity_sensitivity: 1.0,
        };
        let mut c = Charges::default();
        c.push(charges, 64);
        let frame = Frame {
            width: 1,
            height: 1,
            radiance_w_m2_sr: vec![10.0],
            truth: vec![truth],
            sampling: Vec::new(),
            sun: Vec::new(),
            texture: Vec::new(),
            data_error_k,
            charges: c,
        };
        let budget = Budget {
            uncertainties: u,
            scene,
        };
        budget
            .layers(&Band::default(), &frame, &[300.0], None)
            .into_iter()
            .map(|(_, v)| f64::from(v[0]))
            .collect()
    }

    #[test]
    fn the_atmosphere_datas_bound_joins_the_total_as_a_uniform_sigma() {
        let scene = RawScene {
            facets: vec![facet(1, 0)],
            objects: vec!["a".into()],
            ..RawScene::default()
        };
        let u = Uncertainties::default();
        // Nothing declared: the total is the data's alone, a 0.3·√3 K bound's σ = 0.3 K.
        let bound = (0.3 * 3.0_f64.sqrt()) as f32;
        let with = layers_with_data(&u, &scene, &[], vec![bound]);
        assert!((with[5] - 0.3).abs() < 1e-6, "{with:?}");
        assert!(with[..5].iter().all(|&s| s.abs() < 1e-12), "{with:?}");
        // A pixel with no number (NaN) adds nothing.
        let nan = layers_with_data(&u, &scene, &[], vec![f32::NAN]);
        assert!(nan[5].abs() < 1e-12, "{nan:?}");
    }

    fn charge(group: u32, temperature: f32, emissivity: f32) -> Charge {
        Charge {
            group,
            temperature_sensitivity: temperature,
            emissivity_sensitivity: emissivity,
        }
    }

    #[test]
    fn a_pixel_part_stone_gets_that_part_of_stones_sigma_whatever_its_centre_met() {
        // Facets 0 and 1 stone (objects 0 and 1), facet 2 paint: stone's temperature
        // and emissivity declared, paint's temperature under the whole-scene entry.
        let scene = RawScene {
            facets: vec![facet(1, 0), facet(1, 1), facet(2, 0)],
            objects: vec!["a".into(), "b".into()],
            ..RawScene::default()
        };
        let u = Uncertainties {
            temperature: vec![
                TemperatureUncertainty {
                    facets: Facets::All,
                    sigma_k: 0.5,
                },
                TemperatureUncertainty {
                    facets: Facets::Material(MaterialId(1)),
                    sigma_k: 2.0,
                },
            ],
            emissivity: vec![EmissivityUncertainty {
                material: MaterialId(1),
                sigma: 0.02,
            }],
            ..Uncertainties::default()
        };
        let budget = Budget {
            uncertainties: &u,
            scene: &scene,
        };
        // Both stone facets answer to the same entries: one group, one input.
        assert_eq!(budget.groups(), [0, 0, 1]);
        let slope = Band::default().radiance_derivative(300.0);
        // 30 % of the rays met stone (∂L/∂T 0.3 × 0.06), 70 % paint (0.7 × 0.05).
        let (stone, paint) = (0.3 * 0.06, 0.7 * 0.05);
        let got = layers(
            &u,
            &scene,
            &[charge(1, paint as f32, 0.0), charge(0, stone as f32, 3.0)],
        );
        let t_expected = ((stone * 2.0_f64).powi(2) + (paint * 0.5_f64).powi(2)).sqrt() / slope;
        assert!(
            (got[0] / t_expected - 1.0).abs() < 1e-6,
            "{} against {t_expected}",
            got[0]
        );
        let e_expected = 3.0 * 0.02 / slope;
        assert!(
            (got[1] / e_expected - 1.0).abs() < 1e-6,
            "{} against {e_expected}",
            got[1]
        );
        // A pixel of paint alone whose centre met stone gets nothing of stone's σ.
        let got = layers(&u, &scene, &[charge(1, 0.05, 0.0)]);
        assert!((got[0] / (0.05 * 0.5 / slope) - 1.0).abs() < 1e-6);
        assert!(got[1] == 0.0);
    }

    #[test]
    fn groups_under_one_declaration_move_together() {
        // Every facet's temperature under one entry; stone and paint differ in ε's
        // entries, so they are two groups of one temperature input: their partials add
        // before the σ (2 + 1, not the root-sum-square of 2 and 1), and cancel where
        // opposite.
        let scene = RawScene {
            facets: vec![facet(1, 0), facet(2, 0)],
            objects: vec!["a".into()],
            ..RawScene::default()
        };
        let u = Uncertainties {
            temperature: vec![TemperatureUncertainty {
                facets: Facets::All,
                sigma_k: 1.0,
            }],
            emissivity: vec![EmissivityUncertainty {
                material: MaterialId(2),
                sigma: 0.01,
            }],
            ..Uncertainties::default()
        };
        let slope = Band::default().radiance_derivative(300.0);
        let got = layers(&u, &scene, &[charge(0, 2.0, 0.0), charge(1, 1.0, 0.0)]);
        assert!(
            (got[0] * slope / 3.0 - 1.0).abs() < 1e-6,
            "{}",
            got[0] * slope
        );
        let got = layers(&u, &scene, &[charge(0, 2.0, 0.0), charge(1, -2.0, 0.0)]);
        assert!(got[0].abs() < 1e-12);
        // No declaration at all: no group, nothing charged.
        let none = Budget {
            uncertainties: &Uncertainties::default(),
            scene: &scene,
        };
        assert_eq!(none.groups(), [NO_GROUP, NO_GROUP]);
    }
}
