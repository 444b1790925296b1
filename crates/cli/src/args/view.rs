//! The views a tool renders or plans for, and the unit of the 1990 files: repeatable
//! `--view FILE` read with the one sun a view file may give ([`ViewArgs`]), the legacy
//! unit ([`LegacyUnitArgs`]: `--legacy-unit`, km by default, the unit of the thesis's
//! files), and irsig-trace's old spelling of several views after one flag
//! ([`TrailingViews`], hidden).

use clap::{Arg, ArgAction, ArgMatches, FromArgMatches};
use irsig_atmosphere::sun::{SunSpec, keep_one_sun, parse_views_and_sun};
use irsig_formats::legacy::decode;
use irsig_formats::views::ViewSun;
use irsig_model::{LengthUnit, View};

use crate::Input;

/// The unit of the 1990 files' lengths when `--legacy-unit` is not given: km, the unit of
/// the thesis's facet, scene, viewing and execute files.
pub const LEGACY_UNIT_DEFAULT: LengthUnit = LengthUnit::Km;

/// `--legacy-unit UNIT`: the length unit of the 1990 files, converted to metres on reading.
#[derive(Debug, Clone, Copy, Default, clap::Args)]
pub struct LegacyUnitArgs {
    /// Length unit of the 1990 files (facet, scene, viewing and execute files), converted to
    /// metres on reading: m, km, cm, mm, ft or in [default: km, the thesis's]. Canonical
    /// files are always in metres.
    #[arg(
        id = "legacy_unit",
        long = "legacy-unit",
        value_name = "UNIT",
        value_parser = super::length_unit
    )]
    pub given: Option<LengthUnit>,
}

impl LegacyUnitArgs {
    /// The unit: the one given, else km.
    #[must_use]
    pub fn unit(&self) -> LengthUnit {
        self.given.unwrap_or(LEGACY_UNIT_DEFAULT)
    }
}

/// A view file read: its input (bytes and name) and its views.
pub type ViewFile = (Input, Vec<View>);

/// The view files: canonical RON (a view or a list of views) or 1990 viewing files, one per
/// `--view`, frames numbered in the order given; a single RON view may give the run's sun.
#[derive(Debug, Clone, Default, clap::Args)]
pub struct ViewArgs {
    /// A view file: a canonical RON view, a RON list of views, or a 1990 viewing file
    /// (told apart by the first character: a number starts a viewing file); repeat for
    /// more, frames numbered in the order given.
    #[arg(id = "view", long = "view", value_name = "FILE")]
    pub files: Vec<String>,
    /// The unit of 1990 viewing files.
    #[command(flatten)]
    pub unit: LegacyUnitArgs,
}

impl ViewArgs {
    /// The views of every file, each with its file (its bytes go into a run's record), and
    /// the one `sun` they may give: a second file with a sun is refused at its place.
    ///
    /// # Errors
    /// A file that cannot be read or parsed, a bad sun at its line and column, two suns.
    pub fn read(&self) -> miette::Result<(Vec<ViewFile>, Option<ViewSun<SunSpec>>)> {
        read_views(&self.files, self.unit.unit())
    }
}

/// The views of the view files `paths` in `unit` (1990 viewing files), as
/// [`ViewArgs::read`].
///
/// # Errors
/// As [`ViewArgs::read`].
pub fn read_views(
    paths: &[String],
    unit: LengthUnit,
) -> miette::Result<(Vec<ViewFile>, Option<ViewSun<SunSpec>>)> {
    let mut files = Vec::new();
    let mut sun: Option<ViewSun<SunSpec>> = None;
    for path in paths {
        let input = crate::read_input(path)?;
        let text = decode(&input.name, &input.bytes)?;
        let (views, this) = parse_views_and_sun(&input.name, text, unit)?;
        keep_one_sun(&mut sun, this).map_err(|e| miette::miette!("{e}"))?;
        files.push((input, views));
    }
    Ok((files, sun))
}

/// The clap id of [`TrailingViews`]' hidden values.
const TRAILING: &str = "views_after_view";

/// irsig-trace's old spelling of several views, `--view A B C`, kept hidden: the files that
/// follow a `--view`'s own, merged with [`ViewArgs::files`] in the order given. A value
/// anywhere else on the line is refused as clap refuses a stray word. Flatten it before the
/// [`ViewArgs`] (clap's derive takes a flattened struct's values out of the matches as it
/// reads them, and this reads `--view`'s places); after them, a trailing file is refused.
#[derive(Debug, Clone, Default)]
pub struct TrailingViews {
    /// Every view file in the order given, `--view`'s and the trailing ones; `None` when
    /// none trails, so that [`ViewArgs::files`] stands as it is.
    pub in_order: Option<Vec<String>>,
}

impl TrailingViews {
    /// The view files in the order given: `views`' own, with the trailing ones among them.
    #[must_use]
    pub fn files<'a>(&'a self, views: &'a ViewArgs) -> &'a [String] {
        self.in_order.as_deref().unwrap_or(&views.files)
    }
}

impl clap::Args for TrailingViews {
    fn augment_args(cmd: clap::Command) -> clap::Command {
        cmd.arg(
            Arg::new(TRAILING)
                .value_name("FILE")
                .num_args(1..)
                .action(ArgAction::Append)
                .requires("view")
                .hide(true),
        )
    }

    fn augment_args_for_update(cmd: clap::Command) -> clap::Command {
        Self::augment_args(cmd)
    }
}

impl FromArgMatches for TrailingViews {
    fn from_arg_matches(matches: &ArgMatches) -> Result<Self, clap::Error> {
        let indexed = |id: &str| -> Vec<(usize, String)> {
            match (matches.indices_of(id), matches.get_many::<String>(id)) {
                (Some(at), Some(values)) => at.zip(values.cloned()).collect(),
                _ => Vec::new(),
            }
        };
        let trailing = indexed(TRAILING);
        if trailing.is_empty() {
            return Ok(Self::default());
        }
        let mut all = indexed("view");
        let views: Vec<usize> = all.iter().map(|(i, _)| *i).collect();
        // Each trailing value follows a --view's value or another trailing one at once.
        for (i, (at, value)) in trailing.iter().enumerate() {
            let previous = at.checked_sub(1);
            let follows = previous
                .is_some_and(|p| views.contains(&p) || trailing[..i].iter().any(|(t, _)| *t == p));
            if !follows {
                return Err(clap::Error::raw(
                    clap::error::ErrorKind::UnknownArgument,
                    format!(
                        "unexpected argument '{value}' found: give each view file with its \
                         own --view FILE\n"
                    ),
                ));
            }
        }
        all.extend(trailing);
        all.sort_by_key(|(i, _)| *i);
        Ok(Self {
            in_order: Some(all.into_iter().map(|(_, v)| v).collect()),
        })
    }

    fn update_from_arg_matches(&mut self, matches: &ArgMatches) -> Result<(), clap::Error> {
        *self = Self::from_arg_matches(matches)?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Debug, clap::Parser)]
    struct Cli {
        #[command(flatten)]
        trailing: TrailingViews,
        #[command(flatten)]
        views: ViewArgs,
        #[arg(long)]
        scene: Option<String>,
    }

    fn files(args: &[&str]) -> Result<Vec<String>, String> {
        use clap::Parser;
        let cli = Cli::try_parse_from(std::iter::once("t").chain(args.iter().copied()))
            .map_err(|e| e.to_string())?;
        Ok(cli.trailing.files(&cli.views).to_vec())
    }

    #[test]
    fn views_repeat_and_the_old_list_after_one_flag_keeps_its_order() {
        assert_eq!(files(&["--view", "a", "--view", "b"]).unwrap(), ["a", "b"]);
        assert_eq!(
            files(&["--view", "a", "b", "c", "--scene", "s"]).unwrap(),
            ["a", "b", "c"]
        );
        assert_eq!(
            files(&["--view", "a", "b", "--view", "c", "d"]).unwrap(),
            ["a", "b", "c", "d"]
        );
        assert_eq!(files(&["--view=a", "b"]).unwrap(), ["a", "b"]);
        assert!(files(&[]).unwrap().is_empty());
        // A stray word elsewhere is not a view.
        let e = files(&["--scene", "s", "x", "--view", "a"]).unwrap_err();
        assert!(e.contains("'x'") && e.contains("--view FILE"), "{e}");
        assert!(files(&["x"]).is_err());
    }

    #[test]
    fn the_legacy_unit_is_km_unless_given() {
        assert_eq!(LegacyUnitArgs::default().unit(), LengthUnit::Km);
        let m = LegacyUnitArgs {
            given: Some(LengthUnit::M),
        };
        assert_eq!(m.unit(), LengthUnit::M);
    }
}
