//! Provenance along the whole chain: what the images record of their making (every input
//! the trace and the sensor read, by stage, role and SHA-256: `irsig_model::provenance`, in
//! the EXRs' comments), the report's own inputs, and, when a pipeline file is given, its
//! files as they are now. Each recorded input is matched by content to a file the report
//! knows, so that the page names the file an image was made from, or says that no file it
//! knows holds that content any more.

use irsig_model::provenance::{InputRecord, Provenance};

/// The role the tracer gives a built-in atmosphere's spectra, which no file holds.
const BUILTIN_ATMOSPHERE_ROLE: &str = "atmosphere (a built-in's spectra)";

/// A file whose content the report has read: one of its inputs or a file of the pipeline.
#[derive(Debug, Clone)]
pub struct Known {
    /// Its name on the page (relative to the report).
    pub shown: String,
    /// `sha256:` and 64 hex digits.
    pub sha256: String,
}

/// One input of the chain as the page lists it.
#[derive(Debug, Clone)]
pub struct Row {
    /// The stage that read it: `trace`, `sensor`, `report`.
    pub stage: String,
    /// What it was to that stage.
    pub role: String,
    /// The file with that content, `built in: NAME`, or `None` when no known file has it.
    pub file: Option<String>,
    /// Hex digits of its SHA-256.
    pub sha256_hex: String,
    /// Which images record it (`truth EXR`, `radiance EXR`), or `this page`.
    pub recorded_in: String,
}

/// What the images record, merged.
#[derive(Debug, Clone, Default)]
pub struct Recorded {
    /// Each input once, with the images that record it.
    pub inputs: Vec<(InputRecord, Vec<&'static str>)>,
    /// The band, sub-bands and atmosphere, from the first image that records them.
    pub summary: Option<Provenance>,
    /// The trace's inputs differ between the two images: they are not from one run.
    pub disagree: Option<String>,
}

/// Merges the records of the truth EXR and the radiance image.
#[must_use]
pub fn merge(truth: Option<&Provenance>, radiance: Option<&Provenance>) -> Recorded {
    let mut out = Recorded::default();
    for (image, p) in [("truth EXR", truth), ("radiance EXR", radiance)] {
        let Some(p) = p else { continue };
        if out.summary.is_none() {
            out.summary = Some(p.clone());
        }
        for input in &p.inputs {
            match out.inputs.iter_mut().find(|(r, _)| r == input) {
                Some((_, images)) => images.push(image),
                None => out.inputs.push((input.clone(), vec![image])),
            }
        }
    }
    if let (Some(t), Some(r)) = (truth, radiance) {
        let trace = |p: &Provenance| -> Vec<InputRecord> {
            p.inputs
                .iter()
                .filter(|i| i.stage == "trace")
                .cloned()
                .collect()
        };
        let (a, b) = (trace(t), trace(r));
        if a != b {
            let only = |x: &[InputRecord], y: &[InputRecord]| -> Vec<String> {
                x.iter()
                    .filter(|i| !y.contains(i))
                    .map(|i| i.role.clone())
                    .collect()
            };
            let mut roles = only(&a, &b);
            for role in only(&b, &a) {
                if !roles.contains(&role) {
                    roles.push(role);
                }
            }
            out.disagree = Some(roles.join(", "));
        }
    }
    out
}

/// The page's rows: every recorded input, matched by content to a known file, then the
/// report's own inputs.
#[must_use]
pub fn rows(recorded: &Recorded, known: &[Known], own: &[(String, Known)]) -> Vec<Row> {
    let atmosphere = recorded
        .summary
        .as_ref()
        .map_or_else(String::new, |p| p.atmosphere.clone());
    let mut rows: Vec<Row> = recorded
        .inputs
        .iter()
        .map(|(input, images)| {
            let file = if input.role == BUILTIN_ATMOSPHERE_ROLE {
                Some(format!("built in: {atmosphere}"))
            } else {
                known
                    .iter()
                    .chain(own.iter().map(|(_, k)| k))
                    .find(|k| k.sha256 == input.sha256)
                    .map(|k| k.shown.clone())
            };
            Row {
                stage: input.stage.clone(),
                role: input.role.clone(),
                file,
                sha256_hex: hex(&input.sha256),
                recorded_in: images.join(", "),
            }
        })
        .collect();
    rows.extend(own.iter().map(|(role, k)| Row {
        stage: "report".into(),
        role: role.clone(),
        file: Some(k.shown.clone()),
        sha256_hex: hex(&k.sha256),
        recorded_in: "this page".into(),
    }));
    rows
}

/// The recorded inputs no known file holds (a built-in atmosphere aside): `stage: role`.
#[must_use]
pub fn unmatched(rows: &[Row]) -> Vec<String> {
    rows.iter()
        .filter(|r| r.file.is_none())
        .map(|r| format!("{}: {}", r.stage, r.role))
        .collect()
}

/// The hex digits of a `sha256:` digest.
#[must_use]
pub fn hex(sha256: &str) -> String {
    sha256.strip_prefix("sha256:").unwrap_or(sha256).to_owned()
}

#[cfg(test)]
mod tests {
    use super::*;
    use irsig_model::provenance::BandRecord;

    fn record(stage: &str, role: &str, sha: &str) -> InputRecord {
        InputRecord {
            stage: stage.into(),
            role: role.into(),
            sha256: format!("sha256:{sha}"),
        }
    }

    fn provenance(inputs: Vec<InputRecord>) -> Provenance {
        Provenance {
            band: BandRecord::Flat {
                min_um: 8.0,
                max_um: 14.0,
            },
            sub_bands: "1".into(),
            atmosphere: "us-std-1976".into(),
            atmosphere_model: "table".into(),
            inputs,
            sun: None,
        }
    }

    #[test]
    fn the_chain_is_matched_by_content_and_a_second_run_is_noticed() {
        let trace = vec![
            record("trace", "scene", "aa"),
            record("trace", BUILTIN_ATMOSPHERE_ROLE, "bb"),
            record("trace", "materials", "cc"),
        ];
        let truth = provenance(trace.clone());
        let mut sensed = trace.clone();
        sensed.push(record("sensor", "radiance EXR", "dd"));
        let radiance = provenance(sensed);
        let merged = merge(Some(&truth), Some(&radiance));
        assert_eq!(merged.inputs.len(), 4);
        assert_eq!(merged.inputs[0].1, ["truth EXR", "radiance EXR"]);
        assert_eq!(merged.inputs[3].1, ["radiance EXR"]);
        assert!(merged.disagree.is_none());
        let known = [Known {
            shown: "scene.raw".into(),
            sha256: "sha256:aa".into(),
        }];
        let own = [(
            "LUT".to_owned(),
            Known {
                shown: "lut.txt".into(),
                sha256: "sha256:ee".into(),
            },
        )];
        let rows = rows(&merged, &known, &own);
        assert_eq!(rows[0].file.as_deref(), Some("scene.raw"));
        assert_eq!(rows[1].file.as_deref(), Some("built in: us-std-1976"));
        assert_eq!(rows[0].sha256_hex, "aa");
        assert_eq!(rows[4].stage, "report");
        assert_eq!(
            unmatched(&rows),
            ["trace: materials", "sensor: radiance EXR"]
        );

        // A radiance image traced from other materials.
        let other = provenance(vec![
            record("trace", "scene", "aa"),
            record("trace", BUILTIN_ATMOSPHERE_ROLE, "bb"),
            record("trace", "materials", "c2"),
        ]);
        let merged = merge(Some(&truth), Some(&other));
        assert_eq!(merged.disagree.as_deref(), Some("materials"));
    }
}
