//! What a batch leaves beside the case folders: `metrics.csv` (one row per case, failed ones
//! with their error) and `index.html`, a static gallery (thumbnails linking to each case's
//! outputs, relative links, so it opens from disk and travels with the folder). Both are written
//! as one output set, after every case has reported.

use std::fmt::Write as _;
use std::path::Path;

use super::case::CaseResult;

/// The columns of `metrics.csv`.
pub const CSV_HEADER: &str = "case,status,seconds,memory_mb,structures,cutters,focus,exposure_before,exposure_after,removed_volume_mm3,min_distance_mm,error";

/// Writes `metrics.csv` and `index.html` into `out`.
pub fn write_summary(out: &Path, title: &str, results: &[CaseResult]) -> anyhow::Result<()> {
    let set = crate::io::OutputSet::begin(out)?;
    set.write_bytes(Path::new("metrics.csv"), metrics_csv(results).as_bytes())?;
    set.write_bytes(Path::new("index.html"), gallery(title, results).as_bytes())?;
    set.commit()
}

/// One CSV field: quoted when it holds a comma, a quote or a line break.
fn field(text: &str) -> String {
    if text.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", text.replace('"', "\"\""))
    } else {
        text.to_owned()
    }
}

fn number(value: Option<f64>) -> String {
    value.map(|v| format!("{v}")).unwrap_or_default()
}

pub fn metrics_csv(results: &[CaseResult]) -> String {
    let mut csv = format!("{CSV_HEADER}\n");
    for r in results {
        let row = [
            field(&r.case),
            r.status.clone(),
            format!("{:.3}", r.seconds),
            r.memory_mb.map(|m| format!("{m:.0}")).unwrap_or_default(),
            r.structures.to_string(),
            r.cutters.to_string(),
            field(r.focus.as_deref().unwrap_or("")),
            number(r.exposure_before),
            number(r.exposure_after),
            number(r.removed_volume),
            number(r.min_distance),
            field(r.error.as_deref().unwrap_or("")),
        ];
        csv += &row.join(",");
        csv.push('\n');
    }
    csv
}

fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
        .replace('\'', "&#39;")
}

/// A path segment made safe for a relative link (percent-encoded).
fn link(text: &str) -> String {
    let mut out = String::new();
    for b in text.bytes() {
        if b.is_ascii_alphanumeric() || b"-_.~".contains(&b) {
            out.push(b as char);
        } else {
            let _ = write!(out, "%{b:02X}");
        }
    }
    out
}

pub fn gallery(title: &str, results: &[CaseResult]) -> String {
    let ok = results.iter().filter(|r| r.status != "failed").count();
    let mut html = format!(
        "<!doctype html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\
<title>{t}</title><style>\
body{{font:14px system-ui,sans-serif;margin:24px;background:#f6f6f6;color:#222}}\
.grid{{display:grid;grid-template-columns:repeat(auto-fill,minmax(260px,1fr));gap:16px}}\
.case{{background:#fff;border-radius:6px;padding:8px;box-shadow:0 1px 3px #0002}}\
.case img{{width:100%;border-radius:4px;display:block}}\
.case h2{{font-size:15px;margin:6px 0}}.failed{{border-left:4px solid #c62828}}\
.error{{color:#c62828;font-family:monospace;font-size:12px;word-break:break-word}}\
.links{{display:flex;flex-wrap:wrap;gap:4px 10px}}</style></head><body>\n<h1>{t}</h1>\n\
<p>{ok} of {n} cases done; measures in <a href=\"metrics.csv\">metrics.csv</a>.</p>\n<div class=\"grid\">\n",
        t = escape(title),
        n = results.len()
    );
    for r in results {
        let dir = link(&r.case);
        if r.status == "failed" {
            let _ = writeln!(
                html,
                "<div class=\"case failed\"><h2>{}</h2><p class=\"error\">{}</p></div>",
                escape(&r.case),
                escape(r.error.as_deref().unwrap_or(""))
            );
            continue;
        }
        let mut links = String::new();
        for file in &r.outputs {
            let _ = write!(
                links,
                "<a href=\"{dir}/{}\">{}</a>",
                link(file),
                escape(file)
            );
        }
        let exposure = match (r.exposure_before, r.exposure_after) {
            (Some(b), Some(a)) => format!(
                " · {} exposure {:.0}% → {:.0}%",
                escape(r.focus.as_deref().unwrap_or("")),
                b * 100.0,
                a * 100.0
            ),
            _ => String::new(),
        };
        let _ = writeln!(
            html,
            "<div class=\"case\"><a href=\"{dir}/picture.png\"><img src=\"{dir}/picture.png\" alt=\"{name}\" loading=\"lazy\"></a>\
<h2>{name}</h2><p>{s} structures · {c} cutters{exposure} · {sec:.1} s{mem}</p><p class=\"links\">{links}</p></div>",
            name = escape(&r.case),
            s = r.structures,
            c = r.cutters,
            sec = r.seconds,
            mem = r
                .memory_mb
                .map(|m| format!(" · {m:.0} MiB"))
                .unwrap_or_default(),
        );
    }
    html += "</div>\n</body></html>\n";
    html
}

#[cfg(test)]
mod tests {
    use super::*;

    fn result(case: &str, status: &str, error: Option<&str>) -> CaseResult {
        CaseResult {
            case: case.into(),
            status: status.into(),
            error: error.map(Into::into),
            recipe: String::new(),
            seconds: 1.5,
            memory_mb: Some(300.0),
            structures: 3,
            cutters: 2,
            focus: Some("brain, left".into()),
            exposure_before: Some(0.1),
            exposure_after: Some(0.8),
            removed_volume: Some(12.5),
            min_distance: None,
            outputs: vec!["picture.png".into(), "case.json".into()],
        }
    }

    #[test]
    fn csv_quotes_fields_and_keeps_failed_rows() {
        let csv = metrics_csv(&[
            result("a", "ok", None),
            result("b", "failed", Some("b: no volume named like \"*.nrrd\"")),
        ]);
        let lines: Vec<&str> = csv.lines().collect();
        assert_eq!(lines[0], CSV_HEADER);
        assert_eq!(
            lines[1],
            "a,ok,1.500,300,3,2,\"brain, left\",0.1,0.8,12.5,,"
        );
        assert!(lines[2].ends_with(",\"b: no volume named like \"\"*.nrrd\"\"\""));
    }

    #[test]
    fn gallery_links_relative_and_escapes() {
        let html = gallery(
            "t<1>",
            &[
                result("case 1", "ok", None),
                result("x", "failed", Some("<bad>")),
            ],
        );
        assert!(html.contains("<img src=\"case%201/picture.png\""));
        assert!(html.contains("&lt;bad&gt;"));
        assert!(html.contains("<title>t&lt;1&gt;</title>"));
        assert!(!html.contains("file://"));
        assert!(html.contains("1 of 2 cases done"));
    }
}
