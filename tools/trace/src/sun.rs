//! The sun's flags: a direction (`--sun-zenith-deg`, `--sun-azimuth-deg`) or a UTC time and
//! a place (`--sun-utc`, `--latitude-deg`, `--longitude-deg`, `--altitude-m`, spelt as
//! `irsig-atmos sun` spells them), and `--sun-shadow-rays`; or a view file's `sun`
//! (`formats/canonical/view.md`), which is read here with the views. A sun given both ways
//! is refused, naming the flag and the file's line and column: neither wins silently. What
//! they mean physically is `irsig_render::sun`'s.

use irsig_atmosphere::sun::{SunSpec, keep_one_sun, parse_views_and_sun};
use irsig_cli::Input;
use irsig_formats::legacy::decode;
use irsig_formats::views::ViewSun;
use irsig_model::{LengthUnit, View};
use irsig_render::SunRequest;

/// The sun lighting the scene (issue 30). Without these flags, no sun: a night.
#[derive(Debug, Clone, clap::Args)]
#[command(group(clap::ArgGroup::new("sun").args(["sun_zenith_deg", "sun_utc"])))]
pub struct SunArgs {
    /// Light the scene by the sun at this zenith angle, degrees (0 overhead, below 90),
    /// with --sun-azimuth-deg. The atmosphere must be a spectral one built for this sun,
    /// whose solar table is for this zenith angle within 0.0011 deg: `irsig-atmos plan
    /// --sun-zenith-deg Z --day-of-year D`, then `irsig-atmos build`.
    #[arg(
        long,
        value_name = "DEG",
        requires = "sun_azimuth_deg",
        allow_negative_numbers = true
    )]
    pub sun_zenith_deg: Option<f64>,
    /// The sun's azimuth, degrees clockwise from north (the scene's +y; 90 = east, +x), in
    /// [0, 360); with --sun-zenith-deg.
    #[arg(
        long,
        value_name = "DEG",
        requires = "sun_zenith_deg",
        allow_negative_numbers = true
    )]
    pub sun_azimuth_deg: Option<f64>,
    /// Light the scene by the sun seen at this time, UTC (`YYYY-MM-DDTHH:MM:SSZ`), from
    /// --latitude-deg, --longitude-deg and --altitude-m (NREL's SPA, geometric: the zenith
    /// angle `irsig-atmos sun` prints without --pressure-hpa, which is the one to build the
    /// atmosphere for).
    #[arg(long, value_name = "TIME", conflicts_with = "sun_zenith_deg",
          requires_all = ["latitude_deg", "longitude_deg"], allow_hyphen_values = true)]
    pub sun_utc: Option<String>,
    /// Latitude of the scene, degrees, positive north, in [-90, 90]; with --sun-utc.
    #[arg(
        long,
        value_name = "DEG",
        requires = "sun_utc",
        allow_hyphen_values = true
    )]
    pub latitude_deg: Option<f64>,
    /// Longitude of the scene, degrees, positive east, in [-180, 180]; with --sun-utc.
    #[arg(
        long,
        value_name = "DEG",
        requires = "sun_utc",
        allow_hyphen_values = true
    )]
    pub longitude_deg: Option<f64>,
    /// Altitude of the scene's ground, metres above mean sea level (the sun's parallax);
    /// with --sun-utc.
    #[arg(
        long,
        default_value_t = 0.0,
        value_name = "M",
        requires = "sun_utc",
        allow_hyphen_values = true
    )]
    pub altitude_m: f64,
    /// Shadow rays per facet hit toward the sun: 1 aims at the disk's centre (hard
    /// shadows); more sample the disk (soft edges). With a sun of these flags or of the
    /// view file; default 1. With --tolerance the pilot chooses them (pin them with
    /// --pin shadow-rays=N).
    #[arg(long, value_name = "N", conflicts_with = "tolerance")]
    pub sun_shadow_rays: Option<u32>,
}

impl SunArgs {
    /// The sun of the flags or of a view file (`view`), if any.
    ///
    /// # Errors
    /// A sun given by both (naming the flag and the file's place), or shadow rays without a
    /// sun: usage errors.
    pub fn request_with(
        &self,
        view: Option<ViewSun<SunSpec>>,
    ) -> miette::Result<Option<SunRequest>> {
        let flags = self.request();
        let flag = if self.sun_utc.is_some() {
            "--sun-utc"
        } else {
            "--sun-zenith-deg"
        };
        match (flags, view) {
            (Some(_), Some(v)) => Err(irsig_cli::usage_error(format!(
                "{flag} and the `sun` of the view file at {} both give a sun: give it once, \
                 by the flags or in the view file",
                v.location
            ))),
            (Some(r), None) => Ok(Some(r)),
            (None, Some(v)) => Ok(Some(SunRequest {
                spec: v.sun,
                shadow_rays: self.sun_shadow_rays.unwrap_or(1),
                origin: Some(v.location),
            })),
            (None, None) if self.sun_shadow_rays.is_some() => Err(irsig_cli::usage_error(
                "--sun-shadow-rays without a sun: give --sun-zenith-deg and --sun-azimuth-deg, \
                 --sun-utc with the place, or a view file with a `sun`",
            )),
            (None, None) => Ok(None),
        }
    }

    /// The sun the flags ask for, if any.
    #[must_use]
    pub fn request(&self) -> Option<SunRequest> {
        let spec = match (
            self.sun_zenith_deg,
            self.sun_azimuth_deg,
            &self.sun_utc,
            self.latitude_deg,
            self.longitude_deg,
        ) {
            (Some(zenith_deg), Some(azimuth_deg), ..) => SunSpec::Direction {
                zenith_deg,
                azimuth_deg,
            },
            (_, _, Some(utc), Some(latitude_deg), Some(longitude_deg)) => SunSpec::At {
                utc: utc.clone(),
                latitude_deg,
                longitude_deg,
                altitude_m: self.altitude_m,
                refraction: None,
                delta_t_s: None,
                delta_ut1_s: None,
            },
            // clap requires the flags of each form together.
            _ => return None,
        };
        Some(SunRequest {
            spec,
            shadow_rays: self.sun_shadow_rays.unwrap_or(1),
            origin: None,
        })
    }
}

/// A view file read: its input (bytes and name) and its views.
pub type ViewFile = (Input, Vec<View>);

/// The views of the view files `paths`, each with its file (its bytes are recorded in the
/// run), and the one `sun` they may give: a second file with a sun is refused at its place.
///
/// # Errors
/// A file that cannot be read or parsed, a bad sun at its line and column, two suns.
pub fn read_views(
    paths: &[String],
    unit: LengthUnit,
) -> miette::Result<(Vec<ViewFile>, Option<ViewSun<SunSpec>>)> {
    let mut files = Vec::new();
    let mut sun: Option<ViewSun<SunSpec>> = None;
    for path in paths {
        let input = irsig_cli::read_input(path)?;
        let text = decode(&input.name, &input.bytes)?;
        let (views, this) = parse_views_and_sun(&input.name, text, unit)?;
        keep_one_sun(&mut sun, this).map_err(|e| miette::miette!("{e}"))?;
        files.push((input, views));
    }
    Ok((files, sun))
}
