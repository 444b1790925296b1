//! The search over every combination of the models' settings for the cheapest that holds
//! ([`choose::holds`], priced by [`choose::cost`]), and the dearer ones in order, for a
//! frame whose predicted percentile the cheapest does not keep.

use rayon::prelude::*;

use super::choose::{self, Combo, Counts, MODELS};
use super::classes::Census;
use super::measure::Measured;
use super::space::PilotSpace;

/// How many settings each model has on offer, in the order of [`Combo`].
pub(crate) fn lens<S>(space: &PilotSpace<S>) -> [usize; MODELS] {
    [
        space.atmospheres.len(),
        space.bounces.len(),
        space.sky_view_rays.len(),
        space.supersampling.len(),
        space.path_terms.len(),
        space.sub_bands.len(),
        space.sun.as_ref().map_or(1, |s| s.lit.len()),
        space.sun.as_ref().map_or(1, |s| s.shadow_rays.len()),
    ]
}

/// The share of the cheapest holding combination's cost within which a more accurate one
/// is taken instead ([`Holding::cheapest`]). The pilot's points are its classes' centre
/// rays; what they cannot see is where a setting's error hides in a sliver of a pixel (a
/// mirror seen in a mirror along a refined edge: on the generated mirrors' mast view at
/// 0.1 K, one bounce measured 0 at every point, and left edge pixels of glass and metal
/// 0.15–0.27 K off, the materials' 90th percentiles 0.18 and 0.16 K; eight cost 0.2 %
/// more and left 0.04 and 0.09 K). Accuracy that costs next to nothing is bought.
pub(crate) const NEARLY_FREE: f64 = 0.01;

/// Every combination for which every guaranteed class and the frame hold, with its cost
/// and verdict, in the odometer's order.
#[derive(Debug, Clone, Default)]
pub(crate) struct Holding(Vec<(Combo, f64, choose::Verdict)>);

impl Holding {
    /// The cheapest; at equal cost (a model that changes nothing here), the cheaper
    /// settings; ties beyond that go to the first in the odometer's order. Then the most
    /// accurate of those at least as accurate in every model that cost more, but at most
    /// [`NEARLY_FREE`] more (the fewest steps down the menus; at equal steps, the
    /// cheaper): a setting that costs more acts somewhere. `None` when no combination
    /// holds.
    pub(crate) fn cheapest(&self) -> Option<(Combo, choose::Verdict)> {
        let steps = |c: &Combo| c.iter().sum::<usize>();
        let mut best: Option<&(Combo, f64, choose::Verdict)> = None;
        for held in &self.0 {
            let (combo, c, _) = held;
            if best.is_none_or(|(b, bc, _)| {
                *c < bc * (1.0 - 1e-12) || (*c <= *bc && steps(combo) > steps(b))
            }) {
                best = Some(held);
            }
        }
        let best = best?;
        let (cheapest, cost) = (best.0, best.1);
        let mut chosen = best;
        for held in &self.0 {
            let (combo, c, _) = held;
            let as_accurate = combo.iter().zip(&cheapest).all(|(a, b)| a <= b);
            let (s, sc) = (steps(combo), steps(&chosen.0));
            if as_accurate
                && *c > cost * (1.0 + 1e-12)
                && *c <= cost * (1.0 + NEARLY_FREE)
                && (s < sc || (s == sc && *c < chosen.1))
            {
                chosen = held;
            }
        }
        Some((chosen.0, chosen.2))
    }

    /// The combinations that cost more than `cost`, cheapest first (at equal cost, the
    /// first in the odometer's order).
    pub(crate) fn dearer_than(&self, cost: f64) -> Vec<(Combo, choose::Verdict)> {
        let mut dearer: Vec<&(Combo, f64, choose::Verdict)> =
            self.0.iter().filter(|(_, c, _)| *c > cost).collect();
        dearer.sort_by(|a, b| a.1.total_cmp(&b.1));
        dearer.into_iter().map(|&(c, _, v)| (c, v)).collect()
    }
}

/// Every combination judged ([`choose::holds`], side by side) and priced: those that hold.
#[allow(clippy::too_many_arguments)]
pub(crate) fn holding<S: Sync>(
    space: &PilotSpace<S>,
    counts: &Counts,
    census: &Census,
    measured: &[Measured],
    by_class: &[Vec<usize>],
    guaranteed: &[bool],
    pixels: choose::Pixels<'_>,
    lens: &[usize; MODELS],
    tolerance_k: f64,
    det_k: f64,
    percentile: f64,
) -> Holding {
    let mut combos: Vec<Combo> = Vec::new();
    let mut combo: Combo = [0; MODELS];
    loop {
        combos.push(combo);
        if !next_combo(&mut combo, lens) {
            break;
        }
    }
    let judged: Vec<Option<(f64, choose::Verdict)>> = combos
        .par_iter()
        .map(|combo| {
            choose::holds(
                census,
                measured,
                by_class,
                guaranteed,
                pixels,
                combo,
                tolerance_k,
                det_k,
                percentile,
            )
            .map(|v| (choose::cost(space, counts, combo), v))
        })
        .collect();
    Holding(
        combos
            .into_iter()
            .zip(judged)
            .filter_map(|(combo, j)| j.map(|(c, v)| (combo, c, v)))
            .collect(),
    )
}

/// The cheapest combination that holds ([`Holding::cheapest`]) and its verdict. When none
/// holds, the most accurate settings with their own verdict: only a pinned model can keep
/// them from holding (against themselves every other error is 0), and its error is the
/// user's.
pub(crate) fn cheapest(
    holding: &Holding,
    census: &Census,
    measured: &[Measured],
    guaranteed: &[bool],
) -> (Combo, choose::Verdict) {
    holding.cheapest().unwrap_or_else(|| {
        let reference: Combo = [0; MODELS];
        (
            reference,
            frame_verdict(census, measured, guaranteed, &reference),
        )
    })
}

/// The frame's verdict on `combo` whether or not it holds (for a pinned model's own
/// error): its largest bound over the guaranteed points.
fn frame_verdict(
    census: &Census,
    measured: &[Measured],
    guaranteed: &[bool],
    combo: &Combo,
) -> choose::Verdict {
    let worst_k = census
        .points
        .iter()
        .zip(measured)
        .filter(|(p, _)| guaranteed[p.class])
        .map(|(_, m)| choose::bound(m, combo))
        .fold(0.0, f64::max);
    choose::Verdict { worst_k }
}

/// Steps `combo` to the next combination (an odometer over the lists); false after the
/// last.
fn next_combo(combo: &mut Combo, lens: &[usize; MODELS]) -> bool {
    for m in 0..MODELS {
        combo[m] += 1;
        if combo[m] < lens[m] {
            return true;
        }
        combo[m] = 0;
    }
    false
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_cheapest_holds_first_and_the_dearer_follow_by_cost() {
        let v = |w: f64| choose::Verdict { worst_k: w };
        let c = |k: usize| {
            let mut combo = [0; MODELS];
            combo[1] = k;
            combo
        };
        // At equal cost the cheaper settings (the larger indices) win.
        let holding = Holding(vec![
            (c(0), 4.0, v(0.0)),
            (c(1), 2.0, v(0.1)),
            (c(2), 2.0, v(0.2)),
            (c(3), 3.0, v(0.3)),
        ]);
        let (cheapest, verdict) = holding.cheapest().unwrap();
        assert_eq!((cheapest, verdict.worst_k), (c(2), 0.2));
        let dearer: Vec<Combo> = holding.dearer_than(2.0).into_iter().map(|d| d.0).collect();
        assert_eq!(dearer, vec![c(3), c(0)]);
        assert!(Holding::default().cheapest().is_none());
    }

    #[test]
    fn a_more_accurate_combination_nearly_free_is_taken() {
        let v = |w: f64| choose::Verdict { worst_k: w };
        let c = |bounces: usize, sky: usize| {
            let mut combo = [0; MODELS];
            combo[1] = bounces;
            combo[2] = sky;
            combo
        };
        // 1 % dearer is taken, the most accurate first; more than 1 % is not, nor a
        // combination less accurate in one model however cheap its accuracy elsewhere.
        let holding = Holding(vec![
            (c(0, 2), 100.5, v(0.0)),
            (c(1, 2), 100.9, v(0.1)),
            (c(3, 2), 100.0, v(0.3)),
            (c(0, 0), 101.5, v(0.0)),
            (c(0, 3), 100.2, v(0.0)),
        ]);
        assert_eq!(holding.cheapest().unwrap().0, c(0, 2));
        let far = Holding(vec![(c(0, 2), 101.5, v(0.0)), (c(3, 2), 100.0, v(0.3))]);
        assert_eq!(far.cheapest().unwrap().0, c(3, 2));
    }

    #[test]
    fn combinations_are_counted_like_an_odometer() {
        let lens = [2, 1, 3, 1, 1, 2, 1, 1];
        let mut combo = [0; MODELS];
        let mut n = 1;
        while next_combo(&mut combo, &lens) {
            n += 1;
        }
        assert_eq!(n, 12);
        assert_eq!(combo, [0; MODELS]);
    }
}
