//! A run's inputs read and checked as they come ([`PlanBuilder`]), each error at its place
//! in its file, into the [`Plan`] that renders them.

use super::*;

/// A run's request and inputs as they are read: each `read_*` checks its input against
/// what was read before it, and [`PlanBuilder::build`] gives the [`Plan`], which reading
/// no longer changes.
#[derive(Debug)]
pub struct PlanBuilder {
    plan: Plan,
}

impl PlanBuilder {
    /// A plan of `request` to read the inputs into, the request checked: a vacuum's sky
    /// radiance finite and not negative, a tolerance above 0 K at a percentile in (0, 100],
    /// a sun above the horizon (with a tolerance, the pilot decides the sun's models too).
    ///
    /// # Errors
    /// A request error naming the setting.
    pub fn new(request: Request) -> Result<Self, RenderError> {
        if let AtmosphereRequest::Vacuum {
            sky_radiance_w_m2_sr: sky,
        } = request.atmosphere
            && (!sky.is_finite() || sky < 0.0)
        {
            return Err(RequestError::with_value(
                Setting::SkyRadiance,
                sky,
                "out of range: expected a finite radiance of 0 or more",
            )
            .into());
        }
        if let Some(t) = &request.tolerance {
            irsig_model::decision::check_tolerance(t.tolerance_k, "tolerance")
                .map_err(|e| RequestError::new(Setting::Tolerance, e.kind.to_string()))?;
            irsig_model::decision::check_percentile(t.percentile, "percentile")
                .map_err(|e| RequestError::new(Setting::TolerancePercentile, e.kind.to_string()))?;
        }
        let sun = match &request.sun {
            None => None,
            Some(s) => Some(s.position()?),
        };
        let mut inputs = Vec::new();
        match &request.atmosphere {
            AtmosphereRequest::File { bytes, .. } => inputs.push(InputRecord {
                stage: "trace".into(),
                role: "atmosphere".into(),
                sha256: sha256_hex(bytes),
            }),
            AtmosphereRequest::Builtin(name) => {
                let data = air::builtin_bytes(name, air::band_range_um(&request.band));
                inputs.push(InputRecord {
                    stage: "trace".into(),
                    role: "atmosphere (a built-in's spectra)".into(),
                    sha256: sha256_hex(data),
                });
            }
            AtmosphereRequest::Vacuum { .. } => {}
        }
        Ok(Self {
            plan: Plan {
                request,
                run: RunHash::default(),
                scene: None,
                scene_name: String::new(),
                materials: MaterialLibrary::default(),
                materials_name: String::new(),
                maps: Vec::new(),
                views: Vec::new(),
                uncertainties: None,
                decision: None,
                decision_file: None,
                sun,
                inputs,
                warnings: Vec::new(),
            },
        })
    }

    /// Reads the raw scene (canonical RON or binary) from `bytes` of the file `name`. The
    /// first input read: the run hash starts with it.
    ///
    /// # Errors
    /// A malformed scene, at its place in the file.
    pub fn read_scene(&mut self, name: &str, bytes: &[u8]) -> Result<(), RenderError> {
        self.plan.run.field("scene", bytes);
        self.record_input("scene", bytes);
        let scene = irsig_formats::canonical::read_raw_scene(name, bytes)
            .map_err(|e| RenderError::input(format!("reading the scene `{name}`"), e))?;
        self.plan.scene = Some(scene);
        name.clone_into(&mut self.plan.scene_name);
        Ok(())
    }

    /// Reads the material library after the scene: spectral materials' band tables become
    /// their curves averaged over the band (the curves stay, for the sub-bands), and every
    /// facet's material must be in it.
    ///
    /// # Errors
    /// A malformed library, a spectral curve short of the band (at its wavelengths), a
    /// facet whose material the library lacks (at the facet in the scene file, `scene` its
    /// bytes), spectral materials with the whole spectrum as band.
    pub fn read_materials(
        &mut self,
        name: &str,
        bytes: &[u8],
        scene_bytes: &[u8],
    ) -> Result<(), RenderError> {
        let lib: MaterialLibrary = from_ron_bytes(name, bytes)
            .map_err(|e| RenderError::input(format!("reading the materials `{name}`"), e))?;
        self.record_input("materials", bytes);
        check_material_bands(
            &lib,
            &self.plan.request.band.band,
            name,
            bytes,
            self.plan.request.spelling,
        )?;
        let lib = match &self.plan.request.band.band {
            _ if lib.materials.iter().all(|m| m.spectral.is_none()) => lib,
            AnyBand::Band(band) => {
                crate::materials::band_library(&lib, band, name, &String::from_utf8_lossy(bytes))?
            }
            AnyBand::Total(_) => {
                return Err(RequestError::with_value(
                    Setting::Band,
                    "total",
                    format!(
                        "`{name}` has spectral materials, which the whole spectrum cannot \
                         average: give a band of wavelengths"
                    ),
                )
                .into());
            }
        };
        let scene = self
            .plan
            .scene
            .as_ref()
            .ok_or_else(|| RenderError::internal("the scene is read before the materials"))?;
        // A terrain or a facet whose material the library lacks, at its place in the scene
        // file.
        let unknown = |path: &str, message: String| {
            RenderError::input(
                format!("the scene's materials in `{name}`"),
                raw_scene_error_at_path(&self.plan.scene_name, scene_bytes, scene, path, message),
            )
        };
        if let Some(m) = scene.terrain.material
            && lib.by_id(m).is_none()
        {
            return Err(unknown(
                "terrain.material",
                format!(
                    "the terrain's material is {}, which the material library {name} does not \
                     define",
                    m.0
                ),
            ));
        }
        if let Some((i, f)) = scene
            .facets
            .iter()
            .enumerate()
            .find(|(_, f)| lib.by_id(f.material).is_none())
        {
            return Err(unknown(
                &format!("facets[{i}].material"),
                format!(
                    "facets[{i}] uses material {}, which the material library {name} does not \
                     define",
                    f.material.0
                ),
            ));
        }
        self.plan
            .run
            .field("materials", format!("{lib:?}").as_bytes());
        let (maps, images) = crate::maps::read_maps(&lib, name)?;
        for bytes in &images {
            self.record_input("map image", bytes);
            self.plan.run.field("map image", bytes);
        }
        self.plan.maps = maps;
        self.plan.materials = lib;
        name.clone_into(&mut self.plan.materials_name);
        Ok(())
    }

    /// Records an input the run read that the plan does not read itself (a view file, an
    /// execute file): its role and its bytes' SHA-256, for the images' provenance.
    pub fn record_input(&mut self, role: &str, bytes: &[u8]) {
        self.plan.inputs.push(InputRecord {
            stage: "trace".into(),
            role: role.into(),
            sha256: sha256_hex(bytes),
        });
    }

    /// Adds frames, one per view, in order; a camera below the ground is warned about.
    pub fn add_views(&mut self, views: impl IntoIterator<Item = View>) {
        let first = self.plan.views.len();
        self.plan.views.extend(views);
        if let Some(w) = crate::observer::below_ground(&self.plan.views[first..], first) {
            self.plan.warnings.push(w);
        }
    }

    /// Reads the declared uncertainties (canonical RON) after the scene and the materials:
    /// an object the scene does not have, or an emissivity ± that would leave [0, 1], is an
    /// error at its line and column.
    ///
    /// # Errors
    /// As said, or a malformed file.
    pub fn read_uncertainties(&mut self, name: &str, bytes: &[u8]) -> Result<(), RenderError> {
        let context = || format!("reading the uncertainties `{name}`");
        let text = irsig_formats::canonical::utf8(name, bytes)
            .map_err(|e| RenderError::input(context(), e))?;
        let u: Uncertainties =
            from_ron_bytes(name, bytes).map_err(|e| RenderError::input(context(), e))?;
        self.record_input("uncertainties", bytes);
        let objects = &self
            .plan
            .scene
            .as_ref()
            .ok_or_else(|| RenderError::internal("the scene is read before the uncertainties"))?
            .objects;
        // An object the raw scene does not have (a misspelt name) would select no facet and
        // silently declare nothing.
        for (i, t) in u.temperature.iter().enumerate() {
            if let Facets::Object(object) = &t.facets
                && !objects.iter().any(|o| o == object)
            {
                return Err(RenderError::input(
                    context(),
                    error_at_path(
                        name,
                        text,
                        &format!("temperature[{i}].facets"),
                        format!(
                            "invalid uncertainties file: `temperature[{i}].facets`: the raw scene \
                         has no object `{object}`; its objects include {}",
                            // A few, not a million names.
                            objects
                                .iter()
                                .take(8)
                                .map(|o| format!("`{o}`"))
                                .collect::<Vec<_>>()
                                .join(", ")
                        ),
                    ),
                ));
            }
        }
        let materials = &self.plan.materials;
        u.check_emissivity(|id| {
            let m = materials.materials.iter().find(|m| m.id == id)?;
            let normal = m.emissivity.first().map(|r| r.1)?;
            let most = m.emissivity.iter().map(|r| r.1).fold(0.0, f64::max);
            Some((normal, most))
        })
        .map_err(|e| {
            RenderError::input(
                context(),
                error_at_path(
                    name,
                    text,
                    &e.path,
                    format!("invalid uncertainties file: `{}`: {}", e.path, e.kind),
                ),
            )
        })?;
        // The budget's layers are pixels of the truth EXR: tiles of other uncertainties
        // differ.
        self.plan
            .run
            .field("uncertainties", format!("{u:?}").as_bytes());
        self.plan.uncertainties = Some(u);
        Ok(())
    }

    /// Reads a decision an earlier run wrote, to apply to every frame: each choice is
    /// checked here, where the file's text can point at it.
    ///
    /// # Errors
    /// A malformed decision, or a choice that is not a setting of its model (at the
    /// choice).
    pub fn read_decision(&mut self, name: &str, bytes: &[u8]) -> Result<(), RenderError> {
        // Not an input of the record: its choices are the frame's settings, which a frame
        // piloted anew and a tile given its decision share, and so do their images.
        let context = || format!("reading the decision `{name}`");
        let d: Decision =
            from_ron_bytes(name, bytes).map_err(|e| RenderError::input(context(), e))?;
        if let Err((i, message)) = Settings::of(&self.plan.request.settings).with_decision(&d) {
            return Err(RenderError::input(
                context(),
                error_at_path(
                    name,
                    &String::from_utf8_lossy(bytes),
                    &format!("choices[{i}].setting"),
                    message,
                ),
            ));
        }
        self.plan.decision = Some(d);
        self.plan.decision_file =
            Some((name.to_owned(), String::from_utf8_lossy(bytes).into_owned()));
        Ok(())
    }

    /// The plan of the inputs read, with the warnings reading them gave (a camera below
    /// the ground), which it says first when it renders.
    #[must_use]
    pub fn build(self) -> Plan {
        self.plan
    }
}

/// Refuses a material whose angular table is one band's (`band_um`) and that has no
/// spectral curve, when the trace's band is not within that band: its 8–14 µm values are
/// not its 3–5 µm ones, and using them there would be silently wrong. The error points at
/// the material's `band_um` in `file` and names the band asked for.
///
/// # Errors
/// The first such material.
fn check_material_bands(
    lib: &MaterialLibrary,
    band: &AnyBand,
    file: &str,
    bytes: &[u8],
    spelling: Spelling,
) -> Result<(), RenderError> {
    let band_setting = spelling.of(Setting::Band);
    // A band is within the table's when its edges are, to a part in 1e9 (the band's edges
    // are parsed from the same decimals the library writes).
    let within = |(shortest, longest): (f64, f64), lo: f64, hi: f64| {
        lo >= shortest * (1.0 - 1e-9) && hi <= longest * (1.0 + 1e-9)
    };
    for (i, m) in lib.materials.iter().enumerate() {
        let (Some(table_band), None) = (m.band_um, &m.spectral) else {
            continue;
        };
        let asked = match band {
            AnyBand::Band(b) if within(table_band, b.lambda_min_um(), b.lambda_max_um()) => {
                continue;
            }
            AnyBand::Band(b) => format!(
                "{band_setting} {}-{} um",
                b.lambda_min_um(),
                b.lambda_max_um()
            ),
            AnyBand::Total(_) => format!("{band_setting} total (the whole spectrum)"),
        };
        return Err(RenderError::input(
            format!("the materials `{file}` for the band"),
            error_at_path(
                file,
                &String::from_utf8_lossy(bytes),
                &format!("materials[{i}].band_um"),
                format!(
                    "material `{}`: its emissivity table is for {}-{} um, and the trace asks for \
                 {asked}: give it a `spectral` curve over that band (irsig-material fresnel \
                 with an n, k table, or DIRSIG .ems curves through irsig-material dirsig) rather than \
                 use its {}-{} um values there",
                    m.name, table_band.0, table_band.1, table_band.0, table_band.1
                ),
            ),
        ));
    }
    Ok(())
}

/// `sha256:` and the 64 hex digits of `bytes`.
fn sha256_hex(bytes: &[u8]) -> String {
    use sha2::Digest as _;
    let mut hex = String::from("sha256:");
    for b in sha2::Sha256::digest(bytes) {
        hex.push_str(&format!("{b:02x}"));
    }
    hex
}
