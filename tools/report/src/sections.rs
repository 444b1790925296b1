//! Sections of the page written whole by one function each: the provenance, the regions'
//! statistics, and the page's style sheet.

use super::*;

/// The provenance section: the images' record, every input with its file and SHA-256, the
/// pipeline's files, the command lines and irsig's version.
pub(crate) fn provenance_section(
    w: &mut String,
    recorded: &chain::Recorded,
    rows: &[chain::Row],
    pipeline: Option<&(String, Vec<PipelineFile>)>,
    commands: &[String],
) {
    let _ = write!(
        w,
        "<section id=\"provenance\">\n<h2>Provenance</h2>\n<p>irsig <span \
         id=\"version\">{}</span>. Files are named relative to this page.</p>\n",
        env!("CARGO_PKG_VERSION")
    );
    match &recorded.summary {
        Some(p) => {
            let _ = writeln!(
                w,
                "<p id=\"recorded\">The images record their band, <span \
                 id=\"recorded-band\">{}</span> (sub-bands: {}), their atmosphere, {} (model \
                 {}), and every input the trace and the sensor read, listed below by SHA-256 \
                 with the file that holds it now.</p>",
                escape(&p.band.to_string()),
                escape(&p.sub_bands),
                escape(&p.atmosphere),
                escape(&p.atmosphere_model)
            );
        }
        None => w.push_str(
            "<p id=\"recorded\">The images record no provenance (made before irsig recorded \
             it, or by another program): only the report's own inputs are listed.</p>\n",
        ),
    }
    w.push_str(
        "<table id=\"inputs\">\n<thead><tr><th>stage</th><th>role</th><th>file</th>\
         <th>SHA-256</th><th>recorded in</th></tr></thead>\n<tbody>\n",
    );
    for r in rows {
        let _ = writeln!(
            w,
            "<tr><td>{}</td><td>{}</td><td>{}</td><td><code>{}</code></td><td>{}</td></tr>",
            escape(&r.stage),
            escape(&r.role),
            r.file.as_deref().map_or_else(
                || "<span class=\"absent\">no file known here holds it</span>".to_owned(),
                escape
            ),
            escape(&r.sha256_hex),
            escape(&r.recorded_in)
        );
    }
    w.push_str("</tbody>\n</table>\n");
    if let Some((base, files)) = pipeline {
        let _ = write!(
            w,
            "<h3>The pipeline's files</h3>\n<p>Every file the pipeline's steps read or write, \
             as it is now (its steps run in {}).</p>\n<table id=\"pipeline-files\">\n<thead>\
             <tr><th>file</th><th>SHA-256</th><th>written by</th><th>read by</th></tr></thead>\
             \n<tbody>\n",
            escape(base)
        );
        for f in files {
            let _ = writeln!(
                w,
                "<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>",
                escape(&f.shown),
                f.sha256.as_deref().map_or_else(
                    || "<span class=\"absent\">missing</span>".to_owned(),
                    |s| format!("<code>{}</code>", chain::hex(s))
                ),
                escape(&f.written_by.join(", ")),
                escape(&f.read_by.join(", "))
            );
        }
        w.push_str("</tbody>\n</table>\n");
    }
    if !commands.is_empty() {
        w.push_str("<h3>Command lines</h3>\n<pre id=\"commands\">");
        for c in commands {
            let _ = writeln!(w, "{}", escape(c));
        }
        w.push_str("</pre>\n");
    }
    w.push_str("</section>\n");
}

pub(crate) const STYLE: &str = "body{font-family:sans-serif;margin:2em;max-width:80em}\
table{border-collapse:collapse;margin:0.5em 0}\
td,th{border:1px solid #bbb;padding:0.2em 0.5em}\
td.num,.num{font-variant-numeric:tabular-nums}td.num{text-align:right}\
.figure{display:flex;align-items:flex-start;gap:1em;flex-wrap:wrap}\
img{image-rendering:pixelated;display:block}.absent{color:#777}pre{white-space:pre-wrap}\
.holder{position:relative;line-height:0}\
.overlay{position:absolute;left:0;top:0;overflow:visible}\
.warning{border:2px solid #b00;background:#fdecea;color:#600;padding:0.5em 0.8em;\
font-weight:bold}";

/// The `irsig-stats` table as HTML, three decimals.
pub(crate) fn stats_table(w: &mut String, table: &irsig_regions::Table) {
    let _ = write!(
        w,
        "<p>Values: {} ({}).</p>\n<table id=\"stats\">\n<thead><tr><th>region</th>\
         <th>pixels</th><th>mean_k</th><th>std_dev_k</th><th>min_k</th><th>max_k</th>",
        escape(&table.values),
        escape(&table.unit)
    );
    for (name, _) in &table.references {
        let n = escape(name);
        let _ = write!(w, "<th>{n}_k</th><th>mean_minus_{n}_k</th>");
    }
    w.push_str("</tr></thead>\n<tbody>\n");
    for row in &table.regions {
        let _ = write!(
            w,
            "<tr><td>{}</td><td class=\"num\">{}</td><td class=\"num\">{:.3}</td>\
             <td class=\"num\">{:.3}</td><td class=\"num\">{:.3}</td><td class=\"num\">{:.3}\
             </td>",
            escape(&row.region),
            row.pixels,
            row.mean,
            row.std_dev,
            row.min,
            row.max
        );
        for r in &row.references {
            match r {
                Some(c) => {
                    let _ = write!(
                        w,
                        "<td class=\"num\">{:.3}</td><td class=\"num\">{:+.3}</td>",
                        c.reference, c.difference
                    );
                }
                None => w.push_str("<td>-</td><td>-</td>"),
            }
        }
        w.push_str("</tr>\n");
    }
    w.push_str("</tbody>\n</table>\n");
    for (name, source) in &table.references {
        let _ = writeln!(
            w,
            "<p class=\"source\">{}: {}</p>",
            escape(name),
            escape(source)
        );
    }
}

/// The decision as the tracer prints it: one row per model, then the combination.
pub(crate) fn decision_table(w: &mut String, d: &Decision) {
    let _ = write!(
        w,
        "<p>Tolerance <span class=\"num\" id=\"tolerance\">{}</span> K at the <span \
         class=\"num\" id=\"percentile\">{}</span>th percentile of the pilot's <span \
         class=\"num\" id=\"pilot-pixels\">{}</span> pixels.</p>\n<table id=\"decision-table\">\
         \n<thead><tr><th>model</th><th>choice</th><th>reference</th><th>pinned</th>\
         <th>error_percentile_k</th><th>error_max_k</th><th>relative_cost</th><th>why</th>\
         </tr></thead>\n<tbody>\n",
        d.tolerance_k, d.percentile, d.pilot_pixels
    );
    for c in &d.choices {
        let _ = writeln!(
            w,
            "<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td class=\"num\">{:.3}</td>\
             <td class=\"num\">{:.3}</td><td class=\"num\">{:.3}</td><td>{}</td></tr>",
            c.model,
            escape(&c.setting),
            escape(&c.reference),
            if c.pinned { "yes" } else { "no" },
            c.error.percentile_k,
            c.error.max_k,
            c.relative_cost,
            escape(&c.reason)
        );
    }
    let _ = writeln!(
        w,
        "<tr class=\"total\"><td>predicted</td><td></td><td></td><td></td><td class=\"num\">\
         {:.3}</td><td class=\"num\">{:.3}</td><td class=\"num\">{:.3}</td><td>the chosen \
         combination's error bound and cost</td></tr>\n</tbody>\n</table>",
        d.predicted.percentile_k, d.predicted.max_k, d.relative_cost
    );
}
