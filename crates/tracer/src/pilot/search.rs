//! The search over every combination of the models' settings for the cheapest that holds
//! ([`choose::holds`], priced by [`choose::cost`]).

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

/// The cheapest combination for which every guaranteed class and the frame hold, and its
/// verdict; at equal cost (a model that changes nothing here), the cheaper settings. When
/// none holds, the most accurate settings with their own verdict: only a pinned model can
/// keep them from holding (against themselves every other error is 0), and its error is
/// the user's.
#[allow(clippy::too_many_arguments)]
pub(crate) fn cheapest<S: Sync>(
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
) -> (Combo, choose::Verdict) {
    // Every combination, in the odometer's order; each judged on its own (side by side),
    // then the cheapest taken in that order, so that ties go as they always did.
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
    let mut best: Option<(f64, Combo, choose::Verdict)> = None;
    for (combo, judged) in combos.into_iter().zip(judged) {
        if let Some((c, v)) = judged {
            let cheaper = |b: &Combo| combo.iter().sum::<usize>() > b.iter().sum::<usize>();
            if best.is_none_or(|(bc, b, _)| c < bc * (1.0 - 1e-12) || (c <= bc && cheaper(&b))) {
                best = Some((c, combo, v));
            }
        }
    }
    match best {
        Some((_, c, v)) => (c, v),
        None => {
            let reference: Combo = [0; MODELS];
            let v = frame_verdict(census, measured, guaranteed, &reference);
            (reference, v)
        }
    }
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
