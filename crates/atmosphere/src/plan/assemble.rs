//! From every path's spectra back to the spectral atmosphere the plan describes.

use super::*;

/// What a run gave for one path.
#[derive(Debug, Clone, PartialEq)]
pub struct PathSpectra {
    /// Wavenumbers, cm⁻¹, increasing.
    pub wavenumber_per_cm: Vec<f64>,
    /// Transmittance, 0–1 (values a little above 1, as LOWTRAN prints them on short paths,
    /// are clamped to 1 by [`assemble`]).
    pub transmission: Vec<f64>,
    /// Path (or sky) radiance, W m⁻² sr⁻¹ per cm⁻¹; empty for the sun's paths.
    pub radiance_w_m2_sr_per_cm: Vec<f64>,
    /// The sun's paths (direct solar irradiance runs): the extraterrestrial solar
    /// irradiance on a surface normal to the beam, W m⁻² per cm⁻¹; empty for the others.
    pub extraterrestrial_w_m2_per_cm: Vec<f64>,
    /// The sunlit paths (IEMSCT = 2 runs): the sunlight scattered into the path, W m⁻²
    /// sr⁻¹ per cm⁻¹; empty for the others.
    pub scattered_w_m2_sr_per_cm: Vec<f64>,
}

/// The spectral atmosphere from the spectra of every path of [`paths`] (same order),
/// `temperature_k(altitude above the ground in m)` for the profile, the ground's altitude
/// above sea level and the source text.
///
/// # Errors
/// A count of spectra that is not the count of paths, runs on different spectral grids,
/// or an atmosphere that fails validation.
pub fn assemble(
    plan: &AtmospherePlan,
    spectra: &[PathSpectra],
    temperature_k: &dyn Fn(f64) -> f64,
    ground_asl_m: f64,
    source: &str,
) -> Result<SpectralAtmosphere, AtmosphereError> {
    let all = paths(plan);
    let grid = common_grid(&all, spectra)?;
    check_lengths(&all, spectra, grid.len())?;
    let runs = Runs {
        spectra,
        index: all.iter().enumerate().map(|(i, p)| (key(p), i)).collect(),
    };
    let tau = |p: Path| runs.tau(p);
    let rad = |p: Path| runs.radiance(p);
    let levels = profile(plan, temperature_k, ground_asl_m);
    let hemi = runs.hemispheric(plan, grid.len());
    let solar = match &plan.sun {
        None => None,
        Some(sun) => Some(runs.solar(plan, sun, &grid)?),
    };
    let slabs = assemble_slabs(plan, &|p| runs.get(p), grid.len());
    let atmosphere = SpectralAtmosphere {
        name: plan.name.clone(),
        source: source.to_owned(),
        grid: SpectralGrid {
            axis: SpectralAxis::WavenumberPerCm,
            points: grid,
        },
        levels,
        level_transmission: flat(plan.levels_m.iter().map(|&a| down(a, 0.0)).collect(), &tau),
        level_path_radiance_w_m2_sr_per_unit: flat(
            plan.levels_m.iter().map(|&a| down(a, 0.0)).collect(),
            &rad,
        ),
        transmission_correction: Some(CorrectionPaths {
            altitude_m: plan.correction_altitude_m,
            nadir_deg: plan.correction_nadir_deg.clone(),
            transmission: flat(
                plan.correction_nadir_deg
                    .iter()
                    .map(|&n| down(plan.correction_altitude_m, n))
                    .collect(),
                &tau,
            ),
        }),
        sky_zenith_deg: plan.ground_sky_zenith_deg.clone(),
        sky_radiance_w_m2_sr_per_unit: flat(
            plan.ground_sky_zenith_deg
                .iter()
                .map(|&z| up(0.0, z))
                .collect(),
            &rad,
        ),
        sky_hemispheric_w_m2_sr_per_unit: Some(f32s(&hemi)),
        radiosonde: match &plan.model {
            PlanModel::Radiosonde(l) => l.clone(),
            PlanModel::Standard(_) => Vec::new(),
        },
        slant: Some(runs.slant(plan)),
        solar,
        slabs,
    };
    atmosphere.validate()?;
    Ok(atmosphere)
}

/// An error in the plan or its runs.
fn plan_error(m: String) -> AtmosphereError {
    AtmosphereErrorKind::Plan(m).into()
}

/// The spectral grid of every run: one run per path of `all`, all on run 0's grid.
fn common_grid(all: &[Path], spectra: &[PathSpectra]) -> Result<Vec<f64>, AtmosphereError> {
    if spectra.len() != all.len() {
        return Err(plan_error(format!(
            "the plan has {} paths, the runs gave {}",
            all.len(),
            spectra.len()
        )));
    }
    let grid = spectra[0].wavenumber_per_cm.clone();
    for (i, s) in spectra.iter().enumerate() {
        if s.wavenumber_per_cm != grid {
            return Err(plan_error(format!(
                "run {i} is on a different spectral grid from run 0 ({} points from {} cm-1, against {} from {} cm-1)",
                s.wavenumber_per_cm.len(),
                s.wavenumber_per_cm.first().copied().unwrap_or(f64::NAN),
                grid.len(),
                grid.first().copied().unwrap_or(f64::NAN)
            )));
        }
    }
    Ok(grid)
}

/// Checks that each run has, at each of the `n` grid points, a transmittance and the
/// spectrum its path is run for.
fn check_lengths(all: &[Path], spectra: &[PathSpectra], n: usize) -> Result<(), AtmosphereError> {
    for (i, (p, s)) in all.iter().zip(spectra).enumerate() {
        let (what, found) = match p {
            Path::Sun { .. } => (
                "an extraterrestrial solar irradiance (a direct solar irradiance run, IEMSCT = 3)",
                s.extraterrestrial_w_m2_per_cm.len(),
            ),
            Path::DownSunlit { .. }
            | Path::UpSunlit { .. }
            | Path::SlabSunlit { .. }
            | Path::Phase { .. } => (
                "a scattered solar radiance (a solar scattering run, IEMSCT = 2)",
                s.scattered_w_m2_sr_per_cm.len(),
            ),
            _ => (
                "a path radiance (a thermal radiance run)",
                s.radiance_w_m2_sr_per_cm.len(),
            ),
        };
        if found != n || s.transmission.len() != n {
            return Err(plan_error(format!(
                "run {i} ({p:?}): expected {what} and a transmittance at each of the {n} grid points, found {found} and {}",
                s.transmission.len()
            )));
        }
    }
    Ok(())
}

/// The downward path from `altitude_m` at `nadir_deg`.
fn down(altitude_m: f64, nadir_deg: f64) -> Path {
    Path::Down {
        altitude_m,
        nadir_deg,
    }
}

/// The upward path from `altitude_m` at `zenith_deg`.
fn up(altitude_m: f64, zenith_deg: f64) -> Path {
    Path::Up {
        altitude_m,
        zenith_deg,
    }
}

/// Values in single precision, as the spectral atmosphere holds them.
#[allow(clippy::cast_possible_truncation)]
fn f32s(v: &[f64]) -> Vec<f32> {
    v.iter().map(|&x| x as f32).collect::<Vec<f32>>()
}

/// The spectra `f` gives for the paths `ps`, one after another.
fn flat(ps: Vec<Path>, f: &dyn Fn(Path) -> Vec<f32>) -> Vec<f32> {
    ps.into_iter().flat_map(f).collect()
}

/// The profile's levels: the plan's altitudes above the ground, their altitudes above sea
/// level and their temperatures (rounded to the mK).
fn profile(
    plan: &AtmospherePlan,
    temperature_k: &dyn Fn(f64) -> f64,
    ground_asl_m: f64,
) -> Vec<ProfileLevel> {
    plan.levels_m
        .iter()
        .map(|&h| ProfileLevel {
            altitude_asl_m: ground_asl_m + h,
            temperature_k: (temperature_k(h) * 1e3).round() / 1e3,
            altitude_m: h,
        })
        .collect()
}

/// The runs' spectra, each found by its path.
struct Runs<'a> {
    spectra: &'a [PathSpectra],
    /// The run number of each path's key.
    index: BTreeMap<Key, usize>,
}

impl<'a> Runs<'a> {
    /// The run of path `p`.
    fn get(&self, p: Path) -> &'a PathSpectra {
        &self.spectra[self.index[&key(&p)]]
    }

    /// The transmittance of path `p`, clamped to 0–1: LOWTRAN prints τ a little above 1
    /// on metre-long paths.
    fn tau(&self, p: Path) -> Vec<f32> {
        let t: Vec<f64> = self
            .get(p)
            .transmission
            .iter()
            .map(|t| t.clamp(0.0, 1.0))
            .collect();
        f32s(&t)
    }

    /// The path radiance of path `p`.
    fn radiance(&self, p: Path) -> Vec<f32> {
        f32s(&self.get(p).radiance_w_m2_sr_per_cm)
    }

    /// The scattered sunlight of the sunlit path `p`.
    fn scattered(&self, p: Path) -> Vec<f32> {
        f32s(&self.get(p).scattered_w_m2_sr_per_cm)
    }

    /// The ground's hemispheric sky radiance on a grid of `n` points: the plan's weighted
    /// sum of its upward paths' radiances.
    fn hemispheric(&self, plan: &AtmospherePlan, n: usize) -> Vec<f64> {
        let mut hemi = vec![0.0_f64; n];
        for &(z, w) in &plan.hemispheric {
            for (h, l) in hemi
                .iter_mut()
                .zip(&self.get(up(0.0, z)).radiance_w_m2_sr_per_cm)
            {
                *h += w * l;
            }
        }
        hemi
    }

    /// The slant tables: the plan's slant paths' transmittances and radiances, and its
    /// skies' radiances.
    fn slant(&self, plan: &AtmospherePlan) -> SpectralSlantTables {
        let tau = |p: Path| self.tau(p);
        let rad = |p: Path| self.radiance(p);
        let slant_paths: Vec<Path> = plan
            .slant_altitude_m
            .iter()
            .flat_map(|&a| plan.slant_nadir_deg.iter().map(move |&n| down(a, n)))
            .collect();
        let sky_paths: Vec<Path> = plan
            .sky_altitude_m
            .iter()
            .flat_map(|&a| plan.sky_zenith_deg.iter().map(move |&z| up(a, z)))
            .collect();
        SpectralSlantTables {
            altitude_m: plan.slant_altitude_m.clone(),
            nadir_deg: plan.slant_nadir_deg.clone(),
            ground_m: Some(plan.path_end_m),
            transmission: flat(slant_paths.clone(), &tau),
            path_radiance_w_m2_sr_per_unit: flat(slant_paths, &rad),
            sky_altitude_m: plan.sky_altitude_m.clone(),
            sky_zenith_deg: plan.sky_zenith_deg.clone(),
            sky_radiance_w_m2_sr_per_unit: flat(sky_paths, &rad),
            // The plan's rows are the scene's own paths: nothing lies between them that
            // was measured.
            interpolation_residual: None,
        }
    }

    /// The sun's tables: every sun's direct beam and scattered sunlight, with the one
    /// extraterrestrial spectrum of its day.
    fn solar(
        &self,
        plan: &AtmospherePlan,
        sun: &PlanSun,
        grid: &[f64],
    ) -> Result<SpectralSolar, AtmosphereError> {
        let tau = |p: Path| self.tau(p);
        let scattered = |p: Path| self.scattered(p);
        let etoa = self.extraterrestrial(sun, grid)?;
        let further_suns = sun
            .further_zenith_deg
            .iter()
            .map(|&zenith_deg| SolarBeam {
                zenith_deg,
                transmission: flat(sun_paths_at(sun, zenith_deg).collect(), &tau),
                path_scattered_w_m2_sr_per_unit: flat(
                    sunlit_slant_paths(plan, sun, zenith_deg),
                    &scattered,
                ),
                sky_scattered_w_m2_sr_per_unit: flat(
                    sunlit_sky_paths(plan, sun, zenith_deg),
                    &scattered,
                ),
            })
            .collect();
        Ok(SpectralSolar {
            zenith_deg: sun.zenith_deg,
            day_of_year: sun.day_of_year,
            altitude_m: sun.altitude_m.clone(),
            extraterrestrial_w_m2_per_unit: f32s(etoa),
            transmission: flat(sun_paths_at(sun, sun.zenith_deg).collect(), &tau),
            further_suns,
            // The build records the angles LOWTRAN7 ran, which the plan does not know.
            apparent_zenith_deg: Vec::new(),
            phase: super::phase::assemble(plan, &scattered),
            relative_azimuth_deg: sun.relative_azimuth_deg.clone(),
            path_scattered_w_m2_sr_per_unit: flat(
                sunlit_slant_paths(plan, sun, sun.zenith_deg),
                &scattered,
            ),
            sky_scattered_w_m2_sr_per_unit: flat(
                sunlit_sky_paths(plan, sun, sun.zenith_deg),
                &scattered,
            ),
        })
    }

    /// The extraterrestrial spectrum of the sun's day on `grid`: the lowest direct beam
    /// run's, which every other run of the day must agree with to the printed digits.
    fn extraterrestrial(&self, sun: &PlanSun, grid: &[f64]) -> Result<&'a [f64], AtmosphereError> {
        let runs: Vec<Path> = sun_paths(sun).collect();
        let etoa = &self.get(runs[0]).extraterrestrial_w_m2_per_cm;
        for &p in &runs[1..] {
            let other = &self.get(p).extraterrestrial_w_m2_per_cm;
            if let Some(k) = (0..grid.len())
                .find(|&k| (other[k] - etoa[k]).abs() > 1e-6 * etoa[k].abs().max(1e-30))
            {
                return Err(plan_error(format!(
                    "run {} ({p:?}) has another extraterrestrial solar irradiance than run {} at {} cm-1 ({} against {} W m-2 per cm-1): the sun's runs must be of one day",
                    self.index[&key(&p)],
                    self.index[&key(&runs[0])],
                    grid[k],
                    other[k],
                    etoa[k]
                )));
            }
        }
        Ok(etoa)
    }
}

/// The spectral slabs of `plan` from its runs (`get`), one per observer that has any; the
/// observer's own row (its value copied: compared exactly) is τ = 1 and no radiance.
#[allow(clippy::float_cmp)]
pub(super) fn assemble_slabs<'a>(
    plan: &AtmospherePlan,
    get: &dyn Fn(Path) -> &'a PathSpectra,
    n: usize,
) -> Vec<SpectralSlab> {
    let Some(slabs) = &plan.slabs else {
        return Vec::new();
    };
    let azimuths: &[f64] = plan
        .sun
        .as_ref()
        .map_or(&[], |s| s.relative_azimuth_deg.as_slice());
    #[allow(clippy::cast_possible_truncation)]
    let f32s = |v: &[f64], clamp: bool| {
        v.iter()
            .map(|&x| if clamp { x.clamp(0.0, 1.0) } else { x } as f32)
            .collect::<Vec<f32>>()
    };
    let mut observers = plan.observers_m.clone();
    observers.sort_by(f64::total_cmp);
    observers.dedup();
    let mut out = Vec::new();
    for &o in &observers {
        let [down, up] = slab_tables(slabs, o).map(|table| {
            table.map(|(targets, angles, down)| {
                let mut t = SpectralSlabTable {
                    target_m: targets.clone(),
                    angle_deg: angles.to_vec(),
                    transmission: Vec::new(),
                    path_radiance_w_m2_sr_per_unit: Vec::new(),
                    scattered_w_m2_sr_per_unit: Vec::new(),
                };
                for &h in &targets {
                    for &a in angles {
                        let zenith_deg = if down { 180.0 - a } else { a };
                        if h == o {
                            t.transmission.extend(std::iter::repeat_n(1.0, n));
                            t.path_radiance_w_m2_sr_per_unit
                                .extend(std::iter::repeat_n(0.0, n));
                            t.scattered_w_m2_sr_per_unit
                                .extend(std::iter::repeat_n(0.0, n * azimuths.len()));
                            continue;
                        }
                        let run = get(Path::Slab {
                            observer_m: o,
                            target_m: h,
                            zenith_deg,
                        });
                        t.transmission.extend(f32s(&run.transmission, true));
                        t.path_radiance_w_m2_sr_per_unit
                            .extend(f32s(&run.radiance_w_m2_sr_per_cm, false));
                        for &azimuth_deg in azimuths {
                            let lit = get(Path::SlabSunlit {
                                observer_m: o,
                                target_m: h,
                                zenith_deg,
                                azimuth_deg,
                            });
                            t.scattered_w_m2_sr_per_unit
                                .extend(f32s(&lit.scattered_w_m2_sr_per_cm, false));
                        }
                    }
                }
                t
            })
        });
        if down.is_some() || up.is_some() {
            out.push(SpectralSlab {
                observer_m: o,
                down,
                up,
            });
        }
    }
    out
}
