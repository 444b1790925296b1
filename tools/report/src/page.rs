//! The page, section by section, from a report's inputs read and checked
//! ([`crate::read::Run`]): warnings first, then the image, the pixels the counts clip, the
//! histogram, the profile, the regions, the decision, the error budget and the LUT, each
//! left out with one line naming the flag that would fill it, and provenance last.

use super::*;
use crate::read::Run;

/// The whole page of `run`, titled `title`.
///
/// # Errors
/// A plot that cannot be drawn.
pub(crate) fn page(title: &str, run: &Run) -> miette::Result<String> {
    let (lo, hi) = extremes(&run.values);
    let mut page = String::new();
    let w = &mut page;
    let _ = write!(
        w,
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
         <title>irsig report: {t}</title>\n<style>{STYLE}</style>\n</head>\n<body>\n\
         <h1>irsig report: {t}</h1>\n",
        t = escape(title)
    );
    warnings(w, run, (lo, hi));
    image_section(w, run, (lo, hi))?;
    saturation_section(w, run, (lo, hi));
    let range = run.range;
    let _ = write!(
        w,
        "<section id=\"histogram\">\n<h2>Histogram of apparent temperature</h2>\n<p>{} \
         bins of {:.4} K.</p>\n<div class=\"figure\">{}</div>\n</section>\n",
        HISTOGRAM_BINS,
        (range.1 - range.0) / HISTOGRAM_BINS as f64,
        plots::histogram(&run.values, range, HISTOGRAM_BINS)?
    );

    // What is left out, and the flag that would put it in: one line.
    let mut not_shown: Vec<&str> = Vec::new();
    match &run.profile {
        Some((line, points)) => {
            let _ = write!(
                w,
                "<section id=\"profile\">\n<h2>Line profile</h2>\n<p>From pixel ({}, {}) to \
                 ({}, {}), {} pixels (the line on the image above).</p>\n<div class=\"figure\">\
                 {}</div>\n</section>\n",
                line.from.0,
                line.from.1,
                line.to.0,
                line.to.1,
                points.len(),
                plots::line_chart(
                    "line profile",
                    points,
                    "distance from the start (pixels)",
                    "apparent temperature (K)"
                )?
            );
        }
        None => not_shown.push("a line profile (--profile X0,Y0:X1,Y1)"),
    }
    match &run.regions {
        Some((table, _)) => {
            w.push_str("<section id=\"regions\">\n<h2>Per-region statistics</h2>\n");
            stats_table(w, table);
            w.push_str("</section>\n");
        }
        None => not_shown.push("per-region statistics (the truth EXR and --regions FILE)"),
    }
    match &run.decision {
        Some(d) => {
            w.push_str("<section id=\"decision\">\n<h2>The tolerance pilot's decision</h2>\n");
            decision_table(w, d);
            w.push_str("</section>\n");
        }
        None => not_shown.push(
            "the tolerance pilot's decision (trace with --tolerance K, then --decision FILE)",
        ),
    }
    if !budget_section(w, run)? {
        not_shown
            .push("the error budget (trace with --uncertainties FILE, then give its truth EXR)");
    }
    if !lut_section(w, run)? {
        not_shown.push("the LUT and the counts it clips (--lut FILE)");
    }
    if !not_shown.is_empty() {
        let _ = writeln!(
            w,
            "<p class=\"absent\" id=\"not-shown\">Not shown: {}.</p>",
            escape(&not_shown.join("; "))
        );
    }
    provenance_section(
        w,
        &run.recorded,
        &run.chain_rows,
        run.pipeline.as_ref(),
        &run.commands,
    );
    w.push_str("</body>\n</html>\n");
    Ok(page)
}

/// The warnings, first, where nobody can miss them: clipped counts, images from different
/// runs, inputs the pipeline no longer holds.
fn warnings(w: &mut String, run: &Run, (lo, hi): (f64, f64)) {
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
    if warnings.is_empty() {
        return;
    }
    w.push_str("<div id=\"warnings\">\n");
    for (id, text) in &warnings {
        let _ = writeln!(
            w,
            "<p class=\"warning\" id=\"{id}\" role=\"alert\">{}</p>",
            escape(text)
        );
    }
    w.push_str("</div>\n");
}

/// The colour image, the profile's line on it, and its scale.
fn image_section(w: &mut String, run: &Run, (lo, hi): (f64, f64)) -> miette::Result<()> {
    let (width, height) = (run.width, run.height);
    let scale = display_scale(height);
    let _ = write!(
        w,
        "<section id=\"image\">\n<h2>Apparent temperature</h2>\n<p>{} ({width} x {height} \
         pixels): minimum <span class=\"num\" id=\"t-min\">{lo:.3}</span> K, mean <span \
         class=\"num\" id=\"t-mean\">{:.3}</span> K, maximum <span class=\"num\" \
         id=\"t-max\">{hi:.3}</span> K.</p>\n<div class=\"figure\"><div class=\"holder\">{}{}\
         </div>{}</div>\n",
        escape(&run.shown_source),
        finite_mean(&run.values),
        img(
            "colour",
            &false_colour(&run.values, width, height, run.range),
            width,
            height,
            "apparent temperature in the inferno colour map"
        ),
        run.profile
            .as_ref()
            .map(|(line, _)| profile_overlay(line, width, height, scale))
            .unwrap_or_default(),
        plots::colour_bar(run.range, "apparent temperature (K)")?
    );
    if let Some((line, _)) = &run.profile {
        let _ = writeln!(
            w,
            "<p>The line profile's pixels are drawn on the image in cyan, from the ring at \
             ({}, {}) to ({}, {}).</p>",
            line.from.0, line.from.1, line.to.0, line.to.1
        );
    }
    w.push_str("</section>\n");
    Ok(())
}

/// The pixels the counts clip, and per region when regions are given.
fn saturation_section(w: &mut String, run: &Run, (lo, hi): (f64, f64)) {
    let (Some(s), Some((name, rows))) = (&run.saturated, &run.lut) else {
        return;
    };
    let (first, last) = (&rows[0], &rows[rows.len() - 1]);
    let _ = write!(
        w,
        "<section id=\"saturation\">\n<h2>Saturation</h2>\n<p>Of the <span class=\"num\" \
         id=\"sat-pixels\">{}</span> pixels, <span class=\"num\" id=\"sat-zero\">{}</span> \
         ({} %) are at count 0 and <span class=\"num\" id=\"sat-full\">{}</span> ({} %) at \
         full scale, count {}: the counts of {} ({:.4}-{:.4} K) against the image's \
         {lo:.3}-{hi:.3} K ({}).</p>\n",
        s.pixels,
        s.at_zero,
        percent(s.at_zero, s.pixels),
        s.at_full,
        percent(s.at_full, s.pixels),
        s.full_count,
        escape(name),
        first.temperature_k,
        last.temperature_k,
        s.compared
    );
    // The regions' material ids are the truth EXR's, which regions need.
    let ids = run
        .truth
        .as_ref()
        .and_then(|(n, image, _)| layer(image, n, MATERIAL_LAYER).ok());
    if let (Some((table, set)), Some(ids)) = (&run.regions, ids)
        && s.at_zero + s.at_full > 0
    {
        w.push_str(
            "<table id=\"saturation-regions\">\n<thead><tr><th>region</th><th>pixels</th>\
             <th>at count 0</th><th>at full scale</th><th>saturated (%)</th></tr></thead>\
             \n<tbody>\n",
        );
        for (region, row) in set.regions.iter().zip(&table.regions) {
            let count = |mask: &[f32]| {
                irsig_regions::stats::region_stats(region, ids, mask, run.width)
                    .map_or(0, |r| (r.mean * r.pixels as f64).round() as usize)
            };
            let (zero, full) = (count(&s.zero_mask), count(&s.full_mask));
            let _ = writeln!(
                w,
                "<tr><td>{}</td><td class=\"num\">{}</td><td class=\"num\">{zero}</td>\
                 <td class=\"num\">{full}</td><td class=\"num\">{}</td></tr>",
                escape(&row.region),
                row.pixels,
                percent(zero + full, row.pixels)
            );
        }
        w.push_str("</tbody>\n</table>\n");
    }
    w.push_str("</section>\n");
}

/// The error budget, when the truth EXR has `sigma_total`: its image, its sources and what
/// was declared. Whether it was shown.
fn budget_section(w: &mut String, run: &Run) -> miette::Result<bool> {
    let Some((name, image, _)) = run
        .truth
        .as_ref()
        .filter(|(_, i, _)| i.layer(SIGMA_LAYER).is_some())
    else {
        return Ok(false);
    };
    let s = image
        .layer(SIGMA_LAYER)
        .map_or(&[][..], |l| l.data.as_slice());
    let shown = escape(&run.names.show_name(name));
    w.push_str("<section id=\"budget\">\n<h2>Error budget</h2>\n");
    match plots::finite_range(s) {
        Some(r) => {
            let _ = write!(
                w,
                "<p>The `{SIGMA_LAYER}` layer of {shown}: σ of apparent temperature from the \
                 declared uncertainties, root-sum-square of its sources, from <span \
                 class=\"num\" id=\"sigma-min\">{:.4}</span> K to <span class=\"num\" \
                 id=\"sigma-max\">{:.4}</span> K.</p>\n<div class=\"figure\">{}{}</div>\n",
                extremes(s).0,
                extremes(s).1,
                img(
                    "sigma",
                    &false_colour(s, run.width, run.height, r),
                    run.width,
                    run.height,
                    "sigma_total in the inferno colour map"
                ),
                plots::colour_bar(r, "σ total (K)")?
            );
        }
        None => {
            let _ = writeln!(
                w,
                "<p>The `{SIGMA_LAYER}` layer of {shown} has no finite value.</p>"
            );
        }
    }
    w.push_str(
        "<table id=\"budget-sources\">\n<thead><tr><th>source</th><th>layer</th>\
         <th>mean σ (K)</th><th>largest σ (K)</th></tr></thead>\n<tbody>\n",
    );
    for (layer, what) in BUDGET_SOURCES {
        if let Some(l) = image.layer(layer.name()) {
            let _ = writeln!(
                w,
                "<tr><td>{what}</td><td><code>{}</code></td><td class=\"num\">{:.4}</td>\
                 <td class=\"num\">{:.4}</td></tr>",
                layer.name(),
                finite_mean(&l.data),
                extremes(&l.data).1
            );
        }
    }
    w.push_str("</tbody>\n</table>\n<h3>What was declared</h3>\n");
    match (&run.uncertainties, &run.recorded_uncertainties) {
        (Some(u), _) => declared_table(w, u),
        (None, Some(Some(sha))) => {
            let _ = writeln!(
                w,
                "<p id=\"declared-absent\">The truth EXR was traced with declared \
                 uncertainties of SHA-256 <code>{}</code>; give that file as \
                 --uncertainties FILE to list them here.</p>",
                chain::hex(sha)
            );
        }
        (None, _) => w.push_str(
            "<p id=\"declared-absent\">The truth EXR does not record its declared \
             uncertainties' file; give it as --uncertainties FILE to list them here.</p>\n",
        ),
    }
    w.push_str("</section>\n");
    Ok(true)
}

/// The LUT's curve, count against kelvin. Whether it was shown.
fn lut_section(w: &mut String, run: &Run) -> miette::Result<bool> {
    let Some((name, rows)) = &run.lut else {
        return Ok(false);
    };
    let points: Vec<(f64, f64)> = rows
        .iter()
        .map(|r| (r.temperature_k, f64::from(r.dc)))
        .collect();
    let _ = write!(
        w,
        "<section id=\"lut\">\n<h2>LUT: digital count against temperature</h2>\n<p>{}: {} \
         counts, <span class=\"num\" id=\"lut-first\">{:.4}</span> K at count 0 to <span \
         class=\"num\" id=\"lut-last\">{:.4}</span> K at count {}.</p>\n<div \
         class=\"figure\">{}</div>\n</section>\n",
        escape(name),
        rows.len(),
        rows[0].temperature_k,
        rows[rows.len() - 1].temperature_k,
        rows[rows.len() - 1].dc,
        plots::line_chart("LUT curve", &points, "temperature (K)", "digital count")?
    );
    Ok(true)
}
