//! From a raw scene and its material library to what the solver needs per facet: the wall
//! and surface of each material, each facet's orientation, and the facets held at a
//! temperature or heated from behind.

use std::collections::HashMap;

use irsig_model::thermal::ThermalProperties;
use irsig_model::{Material, MaterialLibrary, RawScene};
use irsig_radiometry::{Band, EmissivityTable, band_average_emissivity};
use irsig_thermal::{Convection, Discretisation, Surface, Wall};
use miette::miette;

/// The sun's photosphere as a blackbody, K: the weight a spectral emissivity curve is
/// averaged with over 0.3–4 µm for a solar absorptance (a named approximation: the
/// spectrum at the ground has the atmosphere's absorption bands, which a flat-topped
/// curve does not feel and a curve with structure in them does).
pub const SUN_TEMPERATURE_K: f64 = 5778.0;
/// The solar range a spectral curve must cover to give an absorptance, µm.
pub const SOLAR_RANGE_UM: (f64, f64) = (0.3, 4.0);

/// One material's thermal model: its wall (discretised) and its surface.
#[derive(Debug)]
pub struct MaterialModel {
    /// The material's name, for messages.
    pub name: String,
    /// The wall.
    pub wall: Wall,
    /// The exposed surface.
    pub surface: Surface,
    /// Where the absorptance came from, for the provenance.
    pub absorptance_from: &'static str,
}

/// A value a material's record leaves open, resolved: the solar absorptance, given or from
/// the spectral curve, and the broadband emissivity, given or the angular table's
/// hemispherical mean.
fn surface_of(
    m: &Material,
    t: &ThermalProperties,
    convection: Convection,
) -> miette::Result<(Surface, &'static str)> {
    let (solar_absorptance, from) = match t.solar_absorptance {
        Some(a) => (a, "given"),
        None => {
            let spectral = m.spectral.as_ref().ok_or_else(|| {
                miette!(
                    "material `{}` (id {}) gives no solar_absorptance and has no spectral \
                     emissivity curve to take it from: give thermal.solar_absorptance (the \
                     share of 0.3-4 um sunlight it absorbs)",
                    m.name,
                    m.id.0
                )
            })?;
            let (lo, hi) = SOLAR_RANGE_UM;
            let band = Band::new(lo, hi).map_err(|e| miette!("{e}"))?;
            let a = band_average_emissivity(
                &spectral.wavelength_um,
                &spectral.emissivity,
                &band,
                SUN_TEMPERATURE_K,
            )
            .map_err(|e| {
                miette!(
                    "material `{}` (id {}): its spectral curve cannot give a solar absorptance \
                     over {lo}-{hi} um ({e}); give thermal.solar_absorptance",
                    m.name,
                    m.id.0
                )
            })?;
            (
                a,
                "spectral curve over 0.3-4 um, weighted by a 5778 K blackbody",
            )
        }
    };
    let thermal_emissivity = match t.thermal_emissivity {
        Some(e) => e,
        None => {
            let (angle, eps): (Vec<f64>, Vec<f64>) = m.emissivity.iter().copied().unzip();
            EmissivityTable::new(angle, eps)
                .map_err(|e| miette!("material `{}` (id {}): {e}", m.name, m.id.0))?
                .hemispherical()
        }
    };
    Ok((
        Surface {
            solar_absorptance,
            thermal_emissivity,
            wet_fraction: t.wet_fraction,
            roughness: t.roughness,
            convection,
        },
        from,
    ))
}

/// Every material the scene's solved facets use, by id: its wall cut as `discretisation`
/// says and its surface with `convection`. `solved` says which facets are solved (the
/// others are held), `by_map` which of them are solved by their material map's materials
/// (per-material walls): those need each of the map's materials' thermal records and not
/// their own material's. A needed material without thermal properties is refused, naming
/// it and a facet of it (and the map and its host, for a map's material).
///
/// # Errors
/// A material the library lacks, one without thermal properties, one whose wall cannot be
/// cut, or whose absorptance cannot be found.
pub fn material_models(
    scene: &RawScene,
    materials: &MaterialLibrary,
    (solved, by_map): (&[bool], &[bool]),
    discretisation: &Discretisation,
    convection: Convection,
) -> miette::Result<HashMap<u16, MaterialModel>> {
    let mut out: HashMap<u16, MaterialModel> = HashMap::new();
    for (i, f) in scene.facets.iter().enumerate() {
        if !solved[i] {
            continue;
        }
        let object = scene
            .objects
            .get(f.object as usize)
            .map_or("?", String::as_str);
        let m = materials.by_id(f.material).ok_or_else(|| {
            miette!(
                "facet {i} (object `{object}`) uses material {}, which the material library \
                 does not define",
                f.material.0
            )
        })?;
        if by_map[i] {
            let map = m.maps.as_ref().and_then(|x| x.material.as_ref());
            for name in map.map(|x| x.materials()).unwrap_or_default() {
                // The library's validation found every name.
                let Some(c) = materials.by_name(name) else {
                    continue;
                };
                if out.contains_key(&c.id.0) {
                    continue;
                }
                let t = c.thermal.as_ref().ok_or_else(|| {
                    miette!(
                        "material `{}` (id {}) has no thermal properties, and the material map \
                         `{}` of material `{}` (id {}) mixes it on facet {i} (object \
                         `{object}`): give `{}` a `thermal` record \
                         (formats/canonical/material-library.md), or solve the map's facets \
                         with the host's one wall, --mixture one-wall",
                        c.name,
                        c.id.0,
                        map.map_or("?", |x| x.image.as_str()),
                        m.name,
                        m.id.0,
                        c.name
                    )
                })?;
                out.insert(c.id.0, model_of(c, t, discretisation, convection)?);
            }
            continue;
        }
        if out.contains_key(&f.material.0) {
            continue;
        }
        let t = m.thermal.as_ref().ok_or_else(|| {
            miette!(
                "material `{}` (id {}) has no thermal properties, and facet {i} (object \
                 `{object}`) uses it: give the material a `thermal` record (layers, back, \
                 solar absorptance; formats/canonical/material-library.md), or hold the \
                 object at a temperature with --hold {object}=K",
                m.name,
                m.id.0
            )
        })?;
        out.insert(f.material.0, model_of(m, t, discretisation, convection)?);
    }
    Ok(out)
}

/// Material `m`'s model from its thermal record `t`.
fn model_of(
    m: &Material,
    t: &ThermalProperties,
    discretisation: &Discretisation,
    convection: Convection,
) -> miette::Result<MaterialModel> {
    let wall = Wall::new(t, discretisation)
        .map_err(|e| miette!("material `{}` (id {}): {e}", m.name, m.id.0))?;
    let (surface, absorptance_from) = surface_of(m, t, convection)?;
    Ok(MaterialModel {
        name: m.name.clone(),
        wall,
        surface,
        absorptance_from,
    })
}

/// `OBJECT=VALUE` pairs (`--hold`, `--heat`) resolved to a value per facet. `OBJECT` is a
/// placed object's name, or `#N`, the N-th placed object (from 0, the raw scene's order),
/// for a name two placements share.
///
/// # Errors
/// A pair without `=`, a value that is not a finite number within `range`, or a name the
/// scene has no object of (the message lists the scene's objects).
pub fn per_facet(
    scene: &RawScene,
    pairs: &[String],
    flag: &str,
    unit: &str,
    range: (f64, f64),
) -> miette::Result<Vec<Option<f64>>> {
    let mut by_object: Vec<Option<f64>> = vec![None; scene.objects.len()];
    for pair in pairs {
        let (name, value) = pair.split_once('=').ok_or_else(|| {
            irsig_cli::usage_error(format!("{flag} `{pair}`: expected OBJECT={unit}"))
        })?;
        let value: f64 = value
            .trim()
            .parse()
            .ok()
            .filter(|v: &f64| v.is_finite() && (range.0..=range.1).contains(v))
            .ok_or_else(|| {
                irsig_cli::usage_error(format!(
                    "{flag} `{pair}`: expected a number of {unit} from {} to {}",
                    range.0, range.1
                ))
            })?;
        let index = object_index(scene, name)
            .map_err(|why| irsig_cli::usage_error(format!("{flag} `{pair}`: {why}")))?;
        if by_object[index].replace(value).is_some() {
            return Err(irsig_cli::usage_error(format!(
                "{flag} names object `{name}` twice"
            )));
        }
    }
    Ok(scene
        .facets
        .iter()
        .map(|f| by_object[f.object as usize])
        .collect())
}

/// The ground beyond the scene's model: the library material named `name`, which needs a
/// thermal record.
///
/// # Errors
/// No material of that name, or one without thermal properties.
pub fn ground_model(
    materials: &MaterialLibrary,
    name: &str,
    discretisation: &Discretisation,
    convection: Convection,
) -> miette::Result<MaterialModel> {
    let m = materials.by_name(name).ok_or_else(|| {
        irsig_cli::usage_error(format!(
            "--ground-material `{name}`: the material library has no material of that name"
        ))
    })?;
    let t = m.thermal.as_ref().ok_or_else(|| {
        irsig_cli::usage_error(format!(
            "--ground-material `{name}`: the material has no thermal properties"
        ))
    })?;
    model_of(m, t, discretisation, convection)
}

/// The placed object `name` names: a name only one placement has, or `#N`.
fn object_index(scene: &RawScene, name: &str) -> Result<usize, String> {
    if let Some(n) = name.strip_prefix('#') {
        return n
            .parse::<usize>()
            .ok()
            .filter(|&i| i < scene.objects.len())
            .ok_or_else(|| {
                format!(
                    "`#{n}`: expected a placed object's place, 0 to {}",
                    scene.objects.len().saturating_sub(1)
                )
            });
    }
    let places: Vec<usize> = (0..scene.objects.len())
        .filter(|&i| scene.objects[i] == name)
        .collect();
    match places.as_slice() {
        [i] => Ok(*i),
        [] => Err(format!(
            "the scene has no object `{name}`; its objects are {}",
            scene
                .objects
                .iter()
                .enumerate()
                .map(|(i, o)| format!("`{o}` (#{i})"))
                .collect::<Vec<_>>()
                .join(", ")
        )),
        many => Err(format!(
            "{} placed objects are named `{name}` ({}): name one by its place, #N",
            many.len(),
            many.iter()
                .map(|i| format!("#{i}"))
                .collect::<Vec<_>>()
                .join(", ")
        )),
    }
}
