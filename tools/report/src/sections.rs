//! Sections of the page written whole by one function each: the provenance, the regions'
//! statistics, the decision, and the page's style sheet.

use maud::{Markup, html};

use super::*;

/// The provenance section: the images' record, every input with its file and SHA-256, the
/// pipeline's files, the command lines and irsig's version.
pub(crate) fn provenance_section(
    recorded: &chain::Recorded,
    rows: &[chain::Row],
    pipeline: Option<&(String, Vec<PipelineFile>)>,
    commands: &[String],
) -> Markup {
    html! {
        section id="provenance" {
            h2 { "Provenance" }
            p {
                "irsig " span id="version" { (env!("CARGO_PKG_VERSION")) }
                ". Files are named relative to this page."
            }
            @match &recorded.summary {
                Some(p) => {
                    p id="recorded" {
                        "The images record their band, "
                        span id="recorded-band" { (p.band.to_string()) }
                        " (sub-bands: " (p.sub_bands) "), their atmosphere, " (p.atmosphere)
                        " (model " (p.atmosphere_model) "), and every input the trace and the \
                         sensor read, listed below by SHA-256 with the file that holds it now."
                    }
                }
                None => {
                    p id="recorded" {
                        "The images record no provenance (made before irsig recorded it, or by \
                         another program): only the report's own inputs are listed."
                    }
                }
            }
            table id="inputs" {
                thead { tr {
                    th { "stage" } th { "role" } th { "file" } th { "SHA-256" }
                    th { "recorded in" }
                } }
                tbody {
                    @for r in rows {
                        tr {
                            td { (r.stage) }
                            td { (r.role) }
                            td {
                                @match &r.file {
                                    Some(f) => { (f) }
                                    None => {
                                        span class="absent" { "no file known here holds it" }
                                    }
                                }
                            }
                            td { code { (r.sha256_hex) } }
                            td { (r.recorded_in) }
                        }
                    }
                }
            }
            @if let Some((base, files)) = pipeline {
                h3 { "The pipeline's files" }
                p {
                    "Every file the pipeline's steps read or write, as it is now (its steps \
                     run in " (base) ")."
                }
                table id="pipeline-files" {
                    thead { tr {
                        th { "file" } th { "SHA-256" } th { "written by" } th { "read by" }
                    } }
                    tbody {
                        @for f in files {
                            tr {
                                td { (f.shown) }
                                td {
                                    @match &f.sha256 {
                                        Some(s) => { code { (chain::hex(s)) } }
                                        None => { span class="absent" { "missing" } }
                                    }
                                }
                                td { (f.written_by.join(", ")) }
                                td { (f.read_by.join(", ")) }
                            }
                        }
                    }
                }
            }
            @if !commands.is_empty() {
                h3 { "Command lines" }
                pre id="commands" { @for c in commands { (c) "\n" } }
            }
        }
    }
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
pub(crate) fn stats_table(table: &irsig_regions::Table) -> Markup {
    html! {
        p { "Values: " (table.values) " (" (table.unit) ")." }
        table id="stats" {
            thead { tr {
                th { "region" } th { "pixels" } th { "mean_k" } th { "std_dev_k" }
                th { "min_k" } th { "max_k" }
                @for (name, _) in &table.references {
                    th { (name) "_k" } th { "mean_minus_" (name) "_k" }
                }
            } }
            tbody {
                @for row in &table.regions {
                    tr {
                        td { (row.region) }
                        td class="num" { (row.pixels) }
                        td class="num" { (format!("{:.3}", row.mean)) }
                        td class="num" { (format!("{:.3}", row.std_dev)) }
                        td class="num" { (format!("{:.3}", row.min)) }
                        td class="num" { (format!("{:.3}", row.max)) }
                        @for r in &row.references {
                            @match r {
                                Some(c) => {
                                    td class="num" { (format!("{:.3}", c.reference)) }
                                    td class="num" { (format!("{:+.3}", c.difference)) }
                                }
                                None => { td { "-" } td { "-" } }
                            }
                        }
                    }
                }
            }
        }
        @for (name, source) in &table.references {
            p class="source" { (name) ": " (source) }
        }
    }
}

/// The decision as the tracer prints it: one row per model, then the combination.
pub(crate) fn decision_table(d: &Decision) -> Markup {
    html! {
        p {
            "Tolerance " span class="num" id="tolerance" { (d.tolerance_k) } " K at the "
            span class="num" id="percentile" { (d.percentile) } "th percentile of the pilot's "
            span class="num" id="pilot-pixels" { (d.pilot_pixels) } " pixels."
        }
        table id="decision-table" {
            thead { tr {
                th { "model" } th { "choice" } th { "reference" } th { "pinned" }
                th { "error_percentile_k" } th { "error_max_k" } th { "relative_cost" }
                th { "why" }
            } }
            tbody {
                @for c in &d.choices {
                    tr {
                        td { (c.model) }
                        td { (c.setting) }
                        td { (c.reference) }
                        td { @if c.pinned { "yes" } @else { "no" } }
                        td class="num" { (format!("{:.3}", c.error.percentile_k)) }
                        td class="num" { (format!("{:.3}", c.error.max_k)) }
                        td class="num" { (format!("{:.3}", c.relative_cost)) }
                        td { (c.reason) }
                    }
                }
                tr class="total" {
                    td { "predicted" } td {} td {} td {}
                    td class="num" { (format!("{:.3}", d.predicted.percentile_k)) }
                    td class="num" { (format!("{:.3}", d.predicted.max_k)) }
                    td class="num" { (format!("{:.3}", d.relative_cost)) }
                    td { "the chosen combination's error bound and cost" }
                }
            }
        }
    }
}
