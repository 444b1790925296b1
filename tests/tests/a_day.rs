//! The day pipeline (`pipelines/a-day.ron`) end to end, by the README's recipe as written
//! in a copy of it whose camera is 64 × 48 pixels (the 512 × 384 day is the README's
//! picture, made by `scripts/docs/a-day-picture.sh`): one `irsig-therm` for the whole day,
//! one LOWTRAN7 build for every sun of the day, 24 hourly frames traced in 8-14 and 3-5 µm
//! by each hour's sun and sensed, each band's contact sheet and animation.
//!
//! - The open grass and the open clay track are warmest within three hours of solar noon
//!   and coolest in the hours before dawn, as the sun heats them and the night sky cools
//!   them.
//! - The panel, held at 325 K, keeps one apparent temperature all day while the ground
//!   swings around it.
//! - The sun lights the lit hours and no other: its share of the open grass is a few per
//!   cent in 3-5 µm and under 0.1 % in 8-14 µm, as hand estimates of the reflected beam
//!   say.
//! - Each band's contact sheet is four rows of six 64 × 48 tiles, and its animation holds
//!   the 24 frames' count images, in time order, exactly.
//!
//! LOWTRAN7 is `$IRSIG_LOWTRAN`, else `lowtran7` on PATH: the test fails when it is
//! missing, saying so; it never skips.

use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use irsig_raster::read_exr;
use irsig_tests::{lowtran, recipe, repo_root};

/// The frames' local hours (MDT) and their UTC stamps (MDT + 6 h) on 7 August 2001.
fn frames() -> Vec<(u32, String)> {
    (0..24)
        .map(|h| {
            let utc = h + 6;
            let stamp = if utc < 24 {
                format!("20010807T{utc:02}0000Z")
            } else {
                format!("20010808T{:02}0000Z", utc - 24)
            };
            (h, stamp)
        })
        .collect()
}

/// The camera's size in the test, pixels.
const W: usize = 64;
const H: usize = 48;
/// The material ids of the ground and the panel (pipelines/thermal/materials.ron).
const GRASS: u16 = 6;
const TRACK: u16 = 100;
const PANEL_PAINT: u16 = 19;

/// The pipeline, copied with what it reads into a temporary directory with a 64 × 48
/// camera of the same pose, and run once.
fn day() -> &'static tempfile::TempDir {
    static RUN: OnceLock<tempfile::TempDir> = OnceLock::new();
    RUN.get_or_init(|| {
        let dir = tempfile::tempdir().unwrap();
        let root = repo_root();
        let copy = |from: &Path, to: &Path| {
            std::fs::create_dir_all(to.parent().unwrap()).unwrap();
            std::fs::copy(from, to).unwrap();
        };
        for sub in ["thermal", "quickstart"] {
            for entry in std::fs::read_dir(root.join("pipelines").join(sub)).unwrap() {
                let path = entry.unwrap().path();
                if path.is_file() {
                    let name = path.file_name().unwrap();
                    copy(&path, &dir.path().join("pipelines").join(sub).join(name));
                }
            }
        }
        for file in ["pipelines/a-day.ron", "formats/samples/golden-tmy3-aug.epw"] {
            copy(&root.join(file), &dir.path().join(file));
        }
        let view = std::fs::read_to_string(root.join("pipelines/thermal/view.ron")).unwrap();
        assert!(view.contains("pixels: (512, 384)"), "{view}");
        std::fs::write(
            dir.path().join("pipelines/thermal/view.ron"),
            view.replace("pixels: (512, 384)", &format!("pixels: ({W}, {H})")),
        )
        .unwrap();
        // The README's recipe, as written.
        let block = recipe::block(
            "README.md",
            "irsig-run pipelines/a-day.ron      # everything in out/a-day/, named by UTC time",
        );
        recipe::run_ok(
            &block,
            dir.path(),
            &[("IRSIG_LOWTRAN", lowtran().as_os_str())],
        );
        dir
    })
}

fn out(name: &str) -> PathBuf {
    day().path().join("out/a-day").join(name)
}

fn layer(path: &Path, name: &str) -> Vec<f32> {
    let raster = read_exr(&std::fs::read(path).unwrap()).unwrap();
    assert_eq!((raster.width, raster.height), (W, H), "{}", path.display());
    raster.layer(name).unwrap().data.clone()
}

/// The pixels whose whole footprint is of `material`: a pixel and its eight neighbours all
/// of it, so that the 5 × 5 IFOV mixes in little else.
fn inside(material: u16) -> Vec<usize> {
    let (_, first) = &frames()[0];
    // The truth layer holds each pixel's material id as a float.
    let ids: Vec<u16> = layer(&out(&format!("{first}.lwir.truth.exr")), "material_primary")
        .iter()
        .map(|&id| id.round() as u16)
        .collect();
    let inside: Vec<usize> = (1..H - 1)
        .flat_map(|y| (1..W - 1).map(move |x| (x, y)))
        .filter(|&(x, y)| {
            (y - 1..=y + 1).all(|v| (x - 1..=x + 1).all(|u| ids[v * W + u] == material))
        })
        .map(|(x, y)| y * W + x)
        .collect();
    assert!(
        inside.len() >= 10,
        "{} pixels of material {material}",
        inside.len()
    );
    inside
}

/// Per frame, the median 8-14 µm apparent temperature (K) of [`inside`] `material`.
fn median_apparent_k(material: u16) -> Vec<f64> {
    let inside = inside(material);
    frames()
        .iter()
        .map(|(_, stamp)| {
            let t = layer(
                &out(&format!("{stamp}.lwir.temperature.exr")),
                "apparent_temperature",
            );
            let mut v: Vec<f64> = inside.iter().map(|&i| f64::from(t[i])).collect();
            v.sort_by(f64::total_cmp);
            v[v.len() / 2]
        })
        .collect()
}

/// The local hour of the warmest and the coolest frame.
fn extremes(t: &[f64]) -> (u32, u32) {
    let by = |better: fn(f64, f64) -> bool| {
        (0..t.len()).fold(0, |b, i| if better(t[i], t[b]) { i } else { b }) as u32
    };
    (by(|a, b| a > b), by(|a, b| a < b))
}

/// By hand: on 7 August the sun's declination is 16.3°, so at 39.74° N its centre rises
/// at an hour angle of acos(−tan 39.74° tan 16.3°) = 104.1° (6 h 56 min) before its noon,
/// which at 105.18° W with the equation of time at −5.7 min is 12:06 MST, 13:06 MDT:
/// sunrise at 06:10 MDT (06:06 with refraction and the disc's upper edge), sunset at
/// 20:03 (20:07). Within three hours of noon (10:00-16:00 MDT) the sun stands above
/// asin(sin φ sin δ + cos φ cos δ cos 45°) = 44° and brings most of the day's sunlight:
/// open ground, heated by it, is warmest then (a clear, still day puts the maximum an
/// hour or two after noon, Oke 1987 §2.2; wind that rises through the day, as this
/// record's does from 2 to 7 m/s, cools the afternoon and moves it earlier). It cools
/// all night by radiation to the sky and is coolest just before the sun is back,
/// 03:00-06:00 MDT. Golden's dry August day swings such ground by well over 10 K.
#[test]
fn open_ground_is_warmest_near_noon_and_coolest_before_dawn() {
    for (name, material) in [("grass", GRASS), ("track", TRACK)] {
        let t = median_apparent_k(material);
        let (warmest, coolest) = extremes(&t);
        let swing = t[warmest as usize] - t[coolest as usize];
        assert!(
            (10..=16).contains(&warmest),
            "the open {name} is warmest at {warmest}:00 MDT: {t:.1?}"
        );
        assert!(
            (3..=6).contains(&coolest),
            "the open {name} is coolest at {coolest}:00 MDT: {t:.1?}"
        );
        assert!(
            swing > 10.0,
            "the open {name} swings by {swing:.1} K: {t:.1?}"
        );
    }
}

/// The panel is held at 325 K: its apparent temperature, ε = 0.95 of it and 5 % reflected
/// surroundings, moves only by what the reflected sky and ground do, 0.05 × their swing,
/// while the open grass in front of it swings by more than ten times as much.
#[test]
fn the_held_panel_stays_put_while_the_ground_swings() {
    let panel = median_apparent_k(PANEL_PAINT);
    let grass = median_apparent_k(GRASS);
    let range = |t: &[f64]| {
        t.iter().fold(f64::MIN, |a, &b| a.max(b)) - t.iter().fold(f64::MAX, |a, &b| a.min(b))
    };
    let (p, g) = (range(&panel), range(&grass));
    assert!(
        p < 2.0 && p * 10.0 < g,
        "panel {p:.2} K, grass {g:.2} K: {panel:.1?}"
    );
    // Below the 325 K it is held at: a grey body reflecting a colder world.
    assert!(panel.iter().all(|&t| t < 325.0 && t > 315.0), "{panel:.1?}");
}

/// The sun's position by hand (the declination and hour angle above): above the horizon
/// from 06:10 to 20:03 MDT, so the frames of 07:00-20:00 are lit and those of 00:00-05:00
/// and 21:00-23:00 are not (06:00 is within minutes of sunrise, left out either way).
fn lit(hour: u32) -> Option<bool> {
    match hour {
        7..=20 => Some(true),
        0..=5 | 21..=23 => Some(false),
        _ => None,
    }
}

/// The reflected sun, by hand, for the open grass at 10:00-16:00 MDT (sun 26-46° from the
/// zenith). Above the air the sun's disc (5772 K, 6.8e-5 sr) gives about 17 W m⁻² in
/// 3-5 µm (Planck: 9 W m⁻² µm⁻¹ at 4 µm) and 1.5 W m⁻² in 8-14 µm. Through a summer
/// path of τ 0.4-0.8 onto level ground at cos θ 0.69-0.9 that is 4.7-12 W m⁻² in
/// 3-5 µm; grass of ε 0.95 reflects 0.05 of it over π sr, 0.08-0.21 W m⁻² sr⁻¹, against
/// the 1.8-2.1 W m⁻² sr⁻¹ it emits at 300-305 K: a share of 4-10 %. In 8-14 µm the
/// reflected 0.005-0.017 W m⁻² sr⁻¹ stands against some 40 emitted: 0.01-0.04 %. The
/// test holds the 3-5 µm share within a factor two of that range (2-20 %: the grass is
/// seen obliquely and its ε and the path's τ vary over the band), the 8-14 µm one under
/// 0.1 %, and the first at least 30 times the second, pixel by pixel of the median.
#[test]
fn the_sun_lights_the_lit_hours_a_few_per_cent_in_3_5_um_and_little_in_8_14_um() {
    let grass = inside(GRASS);
    for (hour, stamp) in frames() {
        let Some(is_lit) = lit(hour) else { continue };
        let mut medians = Vec::new();
        for band in ["lwir", "mwir"] {
            let path = out(&format!("{stamp}.{band}.truth.exr"));
            let raster = read_exr(&std::fs::read(&path).unwrap()).unwrap();
            let share = raster.layer("sun_share");
            assert_eq!(
                share.is_some(),
                is_lit,
                "{hour}:00 MDT {band}: the sun's layers are there only when it is up"
            );
            let Some(share) = share else { continue };
            let mut v: Vec<f64> = grass.iter().map(|&i| f64::from(share.data[i])).collect();
            v.sort_by(f64::total_cmp);
            medians.push(v[v.len() / 2]);
        }
        let [lwir, mwir] = medians[..] else { continue };
        assert!(lwir < 1e-3, "{hour}:00 MDT 8-14 um: the sun's share {lwir}");
        assert!(
            mwir > 30.0 * lwir,
            "{hour}:00 MDT: the sun's share {mwir} in 3-5 um, {lwir} in 8-14 um"
        );
        if (10..=16).contains(&hour) {
            assert!(
                (0.02..=0.2).contains(&mwir),
                "{hour}:00 MDT 3-5 um: the sun's share of the grass {mwir}"
            );
        }
    }
}

#[test]
fn each_contact_sheet_holds_the_24_frames_in_four_rows_of_six() {
    for band in ["lwir", "mwir"] {
        let sheet = image::open(out(&format!("{band}-contact-sheet.png")))
            .unwrap()
            .to_luma8();
        // Six columns of 64-pixel tiles and four rows of 48, a 4-pixel gap around each.
        assert_eq!(
            (sheet.width(), sheet.height()),
            ((6 * W + 7 * 4) as u32, (4 * H + 5 * 4) as u32)
        );
        let suffix = format!(".{band}.dc.png");
        let count_images = std::fs::read_dir(out(""))
            .unwrap()
            .filter(|e| {
                e.as_ref()
                    .unwrap()
                    .file_name()
                    .to_string_lossy()
                    .ends_with(&suffix)
            })
            .count();
        assert_eq!(count_images, 24);
        // Tile 24 (row 4, column 6), its bottom-right pixel, clear of its label, is frame
        // 24's.
        let (_, last) = &frames()[23];
        let dc = image::open(out(&format!("{last}{suffix}")))
            .unwrap()
            .to_luma8();
        let (x0, y0) = (4 + 5 * (W + 4), 4 + 3 * (H + 4));
        assert_eq!(
            sheet.get_pixel((x0 + W - 1) as u32, (y0 + H - 1) as u32),
            dc.get_pixel((W - 1) as u32, (H - 1) as u32)
        );
    }
}

/// Each animation: 24 frames, a quarter of a second each, frame k the k-th hour's count
/// image exactly (8-bit grey, so GIF's palette holds every level).
#[test]
fn each_animation_is_the_24_count_images_in_time_order() {
    use image::AnimationDecoder;
    for band in ["lwir", "mwir"] {
        let gif = out(&format!("{band}-day.gif"));
        let file = std::io::BufReader::new(std::fs::File::open(gif).unwrap());
        let gif = image::codecs::gif::GifDecoder::new(file)
            .unwrap()
            .into_frames()
            .collect_frames()
            .unwrap();
        assert_eq!(gif.len(), 24);
        for (frame, (hour, stamp)) in gif.iter().zip(frames()) {
            assert_eq!(frame.delay().numer_denom_ms(), (250, 1));
            let dc = image::open(out(&format!("{stamp}.{band}.dc.png")))
                .unwrap()
                .to_luma8();
            assert_eq!(frame.buffer().dimensions(), dc.dimensions());
            for (x, y, p) in frame.buffer().enumerate_pixels() {
                let v = dc.get_pixel(x, y).0[0];
                assert_eq!(
                    p.0,
                    [v, v, v, 255],
                    "{band} {hour}:00 MDT, pixel ({x}, {y})"
                );
            }
        }
    }
}
