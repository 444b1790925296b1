//! The page, section by section, from a report's inputs read and checked
//! ([`crate::read::Run`]): warnings first, then the image, the pixels the counts clip, the
//! histogram, the profile, the regions, the decision, the error budget and the LUT, each
//! left out with one line naming the flag that would fill it, and provenance last. Every
//! part is a maud template: text and attribute values are escaped by construction, and
//! only the style sheet and plotters' SVG go in as they are.

use maud::{DOCTYPE, Markup, PreEscaped, html};

use super::*;
use crate::read::Run;

/// The whole page of `run`, titled `title`.
///
/// # Errors
/// A plot that cannot be drawn.
pub(crate) fn page(title: &str, run: &Run) -> miette::Result<String> {
    let (lo, hi) = extremes(&run.values);
    let range = run.range;
    // What is left out, and the flag that would put it in: one line.
    let mut not_shown: Vec<&str> = Vec::new();
    let profile = match &run.profile {
        Some((line, points)) => Some(profile_section(line, points)?),
        None => {
            not_shown.push("a line profile (--profile X0,Y0:X1,Y1)");
            None
        }
    };
    let regions = match &run.regions {
        Some((table, _)) => Some(html! {
            section id="regions" { h2 { "Per-region statistics" } (stats_table(table)) }
        }),
        None => {
            not_shown.push("per-region statistics (the truth EXR and --regions FILE)");
            None
        }
    };
    let decision = match &run.decision {
        Some(d) => Some(html! {
            section id="decision" { h2 { "The tolerance pilot's decision" } (decision_table(d)) }
        }),
        None => {
            not_shown.push(
                "the tolerance pilot's decision (trace with --tolerance K, then --decision FILE)",
            );
            None
        }
    };
    let budget = budget_section(run)?;
    if budget.is_none() {
        not_shown
            .push("the error budget (trace with --uncertainties FILE, then give its truth EXR)");
    }
    let lut = lut_section(run)?;
    if lut.is_none() {
        not_shown.push("the LUT and the counts it clips (--lut FILE)");
    }
    let image = image_section(run, (lo, hi))?;
    let histogram = plots::histogram(&run.values, range, HISTOGRAM_BINS)?;
    let page = html! {
        (DOCTYPE)
        html lang="en" {
            head {
                meta charset="utf-8";
                title { "irsig report: " (title) }
                style { (PreEscaped(STYLE)) }
            }
            body {
                h1 { "irsig report: " (title) }
                (warnings(run, (lo, hi)))
                (image)
                (saturation_section(run, (lo, hi)))
                section id="histogram" {
                    h2 { "Histogram of apparent temperature" }
                    p {
                        (HISTOGRAM_BINS) " bins of "
                        (format!("{:.4}", (range.1 - range.0) / HISTOGRAM_BINS as f64)) " K."
                    }
                    div class="figure" { (PreEscaped(histogram)) }
                }
                @if let Some(m) = profile { (m) }
                @if let Some(m) = regions { (m) }
                @if let Some(m) = decision { (m) }
                @if let Some(m) = budget { (m) }
                @if let Some(m) = lut { (m) }
                @if !not_shown.is_empty() {
                    p class="absent" id="not-shown" { "Not shown: " (not_shown.join("; ")) "." }
                }
                (provenance_section(
                    &run.recorded,
                    &run.chain_rows,
                    run.pipeline.as_ref(),
                    &run.commands,
                ))
            }
        }
    };
    Ok(page.into_string())
}

/// The line profile's chart, from the pixels along `line`.
fn profile_section(line: &ProfileLine, points: &[(f64, f64)]) -> miette::Result<Markup> {
    let chart = plots::line_chart(
        "line profile",
        points,
        "distance from the start (pixels)",
        "apparent temperature (K)",
    )?;
    Ok(html! {
        section id="profile" {
            h2 { "Line profile" }
            p {
                "From pixel (" (line.from.0) ", " (line.from.1) ") to (" (line.to.0) ", "
                (line.to.1) "), " (points.len()) " pixels (the line on the image above)."
            }
            div class="figure" { (PreEscaped(chart)) }
        }
    })
}

/// The warnings, first, where nobody can miss them: clipped counts, images from different
/// runs, inputs the pipeline no longer holds.
fn warnings(run: &Run, (lo, hi): (f64, f64)) -> Markup {
    let mut warnings: Vec<(&str, String)> = Vec::new();
    if let (Some(s), Some((_, rows))) = (&run.saturated, &run.lut)
        && s.at_zero + s.at_full > 0
    {
        warnings.push((
            "saturation-warning",
            format!(
                "Saturated counts: {} pixels ({} %) are at full scale, count {}, and {} ({} %) \
                 at count 0; their counts do not tell their temperatures. The LUT spans \
                 {:.2}-{:.2} K, the image {lo:.2}-{hi:.2} K: give the sensor fewer counts per \
                 kelvin (--dc-per-kelvin), more bits (--dc-bits) or a fixed calibration \
                 (--reference-k) whose counts cover the scene.",
                s.at_full,
                percent(s.at_full, s.pixels),
                s.full_count,
                s.at_zero,
                percent(s.at_zero, s.pixels),
                rows[0].temperature_k,
                rows[rows.len() - 1].temperature_k,
            ),
        ));
    }
    if let Some(roles) = &run.recorded.disagree {
        warnings.push((
            "chain-warning",
            format!(
                "The truth EXR and the radiance image record different inputs of the trace \
                 ({roles}): they are not from one run, and statistics that pair the one's \
                 materials with the other's values mean nothing."
            ),
        ));
    }
    if run.pipeline.is_some() {
        let stale = chain::unmatched(&run.chain_rows);
        if !stale.is_empty() {
            warnings.push((
                "stale-warning",
                format!(
                    "The images were made from inputs that no file of the pipeline holds now \
                     ({}): the pipeline's files changed since; run it again.",
                    stale.join(", ")
                ),
            ));
        }
    }
    html! {
        @if !warnings.is_empty() {
            div id="warnings" {
                @for (id, text) in &warnings {
                    p class="warning" id=(id) role="alert" { (text) }
                }
            }
        }
    }
}

/// The colour image, the profile's line on it, and its scale.
fn image_section(run: &Run, (lo, hi): (f64, f64)) -> miette::Result<Markup> {
    let (width, height) = (run.width, run.height);
    let scale = display_scale(height);
    let bar = plots::colour_bar(run.range, "apparent temperature (K)")?;
    let colour = false_colour(&run.values, width, height, run.range);
    Ok(html! {
        section id="image" {
            h2 { "Apparent temperature" }
            p {
                (run.shown_source) " (" (width) " x " (height) " pixels): minimum "
                span class="num" id="t-min" { (format!("{lo:.3}")) } " K, mean "
                span class="num" id="t-mean" { (format!("{:.3}", finite_mean(&run.values))) }
                " K, maximum " span class="num" id="t-max" { (format!("{hi:.3}")) } " K."
            }
            div class="figure" {
                div class="holder" {
                    (img("colour", &colour, width, height,
                        "apparent temperature in the inferno colour map"))
                    @if let Some((line, _)) = &run.profile {
                        (profile_overlay(line, width, height, scale))
                    }
                }
                (PreEscaped(bar))
            }
            @if let Some((line, _)) = &run.profile {
                p {
                    "The line profile's pixels are drawn on the image in cyan, from the ring at ("
                    (line.from.0) ", " (line.from.1) ") to (" (line.to.0) ", " (line.to.1) ")."
                }
            }
        }
    })
}

/// The pixels the counts clip, and per region when regions are given.
fn saturation_section(run: &Run, (lo, hi): (f64, f64)) -> Markup {
    let (Some(s), Some((name, rows))) = (&run.saturated, &run.lut) else {
        return html! {};
    };
    let (first, last) = (&rows[0], &rows[rows.len() - 1]);
    // The regions' material ids are the truth EXR's, which regions need.
    let ids = run
        .truth
        .as_ref()
        .and_then(|(n, image, _)| layer(image, n, MATERIAL_LAYER).ok());
    let per_region = match (&run.regions, ids) {
        (Some((table, set)), Some(ids)) if s.at_zero + s.at_full > 0 => set
            .regions
            .iter()
            .zip(&table.regions)
            .map(|(region, row)| {
                let count = |mask: &[f32]| {
                    irsig_regions::stats::region_stats(region, ids, mask, run.width)
                        .map_or(0, |r| (r.mean * r.pixels as f64).round() as usize)
                };
                (row, count(&s.zero_mask), count(&s.full_mask))
            })
            .collect(),
        _ => Vec::new(),
    };
    html! {
        section id="saturation" {
            h2 { "Saturation" }
            p {
                "Of the " span class="num" id="sat-pixels" { (s.pixels) } " pixels, "
                span class="num" id="sat-zero" { (s.at_zero) } " ("
                (percent(s.at_zero, s.pixels)) " %) are at count 0 and "
                span class="num" id="sat-full" { (s.at_full) } " ("
                (percent(s.at_full, s.pixels)) " %) at full scale, count " (s.full_count)
                ": the counts of " (name) " ("
                (format!("{:.4}-{:.4}", first.temperature_k, last.temperature_k))
                " K) against the image's " (format!("{lo:.3}-{hi:.3}")) " K ("
                (s.compared) ")."
            }
            @if !per_region.is_empty() {
                table id="saturation-regions" {
                    thead { tr {
                        th { "region" } th { "pixels" } th { "at count 0" }
                        th { "at full scale" } th { "saturated (%)" }
                    } }
                    tbody {
                        @for (row, zero, full) in &per_region {
                            tr {
                                td { (row.region) }
                                td class="num" { (row.pixels) }
                                td class="num" { (zero) }
                                td class="num" { (full) }
                                td class="num" { (percent(zero + full, row.pixels)) }
                            }
                        }
                    }
                }
            }
        }
    }
}

/// The error budget, when the truth EXR has `sigma_total`: its image, its sources and what
/// was declared. `None` when it has not.
fn budget_section(run: &Run) -> miette::Result<Option<Markup>> {
    let Some((name, image, _)) = run
        .truth
        .as_ref()
        .filter(|(_, i, _)| i.layer(SIGMA_LAYER).is_some())
    else {
        return Ok(None);
    };
    let s = image
        .layer(SIGMA_LAYER)
        .map_or(&[][..], |l| l.data.as_slice());
    let shown = run.names.show_name(name);
    let figure = match plots::finite_range(s) {
        Some(r) => Some((
            img(
                "sigma",
                &false_colour(s, run.width, run.height, r),
                run.width,
                run.height,
                "sigma_total in the inferno colour map",
            ),
            plots::colour_bar(r, "σ total (K)")?,
        )),
        None => None,
    };
    let (least, largest) = extremes(s);
    Ok(Some(html! {
        section id="budget" {
            h2 { "Error budget" }
            @match figure {
                Some((image, bar)) => {
                    p {
                        "The `" (SIGMA_LAYER) "` layer of " (shown) ": σ of apparent \
                         temperature from the declared uncertainties, root-sum-square of its \
                         sources, from "
                        span class="num" id="sigma-min" { (format!("{least:.4}")) } " K to "
                        span class="num" id="sigma-max" { (format!("{largest:.4}")) } " K."
                    }
                    div class="figure" { (image) (PreEscaped(bar)) }
                }
                None => {
                    p { "The `" (SIGMA_LAYER) "` layer of " (shown) " has no finite value." }
                }
            }
            table id="budget-sources" {
                thead { tr {
                    th { "source" } th { "layer" } th { "mean σ (K)" } th { "largest σ (K)" }
                } }
                tbody {
                    @for (layer, what) in BUDGET_SOURCES {
                        @if let Some(l) = image.layer(layer.name()) {
                            tr {
                                td { (what) }
                                td { code { (layer.name()) } }
                                td class="num" { (format!("{:.4}", finite_mean(&l.data))) }
                                td class="num" { (format!("{:.4}", extremes(&l.data).1)) }
                            }
                        }
                    }
                }
            }
            h3 { "What was declared" }
            @match (&run.uncertainties, &run.recorded_uncertainties) {
                (Some(u), _) => { (declared_table(u)) }
                (None, Some(Some(sha))) => {
                    p id="declared-absent" {
                        "The truth EXR was traced with declared uncertainties of SHA-256 "
                        code { (chain::hex(sha)) }
                        "; give that file as --uncertainties FILE to list them here."
                    }
                }
                (None, _) => {
                    p id="declared-absent" {
                        "The truth EXR does not record its declared uncertainties' file; give \
                         it as --uncertainties FILE to list them here."
                    }
                }
            }
        }
    }))
}

/// The LUT's curve, count against kelvin. `None` without a LUT.
fn lut_section(run: &Run) -> miette::Result<Option<Markup>> {
    let Some((name, rows)) = &run.lut else {
        return Ok(None);
    };
    let points: Vec<(f64, f64)> = rows
        .iter()
        .map(|r| (r.temperature_k, f64::from(r.dc)))
        .collect();
    let chart = plots::line_chart("LUT curve", &points, "temperature (K)", "digital count")?;
    let (first, last) = (&rows[0], &rows[rows.len() - 1]);
    Ok(Some(html! {
        section id="lut" {
            h2 { "LUT: digital count against temperature" }
            p {
                (name) ": " (rows.len()) " counts, "
                span class="num" id="lut-first" { (format!("{:.4}", first.temperature_k)) }
                " K at count 0 to "
                span class="num" id="lut-last" { (format!("{:.4}", last.temperature_k)) }
                " K at count " (last.dc) "."
            }
            div class="figure" { (PreEscaped(chart)) }
        }
    }))
}
