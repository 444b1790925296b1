//! The sun of a request: where it is, checked before anything is read, and its
//! direct beam in each sub-band, from the `solar` table of the spectral atmosphere the
//! frame is traced through.
//!
//! The table holds the beam for the sun zenith angles its plan was made for: one sun, which
//! the sun asked for must then be, within
//! [`irsig_atmosphere::solar::ZENITH_TOLERANCE_DEG`]; or several (one build for a day's
//! suns), between which the beam is interpolated ([`DirectSun::at_zenith`]), a sun outside
//! them refused with their range. Each sub-band's beam is
//! [`DirectSun`] over the sub-band's wavelengths with the band's response, the weight its
//! radiances are collapsed with, so that the sunlight and the path radiance of a sub-band
//! are integrated alike. The table's altitudes are metres above the ground, as the
//! tracer's are (a hit's altitude is its scene `z`, the ground at `z = 0`).
//!
//! The table's extraterrestrial spectrum is LOWTRAN7's at the Earth–Sun distance of the
//! day its plan was made for (IDAY). A sun given by time is seen on its date's day, which
//! need not be the table's: the beam is then scaled by the ratio of the two days'
//! inverse-square factors `(r₀/r)²` (Spencer 1971,
//! [`irsig_atmosphere::loads::weathered::earth_sun_factor`]), and a warning says so once.
//! The transmittance does not depend on the day, so the scaled beam is what LOWTRAN7 run
//! for the date would give, to Spencer's 0.1 %; correcting is what a user asking for a
//! date wants, where refusing would cost a LOWTRAN7 build per day for a known factor. The
//! sunlight the air scatters (the scattered tables), where there is any, keeps the table's
//! day. The disk's angular radius follows the same distance, `α = α₀ r₀/r`
//! ([`SunDay::angular_radius_deg`]), so that the disk's radiance `E_n/Ω_sun` is the
//! same on every day, as the sun's is (radiance is conserved; only the solid angle and
//! the irradiance follow `1/r²`).

use irsig_atmosphere::loads::weathered::earth_sun_factor;
use irsig_atmosphere::scattered::ScatteredSunlight;
use irsig_atmosphere::solar::{DirectSun, ZENITH_TOLERANCE_DEG};
use irsig_atmosphere::sun::{SunField, SunPosition, SunSpec};
use irsig_atmosphere::{AtmosphereErrorKind, BandQuadrature, SubBandCount};
use irsig_model::SpectralAtmosphere;
use irsig_radiometry::spectral_radiance_per_um;
use irsig_tracer::{SUN_ANGULAR_RADIUS_DEG, Sun, SunBeam};

use crate::band::{Collapsed, Split};
use crate::error::{RenderError, RequestError, Setting, Spelling};

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
    pub fn position(&self) -> Result<SunPosition, RenderError> {
        let max = irsig_tracer::sun::MAX_SHADOW_RAYS;
        if !(1..=max).contains(&self.shadow_rays) {
            return Err(RequestError::with_value(
                Setting::SunShadowRays,
                self.shadow_rays,
                format!("out of range: expected 1 to {max} shadow rays per hit"),
            )
            .into());
        }
        let position = self.spec.position().map_err(|e| match e.kind {
            AtmosphereErrorKind::Sun { field, message } if self.origin.is_some() => self.refuse(
                Setting::Sun(field),
                format!("`{}`: {message}", field.path()),
            ),
            AtmosphereErrorKind::Sun { field, message } => {
                RequestError::new(Setting::Sun(field), message).into()
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
    pub(crate) fn refuse(&self, setting: Setting, message: String) -> RenderError {
        match &self.origin {
            Some(at) => RenderError::refused(format!("{at}: the sun: {message}")),
            None => RequestError::new(setting, message).into(),
        }
    }
}

/// The day of the year a sun is seen on, and the day its solar table was made for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SunDay {
    /// The day the sun is seen on (1–366): its date's for a sun given by time, the table's
    /// for a direction (which has no date).
    pub day_of_year: u16,
    /// The day the solar table was made for (LOWTRAN7's IDAY).
    pub table_day_of_year: u16,
}

impl SunDay {
    /// The day of `spec` against a table made for `table_day_of_year`.
    #[must_use]
    pub fn new(spec: &SunSpec, table_day_of_year: u16) -> Self {
        Self {
            day_of_year: spec.day_of_year().unwrap_or(table_day_of_year),
            table_day_of_year,
        }
    }

    /// The factor on the table's beam: the day's `(r₀/r)²` over the table day's (exactly 1
    /// on the table's own day).
    #[must_use]
    pub fn beam_factor(self) -> f64 {
        if self.day_of_year == self.table_day_of_year {
            return 1.0;
        }
        earth_sun_factor(self.day_of_year) / earth_sun_factor(self.table_day_of_year)
    }

    /// The sun's angular radius on the day, degrees: the mean radius (at the mean
    /// distance `r₀`) times `r₀/r`, the square root of Spencer's `(r₀/r)²`.
    #[must_use]
    pub fn angular_radius_deg(self) -> f64 {
        SUN_ANGULAR_RADIUS_DEG * earth_sun_factor(self.day_of_year).sqrt()
    }
}

/// The warning for a sun seen on another day than its table's (`None` on the table's own
/// day, for a direction, or without a solar table): what the beam was scaled by.
pub(crate) fn distance_note(
    request: &SunRequest,
    spectral: &SpectralAtmosphere,
    name: &str,
) -> Option<String> {
    let solar = spectral.solar.as_ref()?;
    let day = SunDay::new(&request.spec, solar.day_of_year);
    if day.day_of_year == day.table_day_of_year {
        return None;
    }
    let scattered = if solar.relative_azimuth_deg.is_empty() {
        ""
    } else {
        "; the sunlight the air scatters keeps the table's day"
    };
    Some(format!(
        "the sun is seen on day {} of its year, and the solar table of `{name}` was made for \
         day {}: the sun's beam is scaled by the two days' Earth-Sun distance factors, x{:.4} \
         (Spencer 1971; the transmittance is the table's), and the disk's radius is the \
         day's, {:.4} deg{scattered}",
        day.day_of_year,
        day.table_day_of_year,
        day.beam_factor(),
        day.angular_radius_deg()
    ))
}

/// What the sun's day and table make of a frame, said once before it is traced: the
/// warning of [`distance_note`], then [`scattering`]'s direction and warning.
pub(crate) fn by_day(
    request: Option<&SunRequest>,
    position: Option<&SunPosition>,
    spectral: &SpectralAtmosphere,
    name: &str,
    mut warn: impl FnMut(String),
) -> Option<ScatterSun> {
    if let Some(note) = request.and_then(|r| distance_note(r, spectral, name)) {
        warn(note);
    }
    scattering(request, position, spectral, name, warn)
}

/// The sub-bands a sunlit frame is traced with when no count was asked for, chosen or
/// piloted. One sub-band (the band model) is off by kelvins by day on the surfaces that
/// reflect most: besides the sunlight (whose own path τ, [`sunlit_path_transmission`],
/// holds it within 0.6 % at any count), a sub-band multiplies band averages of the view
/// path's τ, the sky it reflects and the emission's Planck weight. Measured against the
/// full grid through LOWTRAN7's US Standard 1976 (a 300 K plate 1 m above the ground seen
/// straight down from 1 km, the sun 60° from the zenith, docs/accuracy.md "Sub-bands by
/// day"): an ε 0.3 plate in 3–5 µm +1.40, +0.84, +0.14, +0.11, +0.06 K at 1, 2, 4, 8,
/// 16 sub-bands, in 8–14 µm +1.37, +1.63, +0.77, +0.16, +0.06 K (the reflected sky's,
/// the same at night); the daylight library's aluminium +2.10 to +0.12 K in 3–5 µm and
/// +3.35 to +0.12 K in 8–14 µm, its grass, water, clay and panel within 0.03 K from 8 on.
/// 16 is the least count that holds every one of them within 0.3 K, with the same rays:
/// the daylight pipeline's 3–5 µm frame takes 1.6 s against 0.8 s at one sub-band.
pub const DAYLIGHT_SUB_BANDS: usize = 16;

/// The count a sunlit frame takes by default over `split` on `spectral`'s grid:
/// [`DAYLIGHT_SUB_BANDS`], or the full grid where the band holds fewer intervals.
pub(crate) fn day_sub_bands(spectral: &SpectralAtmosphere, split: &Split<'_>) -> SubBandCount {
    let [lo, hi] = split.range_um;
    let intervals =
        irsig_atmosphere::sub_band_edges(&spectral.grid, lo, hi, SubBandCount::Full, |_, _| 1.0)
            .map_or(0, |edges| edges.len().saturating_sub(1));
    if intervals > DAYLIGHT_SUB_BANDS {
        SubBandCount::Count(DAYLIGHT_SUB_BANDS)
    } else {
        SubBandCount::Full
    }
}

/// What a sunlit frame's default sub-bands are and why, said once on stderr.
pub(crate) fn day_sub_bands_note(spelling: Spelling, count: SubBandCount) -> String {
    let sub_bands = spelling.of(Setting::SubBands);
    let chosen = match count {
        SubBandCount::Full => {
            "one sub-band per interval of the atmosphere's grid (the full grid, which has \
             fewer intervals in this band)"
                .to_owned()
        }
        SubBandCount::Count(k) => format!("{k} sub-bands"),
    };
    format!(
        "by day with no sub-band count given, the frame is traced in {chosen}: one sub-band \
         (the band model) is up to 1.4 K off an e 0.3 surface and 3.3 K off aluminium by day, \
         against 0.12 K at most with {DAYLIGHT_SUB_BANDS} (docs/accuracy.md, \"Sub-bands by \
         day\"); give {sub_bands} 1 for the band model or {sub_bands} full for the spectral \
         integral"
    )
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
) -> RenderError {
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
/// `spectral`'s `solar` table at the Earth–Sun distance of the sun's day, its disk's
/// radius that day's ([`SunDay`]).
///
/// # Errors
/// An atmosphere without a `solar` table, or one made for another zenith angle or whose
/// suns do not cover this one (a request error naming the sun's setting, with the angles),
/// or a sub-band the table cannot be integrated over.
pub(crate) fn sun(
    request: &SunRequest,
    position: &SunPosition,
    name: &str,
    spectral: &SpectralAtmosphere,
    split: &Split<'_>,
    collapsed: (SubBandCount, &Collapsed),
    spelling: Spelling,
) -> Result<Sun, RenderError> {
    let (count, collapsed) = collapsed;
    let Some(solar) = spectral.solar.as_ref() else {
        return Err(no_solar_table(
            request,
            name,
            "a night atmosphere (its plan had no sun)",
            spelling,
        ));
    };
    let zeniths = solar.zeniths_deg();
    let (first, last) = (zeniths[0], zeniths[zeniths.len() - 1]);
    let z = position.geometric_zenith_deg;
    if !(z >= first - ZENITH_TOLERANCE_DEG && z <= last + ZENITH_TOLERANCE_DEG) {
        let table = if zeniths.len() == 1 {
            format!(
                "is for a sun at {first} deg (the two must agree within \
                 {ZENITH_TOLERANCE_DEG} deg)"
            )
        } else {
            format!(
                "holds suns from {first} to {last} deg (the beam is interpolated between \
                 them, not beyond)"
            )
        };
        let fix = if zeniths.len() == 1 {
            how_to_build(spelling)
        } else {
            format!(
                "plan suns that cover this one (irsig-atmos plan --sun-utc START/END/STEP \
                 with the place, or --sun-zeniths-deg) and build again; or {}",
                how_to_build(spelling)
            )
        };
        return Err(request.refuse(
            request.setting(),
            format!(
                "the sun is {z:.4} deg from the zenith, but the solar table of `{name}` \
                 {table}: {fix}"
            ),
        ));
    }
    let day = SunDay::new(&request.spec, solar.day_of_year);
    let factor = day.beam_factor();
    let beams = collapsed
        .iter()
        .map(|(band, _)| {
            let (lo, hi) = (band.lambda_min_um(), band.lambda_max_um());
            let direct = DirectSun::new(spectral, lo, hi, |l| split.weight(l))
                .and_then(|d| d.at_zenith(z))
                .map_err(|e| {
                    RenderError::atmosphere(format!("the sun's beam over {lo}-{hi} um"), e)
                })?;
            let normal = solar
                .altitude_m
                .iter()
                .map(|&h| direct.normal_w_m2(h) * factor)
                .collect();
            let pairs =
                sunlit_path_transmission(spectral, split, [lo, hi], count, z).map_err(|e| {
                    RenderError::atmosphere(
                        format!("the sunlight's path transmittance over {lo}-{hi} um"),
                        e,
                    )
                })?;
            SunBeam::new(solar.altitude_m.clone(), normal)
                .and_then(|b| b.with_path_transmission(pairs))
                .map_err(|e| RenderError::trace(format!("the sun's beam over {lo}-{hi} um"), e))
        })
        .collect::<Result<Vec<_>, _>>()?;
    let mut sun = Sun::new(position.to_scene_direction().into(), beams);
    sun.angular_radius_deg = day.angular_radius_deg();
    sun.shadow_rays = request.shadow_rays;
    Ok(sun)
}

/// The `(τ, τ_sun)` pairs of the sub-band `[lo, hi]` µm of `split` (a sub-band of a count
/// `count`) for [`SunBeam::with_path_transmission`]: for every slant path of `spectral`'s
/// slant table, its τ as the sub-band's atmosphere is collapsed (weighted by the response;
/// with more than one sub-band, times the blackbody at
/// [`SHARE_REFERENCE_K`](crate::band::SHARE_REFERENCE_K)), and its τ weighted by the
/// response times the direct beam at the ground, `E_toa(λ)·τ_sun(λ, 0 m)`, of the table's sun
/// nearest `zenith_deg`.
///
/// Why: a sub-band's reflected sunlight at the sensor is `∫ τ_path ρ E dλ`, and the tracer
/// has `τ̄_path·ρ̄·Ē`. The beam `Ē` is integrated exactly (`DirectSun`), ρ is grey within a
/// sub-band for most materials; what the product misses is `τ̄_path`: the sun's own path
/// (an air mass of 2.9 at 70°) has already taken out the wavelengths the view path absorbs,
/// so the sunlight sees the view path at its clear wavelengths. On the daylight pipeline's
/// LOWTRAN7 atmosphere (mid-latitude winter, sun at 70°), 3–5 µm, one sub-band: through 1
/// km straight down τ̄ = 0.677 (response-weighted) and 0.640 (300 K Planck-weighted)
/// against 0.856 sunlight-weighted, so the product is 20.9 % short (−1.29 K on a 300 K
/// plate of ε 0.3); along the camera's 23 m path at 80° from the nadir, 0.884 against
/// 0.978, 9.7 % short (the grass's 8.6 % in docs/accuracy.md); in 8–14 µm 6.9 % and 1.0 %.
/// More sub-bands shrink the covariance only as their edges happen to fall on the CO₂ and
/// water bands' edges: with edges on equal shares of the 300 K emission, 2 sub-bands are
/// worse than 1 (−2.9 K), 4 and 8 near exact, 16 −0.09 K on the same plate; edges on
/// equal shares of the emission plus a reflectance-0.5 surface's sunlight were tried and are
/// worse at 4 and 8 (they move the edges off the CO₂ band). Weighting the sunlight's τ by
/// the sunlight makes each sub-band's product exact at the table's paths, whatever the
/// edges. The two averages of one path are nearly a function of each other
/// (both fall with the absorber along the path): between the table's paths the tracer
/// interpolates `τ_sun` linearly in `τ`, which misses a left-out path of the table by at
/// most 0.6 % of its `τ_sun` (grazing paths above 1 km). An empty list (no slant table, no
/// sunlight in the sub-band) keeps `τ_sun = τ`.
///
/// # Errors
/// A sub-band the tables cannot be integrated over.
fn sunlit_path_transmission(
    spectral: &SpectralAtmosphere,
    split: &Split<'_>,
    [lo, hi]: [f64; 2],
    count: SubBandCount,
    zenith_deg: f64,
) -> Result<Vec<[f64; 2]>, irsig_atmosphere::AtmosphereError> {
    let (Some(slant), Some(solar)) = (&spectral.slant, &spectral.solar) else {
        return Ok(Vec::new());
    };
    let n = spectral.grid.points.len();
    let zeniths = solar.zeniths_deg();
    let row = (0..zeniths.len())
        .min_by(|&a, &b| {
            (zeniths[a] - zenith_deg)
                .abs()
                .total_cmp(&(zeniths[b] - zenith_deg).abs())
        })
        .unwrap_or(0);
    let (Some(ground), etoa) = (
        solar.transmission_of(row).and_then(|t| t.get(..n)),
        &solar.extraterrestrial_w_m2_per_unit,
    ) else {
        return Ok(Vec::new());
    };
    if etoa.len() != n || n == 0 {
        return Ok(Vec::new());
    }
    let beam = |i: usize| f64::from(etoa[i]) * f64::from(ground[i]);
    let sunlit = BandQuadrature::new(&spectral.grid, lo, hi, |l| split.weight(l))?;
    let air = if count.is_band() {
        BandQuadrature::new(&spectral.grid, lo, hi, |l| split.weight(l))?
    } else {
        BandQuadrature::new(&spectral.grid, lo, hi, |l| {
            split.weight(l) * spectral_radiance_per_um(l, crate::band::SHARE_REFERENCE_K)
        })?
    };
    let total = sunlit.integral(beam);
    if !(total.is_finite() && total > 0.0) {
        return Ok(Vec::new());
    }
    let mut pairs: Vec<[f64; 2]> = slant
        .transmission
        .chunks_exact(n)
        .map(|tau| {
            let weighted = sunlit.integral(|i| beam(i) * f64::from(tau[i])) / total;
            [air.transmission(tau), weighted.clamp(0.0, 1.0)]
        })
        .filter(|p| p[0].is_finite() && p[1].is_finite())
        .collect();
    pairs.sort_by(|a, b| a[0].total_cmp(&b[0]));
    // Paths of one τ (an opaque sub-band's zeros, repeated rows) keep their first.
    pairs.dedup_by(|b, a| b[0] <= a[0]);
    Ok(pairs)
}

/// The sun a frame's scattered sunlight is read for: the direction toward it (scene
/// frame), whose horizontal part sets each line of sight's azimuth from the sun, and its
/// geometric zenith angle, at which a day's table of several suns is interpolated (the
/// table's suns are geometric, as the beam's are).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct ScatterSun {
    pub(crate) to_sun: [f64; 3],
    pub(crate) geometric_zenith_deg: f64,
}

/// Whether the frame's sub-band atmospheres add the sunlight scattered into their paths
/// and sky: with a sun and an atmosphere whose `solar` table has scattered tables, the
/// sun they are read for ([`ScatterSun`]); with a sun and none, `None` and a warning
/// (`warn`) that the frame holds the direct beam only.
pub(crate) fn scattering(
    request: Option<&SunRequest>,
    position: Option<&SunPosition>,
    spectral: &SpectralAtmosphere,
    name: &str,
    warn: impl FnOnce(String),
) -> Option<ScatterSun> {
    let (Some(_), Some(position)) = (request, position) else {
        return None;
    };
    match spectral.solar.as_ref() {
        Some(solar) if !solar.relative_azimuth_deg.is_empty() => Some(ScatterSun {
            to_sun: position.to_scene_direction(),
            geometric_zenith_deg: position.geometric_zenith_deg,
        }),
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

/// `atmosphere`, the sub-band `band`'s of `split`, by day (`sun`: the sun it is lit by)
/// with the sunlight `spectral` scatters into it over the sub-band, with the
/// band's response (the weight its radiances are collapsed with).
///
/// # Errors
/// A sub-band the scattered tables cannot be integrated over.
pub(crate) fn scattered(
    atmosphere: irsig_atmosphere::PrecomputedAtmosphere,
    sun: Option<ScatterSun>,
    spectral: &SpectralAtmosphere,
    split: Split<'_>,
    band: &irsig_radiometry::Band,
) -> Result<irsig_atmosphere::PrecomputedAtmosphere, RenderError> {
    let Some(sun) = sun else {
        return Ok(atmosphere);
    };
    let (lo, hi) = (band.lambda_min_um(), band.lambda_max_um());
    let s = ScatteredSunlight::at_sun(
        spectral,
        lo,
        hi,
        |l| split.weight(l),
        sun.to_sun,
        sun.geometric_zenith_deg,
    )
    .map_err(|e| RenderError::atmosphere(format!("the scattered sunlight over {lo}-{hi} um"), e))?;
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
) -> Result<irsig_atmosphere::PrecomputedAtmosphere, RenderError> {
    let (lo, hi) = (band.lambda_min_um(), band.lambda_max_um());
    let slabs = irsig_atmosphere::slab::SlabPaths::new(spectral, lo, hi, |l| split.weight(l))
        .map_err(|e| RenderError::atmosphere(format!("the slab tables over {lo}-{hi} um"), e))?;
    Ok(match slabs {
        Some(s) => atmosphere.with_slabs(s),
        None => atmosphere,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A sun seen at `utc` from the equator on the prime meridian.
    fn at(utc: &str) -> SunSpec {
        SunSpec::At {
            utc: utc.to_owned(),
            latitude_deg: 0.0,
            longitude_deg: 0.0,
            altitude_m: 0.0,
            refraction: None,
            delta_t_s: None,
            delta_ut1_s: None,
        }
    }

    /// `(a/r)²` of a Keplerian orbit to first order in its eccentricity `e = 0.0167`,
    /// `r/a = 1 − e cos M`, the mean anomaly `M` counted from perihelion on 3 January: an
    /// estimate independent of Spencer's series, within about `e²` of the orbit.
    fn kepler(day: u16) -> f64 {
        let m = std::f64::consts::TAU * (f64::from(day) - 3.0) / 365.256;
        (1.0 - 0.0167 * m.cos()).powi(-2)
    }

    #[test]
    fn a_beam_seen_on_another_day_than_its_tables_is_scaled_by_the_distances() {
        // Seen on 1 March 2026 (day 60), the table made for day 286 (13 October).
        // Spencer's series by hand, Γ = 2π(d − 1)/365:
        // day 60, Γ = 1.01564: 1.000110 + 0.034221·0.52708 + 0.001280·0.84982
        //   + 0.000719·(−0.44438) + 0.000077·0.89584 = 1.018984;
        // day 286, Γ = 4.90605: 1.000110 + 0.034221·0.19245 + 0.001280·(−0.98131)
        //   + 0.000719·(−0.92592) + 0.000077·(−0.37771) = 1.004745;
        // the table's beam is 1.4172 % too weak for 1 March.
        let day = SunDay::new(&at("2026-03-01T10:00:00Z"), 286);
        assert_eq!(day.day_of_year, 60);
        let f = day.beam_factor();
        assert!((f - 1.018_984 / 1.004_745).abs() < 2e-6, "{f}");
        assert!((f - 1.014_17).abs() < 1e-5, "{f}");
        // And the orbit's own ratio, to Spencer's 0.1 %.
        assert!((f - kepler(60) / kepler(286)).abs() < 1e-3, "{f}");
        // January against July: ±3.4 % about the mean, (1.01671/0.98329)² = 1.06913 from
        // the aphelion and perihelion distances.
        let jan_july = SunDay::new(&at("2026-01-03T12:00:00Z"), 185).beam_factor();
        assert!((jan_july - 1.069_13).abs() < 2e-3, "{jan_july}");
        let july_jan = SunDay::new(&at("2026-07-04T12:00:00Z"), 3).beam_factor();
        assert!((july_jan * jan_july - 1.0).abs() < 1e-12, "{july_jan}");
        // On the table's own day, or for a direction (no date), the table's beam exactly.
        let same = SunDay::new(&at("2026-10-13T10:00:00Z"), 286);
        assert_eq!(
            (same.day_of_year, same.beam_factor().to_bits()),
            (286, 1f64.to_bits())
        );
        let direction = SunSpec::Direction {
            zenith_deg: 30.0,
            azimuth_deg: 0.0,
        };
        assert_eq!(
            SunDay::new(&direction, 60).beam_factor().to_bits(),
            1f64.to_bits()
        );
        // The last day of a leap year is day 366, taken as it is.
        let leap = SunDay::new(&at("2024-12-31T12:00:00Z"), 1);
        assert_eq!(leap.day_of_year, 366);
        assert!((leap.beam_factor() - 1.0).abs() < 1e-3);
    }

    #[test]
    fn the_disk_is_larger_at_perihelion_and_smaller_at_aphelion() {
        // α = 0.2666° · a/r: 0.2666/0.98329 = 0.27113° on 3 January, 0.2666/1.01671 =
        // 0.26222° on 4 July.
        let radius = |utc: &str, table: u16| SunDay::new(&at(utc), table).angular_radius_deg();
        let near = radius("2026-01-03T12:00:00Z", 185);
        let far = radius("2026-07-04T12:00:00Z", 3);
        assert!((near - 0.27113).abs() < 2e-4, "{near}");
        assert!((far - 0.26222).abs() < 2e-4, "{far}");
        // Near the mean distance (early April, early October) it is the mean radius.
        assert!((radius("2026-04-04T12:00:00Z", 1) - SUN_ANGULAR_RADIUS_DEG).abs() < 2e-4);
        // A direction is seen on its table's day: day 172's radius.
        let direction = SunSpec::Direction {
            zenith_deg: 70.0,
            azimuth_deg: 0.0,
        };
        let june = SunDay::new(&direction, 172).angular_radius_deg();
        assert!((june - 0.2666 / 1.0163).abs() < 2e-4, "{june}");
        // The disk's radiance E/Ω is the same on both days: E ∝ (a/r)², Ω ∝ α².
        let (e_near, e_far) = (earth_sun_factor(3), earth_sun_factor(185));
        let omega = |a: f64| std::f64::consts::TAU * (1.0 - a.to_radians().cos());
        assert!((e_near / omega(near) / (e_far / omega(far)) - 1.0).abs() < 1e-5);
    }
}
