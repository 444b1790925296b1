//! Adaptive supersampling (thesis §3.3.4): only the pixels at an edge get the N × N rays,
//! each exactly as a full N × N rendering computes it, and every pixel a full rendering
//! changes by more than the threshold is one of them.

use irsig_model::View;
use irsig_radiometry::{BandModel, TotalRadiance};
use irsig_tracer::testing::{grey_materials, ground_quad, raw_scene};
use irsig_tracer::{Camera, TraceOptions, Tracer, Vacuum};

#[test]
fn only_edge_pixels_are_refined_and_they_match_the_full_rendering() {
    // A hot square on a cold ground, seen straight down: its outline crosses pixels at
    // every angle.
    let ground = ground_quad([-50.0, -50.0], [50.0, 50.0], 0.0);
    let plate = ground_quad([-7.3, -4.1], [6.2, 8.9], 0.5);
    let scene = raw_scene(&[(&ground, 1, 280.0), (&plate, 2, 340.0)]);
    let materials = grey_materials(&[(1, 0.95, 0.0), (2, 0.95, 0.0)]);
    let tracer = Tracer::new(&scene, &materials, TotalRadiance, Vacuum::default()).unwrap();
    let camera = Camera::from_view(&View::Legacy {
        position_m: [0.3, -0.2, 100.0],
        pixels: [24, 20],
        omega_phi_kappa_deg: [0.0, 0.0, 7.0],
        fov_deg: [14.0, 12.0],
        gain_dc_per_k: None,
    })
    .unwrap();
    let render = |supersampling, adaptive_threshold_k| {
        tracer
            .render(
                &camera,
                &TraceOptions {
                    supersampling,
                    adaptive_threshold_k,
                    seed: 7,
                    ..TraceOptions::default()
                },
                &|_| {},
            )
            .unwrap()
    };
    let centre = render(1, None);
    let full = render(4, None);
    let threshold_k = 0.5;
    let adaptive = render(4, Some(threshold_k));
    let t = |l: f64| TotalRadiance.temperature(l);
    let (w, h) = (24_usize, 20_usize);
    let (mut refined, mut worst_kept) = (0, 0.0_f64);
    for i in 0..w * h {
        let (col, row) = ((i % w) as isize, (i / w) as isize);
        // The rule: some centre ray among the 8 neighbours differs by more than the
        // threshold.
        let edge = (-1..=1)
            .flat_map(|dr| (-1..=1).map(move |dc| (row + dr, col + dc)))
            .any(|(r, c)| {
                (0..h as isize).contains(&r)
                    && (0..w as isize).contains(&c)
                    && (t(centre.radiance_w_m2_sr[r as usize * w + c as usize])
                        - t(centre.radiance_w_m2_sr[i]))
                    .abs()
                        > threshold_k
            });
        let a = adaptive.radiance_w_m2_sr[i];
        if edge {
            // Refined: exactly what the full rendering gives the pixel.
            assert_eq!(a.to_bits(), full.radiance_w_m2_sr[i].to_bits(), "pixel {i}");
            refined += 1;
        } else {
            assert_eq!(
                a.to_bits(),
                centre.radiance_w_m2_sr[i].to_bits(),
                "pixel {i}"
            );
            worst_kept = worst_kept.max((t(full.radiance_w_m2_sr[i]) - t(a)).abs());
        }
    }
    // The outline crosses about 2 × (24 + 20) pixels, each flagging its neighbours too; the
    // rest keep their centre ray, and in this scene the full rendering moves none of them.
    assert!((60..=300).contains(&refined), "{refined} refined");
    assert!(worst_kept < 1e-9, "{worst_kept} K");
    // The truth layers are the centre rays', as in every rendering.
    assert_eq!(adaptive.truth, centre.truth);
    // The same at any thread count.
    let one = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let again = one.install(|| render(4, Some(threshold_k)));
    assert_eq!(again.radiance_w_m2_sr, adaptive.radiance_w_m2_sr);
}
