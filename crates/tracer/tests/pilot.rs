//! The tolerance pilot on a scene whose every effect is known: a diffuse ground beside a
//! hot wall under a uniform sky. Near the wall the sky-view factor matters (F ≈ 0.8 there:
//! the 400 K wall instead of a 20 W m⁻² sr⁻¹ sky moves the ground by about 2 K through its
//! 5 % reflectance); nothing is specular, so bounces cannot matter; the wall's outline is
//! a 100 K edge.

use irsig_atmosphere::{ModelKind, SubBandCount};
use irsig_model::View;
use irsig_model::decision::SwitchableModel;
use irsig_radiometry::TotalRadiance;
use irsig_tracer::pilot::{BandChoice, PilotSpace, Supersample};
use irsig_tracer::testing::{box_mesh, grey_materials, ground_quad, raw_scene};
use irsig_tracer::{Camera, PathTermsMode, SubBand, Tracer, Vacuum};

fn tracer() -> Tracer<TotalRadiance, Vacuum> {
    let ground = ground_quad([-30.0, -30.0], [30.0, 30.0], 0.0);
    let wall = box_mesh([-10.0, 2.0, 0.0], [10.0, 3.0, 8.0]);
    let scene = raw_scene(&[(&ground, 1, 300.0), (&wall, 2, 400.0)]);
    let materials = grey_materials(&[(1, 0.95, 0.0), (2, 0.9, 0.0)]);
    Tracer::new(
        &scene,
        &materials,
        TotalRadiance,
        Vacuum {
            sky_radiance_w_m2_sr: 20.0,
        },
    )
    .unwrap()
}

fn camera() -> Camera {
    Camera::from_view(&View::LookAt {
        position_m: [0.0, -12.0, 15.0],
        target_m: [0.0, 0.0, 0.0],
        up: [0.0, 0.0, 1.0],
        pixels: [96, 72],
        fov_deg: [50.0, 38.0],
        gain_dc_per_k: None,
    })
    .unwrap()
}

fn space(tracer: &Tracer<TotalRadiance, Vacuum>) -> PilotSpace<Vacuum> {
    let set = tracer
        .band_set(vec![SubBand {
            band: TotalRadiance,
            atmosphere: Vacuum {
                sky_radiance_w_m2_sr: 20.0,
            },
            emissivity: None,
        }])
        .unwrap();
    PilotSpace {
        bands: vec![BandChoice {
            atmosphere: ModelKind::None,
            sub_bands: SubBandCount::BAND,
            set,
            path_call_ns: 5.0,
            sky_ns: 0.0,
        }],
        atmospheres: vec![ModelKind::None],
        sub_bands: vec![SubBandCount::BAND],
        bounces: vec![2, 1, 0],
        sky_view_rays: vec![64, 0],
        supersampling: vec![
            Supersample::Every(4),
            Supersample::Adaptive(4),
            Supersample::Every(1),
        ],
        path_terms: vec![PathTermsMode::Exact],
        reasons: Vec::new(),
        pinned: Vec::new(),
    }
}

#[test]
fn a_loose_tolerance_takes_the_cheapest_of_everything() {
    let t = tracer();
    let piloted = t.pilot(&camera(), &space(&t), 100.0, 99.0, 256, 1).unwrap();
    // The settings, typed, are those the decision records.
    let c = piloted.chosen;
    assert_eq!((c.bounces, c.sky_view_rays), (0, 0));
    assert_eq!(c.supersampling, Supersample::Every(1));
    assert_eq!(
        (c.atmosphere, c.sub_bands),
        (ModelKind::None, SubBandCount::BAND)
    );
    let d = piloted.decision;
    let setting = |m| d.choice(m).unwrap().setting.clone();
    assert_eq!(setting(SwitchableModel::Bounces), "0");
    assert_eq!(setting(SwitchableModel::SkyView), "0");
    assert_eq!(setting(SwitchableModel::Supersampling), "1");
    assert!(d.relative_cost < 0.2, "{d:?}");
    assert!(d.predicted.percentile_k <= 100.0);
    // Nothing is specular: cutting bounces costs nothing anywhere.
    let b = d.choice(SwitchableModel::Bounces).unwrap();
    assert!(b.error.max_k < 1e-9, "{b:?}");
}

#[test]
fn near_the_hot_wall_the_sky_view_factor_is_switched_on() {
    let t = tracer();
    // A sample dense enough (1 pixel in 7) that the wall's outline, 2 % of the image,
    // weighs in the 99th percentile.
    let d = t
        .pilot(&camera(), &space(&t), 0.5, 99.0, 1024, 1)
        .unwrap()
        .decision;
    let sky = d.choice(SwitchableModel::SkyView).unwrap();
    assert_eq!(sky.setting, "64", "{d:#?}");
    // What F = 1 would cost: the ground beside the wall reads colder, by up to about 5 K
    // at its foot: (1 − F)·(L_wall − L_sky)·(1 − ε) = 0.5 × 400 × 0.05 W m⁻² sr⁻¹ over
    // dL/dT = 4σT³/π = 1.95 W m⁻² sr⁻¹ K⁻¹ at 300 K.
    let off = t
        .pilot(&camera(), &space(&t), 100.0, 99.0, 256, 1)
        .unwrap()
        .decision;
    let off = off.choice(SwitchableModel::SkyView).unwrap();
    assert!(off.error.max_k > 2.0 && off.error.max_k < 6.0, "{off:?}");
    // The chosen combination meets the tolerance at the percentile, by its own bound.
    assert!(d.predicted.percentile_k <= 0.5, "{d:#?}");
    // The wall's outline is under 1 % of the pixels: at the 99th percentile one ray per
    // pixel will do, but not for every pixel, where the centre ray misses by up to 17 K.
    let centre = d.choice(SwitchableModel::Supersampling).unwrap();
    assert_eq!(centre.setting, "1", "{centre:?}");
    let every = t
        .pilot(&camera(), &space(&t), 0.5, 100.0, 1024, 1)
        .unwrap()
        .decision;
    let ss = every.choice(SwitchableModel::Supersampling).unwrap();
    assert_ne!(ss.setting, "1", "{every:#?}");
    assert!(every.predicted.max_k <= 0.5, "{every:#?}");
}

#[test]
fn a_tiny_tolerance_keeps_the_most_accurate_settings_of_the_models_that_matter() {
    let t = tracer();
    let d = t
        .pilot(&camera(), &space(&t), 1e-6, 99.0, 256, 1)
        .unwrap()
        .decision;
    let setting = |m| d.choice(m).unwrap().setting.clone();
    assert_eq!(setting(SwitchableModel::SkyView), "64", "{d:#?}");
    // Bounces change nothing here: the cheapest, whatever the tolerance.
    assert_eq!(setting(SwitchableModel::Bounces), "0", "{d:#?}");
    assert!(d.predicted.percentile_k <= 1e-6);
    // Bad tolerances and percentiles are refused.
    assert!(t.pilot(&camera(), &space(&t), 0.0, 99.0, 64, 1).is_err());
    assert!(t.pilot(&camera(), &space(&t), -0.1, 99.0, 64, 1).is_err());
    assert!(t.pilot(&camera(), &space(&t), 0.1, 0.0, 64, 1).is_err());
    assert!(t.pilot(&camera(), &space(&t), 0.1, 101.0, 64, 1).is_err());
}

#[test]
fn a_model_that_cannot_matter_in_the_view_says_so() {
    // Ground alone: no facet sees another, so every sky-view ray escapes and F = 1 is
    // exact; nothing is specular, so every bounce count gives the same pixels.
    let ground = ground_quad([-30.0, -30.0], [30.0, 30.0], 0.0);
    let scene = raw_scene(&[(&ground, 1, 300.0)]);
    let materials = grey_materials(&[(1, 0.95, 0.0)]);
    let t = Tracer::new(
        &scene,
        &materials,
        TotalRadiance,
        Vacuum {
            sky_radiance_w_m2_sr: 20.0,
        },
    )
    .unwrap();
    let d = t
        .pilot(&camera(), &space(&t), 1e-6, 99.0, 256, 1)
        .unwrap()
        .decision;
    let sky = d.choice(SwitchableModel::SkyView).unwrap();
    assert_eq!(sky.setting, "0", "{d:#?}");
    assert!(sky.reason.contains("met no facet"), "{sky:?}");
    let bounces = d.choice(SwitchableModel::Bounces).unwrap();
    assert_eq!(bounces.setting, "0", "{d:#?}");
    assert!(bounces.reason.contains("same temperatures"), "{bounces:?}");
    // Beside the wall, the sky-view factor matters and says nothing of the kind.
    let t = tracer();
    let d = t
        .pilot(&camera(), &space(&t), 1e-6, 99.0, 256, 1)
        .unwrap()
        .decision;
    let sky = d.choice(SwitchableModel::SkyView).unwrap();
    assert!(!sky.reason.contains("met no facet"), "{sky:?}");
}
