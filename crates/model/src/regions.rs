use serde::{Deserialize, Serialize};

use crate::error::{ModelError, ModelErrorKind, check_range};
use crate::material::MaterialId;

/// Regions of interest in a traced image, with reference temperatures to compare against:
/// what `irsig-stats` reads (`formats/canonical/regions.md`). The thesis's Tables 5–7
/// (§4.8–5.1) are local-area averages over such regions.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RegionSet {
    /// The reference columns the regions may give values for, in the order they are
    /// reported; each names its source.
    #[serde(default)]
    pub references: Vec<ReferenceColumn>,
    /// The regions, reported in this order.
    pub regions: Vec<Region>,
}

/// One column of reference temperatures (a measurement, another model, a paper's table).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ReferenceColumn {
    /// Short name, unique in the file (`thesis_synthetic`); used as a column heading.
    pub name: String,
    /// Where the values come from.
    #[serde(default)]
    pub source: String,
}

/// A region: the pixels inside `pixels` (when given) whose primary material is `material`
/// (when given). At least one of the two is given.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Region {
    /// The region's name, unique in the file (`Left Pool`).
    pub name: String,
    /// Only pixels whose primary ray hit this material.
    #[serde(default)]
    pub material: Option<MaterialId>,
    /// Only pixels inside this box.
    #[serde(default)]
    pub pixels: Option<PixelBox>,
    /// Reference temperatures of this region, each for one of the file's reference
    /// columns; a column a region does not mention is left empty.
    #[serde(default)]
    pub references: Vec<ReferenceValue>,
}

/// An axis-aligned box of pixels, inclusive at both ends; pixel (0, 0) is the top-left
/// and rows run down (as every irsig image).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PixelBox {
    /// First and last column, inclusive.
    pub columns: (u32, u32),
    /// First and last row, inclusive.
    pub rows: (u32, u32),
}

/// A reference temperature for one region in one reference column.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ReferenceValue {
    /// The reference column (one of [`RegionSet::references`]).
    pub name: String,
    /// The temperature, K.
    pub temperature_k: f64,
}

impl PixelBox {
    /// Whether pixel (`column`, `row`) lies inside the box.
    #[must_use]
    pub fn contains(&self, column: u32, row: u32) -> bool {
        (self.columns.0..=self.columns.1).contains(&column)
            && (self.rows.0..=self.rows.1).contains(&row)
    }
}

impl RegionSet {
    /// Checks that there is at least one region; names are unique; every region selects by
    /// material, box or both; boxes are not inverted; material ids are not 0; reference
    /// values name a declared column at most once and are finite temperatures ≥ 0 K.
    ///
    /// # Errors
    /// The first rule broken, with its path (`regions[2].references[0].temperature_k`).
    pub fn validate(&self) -> Result<(), ModelError> {
        let mut columns = std::collections::HashSet::new();
        for (i, c) in self.references.iter().enumerate() {
            if c.name.trim().is_empty() {
                return Err(ModelError::new(
                    format!("references[{i}].name"),
                    ModelErrorKind::Other("a reference column needs a name".into()),
                ));
            }
            printable(format!("references[{i}].name"), &c.name)?;
            if !columns.insert(c.name.as_str()) {
                return Err(ModelError::new(
                    format!("references[{i}].name"),
                    ModelErrorKind::Duplicate(c.name.clone()),
                ));
            }
        }
        if self.regions.is_empty() {
            return Err(ModelError::new("regions", ModelErrorKind::Empty));
        }
        let mut names = std::collections::HashSet::new();
        for (i, r) in self.regions.iter().enumerate() {
            let prefix = format!("regions[{i}]");
            if r.name.trim().is_empty() {
                return Err(ModelError::new(
                    format!("{prefix}.name"),
                    ModelErrorKind::Other("a region needs a name".into()),
                ));
            }
            printable(format!("{prefix}.name"), &r.name)?;
            if !names.insert(r.name.as_str()) {
                return Err(ModelError::new(
                    format!("{prefix}.name"),
                    ModelErrorKind::Duplicate(r.name.clone()),
                ));
            }
            if r.material.is_none() && r.pixels.is_none() {
                return Err(ModelError::new(
                    prefix,
                    ModelErrorKind::Other(
                        "a region selects by `material`, by `pixels` or both; it gives neither"
                            .into(),
                    ),
                ));
            }
            if r.material == Some(MaterialId(0)) {
                return Err(ModelError::new(
                    format!("{prefix}.material"),
                    ModelErrorKind::Other("material id 0 is reserved for \"nothing hit\"".into()),
                ));
            }
            if let Some(b) = r.pixels {
                for (axis, (first, last)) in [("columns", b.columns), ("rows", b.rows)] {
                    if last < first {
                        return Err(ModelError::new(
                            format!("{prefix}.pixels.{axis}"),
                            ModelErrorKind::NotIncreasing {
                                previous: f64::from(first),
                                value: f64::from(last),
                            },
                        ));
                    }
                }
            }
            let mut seen = std::collections::HashSet::new();
            for (j, v) in r.references.iter().enumerate() {
                let path = format!("{prefix}.references[{j}]");
                if !columns.contains(v.name.as_str()) {
                    return Err(ModelError::new(
                        format!("{path}.name"),
                        ModelErrorKind::Other(format!(
                            "`{}` is not a declared reference column (declared: {})",
                            v.name,
                            declared(&self.references)
                        )),
                    ));
                }
                if !seen.insert(v.name.as_str()) {
                    return Err(ModelError::new(
                        format!("{path}.name"),
                        ModelErrorKind::Duplicate(v.name.clone()),
                    ));
                }
                check_range(
                    || format!("{path}.temperature_k"),
                    v.temperature_k,
                    0.0,
                    f64::MAX,
                )?;
            }
        }
        Ok(())
    }

    /// The value of reference column `name` for region `region`, if it gives one.
    #[must_use]
    pub fn reference(region: &Region, name: &str) -> Option<f64> {
        region
            .references
            .iter()
            .find(|v| v.name == name)
            .map(|v| v.temperature_k)
    }
}

fn declared(columns: &[ReferenceColumn]) -> String {
    if columns.is_empty() {
        return "none".into();
    }
    columns
        .iter()
        .map(|c| format!("`{}`", c.name))
        .collect::<Vec<_>>()
        .join(", ")
}

/// A name printed in tables, CSV, RON and the run report holds no control character (a
/// NUL, a newline ...), which would cut or forge a row of them.
fn printable(path: String, name: &str) -> Result<(), ModelError> {
    match name.chars().find(|c| c.is_control()) {
        None => Ok(()),
        Some(c) => Err(ModelError::new(
            path,
            ModelErrorKind::Other(format!(
                "a name holds the control character U+{:04X}: it is printed in tables, CSV \
                 and the report",
                u32::from(c)
            )),
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn region(name: &str) -> Region {
        Region {
            name: name.into(),
            material: Some(MaterialId(1)),
            pixels: None,
            references: vec![],
        }
    }

    fn set(regions: Vec<Region>) -> RegionSet {
        RegionSet {
            references: vec![ReferenceColumn {
                name: "thesis".into(),
                source: "test".into(),
            }],
            regions,
        }
    }

    #[test]
    fn a_valid_set_passes_and_boxes_are_inclusive() {
        let mut r = region("a");
        r.pixels = Some(PixelBox {
            columns: (2, 4),
            rows: (7, 7),
        });
        r.references.push(ReferenceValue {
            name: "thesis".into(),
            temperature_k: 273.15,
        });
        let s = set(vec![r.clone()]);
        assert_eq!(s.validate(), Ok(()));
        let b = r.pixels.unwrap();
        assert!(b.contains(2, 7) && b.contains(4, 7));
        assert!(!b.contains(5, 7) && !b.contains(3, 6) && !b.contains(1, 7));
        assert_eq!(RegionSet::reference(&r, "thesis"), Some(273.15));
        assert_eq!(RegionSet::reference(&r, "other"), None);
    }

    #[test]
    fn a_control_character_in_a_name_is_refused() {
        // A NUL inside a region name went into the tables, the CSV and the report.
        let e = set(vec![region("Left\0Pool")]).validate().unwrap_err();
        assert_eq!(e.path, "regions[0].name", "{e}");
        let e = set(vec![region("a"), region("b\nc")])
            .validate()
            .unwrap_err();
        assert_eq!(e.path, "regions[1].name", "{e}");
        let mut s = set(vec![region("a")]);
        s.references[0].name = "thesis\r".into();
        assert_eq!(s.validate().unwrap_err().path, "references[0].name");
    }

    #[test]
    fn every_rule_names_its_place() {
        assert_eq!(set(vec![]).validate().unwrap_err().path, "regions");
        assert_eq!(
            set(vec![region("a"), region("a")])
                .validate()
                .unwrap_err()
                .path,
            "regions[1].name"
        );
        let mut neither = region("a");
        neither.material = None;
        assert_eq!(
            set(vec![neither]).validate().unwrap_err().path,
            "regions[0]"
        );
        let mut zero = region("a");
        zero.material = Some(MaterialId(0));
        assert_eq!(
            set(vec![zero]).validate().unwrap_err().path,
            "regions[0].material"
        );
        let mut inverted = region("a");
        inverted.pixels = Some(PixelBox {
            columns: (0, 9),
            rows: (5, 4),
        });
        assert_eq!(
            set(vec![inverted]).validate().unwrap_err().path,
            "regions[0].pixels.rows"
        );
        let mut undeclared = region("a");
        undeclared.references.push(ReferenceValue {
            name: "nope".into(),
            temperature_k: 300.0,
        });
        assert_eq!(
            set(vec![undeclared]).validate().unwrap_err().path,
            "regions[0].references[0].name"
        );
        for bad in [f64::NAN, f64::INFINITY, -1.0] {
            let mut r = region("a");
            r.references.push(ReferenceValue {
                name: "thesis".into(),
                temperature_k: bad,
            });
            assert_eq!(
                set(vec![r]).validate().unwrap_err().path,
                "regions[0].references[0].temperature_k"
            );
        }
    }
}
