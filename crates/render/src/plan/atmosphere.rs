//! The atmosphere a run traces through, resolved for its band: a vacuum, band tables, or
//! spectra collapsed over the band or each sub-band, with the sun's tables by day, and the
//! tracer built over it once.

use super::*;

impl Plan {
    #[allow(clippy::too_many_lines)]
    pub(super) fn with_atmosphere<R: SubBandModel>(
        &self,
        mut run: RunHash,
        band: R,
        split: Option<&Split<'_>>,
        job: &mut Job<'_>,
    ) -> miette::Result<()> {
        let top_scene = self
            .scene
            .lock()
            .map_err(|_| poisoned())?
            .as_ref()
            .ok_or_else(|| miette!("the raw scene was already traced"))?
            .positions_m
            .iter()
            .map(|p| p[2])
            .fold(0.0_f64, f64::max);
        let request = &self.request.atmosphere;
        let name = request.name().to_owned();
        if let AtmosphereRequest::Vacuum {
            sky_radiance_w_m2_sr,
        } = *request
        {
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
            run.field("atmosphere", format!("{vacuum:?}").as_bytes());
            let (b1, b2) = (band.clone(), band.clone());
            let air = Air {
                kinds: None,
                spectral: false,
                precomputed: Box::new(move |_, count| whole(&b1, "none", count, || Ok(vacuum))),
                pilot: Box::new(move |_, count| whole(&b2, "none", count, || Ok(vacuum))),
                data_error_k: None,
                sun: no_sun(),
                day_default: None,
            };
            return self.trace_all(&run, band, &air, job);
        }
        // A built-in is read in spectral form when sub-bands may be asked for.
        let settings = &self.request.settings;
        let wants_spectra = split.is_some()
            && (settings.sub_bands.is_some_and(|c| !c.is_band())
                || self.request.tolerance.is_some()
                || self.decision.is_some());
        let range_um = split.map(|sp| sp.range_um);
        let mut data = air::read(request, wants_spectra, range_um)?;
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
                self.warn(format!(
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
                &name,
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
        // The sky is precomputed up to the highest sensor or scene point.
        let top = self
            .views
            .iter()
            .map(|v| v.position_m()[2])
            .fold(top_scene, f64::max);
        // The sky's precomputed levels depend on the top: so do the pixels.
        match &data {
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
        if matches!(self.request.band.band, AnyBand::Total(_)) {
            let band_um = match &data {
                AirData::Band(a) => format!("{:?}", a.band_um),
                AirData::Spectral(..) => "its spectral range".to_owned(),
            };
            self.warn(format!(
                "the `total` band (whole spectrum) is combined with `{name}`, whose tables \
                 cover {band_um} um: facet radiances and path terms are in different bands; \
                 use this only to check the geometry and the event logic"
            ));
        }
        let model_name = name.clone();
        let model = move |atmosphere: &irsig_model::Atmosphere, kind: ModelKind| {
            AtmosphereModel::new(atmosphere, kind)
                .map_err(|e| miette!("{e}"))
                .wrap_err_with(|| format!("cannot build the {kind} model of `{model_name}`"))
        };
        let warned = std::sync::Once::new();
        let precompute = |model: AtmosphereModel| {
            let air = PrecomputedAtmosphere::new(model, top);
            warned.call_once(|| {
                for w in air.warnings() {
                    self.warn(format!("{name}: {w}"));
                }
            });
            air
        };
        match data {
            AirData::Band(atmosphere) => {
                if let Some(s) = &self.request.sun {
                    return Err(sunlight::no_solar_table(
                        s,
                        &name,
                        "a band atmosphere (tables integrated over a band, without spectra)",
                        self.request.spelling,
                    ));
                }
                let data_error_k = data_error_k(
                    atmosphere
                        .slant
                        .as_ref()
                        .and_then(|s| s.interpolation_residual.as_ref()),
                );
                let kinds: Vec<ModelKind> =
                    [ModelKind::Table, ModelKind::Layered, ModelKind::Thesis]
                        .into_iter()
                        .filter(|&k| AtmosphereModel::new(&atmosphere, k).is_ok())
                        .collect();
                let (a1, a2) = (atmosphere.clone(), atmosphere);
                let (m1, m2) = (model.clone(), model);
                let (b1, b2) = (band.clone(), band.clone());
                let (n1, n2) = (name.clone(), name.clone());
                let precompute = &precompute;
                let air = Air {
                    kinds: Some(kinds),
                    spectral: false,
                    precomputed: Box::new(move |kind, count| {
                        whole(&b1, &n1, count, || Ok(precompute(m1(&a1, kind)?)))
                    }),
                    pilot: Box::new(move |kind, count| {
                        whole(&b2, &n2, count, || {
                            Ok(PrecomputedAtmosphere::new(m2(&a2, kind)?, top))
                        })
                    }),
                    data_error_k,
                    sun: no_sun(),
                    day_default: None,
                };
                self.trace_all(&run, band, &air, job)
            }
            AirData::Spectral(spectral, _) => {
                let Some(split) = split else {
                    return Err(air::no_spectra(&name, SubBandCount::Full));
                };
                // Each count's collapsed sub-bands, made once, from the atmosphere checked
                // once.
                let collapser =
                    irsig_atmosphere::Collapser::new(&spectral).map_err(|e| miette!("{e}"))?;
                let cache: Mutex<HashMap<SubBandCount, Arc<Collapsed>>> = Mutex::default();
                let collapsed = |count: SubBandCount| -> miette::Result<Arc<Collapsed>> {
                    if let Some(c) = cache.lock().map_err(|_| poisoned())?.get(&count) {
                        return Ok(c.clone());
                    }
                    let c = Arc::new(split.collapse(collapser, count)?);
                    cache
                        .lock()
                        .map_err(|_| poisoned())?
                        .insert(count, c.clone());
                    Ok(c)
                };
                let data_error_k = data_error_k(
                    spectral
                        .slant
                        .as_ref()
                        .and_then(|s| s.interpolation_residual.as_ref()),
                );
                let one = collapsed(SubBandCount::BAND)?;
                let kinds: Vec<ModelKind> =
                    [ModelKind::Table, ModelKind::Layered, ModelKind::Thesis]
                        .into_iter()
                        .filter(|&k| one.iter().all(|(_, a)| AtmosphereModel::new(a, k).is_ok()))
                        .collect();
                let collapsed = &collapsed;
                let precompute = &precompute;
                let materials = &self.materials;
                let scatter = crate::sun::by_day(
                    self.request.sun.as_ref(),
                    self.sun.as_ref(),
                    &spectral,
                    &name,
                    |w| self.warn(w),
                );
                let spectral_ref = &spectral;
                // The pilot evaluates its paths in every sub-band: the precomputed sky costs
                // a few ms per sub-band (table model) and saves a slant integration per ray,
                // so the pilot's sets are precomputed too (`S` = `A`), its sub-band sets on
                // PILOT_SKY_LEVELS altitudes (the full grid's 108 skies were most of its
                // cost). Sub-bands are precomputed in parallel; `collect` keeps their order.
                let sub_bands = move |kind: ModelKind, count: SubBandCount, pilot: bool| {
                    collapsed(count)?
                        .par_iter()
                        .map(|(b, a)| {
                            let m = model(a, kind)?;
                            let atmosphere = if pilot && !count.is_band() {
                                PrecomputedAtmosphere::with_levels(m, top, PILOT_SKY_LEVELS)
                            } else {
                                precompute(m)
                            };
                            let atmosphere =
                                crate::sun::with_slabs(atmosphere, spectral_ref, *split, b)?;
                            Ok(SubBand {
                                band: R::of_band(b)?,
                                atmosphere: crate::sun::scattered(
                                    atmosphere,
                                    scatter,
                                    spectral_ref,
                                    *split,
                                    b,
                                )?,
                                emissivity: crate::materials::sub_band_tables(materials, b)?,
                            })
                        })
                        .collect()
                };
                let sub_bands = &sub_bands;
                // The sun's beams over the same sub-bands; the table is checked now, before
                // anything is traced.
                let spectral = &spectral;
                let lit = |count: SubBandCount| -> miette::Result<Option<irsig_tracer::Sun>> {
                    let (Some(request), Some(position)) = (&self.request.sun, &self.sun) else {
                        return Ok(None);
                    };
                    let c = collapsed(count)?;
                    sunlight::sun(
                        request,
                        position,
                        &name,
                        spectral,
                        split,
                        (count, &c),
                        self.request.spelling,
                    )
                    .map(Some)
                };
                lit(SubBandCount::BAND)?;
                // By day with no count asked for, chosen or piloted: enough sub-bands for
                // the sunlight, said once.
                let day_default = (self.request.sun.is_some()
                    && self.request.settings.sub_bands.is_none()
                    && self.request.tolerance.is_none()
                    && self.decision.is_none())
                .then(|| {
                    let count = sunlight::day_sub_bands(spectral, split);
                    self.warn(sunlight::day_sub_bands_note(self.request.spelling, count));
                    count
                });
                let air = Air {
                    kinds: Some(kinds),
                    spectral: true,
                    day_default,
                    precomputed: Box::new(move |kind, count| sub_bands(kind, count, false)),
                    pilot: Box::new(move |kind, count| sub_bands(kind, count, true)),
                    data_error_k,
                    sun: Box::new(lit),
                };
                self.trace_all(&run, band, &air, job)
            }
        }
    }
}
