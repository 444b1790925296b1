//! Each frame's settings (as asked, from a decision, or chosen by the tolerance pilot) and
//! each frame traced and turned into its files.

use super::atmosphere::Air;
use super::*;

impl Plan {
    /// The pilot's decision for `camera`'s frame, with the seconds it took.
    pub(super) fn decide<R: BandModel + Clone + Send, Y: Air<R>>(
        &self,
        tolerance: &ToleranceRequest,
        tracer: &Tracer<R, Y::Atmosphere>,
        air: &Y,
        camera: &Camera,
    ) -> Result<(irsig_tracer::pilot::Piloted, f64), RenderError> {
        let mut offer = tolerance::offer(
            &self.materials,
            air.kinds(),
            air.spectral(),
            tracer.has_sun(),
            &tolerance.pins,
            self.request.spelling,
        )?;
        let (Some(&ref_kind), Some(&ref_count)) =
            (offer.atmospheres.first(), offer.sub_bands.first())
        else {
            return Err(RenderError::internal(
                "the pilot has no atmosphere or sub-band count to offer",
            ));
        };
        // A count the band's grid cannot make (more sub-bands than grid intervals in a
        // narrow band) is not on offer, unless it is the one pinned.
        let pinned_count = offer.sub_bands.len() == 1;
        // The sub-band counts at the reference atmosphere; every other model is measured in
        // the band model (`Tracer::pilot` says why), so each atmosphere in it.
        let mut pairs: Vec<(ModelKind, SubBandCount)> = Vec::new();
        for &count in &offer.sub_bands {
            pairs.push((ref_kind, count));
        }
        pairs.push((ref_kind, SubBandCount::BAND));
        for &kind in &offer.atmospheres {
            pairs.push((kind, SubBandCount::BAND));
        }
        // The pilot's time includes making its band sets (each sub-band's sky).
        let started = std::time::Instant::now();
        let mut bands: Vec<BandChoice<Y::Atmosphere>> = Vec::new();
        let mut unavailable = Vec::new();
        let mut unique: Vec<(ModelKind, SubBandCount)> = Vec::new();
        for pair in pairs {
            if !unique.contains(&pair) {
                unique.push(pair);
            }
        }
        // Made side by side (the full grid's set is most of the time), then taken in order.
        let made: Vec<_> = unique
            .par_iter()
            .map(|&(kind, count)| air.sub_bands(kind, count, true))
            .collect();
        for ((kind, count), made) in unique.into_iter().zip(made) {
            let sub = match made {
                Ok(sub) => sub,
                Err(e) if count == ref_count || count.is_band() || pinned_count => return Err(e),
                Err(_) => {
                    unavailable.push(count);
                    continue;
                }
            };
            // By day each set carries the sun's beams over its own sub-bands.
            let beams = if tracer.has_sun() {
                air.sun(count)?.map(|s| s.beams)
            } else {
                None
            };
            let set = tracer
                .band_set(sub)
                .and_then(|set| tracer.lit_band_set(set, beams))
                .map_err(|e| RenderError::trace(format!("the pilot's {kind} {count}"), e))?;
            let (path_call_ns, sky_ns) = atmosphere_costs(kind, camera.position_m[2].max(0.0));
            bands.push(BandChoice {
                atmosphere: kind,
                sub_bands: count,
                set,
                path_call_ns,
                sky_ns,
            });
        }
        offer.sub_bands.retain(|c| !unavailable.contains(c));
        // The sun switched off is the band model's set without its beams.
        let sun = if offer.sun.is_empty() {
            None
        } else {
            let dark = tracer
                .band_set(air.sub_bands(ref_kind, SubBandCount::BAND, true)?)
                .map_err(|e| RenderError::trace("the pilot's frame without the sun", e))?;
            Some(SunOffer {
                lit: offer.sun,
                shadow_rays: offer.shadow_rays,
                dark,
            })
        };
        let space = PilotSpace {
            bands,
            atmospheres: offer.atmospheres,
            sub_bands: offer.sub_bands,
            bounces: offer.bounces,
            sky_view_rays: offer.sky_view_rays,
            supersampling: offer.supersampling,
            path_terms: offer.path_terms,
            reasons: offer.reasons,
            pinned: offer.pinned,
            sun,
        };
        // About one pixel in 192 (1024 at 512 x 384), at least 1024 (every pixel of a
        // smaller image) and at most 4096: a thin population of pixels (edges, a small hot
        // object) of 1 % needs several hundred samples to be seen at all.
        let pixels =
            (u64::from(camera.pixels[0]) * u64::from(camera.pixels[1]) / 192).clamp(1024, 4096);
        let mut piloted = tracer
            .pilot(
                camera,
                &space,
                tolerance.tolerance_k,
                tolerance.percentile,
                pixels as u32,
                self.request.settings.seed,
            )
            .map_err(|e| RequestError::new(Setting::Tolerance, e.to_string()))?;
        // What no setting removes: said beside the decision, and left to the error budget.
        let whole = Tile::whole(camera.pixels[0], camera.pixels[1]);
        piloted.decision.data_error = air
            .data()
            .map(|data| tracer.data_error_census(data, camera, whole));
        Ok((piloted, started.elapsed().as_secs_f64()))
    }

    /// Builds the tracer once and runs the job with it: a probe, converged references, or
    /// every frame rendered and turned into its files (a probe and references say no
    /// warnings).
    pub(super) fn trace_all<R: BandModel + Clone + Send + Sync, Y: Air<R>>(
        &self,
        taken: Taken,
        band: R,
        air: &Y,
        job: &mut Job<'_>,
    ) -> Result<(), RenderError> {
        let Taken {
            run,
            scene,
            mut notes,
        } = taken;
        let built = self.build_tracer(band, air, scene)?;
        notes.extend(built.notes);
        let (tracer, scene, base) = (built.tracer, built.scene, built.settings);
        let cameras = self
            .views
            .iter()
            .enumerate()
            .map(|(i, v)| camera(i, v))
            .collect::<Result<Vec<_>, _>>()?;
        match job {
            Job::Probe { column, row, text } => {
                let cam = cameras
                    .first()
                    .ok_or_else(|| RequestError::new(Setting::Probe, "no view to probe"))?;
                let s = tracer
                    .probe(cam, &base.options, *column, *row)
                    .map_err(|e| {
                        RenderError::trace(format!("the probed pixel ({column}, {row})"), e)
                    })?;
                let t = tracer.apparent_temperature_k(s.radiance_w_m2_sr);
                let sub_bands = tracer.sub_bands();
                **text = Some(format!(
                    "pixel ({column}, {row}), view 1, {sub_bands} sub-band(s)\n{s}\n\
                     apparent temperature_k     {t}\n"
                ));
                Ok(())
            }
            Job::Converge {
                stop_k,
                rounds,
                out,
            } => {
                **out = cameras
                    .iter()
                    .map(|cam| converged_reference(&tracer, cam, *stop_k, *rounds))
                    .collect::<Result<_, _>>()
                    .map_err(|e| RenderError::trace("the converged reference", e))?;
                Ok(())
            }
            Job::Render {
                tile,
                progress,
                sink,
            } => {
                let frames = Frames {
                    air,
                    run: &run,
                    cameras: &cameras,
                    scene: scene.as_ref(),
                    tiles: self.tiles(*tile)?,
                    whole: tile.is_none(),
                    progress: *progress,
                };
                self.render_frames(tracer, base, &frames, &notes, &mut **sink)
            }
        }
    }

    /// The tracer over the settings asked for (or the decision's), lit by day, with the
    /// budget's groups; the raw scene kept only when the budget reads its facets.
    fn build_tracer<R: BandModel + Clone + Send + Sync, Y: Air<R>>(
        &self,
        band: R,
        air: &Y,
        scene: Option<RawScene>,
    ) -> Result<Built<R, Y::Atmosphere>, RenderError> {
        let scene = scene
            .ok_or_else(|| RenderError::internal("the raw scene is read before it is traced"))?;
        let mut asked = Settings::of(&self.request.settings);
        if let Some(count) = air.day_default() {
            asked.sub_bands = count;
        }
        let asked_sub_bands = asked.sub_bands;
        let base = match &self.decision {
            Some(d) => asked
                .with_decision(d)
                .map_err(|(_, m)| RenderError::internal(m))?,
            None => asked,
        };
        // A count the decision chose that this atmosphere's grid cannot make is the
        // decision's error, not a flag's.
        let sub_bands_of_decision = self.decision.is_some() && base.sub_bands != asked_sub_bands;
        let said = |e: RenderError| {
            if sub_bands_of_decision {
                self.at_decision_sub_bands(e)
            } else {
                e
            }
        };
        let sun = sun_of(air, &base).map_err(said)?;
        let precomputed = air
            .sub_bands(base.kind, base.sub_bands, false)
            .map_err(said)?;
        let notes = air.sky_notes(&precomputed);
        let tracer = Tracer::with_sub_bands_and_maps(
            &scene,
            &self.materials,
            band,
            precomputed,
            self.maps.clone(),
        )
        .and_then(|t| t.with_sun(sun))
        .map_err(|e| {
            RenderError::trace(
                format!(
                    "cannot trace `{}` with `{}`",
                    self.scene_name, self.materials_name
                ),
                e,
            )
        })?
        .with_path_terms(base.path_terms);
        let scene = self.uncertainties.is_some().then_some(scene);
        // With declared uncertainties each frame keeps the budget's charges, per input.
        let tracer =
            tracer.with_budget_groups(self.uncertainties.as_ref().zip(scene.as_ref()).map(
                |(uncertainties, scene)| {
                    Budget {
                        uncertainties,
                        scene,
                    }
                    .groups()
                },
            ));
        Ok(Built {
            tracer,
            scene,
            settings: base,
            notes,
        })
    }

    /// Every frame: its settings (piloted when a tolerance is asked for), the tracer moved
    /// to them, traced and turned into the files the sink wants.
    fn render_frames<R: BandModel + Clone + Send + Sync, Y: Air<R>>(
        &self,
        mut tracer: Tracer<R, Y::Atmosphere>,
        base: Settings,
        frames: &Frames<'_, Y>,
        notes: &[String],
        sink: &mut dyn Sink,
    ) -> Result<(), RenderError> {
        let air = frames.air;
        let (mut kind, mut count) = (base.kind, base.sub_bands);
        // The materials with a specular share: a reflection that meets one is a mirror
        // seen in a mirror, a class of the decision's own.
        let mirrors: Vec<u16> = self
            .materials
            .materials
            .iter()
            .filter(|m| m.specular_fraction > 0.0)
            .map(|m| m.id.0)
            .collect();
        for note in notes {
            sink.warning(note);
        }
        for (i, cam) in frames.cameras.iter().enumerate() {
            let piloted;
            let (settings, decision) = match &self.request.tolerance {
                Some(tolerance) => {
                    // The pilot sees the sun asked for, whatever an earlier frame chose.
                    if self.request.sun.is_some() {
                        tracer = tracer
                            .with_sun(air.sun(count)?)
                            .map_err(|e| RenderError::trace("lighting the pilot's frame", e))?;
                    }
                    let (p, seconds) = self.decide(tolerance, &tracer, air, cam)?;
                    piloted = p;
                    sink.decision(i, &piloted.decision, seconds).map_err(|e| {
                        RenderError::caller(format!("keeping view {}'s decision", i + 1), e)
                    })?;
                    (
                        chosen_settings(base, &piloted.chosen, tolerance.tolerance_k)?,
                        Some(&piloted.decision),
                    )
                }
                None => (base, self.decision.as_ref()),
            };
            if settings.kind != kind || settings.sub_bands != count {
                // New sub-bands drop the sun, whose beams are per sub-band: lit again.
                let sun = sun_of(air, &settings)?;
                tracer = tracer
                    .with_bands(air.sub_bands(settings.kind, settings.sub_bands, false)?)
                    .and_then(|t| t.with_sun(sun))
                    .map_err(|e| RenderError::trace(format!("view {}'s settings", i + 1), e))?;
                (kind, count) = (settings.kind, settings.sub_bands);
            } else if self.request.sun.is_some() {
                tracer = tracer
                    .with_sun(sun_of(air, &settings)?)
                    .map_err(|e| RenderError::trace(format!("view {}'s sun", i + 1), e))?;
            }
            let wanted = sink.files(i);
            if !wanted.any() {
                // Only the pilot's decision was asked for.
                continue;
            }
            tracer = tracer
                .with_path_terms(settings.path_terms)
                .with_refinement(settings.refinement)
                .map_err(|e| RenderError::trace(format!("view {}'s refinement", i + 1), e))?;
            let tile = frames.tiles[i];
            warn_of_uncovered_paths(&tracer, cam, tile, i + 1, sink);
            // The per-pixel terms are kept only when a file of this frame reads them.
            let options = TraceOptions {
                truth: wanted.wants(FrameFile::TruthExr) || wanted.wants(FrameFile::MapPng),
                ..settings.options
            };
            let mut frame = if frames.whole {
                tracer.render(cam, &options, frames.progress)
            } else {
                tracer.render_tile(cam, &options, tile, frames.progress)
            }
            .map_err(|e| RenderError::trace(format!("tracing view {}", i + 1), e))?;
            if wanted.wants(FrameFile::TruthExr)
                && let Some(text) =
                    keep_data_error(&tracer, air.data(), cam, tile, &mut frame, i + 1)
            {
                sink.warning(&text);
            }
            let files = self.file_context(&tracer, frames, i, &settings, decision, &mirrors);
            if i + 1 == frames.cameras.len() {
                // The last frame's files need the band, not the scene: the BVH and the facet
                // records (about 100 bytes a facet) go before the files are made, which hold
                // the frame's layers and encoded files (the frame's peak memory was there).
                drop(tracer);
                return files.emit(frame, &wanted, i, sink);
            }
            files.emit(frame, &wanted, i, sink)?;
        }
        Ok(())
    }

    /// What frame `i`'s files are made with besides its layers: its place in the image, its
    /// radiometry (from `tracer`), the budget's charges and the decision's guarantee.
    fn file_context<'a, R: BandModel + Clone, A: Atmosphere, Y>(
        &'a self,
        tracer: &Tracer<R, A>,
        frames: &Frames<'a, Y>,
        i: usize,
        settings: &Settings,
        decision: Option<&'a Decision>,
        mirrors: &'a [u16],
    ) -> FileContext<'a, R> {
        let (cam, tile) = (&frames.cameras[i], frames.tiles[i]);
        let part = FramePart {
            frame_width: cam.pixels[0] as usize,
            frame_height: cam.pixels[1] as usize,
            x: tile.x as usize,
            y: tile.y as usize,
            run: frames.run.frame(&self.views[i], settings),
        };
        let radiometry = FrameRadiometry {
            band: tracer.band().clone(),
            sub_bands: tracer.sub_bands(),
            view_gain: self.views.get(i).and_then(View::gain_dc_per_k),
            counts: self.request.counts,
            provenance: Some(self.provenance(settings)),
        };
        let budget = self
            .uncertainties
            .as_ref()
            .zip(frames.scene)
            .map(|(u, scene)| Budget {
                uncertainties: u,
                scene,
            });
        let guarantee = decision.map(|decision| Guarantee {
            decision,
            camera: cam,
            origin: [tile.x, tile.y],
            mirrors,
        });
        FileContext {
            part,
            radiometry,
            budget,
            guarantee,
        }
    }
}

/// The tracer built once, the raw scene when the budget reads its facets, the settings it
/// was built with, and what precomputing its skies warned of.
struct Built<R, A> {
    tracer: Tracer<R, A>,
    scene: Option<RawScene>,
    settings: Settings,
    notes: Vec<String>,
}

/// What every frame of a rendering shares.
struct Frames<'a, Y> {
    air: &'a Y,
    run: &'a RunHash,
    cameras: &'a [Camera],
    /// The raw scene, when the budget reads its facets.
    scene: Option<&'a RawScene>,
    /// Each frame's tile (the whole image without a tile request).
    tiles: Vec<Tile>,
    /// No tile was asked for: each frame is rendered whole.
    whole: bool,
    progress: &'a (dyn Fn(u64) + Sync),
}

/// What a traced frame's files are made with besides its layers.
struct FileContext<'a, R> {
    part: FramePart,
    radiometry: FrameRadiometry<R>,
    budget: Option<Budget<'a>>,
    guarantee: Option<Guarantee<'a>>,
}

impl<R: BandModel + Sync> FileContext<'_, R> {
    /// Turns `frame` into the files `wanted` names, each given to `sink` as frame `i`'s.
    fn emit(
        &self,
        frame: irsig_tracer::Frame,
        wanted: &FrameFiles<()>,
        i: usize,
        sink: &mut dyn Sink,
    ) -> Result<(), RenderError> {
        let mut emit = |kind, bytes| sink.file(i, kind, bytes);
        products::traced(
            &self.radiometry,
            frame,
            wanted,
            &self.part,
            self.budget.as_ref(),
            self.guarantee.as_ref(),
            &mut emit,
        )
    }
}

/// Warns `sink` of view `view`'s paths that the slab tables do not cover and of those past
/// the slant tables' widest row.
fn warn_of_uncovered_paths<R: BandModel, A: Atmosphere>(
    tracer: &Tracer<R, A>,
    cam: &Camera,
    tile: Tile,
    view: usize,
    sink: &mut dyn Sink,
) {
    if let Some(text) = tracer
        .slab_census(cam, tile)
        .and_then(|c| slab_fallback(&c, view))
    {
        sink.warning(&text);
    }
    if let Some(text) = tracer
        .horizon_census(cam, tile)
        .and_then(|c| beyond_the_widest_row(&c, view))
    {
        sink.warning(&text);
    }
}

/// The sun as `settings` have it: left out, or with their shadow rays.
fn sun_of<R, Y: Air<R>>(
    air: &Y,
    settings: &Settings,
) -> Result<Option<irsig_tracer::Sun>, RenderError> {
    Ok(air
        .sun(settings.sub_bands)?
        .filter(|_| settings.sun_lit)
        .map(|mut sun| {
            if let Some(n) = settings.shadow_rays {
                sun.shadow_rays = n;
            }
            sun
        }))
}

/// The frame's settings from the pilot's choice: the asked settings with every model the
/// pilot chose.
fn chosen_settings(
    base: Settings,
    c: &irsig_tracer::pilot::Chosen,
    tolerance_k: f64,
) -> Result<Settings, RenderError> {
    let mut settings = base;
    settings.kind = c.atmosphere;
    settings.sub_bands = c.sub_bands;
    settings.path_terms = c.path_terms;
    settings.options = c.trace_options(settings.options, tolerance_k);
    settings.refinement = c.refinement;
    settings.sun_lit = c.sun.is_none_or(|s| s.lit);
    settings.shadow_rays = c.sun.map(|s| s.shadow_rays);
    settings
        .options
        .validate()
        .map_err(|e| RenderError::trace("the pilot's chosen settings", e))?;
    Ok(settings)
}

/// The warning for a frame with view paths past the slant tables' widest nadir row
/// (`None` without): how many, how far, and what that has been measured to cost.
fn beyond_the_widest_row(
    census: &irsig_tracer::horizon_census::HorizonCensus,
    view: usize,
) -> Option<String> {
    if census.beyond == 0 {
        return None;
    }
    Some(format!(
        "view {view}: {} of the {} view paths to the ground and facets ({:.1} %) lie past \
         the slant tables' widest row, {:.2} deg from nadir (up to {:.2} deg, the camera at \
         {:.1} m), where the table model's correction fades to none at 90 deg: against \
         LOWTRAN7 the built-ins' paths to the ground there err by up to 0.55 K at 88.5 deg \
         and 1.9 K nearer the horizon from 5-50 m, and up to 5.4 K from 300 m-1 km (docs/accuracy.md, \"The last degrees to \
         the horizon\"); no table has rows there: the built-ins' and `irsig-atmos plan`'s \
         stop at 88 deg",
        census.beyond,
        census.ground_paths,
        100.0 * census.beyond as f64 / census.ground_paths.max(1) as f64,
        census.widest_row_deg,
        census.largest_nadir_deg,
        census.camera_m,
    ))
}

/// Puts the atmosphere data's error of each pixel into `frame` (its truth EXR's layer)
/// where the atmosphere records it; else the warning saying why the layer is absent.
fn keep_data_error<R: BandModel, A: Atmosphere>(
    tracer: &Tracer<R, A>,
    data: Option<&irsig_atmosphere::data_error::DataError>,
    camera: &Camera,
    tile: Tile,
    frame: &mut irsig_tracer::Frame,
    view: usize,
) -> Option<String> {
    let Some(data) = data else {
        return Some(format!(
            "view {view}: the truth EXR has no `{}` layer: the atmosphere's tables record no \
             interpolation residual (built and slab tables, and a vacuum, do not), so the \
             data's own error is not known",
            irsig_model::truth::Layer::AtmosphereDataError
        ));
    };
    frame.data_error_k = tracer.data_error_layer(data, camera, tile, &frame.truth);
    None
}

/// The warning for a frame whose view paths the slab tables do not all cover (`None` when
/// they do): how many, why, and what the fallback has been measured to cost.
fn slab_fallback(census: &irsig_tracer::slab_census::SlabCensus, view: usize) -> Option<String> {
    let missed = census.missed_paths();
    if missed == 0 {
        return None;
    }
    let why: Vec<String> = census
        .missed
        .iter()
        .map(|(m, n)| format!("{n} because {}", m.describe()))
        .collect();
    let observers: Vec<String> = census
        .observers_m
        .iter()
        .map(|o| format!("{o:.1}"))
        .collect();
    Some(format!(
        "view {view}: {missed} of the {} view paths to facets ({:.1} %) are not the slab \
         tables' ({}; the camera is at {:.1} m, the tables' observers at {} m) and are the \
         slant tables' and the difference of two paths' instead, which on the slabs measured \
         put the path radiance off by +10 % to +58 % (docs/accuracy.md, \"Slab tables\"); \
         a plan with this observer and these rows (`irsig-atmos plan --slabs`) covers them",
        census.facet_paths,
        100.0 * missed as f64 / census.facet_paths.max(1) as f64,
        why.join(", "),
        census.camera_m,
        observers.join(", "),
    ))
}
