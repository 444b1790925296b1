use super::*;
use irsig_model::{ProfileLevel, SpectralAxis, SpectralGrid};

fn small() -> SpectralAtmosphere {
    SpectralAtmosphere {
        name: "t".into(),
        source: "test".into(),
        grid: SpectralGrid {
            axis: SpectralAxis::WavenumberPerCm,
            points: vec![710.0, 715.0],
        },
        levels: vec![ProfileLevel {
            altitude_asl_m: 1000.0,
            temperature_k: 281.0,
            altitude_m: 1000.0,
        }],
        level_transmission: vec![0.1, 0.2],
        level_path_radiance_w_m2_sr_per_unit: vec![0.1, 0.09],
        transmission_correction: None,
        sky_zenith_deg: vec![0.0],
        sky_radiance_w_m2_sr_per_unit: vec![0.1, 0.2],
        sky_hemispheric_w_m2_sr_per_unit: Some(vec![0.3, 0.4]),
        radiosonde: vec![],
        slant: None,
        solar: None,
        slabs: vec![],
    }
}

#[test]
fn either_form_is_read_as_its_kind_and_errors_point_into_its_header() {
    use crate::canonical::{AnyAtmosphere, read_any_atmosphere};
    let a = small();
    let bytes = encode(&a).unwrap();
    assert_eq!(
        read_any_atmosphere("a.bin", &bytes).unwrap(),
        AnyAtmosphere::Spectral(a.clone())
    );
    let ron = crate::canonical::to_ron(&a).unwrap();
    assert_eq!(
        read_any_atmosphere("a.ron", ron.as_bytes()).unwrap(),
        AnyAtmosphere::Spectral(a.clone())
    );
    // A band atmosphere that merely says "grid" in a string is still one.
    let band = crate::canonical::from_ron_bytes::<irsig_model::Atmosphere>(
        "b.ron",
        include_bytes!("../../../../../formats/canonical/samples/atmosphere.ron"),
    )
    .unwrap();
    let mut band_named = band.clone();
    band_named.source = "a grid of nodes".into();
    let text = crate::canonical::to_ron(&band_named).unwrap();
    assert_eq!(
        read_any_atmosphere("b.ron", text.as_bytes()).unwrap(),
        AnyAtmosphere::Band(band_named)
    );
    // In the binary form the error is at the grid's points inside the RON header.
    let (offset, header) = header(&bytes).unwrap();
    let e = crate::canonical::spectral_atmosphere_error_at_path(
        "a.bin",
        &bytes,
        "grid.points",
        "outside",
    );
    let (start, _) = crate::ron_tree::locate(header, "grid.points");
    assert!(header[start..].starts_with('['), "{}", &header[start..]);
    assert_eq!((e.line, e.column), (1, offset + start + 1), "{e}");
    assert!(e.to_string().contains("outside"), "{e}");
}

#[test]
fn round_trips_bit_for_bit() {
    let a = small();
    let bytes = encode(&a).unwrap();
    assert_eq!(decode("a.spa", &bytes).unwrap(), a);
    assert_eq!(encode(&decode("a.spa", &bytes).unwrap()).unwrap(), bytes);
}

#[test]
fn a_solar_table_follows_the_others_and_round_trips() {
    let night = encode(&small()).unwrap();
    let mut a = small();
    a.solar = Some(irsig_model::SpectralSolar {
        zenith_deg: 30.0,
        day_of_year: 172,
        altitude_m: vec![0.0, 300.0],
        extraterrestrial_w_m2_per_unit: vec![0.0092, 0.0094],
        transmission: vec![0.25, 0.5, 0.3, 0.55],
        relative_azimuth_deg: Vec::new(),
        path_scattered_w_m2_sr_per_unit: Vec::new(),
        sky_scattered_w_m2_sr_per_unit: Vec::new(),
        further_suns: Vec::new(),
        apparent_zenith_deg: Vec::new(),
        phase: None,
    });
    let bytes = encode(&a).unwrap();
    assert_eq!(decode("a.spa", &bytes).unwrap(), a);
    // The last two tables are the solar ones, in the page's order: 2 then 4 values.
    let tail = &bytes[bytes.len() - (4 + 8 + 4 + 16)..];
    assert_eq!(u32::from_le_bytes(tail[..4].try_into().unwrap()), 2);
    assert_eq!(tail[4..8], 0.0092_f32.to_le_bytes());
    assert_eq!(u32::from_le_bytes(tail[12..16].try_into().unwrap()), 4);
    assert_eq!(tail[28..32], 0.55_f32.to_le_bytes());
    // Cut off its last table: the reader says the file is truncated.
    let e = decode("a", &bytes[..bytes.len() - 20]).unwrap_err();
    assert!(e.message.contains("truncated"), "{}", e.message);
    // A night atmosphere is written as before.
    assert_eq!(encode(&small()).unwrap(), night);
}

#[test]
fn further_suns_follow_the_first_suns_tables_and_round_trip_in_both_versions() {
    let mut a = small();
    let first = irsig_model::SpectralSolar {
        zenith_deg: 30.0,
        day_of_year: 172,
        altitude_m: vec![0.0, 300.0],
        extraterrestrial_w_m2_per_unit: vec![0.0092, 0.0094],
        transmission: vec![0.25, 0.5, 0.3, 0.55],
        relative_azimuth_deg: Vec::new(),
        path_scattered_w_m2_sr_per_unit: Vec::new(),
        sky_scattered_w_m2_sr_per_unit: Vec::new(),
        further_suns: Vec::new(),
        apparent_zenith_deg: Vec::new(),
        phase: None,
    };
    a.solar = Some(first.clone());
    let one_sun = encode(&a).unwrap();
    let mut s = first;
    s.further_suns = vec![
        irsig_model::SolarBeam {
            zenith_deg: 60.0,
            transmission: vec![0.125, 0.25, 0.15, 0.275],
            path_scattered_w_m2_sr_per_unit: Vec::new(),
            sky_scattered_w_m2_sr_per_unit: Vec::new(),
        },
        irsig_model::SolarBeam {
            zenith_deg: 85.0,
            transmission: vec![0.0625, 0.125, 0.075, 0.1375],
            path_scattered_w_m2_sr_per_unit: Vec::new(),
            sky_scattered_w_m2_sr_per_unit: Vec::new(),
        },
    ];
    a.solar = Some(s);
    let bytes = encode(&a).unwrap();
    assert_eq!(decode("a.spa", &bytes).unwrap(), a);
    // The last table is the last sun's: a count of 4 and its values, in order.
    let tail = &bytes[bytes.len() - (4 + 16)..];
    assert_eq!(u32::from_le_bytes(tail[..4].try_into().unwrap()), 4);
    assert_eq!(tail[4..8], 0.0625_f32.to_le_bytes());
    assert_eq!(tail[16..20], 0.1375_f32.to_le_bytes());
    // Two more tables of 4 values (and the header's two rows) follow the one-sun file.
    assert!(bytes.len() > one_sun.len() + 2 * (4 + 16));
    let quantised = decode("a.spa", &encode_quantised(&a).unwrap()).unwrap();
    let s = quantised.solar.unwrap();
    assert_eq!(s.zeniths_deg(), [30.0, 60.0, 85.0]);
    let last = s.transmission_of(2).unwrap();
    assert!((f64::from(last[3]) - 0.1375).abs() < 0.1375 / 60_000.0);
    // A count that is not the altitudes' is refused at the further sun's path.
    let mut cut = bytes.clone();
    let at = cut.len() - (4 + 16);
    cut[at..at + 4].copy_from_slice(&3u32.to_le_bytes());
    cut.truncate(cut.len() - 4);
    let e = decode("a", &cut).unwrap_err();
    assert!(e.message.contains("further_suns[1]"), "{}", e.message);
}

#[test]
#[allow(clippy::float_cmp)] // largest values and zeros are exact
fn version_2_holds_each_value_within_half_a_step_of_its_spectrums_largest() {
    let mut a = small();
    a.grid.points = vec![2000.0, 2005.0, 2010.0];
    a.level_transmission = vec![1.0, 0.5, 0.0];
    a.level_path_radiance_w_m2_sr_per_unit = vec![3e-9, 1.5e-9, 7e-13];
    a.sky_radiance_w_m2_sr_per_unit = vec![0.0, 0.0, 0.0];
    a.sky_hemispheric_w_m2_sr_per_unit = Some(vec![2e-3, 1e-3, 6e-3]);
    let bytes = encode_quantised(&a).unwrap();
    assert_eq!(u32::from_le_bytes(bytes[8..12].try_into().unwrap()), 2);
    let b = decode("a.bin", &bytes).unwrap();
    // Largest values and zeros come back exactly; the rest within half a step, largest
    // / 131070 (0.5 of 1 is 32767.5 steps: 0.5 + 7.6e-6; 7e-13 of 3e-9 is 15.3 steps,
    // 15: 6.87e-13, 2 % low).
    let t = &b.level_transmission;
    assert_eq!((t[0], t[2]), (1.0, 0.0));
    assert!((f64::from(t[1]) - 0.5).abs() <= 1.0 / 131_070.0, "{t:?}");
    assert!(f64::from(t[1]) != 0.5, "{t:?}: quantised");
    assert_eq!(b.level_path_radiance_w_m2_sr_per_unit[0], 3e-9);
    let l = b.level_path_radiance_w_m2_sr_per_unit[1];
    assert!((f64::from(l) - 1.5e-9).abs() <= 3e-9 / 131_070.0, "{l}");
    let small = b.level_path_radiance_w_m2_sr_per_unit[2];
    assert!(
        (f64::from(small) - 7e-13).abs() <= 3e-9 / 131_070.0,
        "{small}"
    );
    assert_eq!(b.sky_radiance_w_m2_sr_per_unit, vec![0.0; 3]);
    let h = b.sky_hemispheric_w_m2_sr_per_unit.unwrap();
    assert_eq!(h[2], 6e-3);
    assert!((f64::from(h[0]) - 2e-3).abs() <= 6e-3 / 131_070.0, "{h:?}");
    // Everything else of the atmosphere is the header's, exactly.
    assert_eq!((b.grid, b.levels, b.name), (a.grid, a.levels, a.name));
}

fn u32_len(bytes: &[u8], at: usize) -> usize {
    u32::from_le_bytes(bytes[at..at + 4].try_into().unwrap()) as usize
}

#[test]
fn a_version_2_table_larger_than_its_header_is_refused_before_inflating() {
    // An 875 KB file whose `level_transmission` claimed 350M values cost 2.2 GB and 7.7 s
    // before "expected 7 values"; one claiming 2,147,483,646 values aborted (exit 134).
    // The count is now held to the header's dimensions first, whatever the stream.
    let a = small();
    let bytes = encode_quantised(&a).unwrap();
    let first = 16 + u32_len(&bytes, 12);
    for claimed in [350_000_000_u32, 2_147_483_646] {
        // A stream that really inflates to the claim's size would be megabytes; the
        // claim alone must be refused, whatever follows it.
        let raw = vec![0_u8; 1 << 20];
        let z = miniz_oxide::deflate::compress_to_vec_zlib(&raw, 9);
        let mut bomb = bytes[..first].to_vec();
        bomb.extend_from_slice(&claimed.to_le_bytes());
        bomb.extend_from_slice(&u32::try_from(z.len()).unwrap().to_le_bytes());
        bomb.extend_from_slice(&z);
        let e = decode("bomb.spa", &bomb).unwrap_err();
        assert!(
            e.message
                .contains("expected `level_transmission` to hold 2 values"),
            "{}",
            e.message
        );
        assert_eq!((e.line, e.column), (1, first + 1));
    }
}

#[test]
fn a_header_whose_tables_pass_the_memory_budget_is_refused_before_any_is_read() {
    // 70,000 levels × 66,000 points: 4.6 × 10^9 values, 18.5 GB of f32, from a header of
    // a few megabytes. Nothing after the header is needed to refuse it.
    let mut a = small();
    a.grid.points = (0..66_000).map(|i| 700.0 + f64::from(i) * 1e-2).collect();
    a.levels = (0..70_000)
        .map(|i| ProfileLevel {
            altitude_asl_m: f64::from(i),
            temperature_k: 250.0,
            altitude_m: f64::from(i),
        })
        .collect();
    a.level_transmission.clear();
    a.level_path_radiance_w_m2_sr_per_unit.clear();
    a.sky_radiance_w_m2_sr_per_unit.clear();
    a.sky_hemispheric_w_m2_sr_per_unit = Some(vec![]);
    let mut bytes = start(&a, VERSION_QUANTISED, 0).unwrap();
    bytes.extend_from_slice(&[0; 8]);
    let e = decode("big.spa", &bytes).unwrap_err();
    assert!(e.message.contains("memory budget"), "{}", e.message);
}

#[test]
fn the_expected_counts_follow_the_tables_in_order() {
    // Every table the encoder writes, with the count the header's dimensions give it,
    // for an atmosphere with every kind of table the model's own rules accept.
    let mut a = small();
    a.transmission_correction = Some(irsig_model::CorrectionPaths {
        altitude_m: 1000.0,
        nadir_deg: vec![0.0, 30.0, 60.0],
        transmission: vec![0.5; 6],
    });
    a.slant = Some(irsig_model::SpectralSlantTables {
        altitude_m: vec![10.0, 100.0],
        nadir_deg: vec![0.0, 45.0],
        ground_m: None,
        transmission: vec![0.5; 8],
        path_radiance_w_m2_sr_per_unit: vec![0.1; 8],
        sky_altitude_m: vec![0.0],
        sky_zenith_deg: vec![0.0, 60.0, 90.0],
        sky_radiance_w_m2_sr_per_unit: vec![0.1; 6],
        interpolation_residual: None,
    });
    a.solar = Some(irsig_model::SpectralSolar {
        zenith_deg: 30.0,
        day_of_year: 172,
        altitude_m: vec![0.0, 300.0],
        extraterrestrial_w_m2_per_unit: vec![0.01; 2],
        transmission: vec![0.5; 4],
        relative_azimuth_deg: vec![0.0, 180.0],
        path_scattered_w_m2_sr_per_unit: vec![0.01; 16],
        sky_scattered_w_m2_sr_per_unit: vec![0.01; 24],
        further_suns: Vec::new(),
        apparent_zenith_deg: Vec::new(),
        phase: None,
    });
    let own_row =
        |own: f32, away: f32| -> Vec<f32> { [away, away, away, away, own, own, own, own].to_vec() };
    a.slabs = vec![irsig_model::SpectralSlab {
        observer_m: 50.0,
        down: Some(irsig_model::SpectralSlabTable {
            target_m: vec![0.0, 50.0],
            angle_deg: vec![0.0, 30.0],
            transmission: own_row(1.0, 0.5),
            path_radiance_w_m2_sr_per_unit: own_row(0.0, 0.1),
            scattered_w_m2_sr_per_unit: [[0.1; 8], [0.0; 8]].concat(),
        }),
        up: None,
    }];
    a.validate().unwrap();
    let shapes = expected_spectra(&a).unwrap();
    let tables = tables(&a);
    assert_eq!(shapes.len(), tables.len());
    assert_eq!(shapes.len(), 15);
    for ((path, spectra), t) in shapes.iter().zip(tables) {
        assert_eq!(spectra * a.grid.points.len(), t.len(), "{path}");
    }
    for bytes in [encode(&a).unwrap(), encode_quantised(&a).unwrap()] {
        decode("lit.spa", &bytes).unwrap();
    }
    // A day's table: a further sun's scattered spectra follow its beam, and the file
    // reads back what it wrote.
    let one_sun = encode(&a).unwrap();
    if let Some(s) = &mut a.solar {
        s.further_suns.push(irsig_model::SolarBeam {
            zenith_deg: 60.0,
            transmission: vec![0.25; 4],
            path_scattered_w_m2_sr_per_unit: vec![0.005; 16],
            sky_scattered_w_m2_sr_per_unit: vec![0.0025; 24],
        });
    }
    a.validate().unwrap();
    let shapes = expected_spectra(&a).unwrap();
    let names: Vec<&str> = shapes.iter().map(|(p, _)| p.as_str()).collect();
    assert_eq!(
        names[12..15],
        [
            "solar.further_suns[0].transmission",
            "solar.further_suns[0].path_scattered_w_m2_sr_per_unit",
            "solar.further_suns[0].sky_scattered_w_m2_sr_per_unit",
        ]
    );
    for ((path, spectra), t) in shapes.iter().zip(super::tables(&a)) {
        assert_eq!(spectra * a.grid.points.len(), t.len(), "{path}");
    }
    let day = encode(&a).unwrap();
    assert_eq!(decode("day.spa", &day).unwrap(), a);
    // Three tables more than the one-sun file: 4 + 16 + 24 values and their counts.
    assert!(day.len() >= one_sun.len() + 3 * 4 + 4 * (4 + 16 + 24));
    let quantised = decode("day.spa", &encode_quantised(&a).unwrap()).unwrap();
    let b = &quantised.solar.unwrap().further_suns[0];
    assert!((b.sky_scattered_w_m2_sr_per_unit[23] - 0.0025).abs() < 0.0025 / 60_000.0);
}

#[test]
fn version_2_damage_is_refused_at_its_offset() {
    let mut a = small();
    a.level_transmission = vec![0.1, 0.2, 0.3, 0.4];
    a.level_path_radiance_w_m2_sr_per_unit = vec![0.1, 0.09, 0.08, 0.07];
    a.levels.push(a.levels[0]);
    a.levels[1].altitude_m = 2000.0;
    a.levels[1].altitude_asl_m = 2000.0;
    let bytes = encode_quantised(&a).unwrap();
    assert!(decode("a", &bytes).is_ok());
    let h = u32::from_le_bytes(bytes[12..16].try_into().unwrap()) as usize;
    let first = 16 + h;
    // Truncated inside a stream.
    let e = decode("a", &bytes[..bytes.len() - 3]).unwrap_err();
    assert!(e.message.contains("truncated"), "{}", e.message);
    // A count that is not the header's (levels × points = 4): refused at the count,
    // before a byte is inflated, whether one short, odd or beyond the stream's reach.
    for count in [3_u32, 6, u32::MAX - 1] {
        let mut wrong = bytes.clone();
        wrong[first..first + 4].copy_from_slice(&count.to_le_bytes());
        let e = decode("a", &wrong).unwrap_err();
        assert!(
            e.message
                .contains("expected `level_transmission` to hold 4 values"),
            "{}",
            e.message
        );
        assert_eq!(e.column, first + 1);
    }
    // A stream that holds less or more than the header's count (4 values in 2 spectra:
    // 16 bytes).
    let z_len = u32_len(&bytes, first + 4);
    for (len, said) in [(14, "one of 14 bytes"), (18, "a longer one")] {
        let z = miniz_oxide::deflate::compress_to_vec_zlib(&vec![0_u8; len], 9);
        let mut spliced = bytes[..first + 4].to_vec();
        spliced.extend_from_slice(&u32::try_from(z.len()).unwrap().to_le_bytes());
        spliced.extend_from_slice(&z);
        spliced.extend_from_slice(&bytes[first + 8 + z_len..]);
        let e = decode("a", &spliced).unwrap_err();
        assert!(e.message.contains(said), "{}", e.message);
    }
    // A broken stream.
    let mut broken = bytes.clone();
    for b in &mut broken[first + 8..first + 14] {
        *b ^= 0x5a;
    }
    let e = decode("a", &broken).unwrap_err();
    assert!(e.message.contains("zlib stream"), "{}", e.message);
    // An unknown version.
    let mut v3 = bytes.clone();
    v3[8..12].copy_from_slice(&3_u32.to_le_bytes());
    let e = decode("a", &v3).unwrap_err();
    assert!(
        e.message.contains("expected version 1 or 2"),
        "{}",
        e.message
    );
}

#[test]
fn damage_is_reported_at_its_offset() {
    let bytes = encode(&small()).unwrap();
    let e = decode("a", &bytes[..bytes.len() - 2]).unwrap_err();
    assert!(e.message.contains("truncated"), "{}", e.message);
    let mut longer = bytes.clone();
    longer.push(0);
    assert_eq!(decode("a", &longer).unwrap_err().column, bytes.len() + 1);
    let mut huge = bytes.clone();
    let h = u32::from_le_bytes(bytes[12..16].try_into().unwrap()) as usize;
    huge[16 + h..20 + h].copy_from_slice(&u32::MAX.to_le_bytes());
    assert!(decode("a", &huge).is_err());
    let mut bad = bytes.clone();
    let last = bad.len() - 4;
    bad[last..].copy_from_slice(&f32::NAN.to_le_bytes());
    assert!(
        decode("a", &bad)
            .unwrap_err()
            .message
            .contains("invalid spectral atmosphere")
    );
    assert!(decode("a", b"IRSIGRAW").is_err());
}
