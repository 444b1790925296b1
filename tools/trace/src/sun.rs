//! The sun of a trace: irsig-cli's sun flags ([`SunArgs`]) with `--sun-shadow-rays`, or a
//! view file's `sun` (`formats/canonical/view.md`, read with the views). A sun given both
//! ways is refused, naming the flag and the file's line and column: neither wins silently.
//! What they mean physically is `irsig_render::sun`'s.

use irsig_atmosphere::sun::SunSpec;
use irsig_cli::args::SunArgs;
use irsig_formats::views::ViewSun;
use irsig_render::SunRequest;

/// The sun of the flags (`sun`, with `shadow_rays`) or of a view file (`view`), if any.
///
/// # Errors
/// A sun given by both (naming the flag and the file's place), or shadow rays without a
/// sun: usage errors.
pub fn request(
    sun: &SunArgs,
    shadow_rays: Option<u32>,
    view: Option<ViewSun<SunSpec>>,
) -> miette::Result<Option<SunRequest>> {
    let rays = shadow_rays.unwrap_or(1);
    match (sun.spec(), view) {
        (Some(_), Some(v)) => Err(irsig_cli::usage_error(format!(
            "--{} and the `sun` of the view file at {} both give a sun: give it once, by the \
             flags or in the view file",
            sun.given_flag().unwrap_or_default(),
            v.location
        ))),
        (Some(spec), None) => Ok(Some(SunRequest {
            spec,
            shadow_rays: rays,
            origin: None,
        })),
        (None, Some(v)) => Ok(Some(SunRequest {
            spec: v.sun,
            shadow_rays: rays,
            origin: Some(v.location),
        })),
        (None, None) if shadow_rays.is_some() => Err(irsig_cli::usage_error(
            "--sun-shadow-rays without a sun: give --sun-zenith-deg and --sun-azimuth-deg, \
             --sun-utc with the place, or a view file with a `sun`",
        )),
        (None, None) => Ok(None),
    }
}
