//! Spectral materials (`Material::spectral`): ε(λ) averaged over the band for the band
//! model and over each sub-band for the spectral model, response- and Planck-weighted at
//! the sub-bands' reference temperature, as the atmosphere's τ is collapsed. A material with
//! ε(λ, θ) on a grid (`spectral.angular`) is averaged angle by angle; otherwise the angular
//! table gives the shape: ε(λ, θ) = ε(λ) · ε_table(θ) / ε_table(0°), held to [0, 1].

use crate::RenderError;
use irsig_model::{Material, MaterialLibrary};
use irsig_radiometry::{Band, EmissivityTable, band_average_emissivities, band_average_emissivity};

/// The Planck weighting temperature, K: the sub-bands' reference (`SHARE_REFERENCE_K`).
const WEIGHT_K: f64 = crate::band::SHARE_REFERENCE_K;

/// `lib` with every spectral material's angular table replaced by its average over `band`
/// (the `spectral` curve kept, for the sub-bands). A curve that does not cover the band is
/// an error at its wavelengths in `file`.
pub fn band_library(
    lib: &MaterialLibrary,
    band: &Band,
    file: &str,
    text: &str,
) -> Result<MaterialLibrary, RenderError> {
    let mut out = lib.clone();
    for (i, m) in out.materials.iter_mut().enumerate() {
        if m.spectral.is_none() {
            continue;
        }
        let table = averaged(m, band).map_err(|e| {
            RenderError::input(
                format!("the materials `{file}` over the band"),
                irsig_formats::canonical::error_at_path(
                    file,
                    text,
                    &format!("materials[{i}].spectral.wavelength_um"),
                    format!(
                        "material `{}`: {e}; the band is {}-{} um",
                        m.name,
                        band.lambda_min_um(),
                        band.lambda_max_um()
                    ),
                ),
            )
        })?;
        m.emissivity = table
            .angle_deg()
            .iter()
            .copied()
            .zip(table.emissivity().iter().copied())
            .collect();
    }
    Ok(out)
}

/// Each material's angular emissivity over the sub-band `band`, in the library's order;
/// `None` when no material is spectral (the tracer then keeps the band tables).
pub fn sub_band_tables(
    lib: &MaterialLibrary,
    band: &Band,
) -> Result<Option<Vec<EmissivityTable>>, RenderError> {
    if lib.materials.iter().all(|m| m.spectral.is_none()) {
        return Ok(None);
    }
    lib.materials
        .iter()
        .map(|m| {
            averaged(m, band).map_err(|e| {
                RenderError::band(
                    format!(
                        "material `{}` over the sub-band {}-{} um",
                        m.name,
                        band.lambda_min_um(),
                        band.lambda_max_um()
                    ),
                    e,
                )
            })
        })
        .collect::<Result<Vec<_>, _>>()
        .map(Some)
}

/// The material's angular table over `band`: its own for a band-only material, else the
/// shape of its table times the band average of its curve.
fn averaged(
    m: &Material,
    band: &Band,
) -> Result<EmissivityTable, irsig_radiometry::RadiometryError> {
    let (angles, values): (Vec<f64>, Vec<f64>) = m.emissivity.iter().copied().unzip();
    let Some(s) = &m.spectral else {
        return EmissivityTable::new(angles, values);
    };
    if let Some(a) = &s.angular {
        // ε(λ, θ) on a grid: each angle's column averaged over the band (the quadrature's
        // nodes, the same for every column, found once).
        let columns: Vec<Vec<f64>> = (0..a.angle_deg.len())
            .map(|j| a.emissivity.iter().map(|row| row[j]).collect())
            .collect();
        let columns: Vec<&[f64]> = columns.iter().map(Vec::as_slice).collect();
        let averaged = band_average_emissivities(&s.wavelength_um, &columns, band, WEIGHT_K)?;
        return EmissivityTable::new(a.angle_deg.clone(), averaged);
    }
    let mean = band_average_emissivity(&s.wavelength_um, &s.emissivity, band, WEIGHT_K)?;
    let normal = values.first().copied().unwrap_or(1.0);
    let scaled = values
        .iter()
        .map(|&e| (mean * e / normal).clamp(0.0, 1.0))
        .collect();
    EmissivityTable::new(angles, scaled)
}
