//! The tolerance on a textured surface: a ground whose temperature varies over 5 cm,
//! far finer than a pixel's footprint on it (0.4 to 2 m), seen from a mast. A pixel is the
//! mean of its footprint, so the centre ray's point is not the pixel: the pilot must see
//! that the texture varies within a pixel, and the frame it chooses must keep the
//! tolerance against a converged reference, with the texture read at the point (where
//! refinement has to average it) and through the footprint filter (where one ray already
//! gives the pixel's mean, and refinement has far less to do). A texture too faint to make
//! edges is charged its spread within the pixel all the same.

use irsig_model::View;
use irsig_model::texture::{
    CorrelationLength, FieldFilter, FieldSpectrum, RandomField, StatisticalTexture,
};
use irsig_radiometry::TotalRadiance;
use irsig_tracer::reference::{converged_reference, percentile};
use irsig_tracer::testing::{
    grey_materials, ground_quad, raw_scene, temperatures, vacuum_pilot_space,
};
use irsig_tracer::{Camera, TraceOptions, Tracer, Vacuum};

/// A dim sky, as the generated scenes': a diffuse ground reflects it.
const SKY: Vacuum = Vacuum {
    sky_radiance_w_m2_sr: 25.0,
};

/// A ground 300 K, ε 0.95, diffuse, with a temperature field of σ `sigma_k` and ℓ 5 cm
/// read through `filter`, seen from 20 m up at 55° from nadir, 40 × 30 pixels over
/// 30° × 22.5°.
fn textured(filter: FieldFilter, sigma_k: f64) -> (Tracer<TotalRadiance, Vacuum>, Camera) {
    let ground = ground_quad([-400.0, -400.0], [400.0, 400.0], 0.0);
    let scene = raw_scene(&[(&ground, 1, 300.0)]);
    let mut lib = grey_materials(&[(1, 0.95, 0.0)]);
    lib.materials[0].texture = Some(StatisticalTexture {
        seed: 3,
        temperature_offset_k: Some(RandomField {
            sigma: sigma_k,
            spectrum: FieldSpectrum::Gaussian {
                correlation_length_m: CorrelationLength::Isotropic(0.05),
            },
        }),
        emissivity_scale: None,
        filter,
    });
    let tracer = Tracer::new(&scene, &lib, TotalRadiance, SKY).unwrap();
    let camera = Camera::from_view(&View::Legacy {
        position_m: [0.0, 0.0, 20.0],
        pixels: [40, 30],
        omega_phi_kappa_deg: [55.0, 0.0, 0.0],
        fov_deg: [30.0, 22.5],
        gain_dc_per_k: None,
    })
    .unwrap();
    (tracer, camera)
}

/// What one filter gives at `tolerance_k`, against the converged reference.
struct Kept {
    /// The decision's predicted p99 of |ΔT|, K.
    predicted_k: f64,
    /// The measured p99 of the pilot's choice, K.
    measured_k: f64,
    /// The rays the chosen frame traced.
    rays: u64,
    /// The measured p99 of the centre rays alone (no refinement), K.
    centre_k: f64,
}

/// The pilot's choice at `tolerance_k` rendered, and the centre rays alone, measured
/// against the converged reference.
fn kept(filter: FieldFilter, sigma_k: f64, tolerance_k: f64) -> Kept {
    let (tracer, camera) = textured(filter, sigma_k);
    let offer = vacuum_pilot_space(&tracer, SKY);
    let piloted = tracer
        .pilot(&camera, &offer, tolerance_k, 99.0, 1024, 1)
        .unwrap_or_else(|e| panic!("{filter:?} at {tolerance_k} K refused: {e}"));
    let c = piloted.chosen;
    let options = c.trace_options(
        TraceOptions {
            seed: 1,
            truth: true,
            ..TraceOptions::default()
        },
        tolerance_k,
    );
    let (reference_tracer, _) = textured(filter, sigma_k);
    let reference = converged_reference(&reference_tracer, &camera, tolerance_k / 6.0, 3).unwrap();
    assert!(
        reference.error_p99_k() < tolerance_k / 3.0,
        "the reference is not converged: {} K",
        reference.error_p99_k()
    );
    let p99 = |frame: &irsig_tracer::Frame| {
        let error: Vec<f64> = temperatures(frame)
            .iter()
            .zip(&reference.truth)
            .map(|(g, t)| g - t)
            .collect();
        percentile(&error, 99.0)
    };
    let centre = tracer.render(&camera, &options, &|_| {}).unwrap();
    let chosen = tracer
        .with_refinement(c.refinement)
        .unwrap()
        .render(&camera, &options, &|_| {})
        .unwrap();
    let out = Kept {
        predicted_k: piloted.decision.predicted.percentile_k,
        measured_k: p99(&chosen),
        rays: chosen.sampling.iter().map(|s| u64::from(s.rays)).sum(),
        centre_k: p99(&centre),
    };
    eprintln!(
        "{filter:?}, σ {sigma_k} K, at {tolerance_k} K: predicted p99 {:.4} K, measured {:.4} K from {} rays; \
         the centre rays alone {:.3} K",
        out.predicted_k, out.measured_k, out.rays, out.centre_k
    );
    out
}

#[test]
fn a_texture_finer_than_a_pixel_keeps_the_tolerance_at_the_point_and_through_the_footprint() {
    let tolerance_k = 0.3;
    // At the point, a centre ray misses the pixel's mean by about the field's σ (1 K):
    // the pilot must see it, and refinement average it.
    let point = kept(FieldFilter::Point, 1.0, tolerance_k);
    assert!(point.centre_k > 1.0, "{} K", point.centre_k);
    assert!(
        point.measured_k <= tolerance_k,
        "point: p99 {} K",
        point.measured_k
    );
    assert!(
        point.predicted_k >= point.measured_k,
        "point: predicted {} K",
        point.predicted_k
    );
    // Through the footprint, the centre ray is the pixel's mean already (within the
    // perspective across one pixel and the radiance's curvature, hundredths of a kelvin):
    // the same tolerance kept, for a fraction of the rays (what refinement still does, it
    // does for the differences between pixels, which stay).
    let footprint = kept(FieldFilter::Footprint, 1.0, tolerance_k);
    assert!(footprint.centre_k < 0.05, "{} K", footprint.centre_k);
    assert!(
        footprint.measured_k <= tolerance_k,
        "footprint: p99 {} K",
        footprint.measured_k
    );
    assert!(
        footprint.predicted_k >= footprint.measured_k,
        "footprint: predicted {} K",
        footprint.predicted_k
    );
    assert!(
        footprint.rays * 4 < point.rays,
        "{} against {} rays",
        footprint.rays,
        point.rays
    );
}

#[test]
fn a_texture_too_faint_to_make_edges_is_still_charged_its_spread_within_the_pixel() {
    // σ 0.12 K read at the point, at 1 K: neighbouring centres hardly ever differ by the
    // 0.5 K that makes a pixel a refinement candidate, so the pixels keep their centre
    // rays, which miss their pixels' means by about σ. The pilot must charge that (it had
    // charged a pixel refinement does not take nothing, and predicted the frame's p99
    // under what it measured): its prediction is not under the measured error, which is
    // there to be seen.
    let tolerance_k = 1.0;
    let faint = kept(FieldFilter::Point, 0.12, tolerance_k);
    assert!(faint.centre_k > 0.2, "{} K", faint.centre_k);
    assert!(
        faint.measured_k <= tolerance_k,
        "p99 {} K",
        faint.measured_k
    );
    assert!(
        faint.predicted_k >= faint.measured_k,
        "predicted {} K, measured {} K",
        faint.predicted_k,
        faint.measured_k
    );
}
