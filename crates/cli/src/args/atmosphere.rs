//! `--atmosphere`: the atmosphere a tool traces through or plans with, one flag whose
//! accepted values depend on the command ([`AtmosphereArgs`] over an
//! [`AtmosphereForms`]): a built-in, a file or a vacuum for the tracer ([`Traced`]); a
//! LOWTRAN7 standard model for a plan of LOWTRAN7 runs ([`StandardModel`]). The value is the
//! name as given, refused at parse time when the command cannot take it.

use std::marker::PhantomData;

use irsig_atmosphere::BUILTIN_NAMES;

/// What a command takes for `--atmosphere`, refused at parse time, and how its help says
/// so.
pub trait AtmosphereForms: std::fmt::Debug + Clone + Default + Send + Sync + 'static {
    /// `--atmosphere`'s help.
    const HELP: &'static str;

    /// Whether the command can take `name`.
    ///
    /// # Errors
    /// A value the command does not take, in words.
    fn accepts(name: &str) -> Result<(), String>;
}

/// A built-in LOWTRAN7 model, an atmosphere file, or `none`, a vacuum (the tracer).
#[derive(Debug, Clone, Copy, Default)]
pub struct Traced;

/// A LOWTRAN7 standard model, by name or by LOWTRAN7's number (a plan of LOWTRAN7 runs).
#[derive(Debug, Clone, Copy, Default)]
pub struct StandardModel;

impl AtmosphereForms for Traced {
    const HELP: &'static str = "The atmosphere: a built-in LOWTRAN7 model (us-std-1976, \
        tropical, midlat-summer, midlat-winter, subarctic-summer, subarctic-winter; spectra \
        7.41-14.08 um, and 2.99-5.00 um at night: with a sun, build the atmosphere for it \
        with `irsig-atmos plan --sun-zenith-deg` and `build`), a canonical or spectral \
        atmosphere file (`irsig-atmos build` writes one), or `none` (a vacuum under \
        --sky-radiance) [default: none, with a note on stderr]. A built-in is collapsed from \
        its spectra over any band other than its tables' flat 8-14; with a band-form \
        atmosphere file, trace the band its tables were integrated over";

    fn accepts(name: &str) -> Result<(), String> {
        if name.is_empty() {
            return Err("expected a built-in's name, a file or `none`".to_owned());
        }
        Ok(())
    }
}

impl AtmosphereForms for StandardModel {
    const HELP: &'static str = "The atmosphere's model: a LOWTRAN7 standard model, tropical, \
        midlat-summer, midlat-winter, subarctic-summer, subarctic-winter or us-std-1976 (or \
        LOWTRAN7's number for it, 1-6)";

    fn accepts(name: &str) -> Result<(), String> {
        let number = name.parse::<u8>().is_ok_and(|n| (1..=6).contains(&n));
        if number || BUILTIN_NAMES.contains(&name) {
            return Ok(());
        }
        Err(format!(
            "expected a LOWTRAN7 standard model, one of {} (or 1-6), found `{name}`",
            BUILTIN_NAMES.join(", ")
        ))
    }
}

/// `--atmosphere` as [`AtmosphereForms`] `K` takes it: one definition of the flag for every
/// command.
#[derive(Debug, Clone, Default, clap::Args)]
pub struct AtmosphereArgs<K: AtmosphereForms> {
    #[arg(id = "atmosphere", long = "atmosphere", value_name = "ATMOSPHERE", help = K::HELP,
          value_parser = parse::<K>)]
    name: Option<String>,
    #[arg(skip)]
    forms: PhantomData<K>,
}

/// `--atmosphere`'s value parser for a command that takes `K`.
fn parse<K: AtmosphereForms>(s: &str) -> Result<String, String> {
    K::accepts(s)?;
    Ok(s.to_owned())
}

impl<K: AtmosphereForms> AtmosphereArgs<K> {
    /// The atmosphere as given, if it was.
    #[must_use]
    pub fn given(&self) -> Option<&str> {
        self.name.as_deref()
    }

    /// `--atmosphere` as if given as `text`.
    ///
    /// # Errors
    /// A value `K` does not take.
    pub fn from_text(text: &str) -> Result<Self, String> {
        Ok(Self {
            name: Some(parse::<K>(text)?),
            forms: PhantomData,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_plan_takes_a_standard_model_and_the_tracer_any_atmosphere() {
        for good in ["us-std-1976", "tropical", "1", "6"] {
            assert!(
                AtmosphereArgs::<StandardModel>::from_text(good).is_ok(),
                "{good}"
            );
        }
        for bad in ["0", "7", "none", "site.spa", "US-STD-1976"] {
            let e = AtmosphereArgs::<StandardModel>::from_text(bad).unwrap_err();
            assert!(e.contains("us-std-1976"), "{bad}: {e}");
        }
        for good in ["none", "us-std-1976", "site.spa"] {
            let a = AtmosphereArgs::<Traced>::from_text(good).unwrap();
            assert_eq!(a.given(), Some(good));
        }
        assert!(AtmosphereArgs::<Traced>::from_text("").is_err());
        assert_eq!(AtmosphereArgs::<Traced>::default().given(), None);
    }

    #[test]
    fn each_help_names_only_what_its_command_takes() {
        assert!(Traced::HELP.contains("`none`") && Traced::HELP.contains("file"));
        assert!(!StandardModel::HELP.contains("none") && !StandardModel::HELP.contains("file"));
        for name in BUILTIN_NAMES {
            assert!(StandardModel::HELP.contains(name) && Traced::HELP.contains(name));
        }
    }
}
