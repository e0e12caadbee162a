//! The compared measures as text: the rows of the table drawn under the pictures (and shown under
//! the window's compare viewports), the CSV file and the JSON document of `cutaway compare`.
//!
//! The CSV has one row per variant and structure; numbers are written in Rust's shortest
//! round-trip form, the same digits as the JSON, so the two files agree exactly. Empty cells
//! mean "not measured" (an open surface's volume, the distance of a structure not marked
//! critical, the exposure of a structure that is not the focus).

use std::fmt::Write as _;

use super::variants::VariantMetrics;
use crate::metrics::Metrics;

/// The CSV header (units in the column names).
pub const CSV_HEADER: &str = "variant,structure,closed,removed_volume_mm3,removed_area_mm2,wall_area_mm2,min_distance_mm,exposure_before,exposure_after";

/// Most per-structure rows in the drawn table (the structures most removed from); the CSV and
/// JSON hold all.
pub const MAX_STRUCTURE_ROWS: usize = 12;

/// One row of the drawn table: a label and one cell per variant.
#[derive(Clone, Debug, PartialEq)]
pub struct Row {
    pub label: String,
    pub cells: Vec<String>,
}

/// The summary rows of `variants`: totals, deepest cut, focus exposure, critical distances,
/// then removed volume per structure for the structures cut most (at most
/// [`MAX_STRUCTURE_ROWS`], a last row saying how many more there are).
pub fn rows(variants: &[VariantMetrics]) -> Vec<Row> {
    let mut rows = Vec::new();
    let row = |label: String, cell: &dyn Fn(&Metrics) -> String| Row {
        label,
        cells: variants.iter().map(|v| cell(&v.metrics)).collect(),
    };
    rows.push(row("removed volume".into(), &|m| {
        mm3(m.structures.iter().filter_map(|s| s.removed_volume).sum())
    }));
    rows.push(row("removed surface".into(), &|m| {
        mm2(m.structures.iter().map(|s| s.removed_area).sum())
    }));
    rows.push(row("wall area".into(), &|m| {
        mm2(m.structures.iter().map(|s| s.wall_area).sum())
    }));
    rows.push(row("deepest cut".into(), &|m| {
        let depth = m.cutters.iter().map(|c| c.depth).fold(0.0, f64::max);
        format!("{depth:.1} mm")
    }));
    if let Some(focus) = variants.first().and_then(|v| v.metrics.focus.as_ref()) {
        rows.push(row(format!("{} seen", focus.name), &|m| {
            m.focus.as_ref().map_or(String::new(), |f| {
                format!(
                    "{:.0} → {:.0} %",
                    f.exposure_before * 100.0,
                    f.exposure_after * 100.0
                )
            })
        }));
    }
    let Some(first) = variants.first() else {
        return rows;
    };
    for (s, structure) in first.metrics.structures.iter().enumerate() {
        if structure.min_distance.is_some()
            || variants
                .iter()
                .any(|v| v.metrics.structures[s].min_distance.is_some())
        {
            rows.push(row(format!("to {}", structure.name), &|m| {
                m.structures[s]
                    .min_distance
                    .map_or("no walls".into(), |d| format!("{d:.1} mm"))
            }));
        }
    }
    // Structures by the most any variant removes from them.
    let removed = |s: usize| {
        variants
            .iter()
            .map(|v| {
                let m = &v.metrics.structures[s];
                m.removed_volume.unwrap_or(0.0).max(m.removed_area * 1e-9)
            })
            .fold(0.0, f64::max)
    };
    let mut cut: Vec<usize> = (0..first.metrics.structures.len())
        .filter(|&s| removed(s) > 0.0)
        .collect();
    cut.sort_by(|&a, &b| removed(b).total_cmp(&removed(a)));
    for &s in cut.iter().take(MAX_STRUCTURE_ROWS) {
        rows.push(row(
            format!("  {}", first.metrics.structures[s].name),
            &|m| {
                let st = &m.structures[s];
                match st.removed_volume {
                    Some(v) => mm3(v),
                    None => mm2(st.removed_area),
                }
            },
        ));
    }
    if cut.len() > MAX_STRUCTURE_ROWS {
        rows.push(Row {
            label: format!("  {} more cut structures", cut.len() - MAX_STRUCTURE_ROWS),
            cells: vec!["(see CSV)".into(); variants.len()],
        });
    }
    rows
}

fn mm3(v: f64) -> String {
    format!("{v:.1} mm³")
}

fn mm2(v: f64) -> String {
    format!("{v:.1} mm²")
}

/// The CSV file: [`CSV_HEADER`], then one line per variant and structure.
pub fn csv(variants: &[VariantMetrics]) -> String {
    let mut text = String::from(CSV_HEADER);
    text.push('\n');
    let number = |v: Option<f64>| v.map_or(String::new(), |v| format!("{v}"));
    for v in variants {
        for s in &v.metrics.structures {
            let focus = v.metrics.focus.as_ref().filter(|f| f.name == s.name);
            writeln!(
                text,
                "{},{},{},{},{},{},{},{},{}",
                quoted(&v.name),
                quoted(&s.name),
                s.closed,
                number(s.removed_volume),
                number(Some(s.removed_area)),
                number(Some(s.wall_area)),
                number(s.min_distance),
                number(focus.map(|f| f.exposure_before)),
                number(focus.map(|f| f.exposure_after)),
            )
            .expect("writing to a String");
        }
    }
    text
}

/// A CSV text field: in double quotes, inner quotes doubled.
fn quoted(text: &str) -> String {
    format!("\"{}\"", text.replace('"', "\"\""))
}

/// The JSON document of `cutaway compare`: `{"variants": [{"name", "image", "metrics"}…],
/// "combined": "compare.png"}`, `metrics` as `cutaway metrics --json` prints it.
pub fn json(variants: &[VariantMetrics], images: &[String], combined: &str) -> serde_json::Value {
    let list: Vec<serde_json::Value> = variants
        .iter()
        .zip(images)
        .map(|(v, image)| serde_json::json!({"name": v.name, "image": image, "metrics": v.metrics}))
        .collect();
    serde_json::json!({"variants": list, "combined": combined})
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::metrics::{FocusMeasures, StructureMeasures};

    fn structure(name: &str, volume: Option<f64>, area: f64) -> StructureMeasures {
        StructureMeasures {
            name: name.into(),
            closed: volume.is_some(),
            removed_volume: volume,
            removed_area: area,
            wall_area: 1.5,
            min_distance: None,
            closest_point: None,
            wall_point: None,
        }
    }

    fn variant(name: &str, skull: f64) -> VariantMetrics {
        VariantMetrics {
            name: name.into(),
            metrics: Metrics {
                cutters: Vec::new(),
                structures: vec![
                    structure("skin, \"outer\"", Some(10.0), 4.0),
                    structure("skull", Some(skull), 2.0),
                    structure("sheet", None, 0.0),
                ],
                focus: Some(FocusMeasures {
                    name: "skull".into(),
                    exposure_before: 0.25,
                    exposure_after: 0.5,
                    samples: 100,
                }),
            },
        }
    }

    #[test]
    fn rows_total_and_order_structures_by_removal() {
        let rows = rows(&[variant("a", 30.0), variant("b", 0.0)]);
        assert_eq!(rows[0].label, "removed volume");
        assert_eq!(rows[0].cells, ["40.0 mm³", "10.0 mm³"]);
        assert_eq!(rows[4].label, "skull seen");
        assert_eq!(rows[4].cells[0], "25 → 50 %");
        let names: Vec<&str> = rows[5..].iter().map(|r| r.label.as_str()).collect();
        assert_eq!(names, ["  skull", "  skin, \"outer\""]);
    }

    #[test]
    fn csv_quotes_names_and_leaves_unmeasured_cells_empty() {
        let text = csv(&[variant("a,b", 30.0)]);
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines[0], CSV_HEADER);
        assert_eq!(lines[1], "\"a,b\",\"skin, \"\"outer\"\"\",true,10,4,1.5,,,");
        assert_eq!(lines[2], "\"a,b\",\"skull\",true,30,2,1.5,,0.25,0.5");
        assert_eq!(lines[3], "\"a,b\",\"sheet\",false,,0,1.5,,,");
    }
}
