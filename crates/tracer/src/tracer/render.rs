//! The render loops: a whole frame, a tile of it, refined or supersampled, and the probe
//! of one pixel, each ray through the one pixel function.

use super::*;

impl<B: BandModel, A: Atmosphere> Tracer<B, A> {
    /// Renders every pixel of `camera`'s image, rows in parallel (rayon): the whole image as
    /// one tile ([`Self::render_tile`]). `progress` is called with 1 after each row. The
    /// result does not depend on the thread count.
    ///
    /// # Errors
    /// The options are out of range.
    pub fn render(
        &self,
        camera: &Camera,
        options: &TraceOptions,
        progress: &(dyn Fn(u64) + Sync),
    ) -> Result<Frame, TraceError> {
        let [w, h] = camera.pixels;
        self.render_tile(camera, options, Tile::whole(w, h), progress)
    }

    /// The pixels of `frame` whose apparent temperature differs from one of its 8
    /// neighbours' by more than `threshold_k` (the diagonal ones count: a corner of a facet
    /// can cut into a pixel whose 4-neighbours' centres all miss it).
    pub(crate) fn edges(&self, frame: &Frame, threshold_k: f64) -> Vec<bool> {
        let inverse = self.inverse_table();
        let t: Vec<f64> = frame
            .radiance_w_m2_sr
            .par_chunks(4096)
            .flat_map_iter(|run| inverse.temperatures(run.iter().copied()))
            .collect();
        let (w, h) = (frame.width as usize, frame.height as usize);
        contrast_of(&t, w, h)
            .into_iter()
            .map(|c| c > threshold_k)
            .collect()
    }

    /// Renders the pixels of `tile` of `camera`'s image, rows in parallel, exactly as
    /// [`Self::render`] renders them in the whole image: each pixel's rays and random
    /// stream are its own (seeded by its index in the whole image), and adaptive
    /// supersampling compares the tile's pixels with their neighbours' centre rays over a
    /// one-pixel margin, so every pixel is bit for bit the whole frame's. The frame returned
    /// is the tile's: `tile.width × tile.height`, row 0 the tile's top row. What it holds
    /// beyond its pixels is of the tile's size too, never the image's: the camera's
    /// per-column and per-row directions over the tile's columns and rows and its margin,
    /// and, with adaptive supersampling or refinement, the centre rays of the margin.
    ///
    /// # Errors
    /// The options are out of range, or the tile is empty or reaches beyond the image.
    pub fn render_tile(
        &self,
        camera: &Camera,
        options: &TraceOptions,
        tile: Tile,
        progress: &(dyn Fn(u64) + Sync),
    ) -> Result<Frame, TraceError> {
        options.validate()?;
        let [w, h] = camera.pixels;
        tile.check(w, h)
            .map_err(|e| TraceError::new(TraceErrorKind::InvalidTile(e)))?;
        // Every pixel a tile traces lies in it or in its one-pixel margin.
        let fc = self.frame_consts(camera, tile.grown(1, w, h));
        if let Some(refinement) = self.refinement {
            if options.supersampling != 1 || options.adaptive_threshold_k.is_some() {
                return Err(TraceError::new(TraceErrorKind::InvalidOptions(
                    "refinement replaces supersampling: give one ray per pixel (supersampling \
                     1, no adaptive threshold) with it"
                        .into(),
                )));
            }
            return Ok(self.render_refined(&fc, options, &refinement, tile, progress));
        }
        let adaptive = options
            .adaptive_threshold_k
            .filter(|_| options.supersampling > 1);
        let Some(threshold_k) = adaptive else {
            return Ok(self.render_rect(&fc, options, tile, progress));
        };
        // The centre rays of the tile and a one-pixel margin: an edge test needs all 8
        // neighbours, as in the whole frame (the margin stops at the image's border, where
        // the whole frame's neighbourhood stops too).
        let centre_options = TraceOptions {
            supersampling: 1,
            adaptive_threshold_k: None,
            ..*options
        };
        let halo = tile.grown(1, w, h);
        let centres = self.render_rect(&fc, &centre_options, halo, &|_| {});
        let refine = self.edges(&centres, threshold_k);
        let tw = tile.width as usize;
        let (mut radiance, flags, truth, sun, texture) = if halo == tile {
            // The whole image: the margin is empty, nothing to crop.
            (
                centres.radiance_w_m2_sr,
                refine,
                centres.truth,
                centres.sun,
                centres.texture,
            )
        } else {
            let (dx, dy) = ((tile.x - halo.x) as usize, (tile.y - halo.y) as usize);
            let hw = halo.width as usize;
            let crop = |r: usize| (r + dy) * hw + dx..(r + dy) * hw + dx + tw;
            let mut radiance = Vec::with_capacity(tile.pixels());
            let mut flags = Vec::with_capacity(tile.pixels());
            let mut truth = Vec::new();
            let mut sun = Vec::new();
            let mut texture = Vec::new();
            for r in 0..tile.height as usize {
                radiance.extend_from_slice(&centres.radiance_w_m2_sr[crop(r)]);
                flags.extend_from_slice(&refine[crop(r)]);
                if !centres.truth.is_empty() {
                    truth.extend_from_slice(&centres.truth[crop(r)]);
                }
                if !centres.sun.is_empty() {
                    sun.extend_from_slice(&centres.sun[crop(r)]);
                }
                if !centres.texture.is_empty() {
                    texture.extend_from_slice(&centres.texture[crop(r)]);
                }
            }
            (radiance, flags, truth, sun, texture)
        };
        let full = TraceOptions {
            adaptive_threshold_k: None,
            ..*options
        };
        // The budget's charges: a refined pixel's from its rays, the others' its centre's.
        let charging = !centres.charges.is_empty();
        let (dx, dy) = ((tile.x - halo.x) as usize, (tile.y - halo.y) as usize);
        let hw = halo.width as usize;
        let mut charge_rows: Vec<Charges> = (0..tile.height).map(|_| Charges::default()).collect();
        radiance
            .par_chunks_mut(tw)
            .zip(flags.par_chunks(tw))
            .zip(charge_rows.par_iter_mut())
            .enumerate()
            .for_each(|(r, ((rad, flags), charges))| {
                let mut path = Path::default();
                let mut scratch = Sample::miss(Event::Sky);
                let mut tally = Tally::default();
                let row = tile.y + r as u32;
                for (c, (l_out, &flag)) in rad.iter_mut().zip(flags).enumerate() {
                    let col = tile.x + c as u32;
                    match (flag, charging) {
                        (true, true) => {
                            tally.restart();
                            *l_out = self.pixel::<false, Tally>(
                                &fc,
                                &full,
                                [col, row],
                                &mut path,
                                &mut scratch,
                                &mut tally,
                            );
                            tally.finish_into(charges);
                        }
                        (true, false) => {
                            *l_out = self.pixel::<false, ()>(
                                &fc,
                                &full,
                                [col, row],
                                &mut path,
                                &mut scratch,
                                &mut (),
                            );
                        }
                        (false, true) => {
                            charges.push_from(&centres.charges, (r + dy) * hw + c + dx);
                        }
                        (false, false) => {}
                    }
                }
                progress(1);
            });
        Ok(Frame {
            width: tile.width,
            height: tile.height,
            radiance_w_m2_sr: radiance,
            truth,
            sampling: Vec::new(),
            sun,
            texture,
            data_error_k: Vec::new(),
            charges: Charges::concat(charge_rows),
        })
    }

    /// [`Self::render_tile`] with refinement: the centre rays of the tile and a one-pixel
    /// margin, the candidates among the tile's pixels (an edge against a neighbour, or a
    /// thin facet near), and each candidate refined to the target.
    pub(super) fn render_refined(
        &self,
        fc: &FrameConsts<'_>,
        options: &TraceOptions,
        refinement: &Refinement,
        tile: Tile,
        progress: &(dyn Fn(u64) + Sync),
    ) -> Frame {
        let camera = fc.camera();
        let [w, h] = camera.pixels;
        let halo = tile.grown(1, w, h);
        // The centre pass keeps every centre's terms: a pixel that stays with its centre
        // ray gives the budget its sensitivities.
        let centres = self.refinement_centres(fc, options, halo);
        let inverse = self.inverse_table();
        let calm: Vec<f64> = centres
            .calm_w_m2_sr
            .par_chunks(4096)
            .flat_map_iter(|run| inverse.temperatures(run.iter().copied()))
            .collect();
        let contrast = contrast_of(&calm, halo.width as usize, halo.height as usize);
        let thin = self.thin_pixels_in(camera, tile);
        // What a thin facet, which no centre may have seen, could hide: the same for a tile
        // as for its frame.
        let thin_contrast_k = self.contrast_bound_k();
        let (hw, tw) = (halo.width as usize, tile.width as usize);
        let (dx, dy) = ((tile.x - halo.x) as usize, (tile.y - halo.y) as usize);
        let mut radiance = vec![0.0; tile.pixels()];
        let mut sampling = vec![PixelSampling::default(); tile.pixels()];
        let charging = !centres.charges.is_empty();
        let mut charge_rows: Vec<Charges> = (0..tile.height).map(|_| Charges::default()).collect();
        radiance
            .par_chunks_mut(tw)
            .zip(sampling.par_chunks_mut(tw))
            .zip(charge_rows.par_iter_mut())
            .enumerate()
            .for_each(|(r, ((rad, smp), charges))| {
                let mut path = Path::default();
                let mut tally = Tally::default();
                let row = tile.y + r as u32;
                for (c, (l_out, s_out)) in rad.iter_mut().zip(smp.iter_mut()).enumerate() {
                    let col = tile.x + c as u32;
                    let at = (r + dy) * hw + c + dx;
                    let is_thin = thin[r * tw + c];
                    if contrast[at] > refinement.edge_k || is_thin {
                        let start = if is_thin {
                            refinement.thin_side
                        } else {
                            EDGE_SIDE.min(refinement.max_side)
                        };
                        let one = (col, row);
                        // What a sliver could hide: the neighbours' contrast, or for a thin
                        // facet, which no centre may have seen, the frame's.
                        let hide = if is_thin {
                            thin_contrast_k
                        } else {
                            contrast[at]
                        };
                        (*l_out, *s_out) = match (options.truth, charging) {
                            (true, true) => {
                                let refined = self.refine_pixel::<true, Tally>(
                                    fc, options, refinement, &inverse, one, start, hide, &mut path,
                                    &mut tally,
                                );
                                tally.finish_into(charges);
                                refined
                            }
                            (true, false) => self.refine_pixel::<true, ()>(
                                fc,
                                options,
                                refinement,
                                &inverse,
                                one,
                                start,
                                hide,
                                &mut path,
                                &mut (),
                            ),
                            (false, _) => self.refine_pixel::<false, ()>(
                                fc,
                                options,
                                refinement,
                                &inverse,
                                one,
                                start,
                                hide,
                                &mut path,
                                &mut (),
                            ),
                        };
                    } else {
                        *l_out = centres.radiance_w_m2_sr[at];
                        *s_out = PixelSampling::from_truth(&centres.truth[at]);
                        if charging {
                            charges.push_from(&centres.charges, at);
                        }
                    }
                }
                progress(1);
            });
        // The tile's rows of each layer kept over the halo (empty where one is not).
        let th = tile.height as usize;
        let (truth, sun, texture) = if options.truth {
            (
                crop_rows(&centres.truth, [dx, dy], hw, tw, th),
                crop_rows(&centres.sun, [dx, dy], hw, tw, th),
                crop_rows(&centres.texture, [dx, dy], hw, tw, th),
            )
        } else {
            (Vec::new(), Vec::new(), Vec::new())
        };
        Frame {
            width: tile.width,
            height: tile.height,
            radiance_w_m2_sr: radiance,
            truth,
            sampling,
            sun,
            texture,
            data_error_k: Vec::new(),
            charges: Charges::concat(charge_rows),
        }
    }

    /// The pixels of `tile` (checked to lie in the image), rows in parallel: a frame of the
    /// tile's size.
    pub(super) fn render_rect(
        &self,
        fc: &FrameConsts<'_>,
        options: &TraceOptions,
        tile: Tile,
        progress: &(dyn Fn(u64) + Sync),
    ) -> Frame {
        let n = tile.pixels();
        let row_len = tile.width.max(1) as usize;
        let mut radiance = vec![0.0; n];
        let mut truth = Vec::new();
        let mut sun = Vec::new();
        let mut texture = Vec::new();
        // The budget's charges, a row's at a time (empty unless the tracer keeps them).
        let charging = options.truth && self.keeps_charges();
        let rows = n.div_ceil(row_len);
        let mut charge_rows: Vec<Charges> = (0..rows).map(|_| Charges::default()).collect();
        // One pixel with its truth, its charges appended to `charges` when kept.
        let truth_pixel = |col: u32,
                           row: u32,
                           path: &mut Path,
                           centre: &mut Sample,
                           tally: &mut Tally,
                           charges: &mut Charges| {
            if charging {
                tally.restart();
                let l = self.pixel::<true, Tally>(fc, options, [col, row], path, centre, tally);
                tally.finish_into(charges);
                l
            } else {
                self.pixel::<true, ()>(fc, options, [col, row], path, centre, &mut ())
            }
        };
        if options.truth {
            truth = vec![TruthPixel::from(&Sample::miss(Event::Sky)); n];
        }
        if options.truth && self.sun.is_some() {
            // The sun's layers in a vector of their own, empty on a night frame.
            sun = vec![SunPixel::from(&Sample::miss(Event::Sky)); n];
        }
        if options.truth && self.is_textured() {
            // The texture's layers likewise, empty for an untextured scene.
            texture = vec![TexturePixel::from(&Sample::miss(Event::Sky)); n];
        }
        // Each row's share of the layers kept (none where a layer is not).
        let mut truth_rows = row_slices(&mut truth, row_len, rows);
        let mut sun_rows = row_slices(&mut sun, row_len, rows);
        let mut texture_rows = row_slices(&mut texture, row_len, rows);
        radiance
            .par_chunks_mut(row_len)
            .zip(truth_rows.par_iter_mut())
            .zip(sun_rows.par_iter_mut())
            .zip(texture_rows.par_iter_mut())
            .zip(charge_rows.par_iter_mut())
            .enumerate()
            .for_each(|(r, ((((rad, tru), sun), tex), charges))| {
                let mut path = Path::default();
                let mut centre = Sample::miss(Event::Sky);
                let mut tally = Tally::default();
                let row = tile.y + r as u32;
                for (c, l_out) in rad.iter_mut().enumerate() {
                    let col = tile.x + c as u32;
                    *l_out = if options.truth {
                        truth_pixel(col, row, &mut path, &mut centre, &mut tally, charges)
                    } else {
                        self.pixel::<false, ()>(
                            fc,
                            options,
                            [col, row],
                            &mut path,
                            &mut centre,
                            &mut (),
                        )
                    };
                    if let Some(t) = tru {
                        t[c] = TruthPixel::from(&centre);
                    }
                    if let Some(s) = sun {
                        s[c] = SunPixel::from(&centre);
                    }
                    if let Some(t) = tex {
                        t[c] = TexturePixel::from(&centre);
                    }
                }
                progress(1);
            });
        Frame {
            width: tile.width,
            height: tile.height,
            radiance_w_m2_sr: radiance,
            truth,
            sampling: Vec::new(),
            sun,
            texture,
            data_error_k: Vec::new(),
            charges: if charging {
                Charges::concat(charge_rows)
            } else {
                Charges::default()
            },
        }
    }

    /// Every term of the ray through the centre of pixel `(column, row)`, exactly as
    /// [`Self::render`] computes them for the truth outputs, in f64.
    ///
    /// # Errors
    /// The pixel lies outside the image, or the options are out of range.
    pub fn probe(
        &self,
        camera: &Camera,
        options: &TraceOptions,
        column: u32,
        row: u32,
    ) -> Result<Sample, TraceError> {
        options.validate()?;
        let [w, h] = camera.pixels;
        if column >= w || row >= h {
            return Err(TraceError::new(TraceErrorKind::PixelOutsideImage {
                column,
                row,
                width: w,
                height: h,
            }));
        }
        let mut s = Sample::miss(Event::Sky);
        let mut path = Path::default();
        self.pixel::<true, ()>(
            &self.frame_consts(
                camera,
                Tile {
                    x: column,
                    y: row,
                    width: 1,
                    height: 1,
                },
            ),
            options,
            [column, row],
            &mut path,
            &mut s,
            &mut (),
        );
        Ok(s)
    }

    /// Radiance of a pixel (mean over its sub-pixel rays). With `TRUTH`, the centre ray's
    /// terms go to `centre` (written in place: a sample is 192 bytes, and moving it
    /// through every call level showed as memory copies in the profile); without, `centre`
    /// is not touched. The rays the value is the mean of are charged to `sink`, which the
    /// caller has restarted. `path` is scratch space reused from pixel to pixel.
    pub(super) fn pixel<const TRUTH: bool, C: ChargeSink>(
        &self,
        fc: &FrameConsts<'_>,
        options: &TraceOptions,
        [col, row]: [u32; 2],
        path: &mut Path,
        centre: &mut Sample,
        sink: &mut C,
    ) -> f64 {
        let camera = fc.camera;
        let mut ctx = Ctx::for_pixel(
            options,
            u64::from(row) * u64::from(camera.pixels[0]) + u64::from(col),
        );
        // Bit for bit `camera.pixel_direction(col, row)`, without its divisions; the pixel
        // lies in the window (`frame_consts`'s callers make it so).
        let dir = camera.direction_uv(
            fc.us[(col - fc.window.x) as usize],
            fc.vs[(row - fc.window.y) as usize],
        );
        ctx.sun_truth = TRUTH;
        self.follow(fc, dir, &mut ctx, path);
        ctx.sun_truth = false;
        let n = options.supersampling;
        if n <= 1 {
            sink.set_rays(1);
            return self.radiance_charged::<TRUTH, C>(fc, path, centre, sink);
        }
        self.radiance::<TRUTH>(fc, path, centre);
        let mut sum = 0.0;
        ctx.for_each_subpixel((col, row), n, |ctx, x, y| {
            // Only the centre ray's terms are kept: the sub-pixel rays compute radiance.
            self.follow(fc, camera.direction_at(x, y), ctx, path);
            sum += self.radiance_charged::<false, C>(fc, path, centre, sink);
        });
        sink.set_rays(n * n);
        sum / f64::from(n * n)
    }
}

/// `layer` cut into its rows of `row_len` pixels, one entry per row of `rows`: `None` for
/// every row when the layer is not kept (empty).
/// The `rows` rows of `width` pixels that start at `[dx, dy]` in a layer of rows of
/// `stride` pixels (a tile within its halo); empty for an empty layer (one not kept).
fn crop_rows<T: Copy>(
    layer: &[T],
    [dx, dy]: [usize; 2],
    stride: usize,
    width: usize,
    rows: usize,
) -> Vec<T> {
    if layer.is_empty() {
        return Vec::new();
    }
    (0..rows)
        .flat_map(|r| {
            let start = (r + dy) * stride + dx;
            layer[start..start + width].iter().copied()
        })
        .collect()
}

fn row_slices<T>(layer: &mut [T], row_len: usize, rows: usize) -> Vec<Option<&mut [T]>> {
    if layer.is_empty() {
        (0..rows).map(|_| None).collect()
    } else {
        layer.chunks_mut(row_len).map(Some).collect()
    }
}
