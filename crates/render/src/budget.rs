//! The error budget (thesis §5.1): each declared uncertainty of the inputs propagated to
//! the apparent temperature, pixel by pixel, through the radiance equation's partial
//! derivatives, and the residual of the models the tolerance pilot chose
//! ([`crate::guarantee`]).

use irsig_model::RawScene;
use irsig_model::truth::Layer;
use irsig_model::uncertainty::Uncertainties;
use irsig_radiometry::BandModel;
use irsig_tracer::Frame;
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

impl Budget<'_> {
    /// The σ layers ([`Layer::BUDGET`]), K: each declared uncertainty propagated to the
    /// apparent temperature through the radiance equation's partial derivatives at the
    /// pixel (`∂L/∂T = Σ τ·ε·dL_T/dT`, `∂L/∂ε = Σ τ·(L_T − L_reflected)`, `∂L/∂τ = L − L_u`
    /// for a relative σ of τ, `L_u` for a relative σ of the path radiance), over the band's
    /// dL/dT at the pixel's apparent temperature; the models' σ at each pixel, `model_k`
    /// (0 without a tolerance); and their root-sum-square. A refined pixel's derivatives
    /// are the means over its rays ([`irsig_tracer::PixelSampling`]), not its centre's.
    #[must_use]
    pub fn layers<R: BandModel + Sync>(
        &self,
        band: &R,
        frame: &Frame,
        apparent: &[f64],
        model_k: Option<&[f64]>,
    ) -> Vec<(Layer, Vec<f32>)> {
        let u = self.uncertainties;
        let per_pixel: Vec<[f64; 5]> = frame
            .truth
            .par_iter()
            .zip(&frame.radiance_w_m2_sr)
            .zip(apparent)
            .enumerate()
            .map(|(i, ((p, &l), &t))| {
                // A refined pixel's derivatives and path radiance are its rays' means.
                let (dl_dt, dl_de, path) = match frame.sampling.get(i) {
                    Some(s) if s.rays > 1 => (
                        s.temperature_sensitivity,
                        s.emissivity_sensitivity,
                        s.path_radiance_w_m2_sr,
                    ),
                    _ => (
                        p.temperature_sensitivity,
                        p.emissivity_sensitivity,
                        p.path_radiance_w_m2_sr,
                    ),
                };
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
                            in_k(f64::from(dl_dt) * u.temperature_sigma_k(facet.material, object)),
                            in_k(f64::from(dl_de) * u.emissivity_sigma(facet.material)),
                        )
                    }
                    None => (0.0, 0.0),
                };
                let path = f64::from(path);
                let path = if path.is_finite() { path } else { 0.0 };
                [
                    temperature,
                    emissivity,
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
