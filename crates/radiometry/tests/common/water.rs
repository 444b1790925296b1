//! Independent references shared by the Fresnel tests and the `radiometry_accuracy` example
//! (which includes this file by path): Dunkle's closed form and the Hale & Querry water
//! indices.

use irsig_radiometry::fresnel::IndexTable;

/// Hemispherical emissivity of a non-absorbing dielectric, closed form (Dunkle 1963, as
/// given by Siegel & Howell, *Thermal Radiation Heat Transfer*, ideal dielectric surfaces).
pub fn dunkle_hemispherical(n: f64) -> f64 {
    let n2 = n * n;
    let n4 = n2 * n2;
    0.5 - (3.0 * n + 1.0) * (n - 1.0) / (6.0 * (n + 1.0) * (n + 1.0))
        - n2 * (n2 - 1.0) * (n2 - 1.0) / ((n2 + 1.0).powi(3)) * ((n - 1.0) / (n + 1.0)).ln()
        + 2.0 * n2 * n * (n2 + 2.0 * n - 1.0) / ((n2 + 1.0) * (n4 - 1.0))
        - 8.0 * n4 * (n4 + 1.0) / ((n2 + 1.0) * (n4 - 1.0) * (n4 - 1.0)) * n.ln()
}

/// Hale & Querry (1973), "Optical constants of water in the 200-nm to 200-µm wavelength
/// region", Appl. Opt. 12, 555, doi:10.1364/AO.12.000555; liquid water, 25 °C; the
/// tabulated points in 8–14 µm as listed in `shared/reference/materials/README.md`
/// (and in `formats/samples/water-hale-querry-nk.txt`): (µm, n, k).
const HALE_QUERRY: [(f64, f64, f64); 19] = [
    (8.0, 1.291, 0.0343),
    (8.2, 1.286, 0.0351),
    (8.4, 1.281, 0.0361),
    (8.6, 1.275, 0.0372),
    (8.8, 1.269, 0.0385),
    (9.0, 1.262, 0.0399),
    (9.2, 1.255, 0.0415),
    (9.4, 1.247, 0.0433),
    (9.6, 1.239, 0.0454),
    (9.8, 1.229, 0.0479),
    (10.0, 1.218, 0.0508),
    (10.5, 1.185, 0.0662),
    (11.0, 1.153, 0.0968),
    (11.5, 1.126, 0.142),
    (12.0, 1.111, 0.199),
    (12.5, 1.123, 0.259),
    (13.0, 1.146, 0.305),
    (13.5, 1.177, 0.343),
    (14.0, 1.210, 0.370),
];

/// [`HALE_QUERRY`] as an index table.
pub fn water() -> IndexTable {
    IndexTable::new(
        HALE_QUERRY.iter().map(|r| r.0).collect(),
        &HALE_QUERRY.iter().map(|r| r.1).collect::<Vec<_>>(),
        &HALE_QUERRY.iter().map(|r| r.2).collect::<Vec<_>>(),
    )
    .unwrap()
}
