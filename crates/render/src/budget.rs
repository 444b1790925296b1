//! The error budget (thesis §5.1): each declared uncertainty of the inputs propagated to
//! the apparent temperature, pixel by pixel, through the radiance equation's partial
//! derivatives, and the residual of the models the tolerance pilot chose.

use irsig_model::RawScene;
use irsig_model::truth::Layer;
use irsig_model::uncertainty::Uncertainties;
use irsig_radiometry::BandModel;
use irsig_tracer::Frame;
use rayon::prelude::*;

/// The error budget of a run: the declared uncertainties, the scene they name facets of,
/// and the residual of the models chosen by the tolerance pilot.
#[derive(Debug)]
pub struct Budget<'a> {
    /// The declared uncertainties.
    pub uncertainties: &'a Uncertainties,
    /// The scene whose facets they name.
    pub scene: &'a RawScene,
    /// The pilot's predicted error at its percentile, K (0 without a tolerance).
    pub model_k: f64,
}

impl Budget<'_> {
    /// The σ layers ([`Layer::BUDGET`]), K: each declared uncertainty propagated to the
    /// apparent temperature through the radiance equation's partial derivatives at the
    /// pixel (`∂L/∂T = Σ τ·ε·dL_T/dT`, `∂L/∂ε = Σ τ·(L_T − L_reflected)`, `∂L/∂τ = L − L_u`
    /// for a relative σ of τ, `L_u` for a relative σ of the path radiance), over the band's
    /// dL/dT at the pixel's apparent temperature; and their root-sum-square.
    #[must_use]
    pub fn layers<R: BandModel + Sync>(
        &self,
        band: &R,
        frame: &Frame,
        apparent: &[f64],
    ) -> Vec<(Layer, Vec<f32>)> {
        let u = self.uncertainties;
        let per_pixel: Vec<[f64; 5]> = frame
            .truth
            .par_iter()
            .zip(&frame.radiance_w_m2_sr)
            .zip(apparent)
            .map(|((p, &l), &t)| {
                let slope = band.radiance_derivative(t);
                let in_k = |sigma_l: f64| {
                    if slope > 0.0 && sigma_l.is_finite() {
                        sigma_l.abs() / slope
                    } else {
                        0.0
                    }
                };
                let (temperature, emissivity) = match self.scene.facets.get(p.facet as usize) {
                    Some(facet) => {
                        let object = self
                            .scene
                            .objects
                            .get(facet.object as usize)
                            .map_or("", String::as_str);
                        (
                            in_k(
                                f64::from(p.temperature_sensitivity)
                                    * u.temperature_sigma_k(facet.material, object),
                            ),
                            in_k(
                                f64::from(p.emissivity_sensitivity)
                                    * u.emissivity_sigma(facet.material),
                            ),
                        )
                    }
                    None => (0.0, 0.0),
                };
                let path = f64::from(p.path_radiance_w_m2_sr);
                let path = if path.is_finite() { path } else { 0.0 };
                [
                    temperature,
                    emissivity,
                    in_k(u.transmission_relative * (l - path)),
                    in_k(u.path_radiance_relative * path),
                    self.model_k,
                ]
            })
            .collect();
        let mut out: Vec<(Layer, Vec<f32>)> = Layer::BUDGET[..5]
            .iter()
            .enumerate()
            .map(|(k, &layer)| (layer, per_pixel.iter().map(|s| s[k] as f32).collect()))
            .collect();
        out.push((
            Layer::SigmaTotal,
            per_pixel
                .iter()
                .map(|s| s.iter().map(|v| v * v).sum::<f64>().sqrt() as f32)
                .collect(),
        ));
        out
    }
}
