//! A frame's files, encoded: the radiance EXR, the truth EXR (with the error budget's layers
//! when uncertainties are declared), the 1990 interaction map, and the digital-count image
//! with its LUT. Made from a traced frame ([`traced`], `irsig-trace`) or from a frame's
//! merged tiles ([`merged`], `irsig-merge`) by the same functions, so that a frame traced in
//! tiles and merged is byte for byte the frame traced whole. Nothing here writes a file:
//! each file's bytes go to the caller's `emit`, which names and stages them.

use irsig_formats::legacy::map;
use irsig_model::frame::{FrameFile, FrameFiles};
use irsig_model::provenance::Provenance;
use irsig_model::truth::Layer;
use irsig_radiometry::BandModel;
use irsig_raster::{FramePart, Raster, counts_png, into_exr_bytes, write_png_indexed8};
use irsig_sensor_model::quantise::{CountRequest, Quantiser};
use irsig_tracer::Frame;
use rayon::prelude::*;

use crate::RenderError;
use crate::budget::Budget;
use crate::guarantee::Guarantee;

/// The gain of the tracer's digital counts when neither the request nor the view gives
/// one, counts per kelvin (the thesis experiment's viewing files say 2).
pub const TRACER_DC_PER_KELVIN: f64 = 2.0;

/// Where each encoded file goes: the caller's naming and staging.
pub type Emit<'a> = dyn FnMut(FrameFile, Vec<u8>) -> miette::Result<()> + 'a;

/// Gives `bytes`, a frame's file of `kind`, to `emit`: the caller's error, if any, kept
/// whole.
fn give(emit: &mut Emit<'_>, kind: FrameFile, bytes: Vec<u8>) -> Result<(), RenderError> {
    emit(kind, bytes)
        .map_err(|e| RenderError::caller(format!("keeping the frame's {}", kind.suffix()), e))
}

/// The EXR of `raster`, encoded, the frame's file of `kind`.
fn exr(raster: Raster, kind: FrameFile) -> Result<Vec<u8>, RenderError> {
    into_exr_bytes(raster)
        .map_err(|e| RenderError::encode(format!("encoding the frame's {}", kind.suffix()), e))
}

/// What a frame's files need besides its pixels: the band its radiances are in, how many
/// sub-bands they were summed over, the view's gain (DC/K) if it has one, and the counts'
/// calibration as asked for.
#[derive(Debug, Clone)]
pub struct FrameRadiometry<R> {
    /// The band.
    pub band: R,
    /// Sub-bands the radiance was summed over (1: the band model).
    pub sub_bands: usize,
    /// The view's DC/K.
    pub view_gain: Option<f64>,
    /// The counts' calibration.
    pub counts: CountRequest,
    /// What made the frame: recorded in its EXRs (their comments) and, its band, in the
    /// LUT.
    pub provenance: Option<Provenance>,
}

impl<R: BandModel> FrameRadiometry<R> {
    /// The quantiser of the digital-count image, over the whole frame's radiance: the
    /// request's calibration, with the view's DC/K, else [`TRACER_DC_PER_KELVIN`], for a
    /// missing gain. One function for a traced and a merged frame, so that their counts and
    /// LUT are the same.
    ///
    /// # Errors
    /// A calibration the quantiser refuses (no finite radiance, a gain of 0).
    pub fn quantiser(&self, radiance_w_m2_sr: &[f32]) -> Result<Quantiser, RenderError> {
        let calibration = self
            .counts
            .calibration(self.view_gain.or(Some(TRACER_DC_PER_KELVIN)))
            .ok_or_else(|| RenderError::refused("digital counts: no gain"))?;
        Quantiser::calibrate(self.counts.bits, &calibration, radiance_w_m2_sr, &self.band)
            .map_err(|e| RenderError::counts("digital counts", e))
    }

    /// The counts and the LUT of `wanted`, from the frame's radiance.
    fn counts(
        &self,
        radiance: &[f32],
        width: usize,
        height: usize,
        wanted: &FrameFiles<()>,
        emit: &mut Emit<'_>,
    ) -> Result<(), RenderError> {
        if !wanted.wants(FrameFile::DcPng) && !wanted.wants(FrameFile::Lut) {
            return Ok(());
        }
        let q = self.quantiser(radiance)?;
        if wanted.wants(FrameFile::DcPng) {
            let counts = q
                .quantise(radiance, width)
                .map_err(|e| RenderError::counts("digital counts", e))?;
            let png = counts_png(&counts, width, height, self.counts.bits)
                .map_err(|e| RenderError::encode("encoding the digital counts' PNG", e))?;
            give(emit, FrameFile::DcPng, png)?;
        }
        if wanted.wants(FrameFile::Lut) {
            let lut = q.lut(&self.band);
            let text = match &self.provenance {
                Some(p) => lut.text_in_band(&p.band.to_string()),
                None => lut.to_string(),
            };
            give(emit, FrameFile::Lut, text.into_bytes())?;
        }
        Ok(())
    }

    /// The EXRs' comments: the provenance as canonical RON.
    fn comments(&self) -> Result<Option<String>, RenderError> {
        self.provenance
            .as_ref()
            .map(|p| {
                irsig_formats::canonical::provenance_comments(p)
                    .map_err(|e| RenderError::encode("writing the provenance as RON", e))
            })
            .transpose()
    }
}

/// Why the interaction map of a frame whose largest material id is `max_id` cannot be
/// made, and where the same information is.
#[must_use]
pub fn map_refusal(max_id: u32) -> String {
    format!(
        "interaction map not written: material id {max_id} does not fit the legacy 4-bit \
         nibble (ids 1 to 15); the truth EXR's material_primary and material_secondary \
         layers hold the same information losslessly"
    )
}

/// The 1990 interaction map (thesis §4.2) of `width × height` pixels from each pixel's
/// primary and reflected material ids: primary in the upper nibble, reflected in the
/// lower, 0 where nothing was hit, as the indices of an indexed PNG whose palette
/// ([`map::palette`]) makes every material visible. `Ok(Err(id))`: an id does not fit a
/// nibble.
fn interaction_map(
    width: usize,
    height: usize,
    ids: impl ExactSizeIterator<Item = Result<(u16, u16), RenderError>>,
) -> Result<Result<Vec<u8>, u32>, RenderError> {
    let mut data = Vec::with_capacity(ids.len());
    for pair in ids {
        let (p, s) = pair?;
        match map::pixel(p, s) {
            Some(byte) => data.push(byte),
            None => return Ok(Err(u32::from(p.max(s)))),
        }
    }
    let mut png = Vec::new();
    write_png_indexed8(&mut png, width, height, &data, &map::palette())
        .map_err(|e| RenderError::encode("encoding the interaction map's PNG", e))?;
    Ok(Ok(png))
}

fn push(raster: &mut Raster, layer: Layer, data: Vec<f32>) -> Result<(), RenderError> {
    raster
        .push_layer(layer.name(), layer.unit(), data)
        .map_err(|e| RenderError::encode(format!("the `{layer}` layer"), e))
}

/// The layers a truth EXR holds: [`Layer::TRUTH`], then [`Layer::SUN`] when traced with a
/// sun, then [`Layer::TEXTURE`] when the scene has a textured material, then
/// [`Layer::DATA`] when the atmosphere records its data error, then [`Layer::BUDGET`] with
/// declared uncertainties, then [`Layer::TOLERANCE`] when rendered to a tolerance.
#[must_use]
pub fn truth_layers(
    sun: bool,
    texture: bool,
    data: bool,
    budget: bool,
    tolerance: bool,
) -> Vec<Layer> {
    let mut layers = Layer::TRUTH.to_vec();
    if sun {
        layers.extend(Layer::SUN);
    }
    if texture {
        layers.extend(Layer::TEXTURE);
    }
    if data {
        layers.extend(Layer::DATA);
    }
    if budget {
        layers.extend(Layer::BUDGET);
    }
    if tolerance {
        layers.extend(Layer::TOLERANCE);
    }
    layers
}

/// Encodes the files `wanted` of one traced frame (or tile) and gives each to `emit`: the
/// map, the counts and LUT, the radiance EXR, and the truth EXR last, its layers made from
/// the frame's per-pixel records, which are dropped before the layers are encoded. A map
/// whose ids do not fit a nibble is an error here: the caller leaves it out of `wanted`
/// when the materials say so.
///
/// # Errors
/// A calibration the quantiser refuses, or a file that cannot be encoded.
pub fn traced<R: BandModel + Sync>(
    radiometry: &FrameRadiometry<R>,
    mut frame: Frame,
    wanted: &FrameFiles<()>,
    part: &FramePart,
    budget: Option<&Budget<'_>>,
    guarantee: Option<&Guarantee<'_>>,
    emit: &mut Emit<'_>,
) -> Result<(), RenderError> {
    let radiance = frame.radiance_f32();
    let (w, h) = (frame.width as usize, frame.height as usize);
    if wanted.wants(FrameFile::MapPng) {
        let ids = frame
            .truth
            .iter()
            .map(|s| Ok((s.primary_material, s.secondary_material)));
        let png = interaction_map(w, h, ids)?
            .map_err(|_| RenderError::internal("material id above 15 in the interaction map"))?;
        give(emit, FrameFile::MapPng, png)?;
    }
    radiometry.counts(&radiance, w, h, wanted, emit)?;
    if wanted.wants(FrameFile::RadianceExr) {
        let mut r = Raster::new(w, h)
            .with_part(part.clone())
            .with_comments(radiometry.comments()?);
        push(&mut r, Layer::Radiance, radiance)?;
        give(
            emit,
            FrameFile::RadianceExr,
            exr(r, FrameFile::RadianceExr)?,
        )?;
    }
    if wanted.wants(FrameFile::TruthExr) {
        let r = truth_raster(radiometry, &frame, budget, guarantee)?
            .with_part(part.clone())
            .with_comments(radiometry.comments()?);
        frame.truth = Vec::new();
        frame.sun = Vec::new();
        frame.texture = Vec::new();
        frame.data_error_k = Vec::new();
        give(emit, FrameFile::TruthExr, exr(r, FrameFile::TruthExr)?)?;
    }
    Ok(())
}

/// The truth layers ([`truth_layers`], in order): the terms of each pixel's centre ray, the
/// apparent temperature of its radiance, the sun's, the texture's and the atmosphere
/// data's (when the frame kept them), the error budget's and the tolerance's layers. NaN where a term does not apply (no facet hit).
fn truth_raster<R: BandModel + Sync>(
    radiometry: &FrameRadiometry<R>,
    frame: &Frame,
    budget: Option<&Budget<'_>>,
    guarantee: Option<&Guarantee<'_>>,
) -> Result<Raster, RenderError> {
    let mut r = Raster::new(frame.width as usize, frame.height as usize);
    // The tracer's table, the same for a frame and its tiles.
    let inverse = irsig_tracer::inverse_table(&radiometry.band);
    let apparent: Vec<f64> = frame
        .radiance_w_m2_sr
        .par_chunks(4096)
        .flat_map_iter(|run| inverse.temperatures(run.iter().copied()))
        .collect();
    // The layers in parallel, each one pass over the pixels.
    let layers: Vec<Result<Vec<f32>, RenderError>> = Layer::TRUTH
        .par_iter()
        .map(|&layer| match frame.truth_layer(layer) {
            Some(data) => Ok(data),
            None if layer == Layer::ApparentTemperature => {
                Ok(apparent.iter().map(|&t| t as f32).collect())
            }
            None if layer == Layer::SubBands => {
                Ok(vec![radiometry.sub_bands as f32; apparent.len()])
            }
            None => Err(RenderError::internal(format!(
                "the frame holds no `{layer}` layer"
            ))),
        })
        .collect();
    for (layer, data) in Layer::TRUTH.into_iter().zip(layers) {
        push(&mut r, layer, data?)?;
    }
    let kept = [
        (!frame.sun.is_empty(), Layer::SUN.as_slice()),
        (!frame.texture.is_empty(), Layer::TEXTURE.as_slice()),
        (!frame.data_error_k.is_empty(), Layer::DATA.as_slice()),
    ];
    for layer in kept.into_iter().filter(|(k, _)| *k).flat_map(|(_, l)| l) {
        let data = frame
            .truth_layer(*layer)
            .ok_or_else(|| RenderError::internal(format!("the frame holds no `{layer}` layer")))?;
        push(&mut r, *layer, data)?;
    }
    if let Some(budget) = budget {
        let model_k = guarantee.map(|g| g.model_sigma_k(frame));
        for (layer, data) in budget.layers(&radiometry.band, frame, &apparent, model_k.as_deref()) {
            push(&mut r, layer, data)?;
        }
    }
    if let Some(g) = guarantee {
        push(&mut r, Layer::NotGuaranteed, g.not_guaranteed(frame))?;
        push(&mut r, Layer::Samples, samples(frame))?;
    }
    Ok(r)
}

/// The [`Layer::Samples`] layer: the rays each pixel's value is the mean of where the
/// frame was refined, NaN where it was not.
fn samples(frame: &Frame) -> Vec<f32> {
    if frame.sampling.is_empty() {
        return vec![f32::NAN; frame.radiance_w_m2_sr.len()];
    }
    frame.sampling.iter().map(|s| s.rays as f32).collect()
}

/// What [`merged`] does with an interaction map that cannot be made.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MapRefused {
    /// Leave it out and say why through `note` (the map came with every other file).
    Skip,
    /// Fail (the map was asked for by name).
    Fail,
}

/// Encodes the files `wanted` of a frame from its merged tiles (`radiance`: the radiance
/// layer; `truth`: the truth layers) and gives each to `emit`.
///
/// # Errors
/// A file asked for whose layers are missing, a material layer that holds no material id,
/// an interaction map that cannot be made under [`MapRefused::Fail`], a calibration the
/// quantiser refuses, or a file that cannot be encoded.
pub fn merged<R: BandModel>(
    radiometry: &FrameRadiometry<R>,
    radiance: Option<Raster>,
    truth: Option<Raster>,
    wanted: &FrameFiles<()>,
    map_refused: MapRefused,
    note: &mut dyn FnMut(String),
    emit: &mut Emit<'_>,
) -> Result<(), RenderError> {
    if let Some(frame) = radiance {
        let data = &frame
            .layer(Layer::Radiance.name())
            .ok_or_else(|| RenderError::refused("the merged frame has no radiance layer"))?
            .data;
        radiometry.counts(data, frame.width, frame.height, wanted, emit)?;
        // The merged frame's layers go into the encoder, not a copy of them.
        if wanted.wants(FrameFile::RadianceExr) {
            give(
                emit,
                FrameFile::RadianceExr,
                exr(frame, FrameFile::RadianceExr)?,
            )?;
        }
    }
    if let Some(frame) = truth {
        if wanted.wants(FrameFile::MapPng) {
            let layer = |l: Layer| {
                frame.layer(l.name()).map(|l| &l.data).ok_or_else(|| {
                    RenderError::refused(format!("the merged truth has no `{}` layer", l.name()))
                })
            };
            let (primary, secondary) = (
                layer(Layer::MaterialPrimary)?,
                layer(Layer::MaterialSecondary)?,
            );
            let ids = primary
                .iter()
                .zip(secondary)
                .map(|(&p, &s)| Ok((material_id(p)?, material_id(s)?)));
            match interaction_map(frame.width, frame.height, ids)? {
                Ok(png) => give(emit, FrameFile::MapPng, png)?,
                Err(id) if map_refused == MapRefused::Skip => note(map_refusal(id)),
                Err(id) => return Err(RenderError::refused(map_refusal(id))),
            }
        }
        if wanted.wants(FrameFile::TruthExr) {
            give(emit, FrameFile::TruthExr, exr(frame, FrameFile::TruthExr)?)?;
        }
    }
    Ok(())
}

/// A material layer's value as a material id.
fn material_id(v: f32) -> Result<u16, RenderError> {
    if v.is_finite() && v.fract() == 0.0 && (0.0..=f32::from(u16::MAX)).contains(&v) {
        Ok(v as u16)
    } else {
        Err(RenderError::refused(format!(
            "a material layer holds {v}, which is not a material id (0 to 65535)"
        )))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use irsig_radiometry::Band;

    #[test]
    fn a_map_holds_primary_then_reflected_ids_and_refuses_wide_ones() {
        let ids = [(1, 0), (2, 15), (0, 0), (15, 3)].map(Ok);
        let png = interaction_map(2, 2, ids.into_iter()).unwrap().unwrap();
        let indices = irsig_raster::read_png_indices(&png).unwrap();
        assert_eq!(indices, (2, 2, vec![0x10, 0x2f, 0x00, 0xf3]));
        // A viewer sees the palette: material 1 in Kelly's yellow, nothing hit in black.
        let rgb = image::load_from_memory(&png).unwrap().into_rgb8();
        assert_eq!(rgb.get_pixel(0, 0).0, [0xf3, 0xc3, 0x00]);
        assert_eq!(rgb.get_pixel(0, 1).0, [0, 0, 0]);
        let wide = [(1, 0), (16, 2)].map(Ok);
        assert_eq!(interaction_map(2, 1, wide.into_iter()).unwrap(), Err(16));
        assert!(material_id(2.5).is_err() && material_id(f32::NAN).is_err());
        assert_eq!(material_id(7.0).unwrap(), 7);
    }

    #[test]
    fn counts_default_to_the_views_gain_then_two_per_kelvin() {
        let band = Band::new(8.0, 14.0).unwrap();
        let radiance: Vec<f32> = [280.0, 300.0, 320.0]
            .iter()
            .map(|&t| band.radiance(t) as f32)
            .collect();
        let per_kelvin = |view_gain| {
            let r = FrameRadiometry {
                band: band.clone(),
                sub_bands: 1,
                view_gain,
                counts: CountRequest {
                    bits: 12,
                    ..CountRequest::default()
                },
                provenance: None,
            };
            let q = r.quantiser(&radiance).unwrap();
            // Counts per kelvin at 300 K, by a centred difference.
            let l = |t: f64| band.radiance(t) as f32;
            let c = |t| f64::from(q.quantise(&[l(t)], 1).unwrap()[0]);
            (c(305.0) - c(295.0)) / 10.0
        };
        assert!((per_kelvin(None) - TRACER_DC_PER_KELVIN).abs() < 0.11);
        assert!((per_kelvin(Some(5.0)) - 5.0).abs() < 0.11);
    }
}
