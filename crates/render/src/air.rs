//! The atmosphere of a request: a vacuum, a built-in (in band or spectral form) or a file
//! (a band atmosphere, or a spectral one in either form), read and checked against the
//! band.

use crate::error::{RenderError, RequestError, Setting};
use irsig_formats::canonical::{AnyAtmosphere, read_any_atmosphere};
use irsig_model::SpectralAtmosphere;

/// Where the atmosphere comes from, as asked.
#[derive(Debug, Clone, PartialEq)]
pub enum AtmosphereRequest {
    /// A vacuum whose sky has this radiance, W m⁻² sr⁻¹ (0: cold space).
    Vacuum {
        /// The sky's radiance, W m⁻² sr⁻¹.
        sky_radiance_w_m2_sr: f64,
    },
    /// A built-in by name (`irsig_atmosphere::BUILTIN_NAMES`).
    Builtin(String),
    /// A file's bytes: a band atmosphere (RON) or a spectral one (binary or RON).
    File {
        /// The name errors give it.
        name: String,
        /// Its content.
        bytes: Vec<u8>,
    },
}

impl AtmosphereRequest {
    /// The atmosphere `name` names: `none`, a vacuum whose sky has radiance `sky`; a
    /// built-in; else the file `read` reads (`None`: there is no file of that name).
    ///
    /// # Errors
    /// No built-in or file of that name (a request error listing the built-ins), or the
    /// file's own error.
    pub fn named(
        name: &str,
        sky_radiance_w_m2_sr: f64,
        read: impl FnOnce(&str) -> miette::Result<Option<(String, Vec<u8>)>>,
    ) -> Result<Self, RenderError> {
        if name == "none" {
            return Ok(Self::Vacuum {
                sky_radiance_w_m2_sr,
            });
        }
        if irsig_atmosphere::BUILTIN_NAMES.contains(&name) {
            return Ok(Self::Builtin(name.to_owned()));
        }
        let file = read(name)
            .map_err(|e| RenderError::caller(format!("reading the atmosphere `{name}`"), e))?;
        match file {
            Some((name, bytes)) => Ok(Self::File { name, bytes }),
            None => Err(RequestError::with_value(
                Setting::Atmosphere,
                format!("`{name}`"),
                format!(
                    "no built-in atmosphere or file of that name; built-ins are: {}, or \
                     `none` for a vacuum",
                    irsig_atmosphere::BUILTIN_NAMES.join(", ")
                ),
            )
            .into()),
        }
    }

    /// The name messages give the atmosphere: `none`, the built-in's, the file's.
    #[must_use]
    pub fn name(&self) -> &str {
        match self {
            Self::Vacuum { .. } => "none",
            Self::Builtin(name) | Self::File { name, .. } => name,
        }
    }
}

/// An atmosphere read: band tables, or spectra and the bytes they were read from (what the
/// run hash covers).
#[allow(clippy::large_enum_variant)] // one per run
pub(crate) enum AirData {
    Band(irsig_model::Atmosphere),
    Spectral(SpectralAtmosphere, Vec<u8>),
}

/// The limits of a band request, µm; `None` for the whole spectrum.
pub(crate) fn band_range_um(band: &crate::BandRequest) -> Option<[f64; 2]> {
    match &band.band {
        irsig_radiometry::AnyBand::Band(b) => Some([b.lambda_min_um(), b.lambda_max_um()]),
        irsig_radiometry::AnyBand::Total(_) => None,
    }
}

/// The bytes of the built-in `name`'s spectra a band of `range_um` reads: its 3–5 µm night
/// spectra for a band inside them, else its 8–14 µm ones (which a band outside both is then
/// refused against, [`check_builtin_range`]).
pub(crate) fn builtin_bytes(name: &str, range_um: Option<[f64; 2]>) -> &'static [u8] {
    range_um
        .and_then(|r| irsig_atmosphere::builtin_spectral_bytes_over(name, r))
        .or_else(|| irsig_atmosphere::builtin_spectral_bytes(name))
        .unwrap_or_default()
}

/// The atmosphere of a built-in or a file request: a built-in in spectral form when
/// `spectral` (the spectra over the band of `range_um`, [`builtin_bytes`]), a file in
/// whatever form it holds.
pub(crate) fn read(
    request: &AtmosphereRequest,
    spectral: bool,
    range_um: Option<[f64; 2]>,
) -> Result<AirData, RenderError> {
    match request {
        AtmosphereRequest::Vacuum { .. } => Err(RenderError::internal("a vacuum has no tables")),
        AtmosphereRequest::Builtin(name) if spectral => {
            let bytes = builtin_bytes(name, range_um);
            let a =
                irsig_formats::canonical::binary_spectral::decode(name, bytes).map_err(|e| {
                    RenderError::input(format!("the built-in atmosphere `{name}` is corrupt"), e)
                })?;
            Ok(AirData::Spectral(a, bytes.to_vec()))
        }
        AtmosphereRequest::Builtin(name) => irsig_atmosphere::builtin(name)
            .map(AirData::Band)
            .map_err(|e| RenderError::atmosphere(format!("the built-in atmosphere `{name}`"), e)),
        AtmosphereRequest::File { name, bytes } => Ok(
            match read_any_atmosphere(name, bytes)
                .map_err(|e| RenderError::input(format!("the atmosphere file `{name}`"), e))?
            {
                AnyAtmosphere::Band(a) => AirData::Band(a),
                AnyAtmosphere::Spectral(a) => AirData::Spectral(a, bytes.clone()),
            },
        ),
    }
}

/// Every camera at or below the top of the built-in's data ([`irsig_atmosphere::BUILTIN_TOP_M`],
/// with half a metre for views written to the metre): above it the air over 10 km would be
/// left out of every path, silently.
pub(crate) fn check_builtin_top(
    name: &str,
    views: &[irsig_model::View],
) -> Result<(), RenderError> {
    let top = irsig_atmosphere::BUILTIN_TOP_M;
    match views
        .iter()
        .map(|v| v.position_m()[2])
        .find(|&z| z > top + 0.5)
    {
        None => Ok(()),
        Some(z) => Err(RenderError::refused(format!(
            "the camera is {z:.1} m above the ground, above the {top:.0} m where the built-in \
             atmosphere `{name}`'s data stop: the air above would be left out of every path. \
             Build an atmosphere for this view (irsig-atmos plan --scene SCENE --view VIEW \
             --atmosphere {name}, then irsig-atmos build) and trace through it"
        ))),
    }
}

/// A spectral atmosphere file must cover the band `[lo, hi]` µm: else an error at its grid
/// (`grid.points`, in the RON or in the binary form's RON header), before anything is
/// traced.
pub(crate) fn check_spectral_range(
    name: &str,
    a: &SpectralAtmosphere,
    bytes: &[u8],
    [lo, hi]: [f64; 2],
) -> Result<(), RenderError> {
    let [min, max] = spectral_range_um(a);
    if covers([min, max], [lo, hi]) {
        return Ok(());
    }
    let message = format!(
        "the band {lo}-{hi} um reaches outside this atmosphere's spectral grid, {} um: trace a \
         band inside the grid, or build the atmosphere over the band",
        range_text([min, max], 6)
    );
    Err(RenderError::input(
        format!("the atmosphere `{name}` does not cover the band"),
        irsig_formats::canonical::spectral_atmosphere_error_at_path(
            name,
            bytes,
            "grid.points",
            message,
        ),
    ))
}

/// The wavelengths a spectral atmosphere's grid spans, µm.
pub(crate) fn spectral_range_um(a: &SpectralAtmosphere) -> [f64; 2] {
    let wavelengths = a.grid.points.iter().map(|&p| match a.grid.axis {
        irsig_model::SpectralAxis::WavenumberPerCm => 1e4 / p,
        irsig_model::SpectralAxis::WavelengthUm => p,
    });
    let (min, max) = wavelengths.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), w| {
        (lo.min(w), hi.max(w))
    });
    [min, max]
}

/// Whether `[min, max]` covers `[lo, hi]`, to rounding.
pub(crate) fn covers([min, max]: [f64; 2], [lo, hi]: [f64; 2]) -> bool {
    let slack = covers_slack(max);
    lo >= min - slack && hi <= max + slack
}

/// The rounding [`covers`] forgives at a range's ends, µm.
fn covers_slack(max: f64) -> f64 {
    1e-9 * max
}

/// `[min, max]` µm as a message prints it, `MIN-MAX` to `decimals` places, each end
/// rounded inward (the lower up, the upper down) so that the printed range, typed back as
/// a band, is one [`covers`] takes: a message never offers a range the check refuses.
pub(crate) fn range_text([min, max]: [f64; 2], decimals: i32) -> String {
    let scale = 10_f64.powi(decimals);
    let slack = covers_slack(max);
    let lo = ((min - slack) * scale).ceil() / scale;
    let hi = ((max + slack) * scale).floor() / scale;
    let places = usize::try_from(decimals).unwrap_or(0);
    format!("{lo:.places$}-{hi:.places$}")
}

/// A built-in's spectra must cover the band: else a request error about the band, which
/// names the band, the ranges the built-ins hold and how to get an atmosphere over the
/// band.
pub(crate) fn check_builtin_range(
    name: &str,
    a: &SpectralAtmosphere,
    band: &crate::BandRequest,
    range_um: [f64; 2],
    spelling: crate::Spelling,
) -> Result<(), RenderError> {
    if covers(spectral_range_um(a), range_um) {
        return Ok(());
    }
    let [long, mid] = irsig_atmosphere::BUILTIN_SPECTRAL_RANGES_UM;
    Err(RequestError::with_value(
        Setting::Band,
        &band.label,
        format!(
            "the band, {}, lies inside neither range of the built-in atmosphere `{name}`'s \
             spectra, {} um (8-14 um responses) and {} um (3-5 um responses, night): trace a \
             band inside one of them, or build an atmosphere over the band ({:.3}-{:.3} um) \
             with `irsig-atmos plan` and `irsig-atmos build` (LOWTRAN7) and give its file to \
             {}",
            band.record,
            range_text(long, 3),
            range_text(mid, 3),
            range_um[0],
            range_um[1],
            spelling.of(Setting::Atmosphere)
        ),
    )
    .into())
}

/// The error of sub-bands asked of an atmosphere without spectra.
pub(crate) fn no_spectra(name: &str, count: irsig_atmosphere::SubBandCount) -> RenderError {
    RequestError::with_value(
        Setting::SubBands,
        count,
        format!(
            "the atmosphere `{name}` has no spectra; sub-bands need a spectral atmosphere (a \
             built-in, or a file irsig-atmos build wrote), and the `total` band has none"
        ),
    )
    .into()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_printed_range_typed_back_is_covered() {
        // The built-ins' 3-5 um night spectra span 2000-3340 cm-1: 1e4/3340 = 2.994012 um
        // to 5 um exactly; their 8-14 um spectra 710-1350 cm-1, 7.407407-14.084507 um.
        let [long, mid] = irsig_atmosphere::BUILTIN_SPECTRAL_RANGES_UM;
        assert_eq!(range_text(mid, 3), "2.995-5.000");
        assert_eq!(range_text(long, 3), "7.408-14.084");
        assert_eq!(range_text(mid, 6), "2.994012-5.000000");
        // A band typed as printed is taken, at either precision; 2.994 is below the
        // spectra's first point, 1.2e-5 um further than the data reach, and refused.
        for range in [long, mid] {
            for decimals in [3, 6] {
                let text = range_text(range, decimals);
                let (lo, hi) = text.split_once('-').unwrap();
                let typed = [lo.parse().unwrap(), hi.parse().unwrap()];
                assert!(covers(range, typed), "{text} against {range:?}");
            }
        }
        assert!(!covers(mid, [2.994, 5.0]));
        // Ends that are round numbers print as they are, not a step inward.
        assert_eq!(range_text([3.0, 5.0], 3), "3.000-5.000");
        assert_eq!(range_text([1e4 / 1250.0, 1e4 / 700.0], 2), "8.00-14.28");
    }
}
