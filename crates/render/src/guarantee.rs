//! What a tolerance's decision promises, pixel by pixel: the σ of the models it chose at
//! each pixel (its class's residual and, where the pixel was refined, its own sampling
//! error), and the pixels it does not guarantee (a class it could not afford, a refinement
//! that reached the cap). A frame and each of its tiles give every pixel the same values.

use irsig_model::decision::Decision;
use irsig_tracer::pilot::{DETERMINISTIC_SHARE, PixelClass, ungranted_sigma_k};
use irsig_tracer::{Camera, Frame};
use rayon::prelude::*;

/// A frame (or tile) rendered to a decision.
#[derive(Debug, Clone, Copy)]
pub struct Guarantee<'a> {
    /// The decision it was rendered with.
    pub decision: &'a Decision,
    /// The frame's camera.
    pub camera: &'a Camera,
    /// The tile's top-left pixel in the frame (`[0, 0]` for a whole frame).
    pub origin: [u32; 2],
    /// The ids of the materials with a specular share (a pixel whose reflection meets one
    /// is a mirror seen in a mirror, a class of its own).
    pub mirrors: &'a [u16],
}

impl Guarantee<'_> {
    /// Each pixel's class in the decision (`None`: a population the pilot did not see),
    /// from its centre ray.
    fn classes(&self, frame: &Frame) -> Vec<Option<usize>> {
        let width = frame.width.max(1) as usize;
        let listed: Vec<(usize, PixelClass)> = self
            .decision
            .classes
            .iter()
            .enumerate()
            .filter(|(_, c)| !c.sub_pixel)
            .filter_map(|(i, c)| PixelClass::of_report(c).map(|k| (i, k)))
            .collect();
        frame
            .truth
            .par_iter()
            .enumerate()
            .map(|(i, t)| {
                let col = self.origin[0] + (i % width) as u32;
                let row = self.origin[1] + (i / width) as u32;
                let class = PixelClass::of_truth(t, self.camera.pixel_direction(col, row), |m| {
                    self.mirrors.contains(&m)
                });
                listed
                    .iter()
                    .find(|(_, k)| k.same_population(&class))
                    .map(|&(i, _)| i)
            })
            .collect()
    }

    /// The σ of the models at each pixel, K: its class's root-mean-square error
    /// (`rms_k`; a population the pilot did not see takes the largest of any class) and
    /// its own sampling error, in quadrature.
    #[must_use]
    pub fn model_sigma_k(&self, frame: &Frame) -> Vec<f64> {
        let unseen = self
            .decision
            .classes
            .iter()
            .map(|c| c.rms_k)
            .fold(self.decision.predicted.percentile_k, f64::max);
        self.classes(frame)
            .into_iter()
            .enumerate()
            .map(|(i, class)| {
                let model = class.map_or(unseen, |c| self.decision.classes[c].rms_k);
                let sampling = frame.sampling.get(i).map_or(0.0, |s| f64::from(s.sigma_k));
                model.hypot(sampling)
            })
            .collect()
    }

    /// 1 where the decision does not guarantee the pixel, 0 elsewhere: a class it lists
    /// as not guaranteed, or a refinement that reached the cap with a standard error above
    /// the decision's `sampling.unsure_sigma_k` (a decision written before it: the
    /// [`ungranted_sigma_k`] of a bias of the deterministic models' whole share).
    #[must_use]
    pub fn not_guaranteed(&self, frame: &Frame) -> Vec<f32> {
        let tolerance_k = self.decision.tolerance_k;
        let unsure = self
            .decision
            .sampling
            .as_ref()
            .and_then(|s| s.unsure_sigma_k)
            .unwrap_or_else(|| ungranted_sigma_k(tolerance_k, tolerance_k * DETERMINISTIC_SHARE));
        self.classes(frame)
            .into_iter()
            .enumerate()
            .map(|(i, class)| {
                let capped = frame
                    .sampling
                    .get(i)
                    .is_some_and(|s| s.capped && f64::from(s.sigma_k) > unsure);
                let unlisted = class.is_some_and(|c| !self.decision.classes[c].guaranteed);
                f32::from(u8::from(capped || unlisted))
            })
            .collect()
    }
}
