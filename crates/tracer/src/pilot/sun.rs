//! The sun as the pilot decides it: whether its direct beam may be left out, and how many
//! shadow rays a facet casts toward its disk.
//!
//! Both are measured like every other model ([`super::measure`]): each sample point's path
//! is traced once with the most shadow rays on offer and evaluated in the band model with
//! the sun's beams and without them (the sun's effect), and its shadow rays are cast again
//! at each cheaper count from the same random stream (what a rendering with that count
//! would find). The sub-band sets carry the sun's beams in their own sub-bands, so the
//! sub-bands' error is measured with the sunlight in it. The decision records the sun's
//! effect in kelvin as the reason for its choice.

use irsig_radiometry::BandModel;

use crate::env::Atmosphere;
use crate::pilot::PilotSpace;
use crate::pilot::choose::{Combo, SHADOW_RAYS_MODEL, SUN_MODEL};
use crate::pilot::classes::Census;
use crate::pilot::measure::Measured;
use crate::pilot::stats::{confident_rank, order_statistic, weighted_percentile};
use crate::tracer::Tracer;

impl<B: BandModel, A: Atmosphere> Tracer<B, A> {
    /// Why the sun's model `m` has its setting in `chosen`, with the sun's measured effect
    /// in kelvin; `None` for another model, or where the usual reasons say it.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn sun_reason<S>(
        &self,
        space: &PilotSpace<S>,
        census: &Census,
        measured: &[Measured],
        guaranteed: &[bool],
        chosen: &Combo,
        m: usize,
        percentile: f64,
    ) -> Option<String> {
        let sun = space.sun.as_ref()?;
        let off = sun.lit.iter().position(|&l| !l)?;
        let lit = sun.lit[chosen[SUN_MODEL]];
        if m == SHADOW_RAYS_MODEL && !lit {
            return Some("the sun is off: no shadow rays are cast".to_owned());
        }
        if m != SUN_MODEL {
            return None;
        }
        // The sun's effect at every guaranteed point, weighted back to the frame, and its
        // 90th percentile in the class where it is largest.
        let effect = |i: usize| measured[i].errors[SUN_MODEL][off];
        let mut weighted: Vec<(f64, f64)> = census
            .points
            .iter()
            .enumerate()
            .filter(|(_, p)| guaranteed[p.class])
            .map(|(i, p)| (effect(i), census.classes[p.class].weight()))
            .collect();
        let worst = weighted.iter().map(|e| e.0).fold(0.0, f64::max);
        let frame = weighted_percentile(&mut weighted, percentile);
        let mut largest = (0.0, 0);
        for c in 0..census.classes.len() {
            let mut of: Vec<f64> = census
                .points
                .iter()
                .enumerate()
                .filter(|(_, p)| p.class == c)
                .map(|(i, _)| effect(i))
                .collect();
            if of.is_empty() {
                continue;
            }
            let rank = confident_rank(of.len(), 90.0);
            let p90 = order_statistic(&mut of, rank);
            if p90 > largest.0 {
                largest = (p90, c);
            }
        }
        let class = &census.classes[largest.1];
        let effect = format!(
            "the sun's direct beam changes the pilot's points by {frame:.4} K at the \
             {percentile}th percentile and {worst:.4} K at worst; its largest class 90th \
             percentile is {:.4} K ({})",
            largest.0,
            self.class_name(&class.class, class.sub_pixel)
        );
        Some(if lit {
            format!("{effect}: on (no cheaper combination that holds leaves it out)")
        } else {
            format!("{effect}: within the tolerance in every class, so off")
        })
    }
}
