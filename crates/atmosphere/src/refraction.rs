//! The sun's apparent zenith angle for LOWTRAN7's direct solar irradiance runs.
//!
//! LOWTRAN7 traces card 3's ANGLE as the *apparent* zenith angle at H1: the ray leaves H1
//! at that angle, bends through the refracting atmosphere (its refractivity from Edlén
//! 1966 at the band's mean wavenumber, on a 6371.23 km Earth) and leaves the top in the
//! direction ANGLE + BENDING (TAPE6's geometry summary, `BENDING = x DEG`). The sun is a
//! point at infinity in its *geometric* direction θ_g (NREL's SPA without its refraction
//! term, [`crate::sun`]), so the beam that reaches H1 is the ray whose apparent zenith
//! θ_a satisfies θ_a + B(θ_a) = θ_g. Run at ANGLE = θ_g, the beam would be that of a sun
//! B lower: at 3° elevation (US Standard 1976, the ground) 6 % weak over 3–5 µm and 9 %
//! over 8–14 µm, 0.5 % at 10°, 0.03 % at 30°.
//!
//! [`apparent_zenith`] finds θ_a by iterating on LOWTRAN7's own BENDING (the caller runs
//! LOWTRAN7: a library spawns no process). Measured against LOWTRAN7's BENDING at the
//! apparent zenith of geometric 80°, 87° and 88.3° from 0, 1 and 3 km (tropical,
//! mid-latitude winter, sub-arctic winter and US Standard 1976, 8–14 µm), the other
//! candidates fall short:
//!
//! - a closed form (Bennett 1982 in the apparent elevation, or Sæmundsson 1986 in the
//!   geometric one, each scaled by p/T at H1 as Sæmundsson's eq. does) overestimates
//!   LOWTRAN7's bending by up to 4.9 % (Bennett, tropical, the ground, 88.3°) and 5.4 %
//!   (Sæmundsson, 80°): at 3° elevation that is 0.01°, a quarter of the 1 % floor's
//!   worth in the tropical 8–14 µm beam, and it needs p and T at H1, which a plan of a
//!   standard model does not hold (LOWTRAN7 holds its six profiles);
//! - integrating the refraction through the profile would need those profiles too, and
//!   LOWTRAN7's layering of them, to agree with the ray it actually traces.
//!
//! LOWTRAN7's own BENDING is exact for the ray it runs, for any model, radiosonde,
//! observer altitude and band, to the 0.001° a deck and TAPE6 print; a low sun costs one
//! to three more runs.
//!
//! The solar *scattering* runs (IEMSCT 2) need none of this: LOWTRAN7's `SSGEO` takes card
//! 3A2's PARM2 as the geometric zenith and bends each scattering point's path to the sun
//! itself (its loop on `SOLAR ZENITH CORRECTION FOR BENDING`: PARM2 88.3° from the ground
//! is run at 87.99°, a correction of 0.314°), so PARM2 stays θ_g.

use crate::error::{AtmosphereError, AtmosphereErrorKind};

/// How close θ_a + B(θ_a) must come to θ_g, degrees: twice the 0.001° a deck's ANGLE and
/// TAPE6's BENDING are printed to.
pub const TOLERANCE_DEG: f64 = 0.002;

/// The bending below which a sun is run at its geometric zenith, degrees. LOWTRAN7 bends
/// the ray from the ground 0.027° at 60° (US Standard 1976): run at 60° rather than at
/// 59.973°, the 3–5 µm beam is 0.033 % weak and the 8–14 µm one 0.026 %, under every other
/// error of the solar table (`docs/accuracy.md`); a high sun then keeps the deck, and the
/// beam, it always had.
pub const FLOOR_DEG: f64 = 0.03;

/// The largest zenith angle a deck's ANGLE holds below the horizon's 90°, degrees.
const LAST_BELOW_HORIZON_DEG: f64 = 89.999;

/// The runs [`apparent_zenith`] makes at most. Each step shrinks the error by dB/dθ,
/// under 0.15 even at the horizon (LOWTRAN7 bends 0.384° at 89° and 0.450° at 89.5°): from
/// the first guess's error B(θ_g) ≤ 0.6° the tolerance is met by the fourth run.
const MAX_RUNS: usize = 8;

/// A sun's zenith angles at H1: the geometric one it is at, and the apparent one
/// LOWTRAN7 is run at so that its ray leaves the atmosphere toward it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ApparentZenith {
    /// The sun's geometric zenith angle, degrees.
    pub geometric_deg: f64,
    /// Card 3's ANGLE, degrees (a multiple of 0.001°): the apparent zenith angle at H1.
    pub apparent_deg: f64,
    /// LOWTRAN7's BENDING of the ray run at `apparent_deg`, degrees.
    pub bending_deg: f64,
    /// How many runs it took (1: the sun at its geometric zenith, bent less than
    /// [`FLOOR_DEG`]).
    pub runs: usize,
}

fn round3(x: f64) -> f64 {
    (x * 1000.0).round() / 1000.0
}

fn refused(message: String) -> AtmosphereError {
    AtmosphereErrorKind::Solar(message).into()
}

/// The apparent zenith angle at H1 of a sun at `geometric_deg`, from `bending_at(angle)`:
/// LOWTRAN7's BENDING, degrees, of the direct solar run at card 3 ANGLE = `angle`, from
/// the same H1, model and band.
///
/// The fixed point θ ← θ_g − B(θ), from θ = θ_g (or 89.999° for a sun at or below the
/// geometric horizon), each angle rounded to the 0.001° a deck holds, until
/// |θ + B(θ) − θ_g| ≤ [`TOLERANCE_DEG`]. A sun whose first run bends less than
/// [`FLOOR_DEG`] is left at θ_g. The last angle run is the answer: the caller's last run
/// is the beam.
///
/// A sun below the geometric horizon but above the apparent one (θ_g up to 90° plus the
/// bending of a horizontal ray, about 0.5° at the ground) is found like any other; one
/// lower is refused. (A plan refuses a sun at or below 90° before it gets here: its rows
/// are geometric angles below the horizon.)
///
/// # Errors
/// What `bending_at` returns; and, converted from an [`AtmosphereError`] (kind `Solar`): a
/// geometric zenith that is not finite or outside 0–91°, a bending that is not a finite
/// number of degrees ≥ 0, a sun below the apparent horizon, or no convergence in eight runs.
pub fn apparent_zenith<E: From<AtmosphereError>>(
    geometric_deg: f64,
    mut bending_at: impl FnMut(f64) -> Result<f64, E>,
) -> Result<ApparentZenith, E> {
    if !(geometric_deg.is_finite() && (0.0..=91.0).contains(&geometric_deg)) {
        return Err(refused(format!(
            "expected the sun's geometric zenith angle from 0 to 91 deg, found {geometric_deg}"
        ))
        .into());
    }
    let mut angle = round3(geometric_deg).min(LAST_BELOW_HORIZON_DEG);
    for runs in 1..=MAX_RUNS {
        let bending_deg = bending_at(angle)?;
        if !(bending_deg.is_finite() && bending_deg >= 0.0) {
            return Err(refused(format!(
                "expected LOWTRAN7's BENDING, a finite angle of 0 deg or more, at ANGLE {angle} \
                 deg; found {bending_deg}"
            ))
            .into());
        }
        let done = |apparent_deg: f64| ApparentZenith {
            geometric_deg,
            apparent_deg,
            bending_deg,
            runs,
        };
        if runs == 1 && geometric_deg <= LAST_BELOW_HORIZON_DEG && bending_deg < FLOOR_DEG {
            return Ok(done(angle));
        }
        if (angle + bending_deg - geometric_deg).abs() <= TOLERANCE_DEG {
            return Ok(done(angle));
        }
        let next = round3(geometric_deg - bending_deg).min(LAST_BELOW_HORIZON_DEG);
        if (next - angle).abs() < 5e-4 {
            // At the horizon: the ray LOWTRAN7 can run lowest still leaves the air above
            // the sun. (Elsewhere the step moves by at least the tolerance.)
            return Err(refused(format!(
                "the sun {geometric_deg} deg from the zenith is below the apparent horizon: \
                 LOWTRAN7 bends the ray at {angle} deg only {bending_deg} deg, to {} deg",
                round3(angle + bending_deg)
            ))
            .into());
        }
        angle = next;
    }
    Err(refused(format!(
        "the apparent zenith of the sun {geometric_deg} deg from the zenith did not settle \
         within {TOLERANCE_DEG} deg in {MAX_RUNS} LOWTRAN7 runs (last at {angle} deg)"
    ))
    .into())
}

#[cfg(test)]
#[allow(clippy::float_cmp)] // angles copied or rounded to a deck's 0.001
mod tests {
    use super::*;

    /// Bennett's (1982) refraction, degrees, at apparent elevation `h` degrees:
    /// `cot(h + 7.31/(h + 4.4))` arcminutes, standing in for LOWTRAN7's BENDING (a smooth
    /// refraction of the same size: 0.57° at the horizon, 0.016° at 45°), printed to 0.001°
    /// as TAPE6 prints it.
    fn bennett(apparent_zenith_deg: f64) -> f64 {
        let h = 90.0 - apparent_zenith_deg;
        // At the zenith the formula dips a hair below 0 (cot of 90.08°): no bending.
        let r = (1.0 / (h + 7.31 / (h + 4.4)).to_radians().tan() / 60.0).max(0.0);
        round3(r)
    }

    /// θ_a with θ_a + B(θ_a) = θ_g by bisection on Bennett's refraction unrounded: the
    /// answer found another way than the fixed point's.
    fn bisect(geometric_deg: f64) -> f64 {
        let f = |a: f64| {
            let h = 90.0 - a;
            a + 1.0 / (h + 7.31 / (h + 4.4)).to_radians().tan() / 60.0 - geometric_deg
        };
        let (mut lo, mut hi) = (geometric_deg - 1.0, 90.0_f64.min(geometric_deg));
        for _ in 0..60 {
            let mid = 0.5 * (lo + hi);
            if f(mid) > 0.0 {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        0.5 * (lo + hi)
    }

    fn find(geometric_deg: f64) -> Result<ApparentZenith, AtmosphereError> {
        apparent_zenith(geometric_deg, |a| Ok::<f64, AtmosphereError>(bennett(a)))
    }

    #[test]
    fn a_high_sun_is_run_at_its_geometric_zenith() {
        // At the zenith nothing bends; at 45 deg Bennett's 0.016 deg is under the floor.
        for z in [0.0, 45.0] {
            let a = find(z).unwrap();
            assert_eq!((a.apparent_deg, a.runs), (z, 1), "{a:?}");
            assert!(a.bending_deg < FLOOR_DEG);
        }
        assert_eq!(find(0.0).unwrap().bending_deg, 0.0);
    }

    #[test]
    fn a_low_sun_is_run_where_its_bent_ray_leaves_toward_it() {
        for (z, bent) in [(85.0, 0.15), (89.0, 0.35)] {
            let a = find(z).unwrap();
            let want = bisect(z);
            assert!(
                (a.apparent_deg - want).abs() <= TOLERANCE_DEG,
                "{z}: {a:?}, bisection {want}"
            );
            assert!(
                (a.apparent_deg + bennett(a.apparent_deg) - z).abs() <= TOLERANCE_DEG,
                "{a:?}"
            );
            // Bent by about the refraction near the horizon, in a few runs.
            assert!(z - a.apparent_deg > bent && a.runs <= 4, "{a:?}");
            assert_eq!(a.apparent_deg, round3(a.apparent_deg));
        }
    }

    #[test]
    fn a_sun_just_below_the_geometric_horizon_is_seen_and_a_lower_one_refused() {
        // Bennett's horizontal ray bends 0.57 deg: a sun 0.3 deg below the geometric
        // horizon is seen 0.2-0.3 deg above the apparent one.
        let a = find(90.3).unwrap();
        let want = bisect(90.3);
        assert!(a.apparent_deg < 90.0, "{a:?}");
        assert!(
            (a.apparent_deg - want).abs() <= TOLERANCE_DEG,
            "{a:?} {want}"
        );
        let e = find(90.8).unwrap_err().to_string();
        assert!(e.contains("below the apparent horizon"), "{e}");
        for bad in [f64::NAN, -1.0, 95.0] {
            assert!(find(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn the_callers_failure_and_a_bending_that_is_none_are_reported() {
        let e = apparent_zenith(87.0, |_| {
            Err::<f64, AtmosphereError>(AtmosphereErrorKind::Solar("no TAPE6".into()).into())
        })
        .unwrap_err();
        assert_eq!(e.to_string(), "no TAPE6");
        let e = apparent_zenith(87.0, |_| Ok::<f64, AtmosphereError>(f64::NAN)).unwrap_err();
        assert!(e.to_string().contains("BENDING"), "{e}");
        // A bending that never settles (jumping between 10 and 0.1 deg across 75 deg) is
        // refused.
        let e = apparent_zenith(80.0, |a| {
            Ok::<f64, AtmosphereError>(if a > 75.0 { 10.0 } else { 0.1 })
        })
        .unwrap_err()
        .to_string();
        assert!(e.contains("did not settle"), "{e}");
    }
}
