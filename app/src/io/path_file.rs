//! `cutaway-path/1` files: the tool path `cutaway scalpel` replays (see `CONTRACT.md`).
//!
//! ```json
//! {"format": "cutaway-path/1", "depth": 4.0, "tool": "scalpel",
//!  "points": [[x, y, z], …], "open": {"width": 1.5, "window": 0.5}}
//! ```
//! `strokes: [[[x, y, z], …], …]` may replace `points` (several cuts, one after another). `depth`
//! defaults to 0 (a slit), `tool` to `scalpel`, and without `open` the cut is written closed
//! (rest pose). `window` is in seconds of tool time, samples being 1/60 s apart.
//! Every problem is reported as one line naming the file.

use std::path::Path;

use anyhow::Context;
use cutter::scalpel::{OpenOptions, Tool};
use glam::DVec3;
use serde::Deserialize;

/// The format tag every path file starts with.
pub const FORMAT: &str = "cutaway-path/1";

/// A parsed, validated path file.
#[derive(Clone, Debug, PartialEq)]
pub struct PathFile {
    /// Blade depth (>= 0).
    pub depth: f64,
    pub tool: Tool,
    /// One or more strokes, each with at least one finite sample.
    pub strokes: Vec<Vec<DVec3>>,
    /// How to open the incision, if at all.
    pub open: Option<OpenOptions>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawPathFile {
    format: String,
    #[serde(default)]
    depth: f64,
    #[serde(default)]
    tool: Option<String>,
    #[serde(default)]
    points: Option<Vec<[f64; 3]>>,
    #[serde(default)]
    strokes: Option<Vec<Vec<[f64; 3]>>>,
    #[serde(default)]
    open: Option<RawOpen>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawOpen {
    width: f64,
    #[serde(default = "default_window")]
    window: f64,
}

fn default_window() -> f64 {
    OpenOptions::default().window
}

/// Parses the text of a path file (errors without the file name; see [`read_path_file`]).
pub fn parse_path_file(text: &str) -> Result<PathFile, String> {
    let raw: RawPathFile =
        serde_json::from_str(text).map_err(|e| format!("not a {FORMAT} file: {e}"))?;
    if raw.format != FORMAT {
        return Err(format!("format is {:?}, expected {FORMAT:?}", raw.format));
    }
    if !(raw.depth.is_finite() && raw.depth >= 0.0) {
        return Err(format!("depth {} must be a number >= 0", raw.depth));
    }
    let tool = match raw.tool.as_deref() {
        None | Some("scalpel") => Tool::Scalpel,
        Some("loop") => Tool::Loop,
        Some(other) => return Err(format!("tool {other:?} is not \"scalpel\" or \"loop\"")),
    };
    let strokes: Vec<Vec<[f64; 3]>> = match (raw.points, raw.strokes) {
        (Some(p), None) => vec![p],
        (None, Some(s)) => s,
        (Some(_), Some(_)) => return Err("give either \"points\" or \"strokes\", not both".into()),
        (None, None) => return Err("no \"points\" or \"strokes\"".into()),
    };
    if strokes.is_empty() {
        return Err("\"strokes\" is empty".into());
    }
    let mut out = Vec::with_capacity(strokes.len());
    for (s, stroke) in strokes.iter().enumerate() {
        if stroke.is_empty() {
            return Err(format!("stroke {s} has no points"));
        }
        if let Some((k, p)) = stroke
            .iter()
            .enumerate()
            .find(|(_, p)| !p.iter().all(|c| c.is_finite()))
        {
            return Err(format!("stroke {s} point {k} {p:?} is not finite"));
        }
        out.push(stroke.iter().map(|&p| DVec3::from_array(p)).collect());
    }
    let open = match raw.open {
        None => None,
        Some(o) => {
            if !(o.width.is_finite() && o.width >= 0.0) {
                return Err(format!("open.width {} must be a number >= 0", o.width));
            }
            if !(o.window.is_finite() && o.window >= 0.0) {
                return Err(format!("open.window {} must be a number >= 0", o.window));
            }
            Some(OpenOptions {
                width: o.width,
                window: o.window,
            })
        }
    };
    Ok(PathFile {
        depth: raw.depth,
        tool,
        strokes: out,
        open,
    })
}

/// Reads and validates a path file; errors read `<file>: <problem>`.
pub fn read_path_file(path: &Path) -> anyhow::Result<PathFile> {
    let text = crate::io::bounded::read_text(path, crate::io::bounded::JSON_MAX_BYTES)
        .with_context(|| path.display().to_string())?;
    parse_path_file(&text)
        .map_err(anyhow::Error::msg)
        .with_context(|| path.display().to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_points_and_defaults() {
        let f =
            parse_path_file(r#"{"format":"cutaway-path/1","points":[[0,0,0],[1,2,3]]}"#).unwrap();
        assert_eq!(f.depth, 0.0);
        assert_eq!(f.tool, Tool::Scalpel);
        assert_eq!(f.strokes, vec![vec![DVec3::ZERO, DVec3::new(1., 2., 3.)]]);
        assert_eq!(f.open, None);
    }

    #[test]
    fn parses_strokes_loop_and_open() {
        let f = parse_path_file(
            r#"{"format":"cutaway-path/1","depth":4.0,"tool":"loop","strokes":[[[0,0,0]],[[1,1,1],[2,2,2]]],"open":{"width":1.5,"window":0.25}}"#,
        )
        .unwrap();
        assert_eq!(f.depth, 4.0);
        assert_eq!(f.tool, Tool::Loop);
        assert_eq!(f.strokes.len(), 2);
        assert_eq!(
            f.open,
            Some(OpenOptions {
                width: 1.5,
                window: 0.25
            })
        );
    }

    #[test]
    fn rejects_bad_files_with_a_reason() {
        for (text, needle) in [
            (
                r#"{"format":"cutaway-path/2","points":[[0,0,0]]}"#,
                "expected",
            ),
            (r#"{"format":"cutaway-path/1"}"#, "no \"points\""),
            (
                r#"{"format":"cutaway-path/1","points":[[0,0,0]],"strokes":[[[0,0,0]]]}"#,
                "not both",
            ),
            (
                r#"{"format":"cutaway-path/1","points":[[0,0,0]],"tool":"saw"}"#,
                "tool",
            ),
            (
                r#"{"format":"cutaway-path/1","points":[[0,0,0]],"depth":-1}"#,
                "depth",
            ),
            (r#"{"format":"cutaway-path/1","points":[]}"#, "no points"),
            (
                r#"{"format":"cutaway-path/1","points":[[0,0]]}"#,
                "not a cutaway-path/1",
            ),
            (
                r#"{"format":"cutaway-path/1","points":[[0,0,0]],"open":{"width":-2}}"#,
                "width",
            ),
        ] {
            let e = parse_path_file(text).unwrap_err();
            assert!(e.contains(needle), "{text}: {e}");
        }
    }
}
