//! The two switchable models' trades against exact answers: the sky-view factor's error
//! against its ray count (an exact configuration factor from the literature), and the
//! supersampling's edge-pixel error against N (an exact pixel-area coverage). The figures
//! themselves are printed by `cargo run --release -p irsig-tracer --example trade_tables`
//! and recorded in docs/accuracy.md; these tests hold the error bounds theory gives.

use irsig_tracer::testing::{
    EdgeExperiment, PitExperiment, pit_centre_sky_view_factor, pixel_fraction_left_of_line,
};

#[test]
fn the_exact_references_agree_with_hand_values() {
    // Howell B-3 with a = b = c: 4 · (1/√2) · atan(1/√2) / π = 4 · 0.707107 · 0.615480 / π
    // = 1.740836 / π = 0.554126.
    let f = pit_centre_sky_view_factor(1.0, 1.0);
    assert!((f - 0.554_126).abs() < 1e-6, "{f}");
    // An infinitely wide pit sees the whole sky; an infinitely deep one none of it.
    assert!((pit_centre_sky_view_factor(1e9, 1.0) - 1.0).abs() < 1e-8);
    assert!(pit_centre_sky_view_factor(1.0, 1e9) < 1e-8);
    // Coverage: a vertical line through the middle halves the pixel; a 45° line through
    // its corners too; one entering a corner at slope 1/2 cuts a triangle of 1/4.
    assert!((pixel_fraction_left_of_line(3.5, 0.0, 3.0, 7.0) - 0.5).abs() < 1e-15);
    assert!((pixel_fraction_left_of_line(0.0, 1.0, 3.0, 3.0) - 0.5).abs() < 1e-15);
    // x = 3 + (y − 3)/2 in pixel (3, 3): left of it is the triangle (3,3) (3,4) (3.5,4).
    assert!((pixel_fraction_left_of_line(1.5, 0.5, 3.0, 3.0) - 0.25).abs() < 1e-15);
    assert!(pixel_fraction_left_of_line(1.0, 0.0, 3.0, 3.0).abs() < 1e-15);
    assert!((pixel_fraction_left_of_line(9.0, 0.0, 3.0, 3.0) - 1.0).abs() < 1e-15);
}

#[test]
fn sky_view_factor_error_falls_with_rays_and_stays_unbiased() {
    let pit = PitExperiment::new();
    let exact = pit.exact_sky_view_factor;
    for rays in [4, 16, 64, 256] {
        let est = pit.estimates(rays, 11);
        assert_eq!(est.len(), 256);
        let errors: Vec<f64> = est.iter().map(|(f, _)| f - exact).collect();
        let n = errors.len() as f64;
        let rms = (errors.iter().map(|e| e * e).sum::<f64>() / n).sqrt();
        let mean = errors.iter().sum::<f64>() / n;
        // Stratified sampling never does worse than independent rays, whose standard
        // deviation is the binomial √(F(1 − F)/N).
        let independent = (exact * (1.0 - exact) / f64::from(rays)).sqrt();
        assert!(
            rms < independent,
            "N = {rays}: RMS {rms} ≥ binomial {independent}"
        );
        // Unbiased: the mean of 256 estimates lies within 4 standard errors of F.
        assert!(
            mean.abs() < 4.0 * rms / n.sqrt() + 1e-12,
            "N = {rays}: mean error {mean}, RMS {rms}"
        );
    }
}

#[test]
fn supersampled_edge_pixels_converge_to_their_exact_coverage() {
    let edge = EdgeExperiment::new();
    let [hot, cold] = EdgeExperiment::TEMPERATURES_K.map(|t| {
        use irsig_radiometry::BandModel;
        irsig_radiometry::TotalRadiance.radiance(t)
    });
    let contrast = hot - cold;
    // Pixels the edge does not cross are exact at any N (the image-to-ground map is right).
    let frame = edge
        .tracer
        .render(
            &edge.camera,
            &irsig_tracer::TraceOptions::default(),
            &|_| {},
        )
        .unwrap();
    for (i, &l) in frame.radiance_w_m2_sr.iter().enumerate() {
        let (col, row) = (i as u32 % 24, i as u32 / 24);
        let f = pixel_fraction_left_of_line(
            EdgeExperiment::X0,
            EdgeExperiment::SLOPE,
            col.into(),
            row.into(),
        );
        if f <= 0.0 || f >= 1.0 {
            let exact = EdgeExperiment::exact_radiance_w_m2_sr(col, row);
            assert!((l - exact).abs() < 1e-9 * exact, "pixel ({col}, {row})");
        }
    }
    for n in [2, 4, 8, 16] {
        let px = edge.edge_pixels(n, 3);
        assert!(px.len() > 64, "{} edge pixels", px.len());
        let errors: Vec<f64> = px.iter().map(|(e, l)| (l - e) / contrast).collect();
        let nf = f64::from(n);
        // The edge (|slope| ≤ 1) crosses at most 2 strata per stratum row, 2N in all,
        // and each stratum errs by at most its area 1/N²: |error| ≤ 2/N, always.
        let max = errors.iter().fold(0.0_f64, |m, e| m.max(e.abs()));
        assert!(max <= 2.0 / nf, "N = {n}: max error {max}");
        // Each crossed stratum is a Bernoulli trial of variance ≤ 1/(4N⁴): the expected
        // squared error is ≤ 2N/(4N⁴) = 1/(2N³). Independent (unstratified) rays would
        // give about f(1 − f)/N², far above it for N ≥ 4.
        let rms = (errors.iter().map(|e| e * e).sum::<f64>() / errors.len() as f64).sqrt();
        assert!(
            rms <= (0.5 / nf.powi(3)).sqrt(),
            "N = {n}: RMS {rms} over the stratified bound"
        );
    }
}
