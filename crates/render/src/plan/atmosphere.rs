//! The atmosphere a run traces through, resolved for its band: a vacuum, band tables, or
//! spectra collapsed over the band or each sub-band, with the sun's tables by day, and the
//! tracer built over it once.

use std::sync::Mutex;

use irsig_model::SpectralAtmosphere;

use super::*;

impl Plan {
    /// Reads and checks the atmosphere asked for, then traces every frame through it.
    pub(super) fn with_atmosphere<R: SubBandModel>(
        &self,
        mut taken: Taken,
        band: R,
        split: Option<&Split<'_>>,
        job: &mut Job<'_>,
    ) -> Result<(), RenderError> {
        let request = &self.request.atmosphere;
        if let AtmosphereRequest::Vacuum {
            sky_radiance_w_m2_sr,
        } = *request
        {
            return self.trace_vacuum(taken, band, sky_radiance_w_m2_sr, job);
        }
        let (data, note) = self.air_data(split)?;
        taken.notes.extend(note);
        // The sky is precomputed up to the highest sensor or scene point.
        let top = self
            .views
            .iter()
            .map(|v| v.position_m()[2])
            .fold(scene_top_m(taken.scene.as_ref())?, f64::max);
        self.hash_air(&mut taken.run, &data, top);
        if matches!(self.request.band.band, AnyBand::Total(_)) {
            let band_um = match &data {
                AirData::Band(a) => format!("{:?}", a.band_um),
                AirData::Spectral(..) => "its spectral range".to_owned(),
            };
            taken.notes.push(format!(
                "the `total` band (whole spectrum) is combined with `{}`, whose tables \
                 cover {band_um} um: facet radiances and path terms are in different bands; \
                 use this only to check the geometry and the event logic",
                request.name()
            ));
        }
        match data {
            AirData::Band(atmosphere) => self.trace_band_tables(taken, band, &atmosphere, top, job),
            AirData::Spectral(spectral, _) => {
                let Some(split) = split else {
                    return Err(air::no_spectra(request.name(), SubBandCount::Full));
                };
                self.trace_spectra(taken, band, &spectral, split, top, job)
            }
        }
    }

    /// No air: the sky's radiance as given, no sun.
    fn trace_vacuum<R: SubBandModel>(
        &self,
        mut taken: Taken,
        band: R,
        sky_radiance_w_m2_sr: f64,
        job: &mut Job<'_>,
    ) -> Result<(), RenderError> {
        if let Some(s) = &self.request.sun {
            return Err(sunlight::no_solar_table(
                s,
                "none",
                "a vacuum",
                self.request.spelling,
            ));
        }
        let vacuum = Vacuum {
            sky_radiance_w_m2_sr,
        };
        taken
            .run
            .field("atmosphere", format!("{vacuum:?}").as_bytes());
        let air = VacuumAir {
            band: band.clone(),
            vacuum,
        };
        self.trace_all(taken, band, &air, job)
    }

    /// The atmosphere's data, read in the form the band needs and checked against the
    /// band, the sun and the cameras, with the warning of band tables for another band.
    fn air_data(
        &self,
        split: Option<&Split<'_>>,
    ) -> Result<(AirData, Option<String>), RenderError> {
        let request = &self.request.atmosphere;
        let name = request.name();
        // A built-in is read in spectral form when sub-bands may be asked for.
        let settings = &self.request.settings;
        let wants_spectra = split.is_some()
            && (settings.sub_bands.is_some_and(|c| !c.is_band())
                || self.request.tolerance.is_some()
                || self.decision.is_some());
        let range_um = split.map(|sp| sp.range_um);
        let mut data = air::read(request, wants_spectra, range_um)?;
        let mut note = None;
        // A built-in's band tables are for the flat band they were made for (8-14 um): any
        // other band, or a sensor response, collapses its spectra instead (else the band
        // model would add the flat band's path and sky radiance to a response-weighted
        // emission).
        if let (AirData::Band(a), Some(sp)) = (&data, &split) {
            let other_band = sp.response.is_some()
                || sp
                    .range_um
                    .iter()
                    .zip(a.band_um)
                    .any(|(x, y)| (x - y).abs() > 1e-9 * y);
            if other_band && matches!(request, AtmosphereRequest::Builtin(_)) {
                data = air::read(request, true, range_um)?;
            } else if other_band {
                note = Some(format!(
                    "`{name}` holds band tables for {}-{} um, flat; the band traced is {}-{} \
                     um{}: its path and sky radiances are the tables' band's",
                    a.band_um[0],
                    a.band_um[1],
                    sp.range_um[0],
                    sp.range_um[1],
                    if sp.response.is_some() {
                        " with a sensor response"
                    } else {
                        ""
                    }
                ));
            }
        }
        // The built-ins are night atmospheres: by day the sun's geometry is part of the
        // atmosphere, which a build makes.
        if let (Some(s), AtmosphereRequest::Builtin(_)) = (&self.request.sun, request) {
            let what = match &data {
                AirData::Band(_) => {
                    "a built-in: a band atmosphere (tables integrated over a band, without spectra)"
                }
                AirData::Spectral(..) => "a built-in: a night atmosphere",
            };
            return Err(sunlight::no_solar_table(
                s,
                name,
                &format!(
                    "{what}; the built-ins, 8-14 um and 3-5 um, are for night only, since by \
                     day the sun's geometry is part of the atmosphere"
                ),
                self.request.spelling,
            ));
        }
        match (&data, &split, request) {
            (AirData::Spectral(a, bytes), Some(sp), AtmosphereRequest::File { name, .. }) => {
                air::check_spectral_range(name, a, bytes, sp.range_um)?;
            }
            (AirData::Spectral(a, _), Some(sp), AtmosphereRequest::Builtin(name)) => {
                air::check_builtin_range(
                    name,
                    a,
                    &self.request.band,
                    sp.range_um,
                    self.request.spelling,
                )?;
            }
            _ => {}
        }
        if let AtmosphereRequest::Builtin(name) = request {
            air::check_builtin_top(name, &self.views)?;
        }
        Ok((data, note))
    }

    /// Adds what of the air decides the pixels to the run's hash: the data, the top its sky
    /// is precomputed to, and the sun.
    fn hash_air(&self, run: &mut RunHash, data: &AirData, top: f64) {
        match data {
            AirData::Band(atmosphere) => run.field(
                "atmosphere",
                format!("{atmosphere:?} top {:x}", top.to_bits()).as_bytes(),
            ),
            AirData::Spectral(_, bytes) => {
                run.field("spectral atmosphere", bytes);
                run.field("top", &top.to_bits().to_le_bytes());
            }
        }
        // Tiles of frames lit by different suns must not merge; without a sun the hash is
        // what it always was.
        if let (Some(p), Some(s)) = (&self.sun, &self.request.sun) {
            run.field(
                "sun",
                format!(
                    "{:x} {:x} {}",
                    p.zenith_deg.to_bits(),
                    p.azimuth_deg.to_bits(),
                    s.shadow_rays
                )
                .as_bytes(),
            );
        }
    }

    /// Band tables: the band model only, at night.
    fn trace_band_tables<R: SubBandModel>(
        &self,
        taken: Taken,
        band: R,
        atmosphere: &irsig_model::Atmosphere,
        top: f64,
        job: &mut Job<'_>,
    ) -> Result<(), RenderError> {
        let name = self.request.atmosphere.name();
        if let Some(s) = &self.request.sun {
            return Err(sunlight::no_solar_table(
                s,
                name,
                "a band atmosphere (tables integrated over a band, without spectra)",
                self.request.spelling,
            ));
        }
        let kinds: Vec<ModelKind> = [ModelKind::Table, ModelKind::Layered, ModelKind::Thesis]
            .into_iter()
            .filter(|&k| AtmosphereModel::new(atmosphere, k).is_ok())
            .collect();
        let air = TableAir {
            band: band.clone(),
            name,
            atmosphere,
            models: Models { name, top_m: top },
            kinds,
            data: data_error_of(atmosphere),
        };
        self.trace_all(taken, band, &air, job)
    }

    /// Spectra: collapsed over the band or each sub-band of a count (each count once), with
    /// the sun's beams and scattered sunlight by day.
    fn trace_spectra<R: SubBandModel>(
        &self,
        mut taken: Taken,
        band: R,
        spectral: &SpectralAtmosphere,
        split: &Split<'_>,
        top: f64,
        job: &mut Job<'_>,
    ) -> Result<(), RenderError> {
        let name = self.request.atmosphere.name();
        // Each count's collapsed sub-bands, made once, from the atmosphere checked once.
        let collapser = irsig_atmosphere::Collapser::new(spectral)
            .map_err(|e| RenderError::atmosphere(format!("the spectra of `{name}`"), e))?;
        let mut air = SpectralAir {
            plan: self,
            name,
            spectral,
            split,
            top_m: top,
            collapser,
            cache: Mutex::default(),
            models: Models { name, top_m: top },
            scatter: None,
            kinds: Vec::new(),
            data: None,
            day_default: None,
        };
        let one = air.collapsed(SubBandCount::BAND)?;
        air.kinds = [ModelKind::Table, ModelKind::Layered, ModelKind::Thesis]
            .into_iter()
            .filter(|&k| one.iter().all(|(_, a)| AtmosphereModel::new(a, k).is_ok()))
            .collect();
        air.scatter = crate::sun::by_day(
            self.request.sun.as_ref(),
            self.sun.as_ref(),
            spectral,
            name,
            |w| taken.notes.push(w),
        );
        // The sun's table is checked now, before anything is traced.
        air.lit(SubBandCount::BAND)?;
        air.day_default = self.day_default(spectral, split).map(|(count, note)| {
            taken.notes.push(note);
            count
        });
        air.data = one.first().and_then(|(_, a)| data_error_of(a));
        self.trace_all(taken, band, &air, job)
    }

    /// By day with no count asked for, chosen or piloted: enough sub-bands for the
    /// sunlight, and the note that says so.
    fn day_default(
        &self,
        spectral: &SpectralAtmosphere,
        split: &Split<'_>,
    ) -> Option<(SubBandCount, String)> {
        (self.request.sun.is_some()
            && self.request.settings.sub_bands.is_none()
            && self.request.tolerance.is_none()
            && self.decision.is_none())
        .then(|| {
            let count = sunlight::day_sub_bands(spectral, split);
            (
                count,
                sunlight::day_sub_bands_note(self.request.spelling, count),
            )
        })
    }
}

/// The highest point of the scene, metres (0 for a scene below the ground).
fn scene_top_m(scene: Option<&RawScene>) -> Result<f64, RenderError> {
    Ok(scene
        .ok_or_else(|| RenderError::internal("the raw scene is read before it is traced"))?
        .positions_m
        .iter()
        .map(|p| p[2])
        .fold(0.0_f64, f64::max))
}

fn poisoned() -> RenderError {
    RenderError::internal("a lock of the run was poisoned by a panic")
}

/// Builds a model kind of the run's atmosphere (`name`) and precomputes its sky to the
/// run's top; a precomputed sky keeps its warnings, which [`Air::sky_notes`] says.
struct Models<'p> {
    name: &'p str,
    top_m: f64,
}

impl Models<'_> {
    fn model(
        &self,
        atmosphere: &irsig_model::Atmosphere,
        kind: ModelKind,
    ) -> Result<AtmosphereModel, RenderError> {
        AtmosphereModel::new(atmosphere, kind).map_err(|e| {
            RenderError::atmosphere(
                format!("cannot build the {kind} model of `{}`", self.name),
                e,
            )
        })
    }

    fn precompute(&self, model: AtmosphereModel) -> PrecomputedAtmosphere {
        PrecomputedAtmosphere::new(model, self.top_m)
    }

    /// The warnings of the first sub-band's precomputed sky, each after the atmosphere's
    /// name.
    fn notes<R>(&self, sub_bands: &[SubBand<R, PrecomputedAtmosphere>]) -> Vec<String> {
        sub_bands.first().map_or_else(Vec::new, |s| {
            s.atmosphere
                .warnings()
                .iter()
                .map(|w| format!("{}: {w}", self.name))
                .collect()
        })
    }
}

/// The atmosphere of the run resolved for its band, for any model kind its tables allow,
/// over the band or over sub-bands of it: a vacuum ([`VacuumAir`]), band tables
/// ([`TableAir`]) or spectra ([`SpectralAir`]). A rendering's
/// sub-bands and the pilot's band sets come from the same tables; the pilot's evaluate
/// each kind as a rendering with it would (its sky precomputed: computing the hemispheric
/// sky afresh at every pilot facet cost more than the whole pilot otherwise does, and with
/// K sub-bands K times more).
pub(super) trait Air<R>: Sync {
    /// The atmosphere of a sub-band, as the tracer takes it.
    type Atmosphere: Atmosphere + Send;

    /// The kinds on offer, most accurate first (`None`: a vacuum).
    fn kinds(&self) -> Option<&[ModelKind]>;

    /// The atmosphere is spectral: sub-band counts other than 1 are on offer.
    fn spectral(&self) -> bool {
        false
    }

    /// The sub-bands of a model kind and a count: a rendering's, or (`pilot`) those of the
    /// pilot's band sets.
    ///
    /// # Errors
    /// A count the atmosphere cannot make, or a model its tables do not allow.
    fn sub_bands(
        &self,
        kind: ModelKind,
        count: SubBandCount,
        pilot: bool,
    ) -> Result<Vec<SubBand<R, Self::Atmosphere>>, RenderError>;

    /// The atmosphere data's own error per path, where its slant tables record their
    /// interpolation residual (`None`: built and slab tables, a vacuum).
    fn data(&self) -> Option<&irsig_atmosphere::data_error::DataError> {
        None
    }

    /// The sun over the sub-bands of a count (`None`: no sun asked for).
    ///
    /// # Errors
    /// A solar table that cannot light these sub-bands.
    fn sun(&self, _count: SubBandCount) -> Result<Option<irsig_tracer::Sun>, RenderError> {
        Ok(None)
    }

    /// By day, the sub-band count a frame takes when none was asked for, chosen or piloted
    /// ([`sunlight::day_sub_bands`]); `None` by night or when one was.
    fn day_default(&self) -> Option<SubBandCount> {
        None
    }

    /// What precomputing the skies of `sub_bands` (a rendering's) warned of, said once a
    /// run: the first sub-band's warnings (none for a vacuum).
    fn sky_notes(&self, _sub_bands: &[SubBand<R, Self::Atmosphere>]) -> Vec<String> {
        Vec::new()
    }
}

/// No air: the sky's radiance as given, over the whole band, and no sun.
struct VacuumAir<R> {
    band: R,
    vacuum: Vacuum,
}

impl<R: SubBandModel> Air<R> for VacuumAir<R> {
    type Atmosphere = Vacuum;

    fn kinds(&self) -> Option<&[ModelKind]> {
        None
    }

    fn sub_bands(
        &self,
        _: ModelKind,
        count: SubBandCount,
        _: bool,
    ) -> Result<Vec<SubBand<R, Vacuum>>, RenderError> {
        whole(&self.band, "none", count, || Ok(self.vacuum))
    }
}

/// Band tables: any kind they allow, over the whole band, at night.
struct TableAir<'p, R> {
    band: R,
    name: &'p str,
    atmosphere: &'p irsig_model::Atmosphere,
    models: Models<'p>,
    kinds: Vec<ModelKind>,
    data: Option<irsig_atmosphere::data_error::DataError>,
}

impl<R: SubBandModel> Air<R> for TableAir<'_, R> {
    type Atmosphere = PrecomputedAtmosphere;

    fn kinds(&self) -> Option<&[ModelKind]> {
        Some(&self.kinds)
    }

    fn sub_bands(
        &self,
        kind: ModelKind,
        count: SubBandCount,
        _: bool,
    ) -> Result<Vec<SubBand<R, PrecomputedAtmosphere>>, RenderError> {
        whole(&self.band, self.name, count, || {
            Ok(self
                .models
                .precompute(self.models.model(self.atmosphere, kind)?))
        })
    }

    fn data(&self) -> Option<&irsig_atmosphere::data_error::DataError> {
        self.data.as_ref()
    }

    fn sky_notes(&self, sub_bands: &[SubBand<R, PrecomputedAtmosphere>]) -> Vec<String> {
        self.models.notes(sub_bands)
    }
}

/// Spectra: collapsed over the band or each sub-band of a count (each count once, from
/// the atmosphere checked once), with the sun's beams and scattered sunlight by day.
struct SpectralAir<'p> {
    plan: &'p Plan,
    name: &'p str,
    spectral: &'p SpectralAtmosphere,
    split: &'p Split<'p>,
    top_m: f64,
    collapser: irsig_atmosphere::Collapser<'p>,
    /// Each count's collapsed sub-bands, made once.
    cache: Mutex<HashMap<SubBandCount, Arc<Collapsed>>>,
    models: Models<'p>,
    /// The sun whose scattered light the sub-bands carry, by day.
    scatter: Option<crate::sun::ScatterSun>,
    kinds: Vec<ModelKind>,
    data: Option<irsig_atmosphere::data_error::DataError>,
    day_default: Option<SubBandCount>,
}

impl SpectralAir<'_> {
    /// The sub-bands of `count`, collapsed, made once.
    fn collapsed(&self, count: SubBandCount) -> Result<Arc<Collapsed>, RenderError> {
        if let Some(c) = self.cache.lock().map_err(|_| poisoned())?.get(&count) {
            return Ok(c.clone());
        }
        let c = Arc::new(self.split.collapse(self.collapser, count)?);
        self.cache
            .lock()
            .map_err(|_| poisoned())?
            .insert(count, c.clone());
        Ok(c)
    }

    /// The sun's beams over the sub-bands of `count` (`None`: no sun asked for).
    fn lit(&self, count: SubBandCount) -> Result<Option<irsig_tracer::Sun>, RenderError> {
        let plan = self.plan;
        let (Some(request), Some(position)) = (&plan.request.sun, &plan.sun) else {
            return Ok(None);
        };
        let c = self.collapsed(count)?;
        sunlight::sun(
            request,
            position,
            self.name,
            self.spectral,
            self.split,
            (count, &c),
            plan.request.spelling,
        )
        .map(Some)
    }
}

impl<R: SubBandModel> Air<R> for SpectralAir<'_> {
    type Atmosphere = PrecomputedAtmosphere;

    fn kinds(&self) -> Option<&[ModelKind]> {
        Some(&self.kinds)
    }

    fn spectral(&self) -> bool {
        true
    }

    /// The pilot's sets are precomputed too, its sub-band sets on [`PILOT_SKY_LEVELS`]
    /// altitudes (the full grid's 108 skies were most of its cost): the precomputed sky
    /// costs a few ms per sub-band (table model) and saves a slant integration per ray.
    /// Sub-bands are precomputed in parallel; `collect` keeps their order.
    fn sub_bands(
        &self,
        kind: ModelKind,
        count: SubBandCount,
        pilot: bool,
    ) -> Result<Vec<SubBand<R, PrecomputedAtmosphere>>, RenderError> {
        let split = *self.split;
        self.collapsed(count)?
            .par_iter()
            .map(|(b, a)| {
                let m = self.models.model(a, kind)?;
                let atmosphere = if pilot && !count.is_band() {
                    PrecomputedAtmosphere::with_levels(m, self.top_m, PILOT_SKY_LEVELS)
                } else {
                    self.models.precompute(m)
                };
                let atmosphere = crate::sun::with_slabs(atmosphere, self.spectral, split, b)?;
                Ok(SubBand {
                    band: R::of_band(b),
                    atmosphere: crate::sun::scattered(
                        atmosphere,
                        self.scatter,
                        self.spectral,
                        split,
                        b,
                    )?,
                    emissivity: crate::materials::sub_band_tables(&self.plan.materials, b)?,
                })
            })
            .collect()
    }

    fn data(&self) -> Option<&irsig_atmosphere::data_error::DataError> {
        self.data.as_ref()
    }

    fn sun(&self, count: SubBandCount) -> Result<Option<irsig_tracer::Sun>, RenderError> {
        self.lit(count)
    }

    fn day_default(&self) -> Option<SubBandCount> {
        self.day_default
    }

    fn sky_notes(&self, sub_bands: &[SubBand<R, PrecomputedAtmosphere>]) -> Vec<String> {
        self.models.notes(sub_bands)
    }
}
