//! A camera below the ground, `z < 0`: traced, with a warning, not refused.
//!
//! The ground is the plane `z = 0`: the atmosphere's altitudes are metres above it and the
//! terrain beyond the scene lies in it. A camera below it is traced as if at 0 m: its
//! paths and sky are the ground's, and a ray that leaves the scene downward meets the
//! terrain at no distance. That is right for a camera in a pit, a trench or a quarry the
//! scene models with facets below 0 (its rays meet those facets, and the sky above them is
//! the ground's to within the few metres' air), which is why it is not refused; under open
//! ground it is a view given in the wrong frame or with the wrong sign, which is why it is
//! said.

use irsig_model::View;

/// The warning for the views of `views` whose camera is below the ground (`None` when
/// none is), numbering them from `first` + 1 as the frames are numbered.
pub(crate) fn below_ground(views: &[View], first: usize) -> Option<String> {
    let below: Vec<(usize, f64)> = views
        .iter()
        .enumerate()
        .map(|(i, v)| (first + i + 1, v.position_m()[2]))
        .filter(|&(_, z)| z < 0.0)
        .collect();
    let &(view, z) = below.iter().min_by(|a, b| a.1.total_cmp(&b.1))?;
    let which = if below.len() == 1 {
        format!("view {view} puts the camera {:.3} m below the ground", -z)
    } else {
        format!(
            "{} views put the camera below the ground, view {view} the lowest, {:.3} m",
            below.len(),
            -z
        )
    };
    Some(format!(
        "{which} (z = 0, the terrain's plane; z is metres above it): it is traced as if at \
         0 m, its paths and sky the ground's, and a ray that leaves the scene downward meets \
         the terrain at no distance. Right for a camera in a pit the scene models with \
         facets below 0; otherwise check the view's height"
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn at(z: f64) -> View {
        View::LookAt {
            position_m: [0.0, 0.0, z],
            target_m: [0.0, 10.0, 0.0],
            up: [0.0, 0.0, 1.0],
            pixels: [4, 4],
            fov_deg: [10.0, 10.0],
            gain_dc_per_k: None,
        }
    }

    #[test]
    fn only_a_camera_below_the_ground_is_warned_about() {
        // On the ground and above it: nothing to say.
        assert_eq!(below_ground(&[at(0.0), at(1.5), at(1e4)], 0), None);
        assert_eq!(below_ground(&[], 0), None);
        // 2.5 m below: said, with the frame's number (the third of a run's views).
        let one = below_ground(&[at(-2.5)], 2).unwrap();
        assert!(
            one.starts_with("view 3 puts the camera 2.500 m below the ground"),
            "{one}"
        );
        // A millimetre below is below.
        assert!(
            below_ground(&[at(-1e-3)], 0)
                .unwrap()
                .contains("0.001 m below")
        );
        // Several: counted once, the lowest named.
        let many = below_ground(&[at(-1.0), at(5.0), at(-7.25), at(-0.5)], 0).unwrap();
        assert!(
            many.starts_with("3 views put the camera below the ground, view 3 the lowest, 7.250 m"),
            "{many}"
        );
    }
}
