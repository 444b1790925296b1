//! The sun of a request (issue 30): where it is, checked before anything is read, and its
//! direct beam in each sub-band, from the `solar` table of the spectral atmosphere the
//! frame is traced through.
//!
//! The table holds the beam for one sun zenith angle (the one its plan was made for), so
//! the sun asked for must be that sun, within
//! [`irsig_atmosphere::solar::ZENITH_TOLERANCE_DEG`]. Each sub-band's beam is
//! [`DirectSun`] over the sub-band's wavelengths with the band's response, the weight its
//! radiances are collapsed with, so that the sunlight and the path radiance of a sub-band
//! are integrated alike. The table's altitudes are metres above the ground, as the
//! tracer's are (a hit's altitude is its scene `z`, the ground at `z = 0`).

use irsig_atmosphere::AtmosphereErrorKind;
use irsig_atmosphere::scattered::ScatteredSunlight;
use irsig_atmosphere::solar::{DirectSun, ZENITH_TOLERANCE_DEG};
use irsig_atmosphere::sun::{SunField, SunPosition, SunSpec};
use irsig_model::SpectralAtmosphere;
use irsig_tracer::{Sun, SunBeam};
use miette::miette;

use crate::band::{Collapsed, Split};
use crate::error::{RequestError, Setting, Spelling};

/// A sun to light the scene with.
#[derive(Debug, Clone, PartialEq)]
pub struct SunRequest {
    /// Where it is: a direction, or a UTC time and a place (NREL's SPA).
    pub spec: SunSpec,
    /// Shadow rays per facet hit: 1 aims at the disk's centre; more sample the disk for
    /// soft shadow edges.
    pub shadow_rays: u32,
    /// Where the sun was given when not by the tool's own settings: a view file's
    /// `file:line:column`. Errors about the sun then name that place instead of a setting.
    pub origin: Option<String>,
}

impl SunRequest {
    /// The setting that says where the sun is: its zenith angle for a direction, its time
    /// for a time and a place.
    #[must_use]
    pub fn setting(&self) -> Setting {
        match self.spec {
            SunSpec::Direction { .. } => Setting::Sun(SunField::ZenithDeg),
            SunSpec::At { .. } => Setting::Sun(SunField::Utc),
        }
    }

    /// The sun's position, checked: every field in its range, the sun above the horizon,
    /// 1 to [`irsig_tracer::sun::MAX_SHADOW_RAYS`] shadow rays.
    ///
    /// # Errors
    /// A request error naming the setting at fault.
    pub fn position(&self) -> miette::Result<SunPosition> {
        let max = irsig_tracer::sun::MAX_SHADOW_RAYS;
        if !(1..=max).contains(&self.shadow_rays) {
            return Err(RequestError::of_value(
                Setting::SunShadowRays,
                self.shadow_rays,
                format!("out of range: expected 1 to {max} shadow rays per hit"),
            ));
        }
        let position = self.spec.position().map_err(|e| match e.kind {
            AtmosphereErrorKind::Sun { field, message } if self.origin.is_some() => self.refuse(
                Setting::Sun(field),
                format!("`{}`: {message}", field.path()),
            ),
            AtmosphereErrorKind::Sun { field, message } => {
                RequestError::report(Setting::Sun(field), message)
            }
            _ => self.refuse(self.setting(), e.to_string()),
        })?;
        if !position.is_above_horizon() {
            return Err(self.refuse(
                self.setting(),
                format!(
                    "the sun is {:.4} deg from the zenith, at or below the horizon: a sun \
                     below 90 deg lights the scene; leave the sun out for a night",
                    position.zenith_deg
                ),
            ));
        }
        Ok(position)
    }
}

impl SunRequest {
    /// A refusal of this sun about `setting`: a request error naming the setting, or, for a
    /// sun given in a file ([`Self::origin`]), an error at that place.
    pub(crate) fn refuse(&self, setting: Setting, message: String) -> miette::Report {
        match &self.origin {
            Some(at) => miette!("{at}: the sun: {message}"),
            None => RequestError::report(setting, message),
        }
    }
}

/// How to make an atmosphere with a `solar` table, for messages, the atmosphere's setting
/// spelt as the request's maker spells it.
fn how_to_build(spelling: Spelling) -> String {
    format!(
        "build one for this sun with irsig-atmos plan (for the sun's zenith angle and day of \
         the year) and irsig-atmos build, and give its file to {}",
        spelling.of(Setting::Atmosphere)
    )
}

/// The refusal of a sun with an atmosphere `name` that has no `solar` table (`what` says
/// what it is instead).
pub(crate) fn no_solar_table(
    sun: &SunRequest,
    name: &str,
    what: &str,
    spelling: Spelling,
) -> miette::Report {
    sun.refuse(
        sun.setting(),
        format!(
            "the sun's beam needs a spectral atmosphere with a solar table, and `{name}` is \
             {what}: {}",
            how_to_build(spelling)
        ),
    )
}

/// The sun of `position` over the sub-bands `collapsed` of `split`, its beams from
/// `spectral`'s `solar` table.
///
/// # Errors
/// An atmosphere without a `solar` table, or one made for another zenith angle (a request
/// error naming the sun's setting, with both angles), or a sub-band the table cannot be
/// integrated over.
pub(crate) fn sun(
    request: &SunRequest,
    position: &SunPosition,
    name: &str,
    spectral: &SpectralAtmosphere,
    split: &Split<'_>,
    collapsed: &Collapsed,
    spelling: Spelling,
) -> miette::Result<Sun> {
    let Some(solar) = spectral.solar.as_ref() else {
        return Err(no_solar_table(
            request,
            name,
            "a night atmosphere (its plan had no sun)",
            spelling,
        ));
    };
    if (position.zenith_deg - solar.zenith_deg).abs() > ZENITH_TOLERANCE_DEG {
        return Err(request.refuse(
            request.setting(),
            format!(
                "the sun is {:.4} deg from the zenith, but the solar table of `{name}` is for \
                 a sun at {} deg (the two must agree within {ZENITH_TOLERANCE_DEG} deg): {}",
                position.zenith_deg,
                solar.zenith_deg,
                how_to_build(spelling)
            ),
        ));
    }
    let beams = collapsed
        .iter()
        .map(|(band, _)| {
            let (lo, hi) = (band.lambda_min_um(), band.lambda_max_um());
            let direct = DirectSun::new(spectral, lo, hi, |l| split.weight(l))
                .map_err(|e| miette!("the sun's beam over {lo}-{hi} um: {e}"))?;
            let normal = solar
                .altitude_m
                .iter()
                .map(|&h| direct.normal_w_m2(h))
                .collect();
            SunBeam::new(solar.altitude_m.clone(), normal).map_err(|e| miette!("{e}"))
        })
        .collect::<miette::Result<Vec<_>>>()?;
    let mut sun = Sun::new(position.to_scene_direction(), beams);
    sun.shadow_rays = request.shadow_rays;
    Ok(sun)
}

/// Whether the frame's sub-band atmospheres add the sunlight scattered into their paths
/// and sky: with a sun and an atmosphere whose `solar` table has scattered tables, the
/// direction toward the sun (scene frame); with a sun and none, `None` and a warning
/// (`warn`) that the frame holds the direct beam only.
pub(crate) fn scattering(
    request: Option<&SunRequest>,
    position: Option<&SunPosition>,
    spectral: &SpectralAtmosphere,
    name: &str,
    warn: impl FnOnce(String),
) -> Option<[f64; 3]> {
    let (Some(_), Some(position)) = (request, position) else {
        return None;
    };
    match spectral.solar.as_ref() {
        Some(solar) if !solar.relative_azimuth_deg.is_empty() => {
            Some(position.to_scene_direction())
        }
        Some(_) => {
            warn(format!(
                "`{name}` has the sun's direct beam but no scattered-sunlight tables: the sky \
                 and the path radiance hold the air's own emission only (up to 1.2 % of a \
                 3-5 um slant path and 7.5 % of the sky with an urban 5 km haze, \
                 docs/accuracy.md); plan the atmosphere with the sunlight it scatters \
                 (irsig-atmos plan) and build it again to add them"
            ));
            None
        }
        None => None,
    }
}

/// `atmosphere`, the sub-band `band`'s of `split`, by day (`to_sun`: the direction toward
/// the sun) with the sunlight `spectral` scatters into it over the sub-band, with the
/// band's response (the weight its radiances are collapsed with).
///
/// # Errors
/// A sub-band the scattered tables cannot be integrated over.
pub(crate) fn scattered(
    atmosphere: irsig_atmosphere::PrecomputedAtmosphere,
    to_sun: Option<[f64; 3]>,
    spectral: &SpectralAtmosphere,
    split: Split<'_>,
    band: &irsig_radiometry::Band,
) -> miette::Result<irsig_atmosphere::PrecomputedAtmosphere> {
    let Some(to_sun) = to_sun else {
        return Ok(atmosphere);
    };
    let (lo, hi) = (band.lambda_min_um(), band.lambda_max_um());
    let s = ScatteredSunlight::new(spectral, lo, hi, |l| split.weight(l), to_sun)
        .map_err(|e| miette!("the scattered sunlight over {lo}-{hi} um: {e}"))?;
    Ok(atmosphere.with_scattered(s))
}

/// `atmosphere`, the sub-band `band`'s of `split`, with the slab tables `spectral` holds
/// for paths that end above the ground (`irsig_atmosphere::slab`), over the sub-band with
/// the band's response; unchanged when it holds none.
///
/// # Errors
/// A sub-band the slab tables cannot be integrated over.
pub(crate) fn with_slabs(
    atmosphere: irsig_atmosphere::PrecomputedAtmosphere,
    spectral: &SpectralAtmosphere,
    split: Split<'_>,
    band: &irsig_radiometry::Band,
) -> miette::Result<irsig_atmosphere::PrecomputedAtmosphere> {
    let (lo, hi) = (band.lambda_min_um(), band.lambda_max_um());
    let slabs = irsig_atmosphere::slab::SlabPaths::new(spectral, lo, hi, |l| split.weight(l))
        .map_err(|e| miette!("the slab tables over {lo}-{hi} um: {e}"))?;
    Ok(match slabs {
        Some(s) => atmosphere.with_slabs(s),
        None => atmosphere,
    })
}
