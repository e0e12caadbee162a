//! Colour tables: label value → name and colour.
//!
//! Read formats (one entry per line, `#` comments and blank lines skipped):
//! - 3D Slicer `.ctbl`/`.txt` and FreeSurfer LUT: `value name r g b [a]`, colours 0..=255;
//! - ITK-SNAP label description: `value r g b a visible mesh "name"`, alpha 0..=1.
//!
//! A line that fits neither form is an **error** naming the file and the line, as is a value
//! listed twice: a table is small and hand-edited, and a silently skipped line would give a
//! structure the wrong name. Label 0 (background) may be listed and is ignored.
//!
//! [`find_beside`] looks for the table of a volume: a file with the volume's stem and a table
//! extension (`.ctbl`, `.txt`, `.lut`, `.label`); else the only `.ctbl` in the folder; else the
//! only `.txt`/`.lut` in the folder that reads as a table (other text files, such as a licence,
//! are passed over). A table found by its name or extension must read cleanly.

use std::path::{Path, PathBuf};

use anyhow::Context as _;

use super::LabelInfo;

/// Reads a colour table file. Errors name the file.
pub fn read(path: &Path) -> anyhow::Result<Vec<LabelInfo>> {
    let text = read_text(path).with_context(|| path.display().to_string())?;
    parse(&text).with_context(|| path.display().to_string())
}

/// A table is text and small; a huge or binary file is refused before it is parsed.
fn read_text(path: &Path) -> anyhow::Result<String> {
    const MAX_TABLE: u64 = 64 << 20;
    let metadata = std::fs::metadata(path)?;
    if !metadata.is_file() {
        anyhow::bail!("not a colour table file");
    }
    if metadata.len() > MAX_TABLE {
        anyhow::bail!("{} bytes is too large for a colour table", metadata.len());
    }
    let bytes = crate::io::bounded::read_bytes(path, MAX_TABLE)?;
    String::from_utf8(bytes).map_err(|_| anyhow::anyhow!("a colour table must be text (UTF-8)"))
}

/// Parses a table's text.
pub fn parse(text: &str) -> anyhow::Result<Vec<LabelInfo>> {
    let mut out: Vec<LabelInfo> = Vec::new();
    let mut seen = std::collections::HashMap::new();
    for (number, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let entry = parse_line(line).ok_or_else(|| {
            let shown: String = line.chars().take(60).collect();
            anyhow::anyhow!(
                "line {}: '{shown}' is not a colour table entry (expected 'value name r g b [a]' or ITK-SNAP 'value r g b a vis mesh \"name\"')",
                number + 1
            )
        })?;
        if let Some(first) = seen.insert(entry.value, number + 1) {
            anyhow::bail!(
                "line {}: value {} is listed twice (first on line {first})",
                number + 1,
                entry.value
            );
        }
        if entry.value != 0 {
            out.push(entry);
        }
    }
    if out.is_empty() {
        anyhow::bail!("no label entries in this colour table");
    }
    Ok(out)
}

fn parse_line(line: &str) -> Option<LabelInfo> {
    if let Some(quote) = line.find('"') {
        // ITK-SNAP: seven numbers, then the quoted name.
        let name = line[quote + 1..].strip_suffix('"')?;
        let numbers: Vec<&str> = line[..quote].split_whitespace().collect();
        if numbers.len() != 7 || name.contains('"') {
            return None;
        }
        let value = numbers[0].parse().ok()?;
        let color = rgb(&numbers[1..4])?;
        numbers[4]
            .parse::<f64>()
            .ok()
            .filter(|a| (0.0..=1.0).contains(a))?;
        numbers[5..7]
            .iter()
            .all(|n| n.parse::<u8>().is_ok())
            .then_some(())?;
        return Some(LabelInfo {
            layer: None,
            value,
            name: name.to_owned(),
            color: Some(color),
        });
    }
    let words: Vec<&str> = line.split_whitespace().collect();
    if !(5..=6).contains(&words.len()) {
        return None;
    }
    let value = words[0].parse().ok()?;
    let color = rgb(&words[2..5])?;
    if let Some(alpha) = words.get(5) {
        alpha.parse::<u8>().ok()?;
    }
    Some(LabelInfo {
        layer: None,
        value,
        name: words[1].to_owned(),
        color: Some(color),
    })
}

fn rgb(words: &[&str]) -> Option<[u8; 3]> {
    Some([
        words[0].parse().ok()?,
        words[1].parse().ok()?,
        words[2].parse().ok()?,
    ])
}

const TABLE_EXTENSIONS: [&str; 4] = ["ctbl", "txt", "lut", "label"];

/// The colour table beside a volume file (see the module doc), read; empty when there is none.
pub fn find_beside(volume: &Path) -> anyhow::Result<Vec<LabelInfo>> {
    let dir = match volume.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    };
    let stem = super::volume_stem(volume);
    for ext in TABLE_EXTENSIONS {
        let candidate = dir.join(format!("{stem}.{ext}"));
        if candidate.is_file() {
            return read(&candidate);
        }
    }
    let Ok(entries) = std::fs::read_dir(&dir) else {
        return Ok(Vec::new());
    };
    let mut by_ext: [Vec<PathBuf>; 2] = [Vec::new(), Vec::new()];
    for entry in entries.flatten() {
        let path = entry.path();
        let ext = path
            .extension()
            .map(|e| e.to_string_lossy().to_ascii_lowercase())
            .unwrap_or_default();
        let hidden = entry.file_name().to_string_lossy().starts_with('.');
        if hidden || !path.is_file() {
            continue;
        }
        match ext.as_str() {
            "ctbl" => by_ext[0].push(path),
            "txt" | "lut" => by_ext[1].push(path),
            _ => {}
        }
    }
    if let [only] = by_ext[0].as_slice() {
        return read(only);
    }
    by_ext[1].sort();
    let tables: Vec<Vec<LabelInfo>> = by_ext[1].iter().filter_map(|p| read(p).ok()).collect();
    Ok(match <[_; 1]>::try_from(tables) {
        Ok([only]) => only,
        Err(_) => Vec::new(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn slicer_freesurfer_and_itksnap_lines() {
        let text = "# Slicer\n0 background 0 0 0 0\n2 white_matter 250 250 225 255\n\n17  Left-Hippocampus  220 216 20  0\n   5   255    0    0        1  1  1    \"Label 5 with spaces\"\n3 skin 225 190 150\n";
        let t = parse(text).unwrap();
        let got: Vec<(u32, &str, [u8; 3])> = t
            .iter()
            .map(|e| (e.value, e.name.as_str(), e.color.unwrap()))
            .collect();
        assert_eq!(
            got,
            vec![
                (2, "white_matter", [250, 250, 225]),
                (17, "Left-Hippocampus", [220, 216, 20]),
                (5, "Label 5 with spaces", [255, 0, 0]),
                (3, "skin", [225, 190, 150]),
            ]
        );
    }

    #[test]
    fn junk_lines_and_duplicates_are_errors_with_the_line() {
        let err = parse("1 a 1 2 3 255\nthis is not a table\n").unwrap_err();
        assert!(
            err.to_string().starts_with("line 2: 'this is not a table'"),
            "{err}"
        );
        let err = parse("1 a 1 2 3\n1 b 4 5 6\n").unwrap_err();
        assert_eq!(
            err.to_string(),
            "line 2: value 1 is listed twice (first on line 1)"
        );
        assert!(parse("1 a 300 2 3\n").is_err());
        assert!(parse("# only comments\n0 background 0 0 0 0\n").is_err());
    }
}
