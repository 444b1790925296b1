//! `irsig-sensor` end to end: a radiance EXR through blur, reduction, noise and
//! quantisation, from files and in a pipe; every side output; bad input and bad usage
//! leave no output behind; counts that clip are counted on stderr.

use std::path::Path;

use irsig_raster::{Raster, exr_bytes, read_exr};
use irsig_tests::bin;
use predicates::prelude::*;

const W: usize = 24;
const H: usize = 16;

/// A 24 × 16 radiance image: 40 W m^-2 sr^-1 on the left half, 60 on the right, with
/// truth layers (material ids and a range with NaN where "nothing was hit").
fn scene() -> Raster {
    let mut r = Raster::new(W, H);
    let radiance: Vec<f32> = (0..W * H)
        .map(|i| if i % W < W / 2 { 40.0 } else { 60.0 })
        .collect();
    let material: Vec<f32> = (0..W * H)
        .map(|i| if i % W < 13 { 1.0 } else { 2.0 })
        .collect();
    let range: Vec<f32> = (0..W * H)
        .map(|i| {
            if i / W < 2 {
                f32::NAN
            } else {
                100.0 + (i / W) as f32
            }
        })
        .collect();
    r.push_layer("radiance", "W m^-2 sr^-1", radiance).unwrap();
    r.push_layer("material_primary", "", material).unwrap();
    r.push_layer("range", "m", range).unwrap();
    r
}

fn write_scene(dir: &Path) -> std::path::PathBuf {
    let p = dir.join("radiance.exr");
    std::fs::write(&p, exr_bytes(&scene()).unwrap()).unwrap();
    p
}

#[test]
fn box_blur_matches_the_thesis_by_hand_and_every_output_is_written() {
    let dir = tempfile::tempdir().unwrap();
    let input = write_scene(dir.path());
    let out = dir.path().join("sensor.exr");
    let (dc, lut, t, grey, colour) = (
        dir.path().join("dc.png"),
        dir.path().join("dc.lut"),
        dir.path().join("t.exr"),
        dir.path().join("grey.png"),
        dir.path().join("colour.png"),
    );
    bin("irsig-sensor")
        .arg(&input)
        .arg("-o")
        .arg(&out)
        .args(["--mtf", "box:5x5", "--dc-per-kelvin", "4", "--dc-png"])
        .arg(&dc)
        .arg("--lut")
        .arg(&lut)
        .arg("--temperature-exr")
        .arg(&t)
        .arg("--preview")
        .arg(&grey)
        .arg("--colour-preview")
        .arg(&colour)
        .assert()
        .success();
    let r = read_exr(&std::fs::read(&out).unwrap()).unwrap();
    let radiance = &r.layer("radiance").unwrap().data;
    // Column 11 sees columns 9..=13 through the 5-wide box: three at 40, two at 60.
    let by_hand = (3.0 * 40.0 + 2.0 * 60.0) / 5.0;
    assert!((radiance[5 * W + 11] - by_hand).abs() < 1e-4);
    // Far from the step nothing changes; reflect edges keep the borders level.
    assert!((radiance[5 * W] - 40.0).abs() < 1e-4);
    assert!((radiance[5 * W + W - 1] - 60.0).abs() < 1e-4);
    // Truth layers pass through unchanged (NaN included) and keep their units.
    let range = r.layer("range").unwrap();
    assert_eq!(range.unit, "m");
    assert!(range.data[0].is_nan() && (range.data[5 * W] - 105.0).abs() < 1e-6);
    assert_eq!(
        r.layer("material_primary").unwrap().data,
        scene().layer("material_primary").unwrap().data
    );
    // The LUT has a header, its band (none recorded here: the default's) and one line per
    // 8-bit count.
    let lut_text = std::fs::read_to_string(&lut).unwrap();
    assert_eq!(lut_text.lines().count(), 258);
    assert!(lut_text.starts_with("# dc radiance_w_m2_sr temperature_k temperature_c"));
    assert_eq!(lut_text.lines().nth(1), Some("# band: 8-14 um, flat"));
    let t_exr = read_exr(&std::fs::read(&t).unwrap()).unwrap();
    let temperature = &t_exr.layer("apparent_temperature").unwrap().data;
    // 40 and 60 W m^-2 sr^-1 in 8-14 um are blackbodies of 280.451 K and 305.889 K
    // (Planck's law integrated by Simpson's rule on 20,000 intervals and inverted by
    // bisection, CODATA 2018, independently of irsig). The pixels hold those radiances to
    // 1e-4 W m^-2 sr^-1 (above), 1e-4 K.
    assert!(
        (f64::from(temperature[5 * W]) - 280.451).abs() < 1e-3,
        "{}",
        temperature[5 * W]
    );
    assert!(
        (f64::from(temperature[5 * W + W - 1]) - 305.889).abs() < 1e-3,
        "{}",
        temperature[5 * W + W - 1]
    );
    for png in [&dc, &grey, &colour] {
        let bytes = std::fs::read(png).unwrap();
        assert_eq!(&bytes[1..4], b"PNG", "{}", png.display());
    }
}

#[test]
fn pipe_gives_the_same_image_as_files() {
    let dir = tempfile::tempdir().unwrap();
    let input = write_scene(dir.path());
    let out = dir.path().join("sensor.exr");
    let args = [
        "--mtf",
        "gauss:hp=0.25",
        "--mtf",
        "jitter:0.3",
        "--nedt-k",
        "0.1",
    ];
    bin("irsig-sensor")
        .arg(&input)
        .arg("-o")
        .arg(&out)
        .args(args)
        .assert()
        .success();
    let piped = bin("irsig-sensor")
        .args(["-", "-o", "-"])
        .args(args)
        .write_stdin(std::fs::read(&input).unwrap())
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    assert_eq!(piped, std::fs::read(&out).unwrap());
}

#[test]
fn noise_is_reproducible_by_seed() {
    let dir = tempfile::tempdir().unwrap();
    let input = write_scene(dir.path());
    let run = |seed: &str| {
        bin("irsig-sensor")
            .arg(&input)
            .args(["--nedt-k", "0.05", "--seed", seed])
            .assert()
            .success()
            .get_output()
            .stdout
            .clone()
    };
    assert_eq!(run("3"), run("3"));
    assert_ne!(run("3"), run("4"));
}

#[test]
fn supersampled_input_is_reduced_consistently() {
    let dir = tempfile::tempdir().unwrap();
    let input = write_scene(dir.path());
    let out = bin("irsig-sensor")
        .arg(&input)
        .args(["--samples-per-pixel", "2"])
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    let r = read_exr(&out).unwrap();
    assert_eq!((r.width, r.height), (W / 2, H / 2));
    // Sensor column 6 integrates render columns 12 and 13: material 1 and 2 tie, the
    // smaller id wins; radiance is the mean, 60.
    let m = &r.layer("material_primary").unwrap().data;
    assert!((m[6] - 1.0).abs() < 1e-6 && (m[7] - 2.0).abs() < 1e-6);
    let l = &r.layer("radiance").unwrap().data;
    assert!((l[6] - 60.0).abs() < 1e-4 && (l[5] - 40.0).abs() < 1e-4);
    // Range: row 0 of the sensor covers render rows 0-1, all NaN.
    let range = &r.layer("range").unwrap().data;
    assert!(range[0].is_nan() && (range[W / 2] - 102.5).abs() < 1e-4);
}

#[test]
fn bad_input_names_the_problem_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    // No radiance layer.
    let mut r = Raster::new(4, 4);
    r.push_layer("range", "m", vec![1.0; 16]).unwrap();
    let no_radiance = dir.path().join("no_radiance.exr");
    std::fs::write(&no_radiance, exr_bytes(&r).unwrap()).unwrap();
    let out = dir.path().join("out.exr");
    let lut = dir.path().join("lut.txt");
    bin("irsig-sensor")
        .arg(&no_radiance)
        .arg("-o")
        .arg(&out)
        .args(["--dc-per-kelvin", "2", "--lut"])
        .arg(&lut)
        .assert()
        .code(1)
        .stderr(
            predicate::str::contains("no `radiance` layer").and(predicate::str::contains("range")),
        );
    assert!(!out.exists() && !lut.exists());

    // A NaN radiance is named by column and row.
    let mut r = Raster::new(4, 4);
    let mut data = vec![50.0; 16];
    data[2 * 4 + 3] = f32::NAN;
    r.push_layer("radiance", "W m^-2 sr^-1", data).unwrap();
    let nan = dir.path().join("nan.exr");
    std::fs::write(&nan, exr_bytes(&r).unwrap()).unwrap();
    bin("irsig-sensor")
        .arg(&nan)
        .arg("-o")
        .arg(&out)
        .assert()
        .code(1)
        .stderr(predicate::str::contains("x 3, y 2").and(predicate::str::contains("nan.exr")));
    assert!(!out.exists());

    // Not an EXR at all.
    let junk = dir.path().join("junk.exr");
    std::fs::write(&junk, b"not an image").unwrap();
    bin("irsig-sensor")
        .arg(&junk)
        .assert()
        .code(1)
        .stderr(predicate::str::contains("junk.exr"));

    // A size that does not divide by k.
    let odd = dir.path().join("odd.exr");
    let mut r = Raster::new(5, 4);
    r.push_layer("radiance", "W m^-2 sr^-1", vec![50.0; 20])
        .unwrap();
    std::fs::write(&odd, exr_bytes(&r).unwrap()).unwrap();
    bin("irsig-sensor")
        .arg(&odd)
        .args(["--samples-per-pixel", "2"])
        .assert()
        .code(1)
        .stderr(predicate::str::contains("multiples"));
}

#[test]
fn bad_usage_exits_2() {
    let dir = tempfile::tempdir().unwrap();
    let input = write_scene(dir.path());
    // Counts without a calibration.
    bin("irsig-sensor")
        .arg(&input)
        .arg("--dc-png")
        .arg(dir.path().join("dc.png"))
        .assert()
        .code(2)
        .stderr(predicate::str::contains("calibration"));
    // A malformed MTF.
    bin("irsig-sensor")
        .arg(&input)
        .args(["--mtf", "box:0x3"])
        .assert()
        .code(2)
        .stderr(predicate::str::contains("box width_px"));
    bin("irsig-sensor")
        .arg(&input)
        .args(["--band", "14-8"])
        .assert()
        .code(2);
}

/// Counts that clip are said on stderr, with how many at each end. A straight line of 10
/// counts per W m^-2 sr^-1 puts the scene's 40 and 60 W m^-2 sr^-1 at counts 10·40 + offset
/// and 10·60 + offset: with offset −300 at 100 and 300, so the 192 pixels of the right half
/// clip at 255; with offset −450 at −50 and 150, so the 192 of the left half clip at 0; with
/// a gain of 1 at 40 and 60, and nothing is said.
#[test]
fn saturated_counts_are_said_on_stderr() {
    let dir = tempfile::tempdir().unwrap();
    let input = write_scene(dir.path());
    let dc = dir.path().join("dc.png");
    let sense = |gain: &str, offset: &str| {
        let out = bin("irsig-sensor")
            .arg(&input)
            .arg("-o")
            .arg(dir.path().join("sensor.exr"))
            .args(["--gain-dc-per-radiance", gain])
            .arg(format!("--offset-dc={offset}"))
            .arg("--dc-png")
            .arg(&dc)
            .output()
            .unwrap();
        assert!(out.status.success(), "{out:?}");
        let counts = image::open(&dc).unwrap().into_luma8().into_raw();
        let at = |c: u8| counts.iter().filter(|&&x| x == c).count();
        (String::from_utf8(out.stderr).unwrap(), at(0), at(255))
    };
    let (said, zero, full) = sense("10", "-300");
    assert_eq!((zero, full), (0, W * H / 2));
    assert!(
        said.contains("192 pixel(s) saturate at count 255 and 0 at count 0 of 384"),
        "{said}"
    );
    let (said, zero, full) = sense("10", "-450");
    assert_eq!((zero, full), (W * H / 2, 0));
    assert!(
        said.contains("0 pixel(s) saturate at count 255 and 192 at count 0 of 384"),
        "{said}"
    );
    let (said, zero, full) = sense("1", "0");
    assert_eq!((zero, full), (0, 0));
    assert!(!said.contains("saturate"), "{said}");
}

/// A 6 × 4 colour PNG of four flat quadrant colours that depend on `k`, and the colour
/// of its pixel (x, y).
fn quadrants(k: u8) -> impl Fn(u32, u32) -> [u8; 3] {
    move |x, y| match (x < 3, y < 2) {
        (true, true) => [k, 0, 0],
        (false, true) => [0, k, 0],
        (true, false) => [0, 0, k],
        (false, false) => [k, k, 255 - k],
    }
}

/// `--animation`: colour and grey PNG frames, in the order given, come back from the GIF
/// one for one (each frame has fewer than 256 colours, so GIF's palette holds them
/// exactly), every one shown for the delay asked.
#[test]
fn an_animation_decodes_to_its_input_frames_in_order() {
    use image::AnimationDecoder;
    let dir = tempfile::tempdir().unwrap();
    let mut names = Vec::new();
    for k in [40u8, 120, 200] {
        let colour = quadrants(k);
        let img = image::RgbImage::from_fn(6, 4, |x, y| image::Rgb(colour(x, y)));
        let name = dir.path().join(format!("c{k}.png"));
        img.save(&name).unwrap();
        names.push(name);
    }
    // A grey frame: a ramp over its 24 pixels.
    let grey = image::GrayImage::from_fn(6, 4, |x, y| image::Luma([(10 * (y * 6 + x)) as u8]));
    let grey_name = dir.path().join("grey.png");
    grey.save(&grey_name).unwrap();
    names.push(grey_name);

    let gif = dir.path().join("day.gif");
    bin("irsig-sensor")
        .arg("--animation")
        .arg(&gif)
        .args(["--frame-delay-ms", "120"])
        .args(&names)
        .assert()
        .success();
    let file = std::io::BufReader::new(std::fs::File::open(&gif).unwrap());
    let frames = image::codecs::gif::GifDecoder::new(file)
        .unwrap()
        .into_frames()
        .collect_frames()
        .unwrap();
    assert_eq!(frames.len(), 4);
    for (f, k) in frames.iter().zip([40u8, 120, 200]) {
        assert_eq!(f.delay().numer_denom_ms(), (120, 1));
        let colour = quadrants(k);
        for (x, y, p) in f.buffer().enumerate_pixels() {
            let [r, g, b] = colour(x, y);
            assert_eq!(p.0, [r, g, b, 255], "frame of {k}, pixel ({x}, {y})");
        }
    }
    for (x, y, p) in frames[3].buffer().enumerate_pixels() {
        let v = (10 * (y * 6 + x)) as u8;
        assert_eq!(p.0, [v, v, v, 255], "grey frame, pixel ({x}, {y})");
    }
}

/// Frames of two sizes, a delay GIF cannot hold, an EXR frame and a second mode: refused,
/// the file named, nothing written.
#[test]
fn a_bad_animation_is_refused_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let (a, b) = (dir.path().join("a.png"), dir.path().join("b.png"));
    image::GrayImage::new(6, 4).save(&a).unwrap();
    image::GrayImage::new(6, 5).save(&b).unwrap();
    let gif = dir.path().join("out.gif");
    bin("irsig-sensor")
        .arg("--animation")
        .arg(&gif)
        .arg(&a)
        .arg(&b)
        .assert()
        .code(1)
        .stderr(predicate::str::contains("b.png").and(predicate::str::contains("6 x 5")));
    let exr = write_scene(dir.path());
    bin("irsig-sensor")
        .arg("--animation")
        .arg(&gif)
        .arg(&a)
        .arg(&exr)
        .assert()
        .code(1)
        .stderr(
            predicate::str::contains("radiance.exr").and(predicate::str::contains("not a PNG")),
        );
    bin("irsig-sensor")
        .arg("--animation")
        .arg(&gif)
        .args(["--frame-delay-ms", "15"])
        .arg(&a)
        .assert()
        .code(2)
        .stderr(predicate::str::contains("hundredths"));
    bin("irsig-sensor")
        .arg("--animation")
        .arg(&gif)
        .arg("--contact-sheet")
        .arg(dir.path().join("sheet.png"))
        .arg(&a)
        .assert()
        .code(2);
    // A second image without a mode that takes several.
    bin("irsig-sensor").arg(&a).arg(&b).assert().code(2);
    assert!(!gif.exists() && !dir.path().join("sheet.png").exists());
}
