//! The flags that name an input several tools read, each defined once: the raw scene
//! ([`Scene`]), the material library ([`Materials`]), a regions file ([`Regions`]), a
//! radiance image to measure ([`RadianceImage`]), the pilot's decision ([`Decision`]) and
//! the declared uncertainties ([`Uncertainties`]). Each is a path or `-` (standard input),
//! read through [`crate::read_input`]. A flag one tool needs and another does not is
//! optional here; the tool that needs it requires it with a group.

/// `--scene FILE`: the raw scene.
#[derive(Debug, Clone, Default, clap::Args)]
pub struct Scene {
    /// The raw scene (canonical RON or the binary form `irsig-flatten` writes), or `-` for
    /// stdin.
    #[arg(id = "scene", long = "scene", value_name = "FILE")]
    pub file: Option<String>,
}

impl Scene {
    /// The scene's file, which the tool's group made clap require.
    ///
    /// # Errors
    /// No `--scene` (bad usage): only when the tool's definition does not require it.
    pub fn required(&self) -> miette::Result<&str> {
        self.file
            .as_deref()
            .ok_or_else(|| crate::usage_error("give --scene FILE, the raw scene"))
    }
}

/// `--materials FILE`: the material library.
#[derive(Debug, Clone, Default, clap::Args)]
pub struct Materials {
    /// The material library (canonical RON).
    #[arg(id = "materials", long = "materials", value_name = "FILE")]
    pub file: Option<String>,
}

impl Materials {
    /// The library's file, which the tool's group made clap require.
    ///
    /// # Errors
    /// No `--materials` (bad usage): only when the tool's definition does not require it.
    pub fn required(&self) -> miette::Result<&str> {
        self.file
            .as_deref()
            .ok_or_else(|| crate::usage_error("give --materials FILE, the material library"))
    }
}

/// `--regions FILE`: the regions of the local-area analysis.
#[derive(Debug, Clone, Default, clap::Args)]
pub struct Regions {
    /// The regions file (canonical RON): each region a material id, a pixel box or both,
    /// with its reference temperatures.
    #[arg(id = "regions", long = "regions", value_name = "FILE")]
    pub file: Option<String>,
}

impl Regions {
    /// The regions file, which the tool's group made clap require.
    ///
    /// # Errors
    /// No `--regions` (bad usage): only when the tool's definition does not require it.
    pub fn required(&self) -> miette::Result<&str> {
        self.file
            .as_deref()
            .ok_or_else(|| crate::usage_error("give --regions FILE"))
    }
}

/// `--radiance FILE`: an image whose `radiance` layer is measured in place of a truth layer.
#[derive(Debug, Clone, Default, clap::Args)]
pub struct RadianceImage {
    /// Take apparent temperatures from this image's `radiance` layer (W m^-2 sr^-1) in
    /// --band (the sensor stage's EXR, say); the same size as the truth EXR.
    #[arg(id = "radiance", long = "radiance", value_name = "FILE")]
    pub file: Option<String>,
}

/// `--decision FILE`: the tolerance pilot's decision (`*.decision.ron`).
#[derive(Debug, Clone, Default, clap::Args)]
pub struct Decision {
    /// The tolerance pilot's decision (`irsig-trace --tolerance`, `*.decision.ron`).
    #[arg(id = "decision", long = "decision", value_name = "FILE")]
    pub file: Option<String>,
}

/// `--uncertainties FILE`: the inputs' declared uncertainties.
#[derive(Debug, Clone, Default, clap::Args)]
pub struct Uncertainties {
    /// Declared uncertainties of the inputs (canonical RON,
    /// formats/canonical/uncertainties.md).
    #[arg(id = "uncertainties", long = "uncertainties", value_name = "FILE")]
    pub file: Option<String>,
}
