//! `irsig-atmos plan --loads`: the LOWTRAN7 runs of a day's broadband thermal loads at the
//! ground (`irsig_atmosphere::loads`): for each sun zenith angle of `--sun-zeniths-deg`
//! on `--day-of-year`, the direct beam and the diffuse sky, and once the sky's longwave;
//! with the model, radiosonde, aerosol and name flags of an atmosphere plan, and the
//! ground's albedo. No scene and no view: the loads are the ground's. Written as an
//! atmosphere plan is, a directory (`plan.ron`, `runs/NNNN.tape5`) or a plan file alone;
//! `irsig-atmos build` tells the two kinds of plan apart and writes the loads table.

use std::path::PathBuf;

use irsig_atmosphere::loads::{add_aerosol, deck, make_loads_plan, paths, set_ground_albedo};
use irsig_formats::canonical;
use irsig_formats::radtran::tape5;
use miette::{IntoDiagnostic, miette};

use crate::plan::{PlanArgs, aerosol_of, deck_name, model_of, plan_file_only, write_dir_atomic};

/// `--sun-zeniths-deg`: the sun's zenith angles, degrees.
#[derive(Debug, Clone, PartialEq)]
pub struct SunZeniths(pub Vec<f64>);

/// `--sun-zeniths-deg`: comma-separated items, each a value or an inclusive range
/// `from:to:step` (`irsig_cli::args::values`' forms), every angle from 0 to below 90.
pub(crate) fn sun_zeniths(s: &str) -> Result<SunZeniths, String> {
    let mut out = Vec::new();
    for item in s.split(',') {
        let v = irsig_cli::args::values("--sun-zeniths-deg", item).map_err(|e| e.to_string())?;
        out.extend(v);
    }
    if let Some(z) = out.iter().find(|z| !(**z >= 0.0 && **z < 90.0)) {
        return Err(format!(
            "the sun at {z} deg from the zenith is at or below the horizon and gives no direct \
             light: expected angles from 0 to below 90 deg (89.999 at most, the last a deck \
             holds; a day's last row near the horizon is 89 or 89.9)"
        ));
    }
    if out.is_empty() {
        return Err("expected at least one zenith angle".into());
    }
    Ok(SunZeniths(out))
}

/// Runs `irsig-atmos plan --loads`.
///
/// # Errors
/// A flag the plan refuses (a zenith angle at or below the horizon, no day); an unknown
/// model or an unreadable radiosonde; an output directory that exists and is not empty.
pub(crate) fn run(a: &PlanArgs) -> miette::Result<()> {
    let output = a.output.required()?;
    irsig_cli::refuse_output_is_input(a.radiosonde.iter(), [output])?;
    let aerosol = aerosol_of(a.aerosol.as_deref(), a.visibility_km, a.wind_speed_m_s)?;
    // clap requires both with --loads.
    let (Some(zeniths), Some(day)) = (&a.sun_zeniths_deg, a.day_of_year.day) else {
        return Err(irsig_cli::usage_error(
            "--loads needs --sun-zeniths-deg LIST and --day-of-year D",
        ));
    };
    let (model, default_name) = model_of(a.atmosphere.given(), a.radiosonde.as_deref())?;
    let name = a.name.value.clone().unwrap_or(default_name);
    let mut plan = make_loads_plan(&name, model, day, &zeniths.0)
        .map_err(|e| irsig_cli::usage_error(format!("--sun-zeniths-deg: {e}")))?;
    if let Some(aer) = aerosol {
        add_aerosol(&mut plan, aer)
            .map_err(|e| irsig_cli::usage_error(format!("--aerosol: {e}")))?;
    }
    if let Some(albedo) = a.ground_albedo.value {
        set_ground_albedo(&mut plan, albedo)
            .map_err(|e| irsig_cli::usage_error(format!("--ground-albedo: {e}")))?;
    }
    let plan_text = canonical::to_ron(&plan).into_diagnostic()?;
    let all = paths(&plan);
    let mut files = vec![(PathBuf::from("plan.ron"), plan_text.clone().into_bytes())];
    for (i, p) in all.iter().enumerate() {
        let d = deck(&plan, p).map_err(|e| miette!("{e}"))?;
        let text = tape5::write(&d).map_err(|e| miette!("deck of path {i}: {e}"))?;
        files.push((deck_name(i), text.into_bytes()));
    }
    if plan_file_only(output) {
        irsig_cli::write_output(Some(output), |w: &mut dyn std::io::Write| {
            w.write_all(plan_text.as_bytes())
        })?;
    } else {
        write_dir_atomic(output, &files)?;
    }
    let sky: Vec<usize> = plan.sun.iter().map(|s| s.diffuse.len()).collect();
    let (fewest, most) = (
        sky.iter().min().copied().unwrap_or(0),
        sky.iter().max().copied().unwrap_or(0),
    );
    let lines = if fewest == most {
        format!("{most}")
    } else {
        format!("{fewest} to {most}")
    };
    let zs: Vec<String> = plan
        .sun
        .iter()
        .map(|s| format!("{}", s.zenith_deg))
        .collect();
    irsig_cli::note!(
        "{}: {} paths: the sky's longwave along {} lines of sight, and for each sun ({} deg \
         from the zenith) on day {} its direct beam and the diffuse sky along {lines} lines of \
         sight; {}, ground albedo {}",
        output.display(),
        all.len(),
        plan.longwave.len(),
        zs.join(", "),
        plan.day_of_year,
        plan.aerosol.as_ref().map_or_else(
            || "no aerosol".to_owned(),
            |x| format!(
                "{} aerosol, visibility {} km",
                x.model.name(),
                x.visibility_m / 1000.0
            )
        ),
        plan.ground_albedo
    );
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn zeniths_are_values_and_ranges_below_the_horizon() {
        assert_eq!(
            sun_zeniths("20:35:5,89.9").unwrap(),
            SunZeniths(vec![20.0, 25.0, 30.0, 35.0, 89.9])
        );
        assert_eq!(sun_zeniths("0").unwrap(), SunZeniths(vec![0.0]));
        for (bad, says) in [
            ("80:90:5", "horizon"),
            ("-1", "horizon"),
            ("30,x", "finite number"),
            ("", "finite number"),
            ("30:20:5", "ends before it starts"),
        ] {
            let e = sun_zeniths(bad).unwrap_err();
            assert!(e.contains(says), "{bad}: {e}");
        }
    }
}
