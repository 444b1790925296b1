//! The flags that say where a tool writes, each defined once for every tool that has it:
//! `-o` ([`Output`]), the digital-count image and its LUT ([`DcPng`], [`Lut`]), a colour
//! preview ([`ColourPreview`]), the name of what is written ([`Name`]), RON rather than a
//! binary form ([`Ron`]), the 1990 form of a table ([`Legacy`]) and a conversion back to
//! the 1990 files ([`ToLegacyArgs`]). A tool that says more about one (what `-o` names, an
//! input rather than an output) rewords its help with `mut_arg`; the flag, its value name
//! and its type stay these.

use std::path::PathBuf;

/// `-o/--output PATH`: where the tool writes (a file, a prefix or a directory, as the tool
/// says).
#[derive(Debug, Clone, Default, clap::Args)]
pub struct Output {
    /// Where the output goes (`-` or absent: standard output); written atomically.
    #[arg(id = "output", short = 'o', long = "output", value_name = "PATH")]
    pub path: Option<PathBuf>,
}

impl Output {
    /// The path, which the tool's group or `required_unless_present` made clap require.
    ///
    /// # Errors
    /// No `-o` (bad usage): only when the tool's definition does not require it.
    pub fn required(&self) -> miette::Result<&PathBuf> {
        self.path
            .as_ref()
            .ok_or_else(|| crate::usage_error("give -o PATH: where the output goes"))
    }
}

/// `--dc-png FILE`: the digital-count image.
#[derive(Debug, Clone, Default, clap::Args)]
pub struct DcPng {
    /// Write the digital counts to FILE as a grey PNG, unscaled: 8-bit up to --dc-bits 8,
    /// else 16-bit.
    #[arg(id = "dc_png", long = "dc-png", value_name = "FILE")]
    pub path: Option<PathBuf>,
}

/// `--lut FILE`: the digital counts' lookup table.
#[derive(Debug, Clone, Default, clap::Args)]
pub struct Lut {
    /// Write the digital-count LUT to FILE (text: count, radiance, K, degC for every count).
    #[arg(id = "lut", long = "lut", value_name = "FILE")]
    pub path: Option<PathBuf>,
}

/// `--colour-preview FILE`: the apparent temperature in colour, with its scale.
#[derive(Debug, Clone, Default, clap::Args)]
pub struct ColourPreview {
    /// Write a colour preview PNG (inferno map) with a colour bar labelled in kelvin.
    #[arg(id = "colour_preview", long = "colour-preview", value_name = "FILE")]
    pub path: Option<PathBuf>,
}

/// `--name NAME`: the name of what the tool writes (an object, an atmosphere, a material).
#[derive(Debug, Clone, Default, clap::Args)]
pub struct Name {
    /// The name of what is written (default: the input's).
    #[arg(id = "name", long = "name", value_name = "NAME")]
    pub value: Option<String>,
}

/// `--ron`: write RON, not the binary form a pipe gets.
#[derive(Debug, Clone, Copy, Default, clap::Args)]
pub struct Ron {
    /// Write RON instead of the binary form.
    #[arg(id = "ron", long = "ron")]
    pub on: bool,
}

/// `--legacy`: write a table in its 1990 form.
#[derive(Debug, Clone, Copy, Default, clap::Args)]
pub struct Legacy {
    /// Write the table in its 1990 form rather than the canonical one.
    #[arg(id = "legacy", long = "legacy")]
    pub on: bool,
}

/// `--to-legacy FILE` with `--out-dir DIR` and `--stem STEM`: a canonical file converted
/// back to the 1990 files it stands for.
#[derive(Debug, Clone, Default, clap::Args)]
pub struct ToLegacyArgs {
    /// Convert the other way: this canonical file (or `-`) to the 1990 files, written into
    /// --out-dir.
    #[arg(id = "to_legacy", long = "to-legacy", value_name = "FILE")]
    pub file: Option<String>,
    /// Directory for the 1990 files written by --to-legacy.
    #[arg(
        id = "out_dir",
        long = "out-dir",
        value_name = "DIR",
        requires = "to_legacy",
        default_value = "."
    )]
    pub out_dir: PathBuf,
    /// File stem of the 1990 files written by --to-legacy (default: the name).
    #[arg(
        id = "stem",
        long = "stem",
        value_name = "STEM",
        requires = "to_legacy"
    )]
    pub stem: Option<String>,
}
