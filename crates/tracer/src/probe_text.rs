//! A probed pixel as text ([`Sample`]'s `Display`, what `--probe` prints), and how its
//! numbers are printed: Rust's `{}` never uses an exponent, so a τ of 1e-300 (an opaque
//! path) would print as three hundred zeros. A number whose magnitude is below 1e-4 or from 1e16 up is printed in scientific
//! notation (`1.5e-300`), every other one as `{}` prints it; both are the shortest text
//! that reads back as the same `f64`.

use std::fmt;

use crate::tracer::Sample;

/// Magnitudes below this (but not 0) are printed with an exponent.
const SMALL: f64 = 1e-4;
/// Magnitudes from this up are printed with an exponent.
const LARGE: f64 = 1e16;

/// A number as the probe prints it.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Shown(pub(crate) f64);

impl fmt::Display for Shown {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let x = self.0;
        let magnitude = x.abs();
        if x.is_finite() && x != 0.0 && !(SMALL..LARGE).contains(&magnitude) {
            write!(f, "{x:e}")
        } else {
            write!(f, "{x}")
        }
    }
}

impl fmt::Display for Sample {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let facet = self
            .facet
            .map_or_else(|| "none".to_owned(), |i| i.to_string());
        writeln!(
            f,
            "event                      {} ({:?})",
            self.event.number(),
            self.event
        )?;
        writeln!(
            f,
            "facet                      {facet}{}",
            if self.back_face { " (back face)" } else { "" }
        )?;
        writeln!(f, "primary material           {}", self.primary_material)?;
        writeln!(f, "secondary material         {}", self.secondary_material)?;
        writeln!(f, "range_m                    {}", Shown(self.range_m))?;
        writeln!(
            f,
            "incidence_deg              {}",
            Shown(self.incidence_deg())
        )?;
        writeln!(
            f,
            "kinetic temperature_k      {}",
            Shown(self.temperature_k)
        )?;
        writeln!(f, "emissivity ε               {}", Shown(self.emissivity))?;
        writeln!(f, "reflectance r = 1 − ε      {}", Shown(self.reflectance))?;
        writeln!(
            f,
            "specular fraction s        {}",
            Shown(self.specular_fraction)
        )?;
        writeln!(
            f,
            "L_T (W m-2 sr-1)           {}",
            Shown(self.blackbody_w_m2_sr)
        )?;
        writeln!(
            f,
            "reflected zenith_deg       {}",
            Shown(self.reflected_zenith_deg)
        )?;
        writeln!(
            f,
            "L_spec = L_b or L_d(θr)    {}",
            Shown(self.specular_incident_w_m2_sr)
        )?;
        writeln!(
            f,
            "L_d hemispheric            {}",
            Shown(self.sky_hemispheric_w_m2_sr)
        )?;
        writeln!(
            f,
            "sky-view factor F          {}",
            Shown(self.sky_view_factor)
        )?;
        writeln!(
            f,
            "F·L_d + (1 − F)·L_b        {}",
            Shown(self.diffuse_incident_w_m2_sr)
        )?;
        writeln!(
            f,
            "surface-leaving L(0,θ)     {}",
            Shown(self.surface_leaving_w_m2_sr)
        )?;
        writeln!(f, "τ                          {}", Shown(self.transmission))?;
        writeln!(
            f,
            "L_u (W m-2 sr-1)           {}",
            Shown(self.path_radiance_w_m2_sr)
        )?;
        writeln!(
            f,
            "L at sensor (W m-2 sr-1)   {}",
            Shown(self.radiance_w_m2_sr)
        )?;
        writeln!(
            f,
            "dL/dT_kinetic              {}",
            Shown(self.temperature_sensitivity)
        )?;
        write!(
            f,
            "dL/dε                      {}",
            Shown(self.emissivity_sensitivity)
        )?;
        if self.sun_share.is_nan() {
            return Ok(());
        }
        writeln!(f)?;
        writeln!(
            f,
            "sun: E (W m-2)             {}",
            Shown(self.solar_irradiance_w_m2)
        )?;
        writeln!(
            f,
            "sun: visible fraction V    {}",
            Shown(self.sun_visible_fraction)
        )?;
        writeln!(
            f,
            "sun: reflected (W m-2 sr-1) {}",
            Shown(self.reflected_solar_w_m2_sr)
        )?;
        write!(f, "sun: share of L            {}", Shown(self.sun_share))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tiny_and_huge_numbers_are_printed_with_an_exponent() {
        let shown = |x: f64| Shown(x).to_string();
        assert_eq!(shown(1e-300), "1e-300");
        assert_eq!(shown(-2.5e-7), "-2.5e-7");
        assert_eq!(shown(9.99e-5), "9.99e-5");
        assert_eq!(shown(f64::MIN_POSITIVE), "2.2250738585072014e-308");
        assert_eq!(shown(5e-324), "5e-324");
        assert_eq!(shown(3e20), "3e20");
        // From 1e-4 up to 1e16 as `{}` prints them; 0, NaN and infinities as they are.
        assert_eq!(shown(1e-4), "0.0001");
        assert_eq!(shown(0.5), "0.5");
        assert_eq!(shown(273.15), "273.15");
        assert_eq!(shown(0.0), "0");
        assert_eq!(shown(f64::NAN), "NaN");
        assert_eq!(shown(f64::INFINITY), "inf");
        // Every text reads back as the same number, and none is longer than 24 characters.
        for x in [1e-300, 1.234_567_890_123e-9, 0.123_456_789, 1e-4, 6.02e23] {
            let text = shown(x);
            assert_eq!(
                text.parse::<f64>().unwrap().to_bits(),
                x.to_bits(),
                "{text}"
            );
            assert!(text.len() <= 24, "{text}");
        }
    }
}
