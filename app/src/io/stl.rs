//! STL, ASCII and binary (our own parser and writer).
//!
//! Why not `stl_io`: it treats every file whose first line starts with `solid ` as ASCII, but
//! binary STL headers are free text and many exporters begin them with `solid`, so such binary
//! files fail to load. Here a file is binary exactly when its size is `84 + 50·count` for the
//! count in its header (the layout leaves no other possibility), and ASCII otherwise when it
//! starts with `solid`. The count is checked against the size before anything is allocated.
//!
//! Binary coordinates are `f32`, converted to `f64` exactly. ASCII coordinates are parsed
//! straight to `f64`. Each ASCII `solid … endsolid` block becomes its own part, named after the
//! solid when it has a name. A facet loop of more than three vertices is fan-triangulated.

use std::io::Write;

use csg::{DVec3, Mesh};

use super::RawPart;

const HEADER: usize = 80;
const TRIANGLE_RECORD: u64 = 50;

/// True when `bytes` has exactly the size a binary STL with its header's triangle count has.
pub(crate) fn is_binary_size(bytes: &[u8]) -> bool {
    binary_count(bytes).is_some_and(|count| expected_binary_size(count) == bytes.len() as u64)
}

fn binary_count(bytes: &[u8]) -> Option<u32> {
    let count: [u8; 4] = bytes.get(HEADER..HEADER + 4)?.try_into().ok()?;
    Some(u32::from_le_bytes(count))
}

fn expected_binary_size(count: u32) -> u64 {
    (HEADER as u64 + 4) + TRIANGLE_RECORD * count as u64
}

/// Parses an STL file (binary or ASCII, see the module doc).
pub(crate) fn parse(bytes: &[u8]) -> anyhow::Result<Vec<RawPart>> {
    if is_binary_size(bytes) {
        return Ok(vec![parse_binary(bytes)]);
    }
    let text_start = super::trim_ascii_start(bytes);
    if text_start.starts_with(b"solid") {
        return parse_ascii(text_start);
    }
    match binary_count(bytes) {
        None => anyhow::bail!(
            "not an STL file: {} bytes, too short for a binary STL (84-byte header) and no ASCII 'solid' line",
            bytes.len()
        ),
        Some(count) => {
            let room = (bytes.len() as u64 - (HEADER as u64 + 4)) / TRIANGLE_RECORD;
            anyhow::bail!(
                "binary STL header says {count} triangles ({} bytes), but the file has {} bytes (room for {room} triangles); truncated or not an STL file",
                expected_binary_size(count),
                bytes.len()
            )
        }
    }
}

/// Reads a binary STL whose size has been checked by [`is_binary_size`].
fn parse_binary(bytes: &[u8]) -> RawPart {
    let records = &bytes[HEADER + 4..];
    let count = records.len() / TRIANGLE_RECORD as usize;
    let mut positions = Vec::with_capacity(count * 3);
    let mut triangles = Vec::with_capacity(count);
    for record in records.chunks_exact(TRIANGLE_RECORD as usize) {
        // Bytes 0..12: facet normal (ignored: recomputed from the corners); 48..50: attribute.
        let first = positions.len() as u32;
        for corner in 0..3 {
            let at = 12 + corner * 12;
            let f = |i: usize| {
                let b = &record[at + 4 * i..at + 4 * i + 4];
                f64::from(f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
            };
            positions.push(DVec3::new(f(0), f(1), f(2)));
        }
        triangles.push([first, first + 1, first + 2]);
    }
    RawPart {
        name: None,
        positions,
        triangles,
    }
}

/// Reads ASCII STL: `solid [name]`, then `facet normal nx ny nz`, `outer loop`, `vertex x y z`…,
/// `endloop`, `endfacet`, …, `endsolid [name]`; several solids may follow each other.
fn parse_ascii(bytes: &[u8]) -> anyhow::Result<Vec<RawPart>> {
    let text = std::str::from_utf8(bytes).map_err(|e| {
        anyhow::anyhow!(
            "ASCII STL with a non-text byte at offset {}",
            e.valid_up_to()
        )
    })?;
    let mut parts = Vec::new();
    let mut current: Option<RawPart> = None;
    let mut loop_corners: Vec<DVec3> = Vec::new();
    let mut in_loop = false;
    for (line_index, line) in text.lines().enumerate() {
        let line_number = line_index + 1;
        let mut words = line.split_ascii_whitespace();
        let Some(keyword) = words.next() else {
            continue;
        };
        let at = |what: &str| anyhow::anyhow!("ASCII STL line {line_number}: {what}");
        match keyword {
            "solid" => {
                if current.is_some() {
                    return Err(at("'solid' inside a solid (missing 'endsolid')"));
                }
                let name = line.trim_start()["solid".len()..].trim();
                current = Some(RawPart {
                    name: (!name.is_empty()).then(|| name.to_owned()),
                    ..RawPart::default()
                });
            }
            "endsolid" => {
                if in_loop {
                    return Err(at("'endsolid' inside a facet loop"));
                }
                parts.push(
                    current
                        .take()
                        .ok_or_else(|| at("'endsolid' without 'solid'"))?,
                );
            }
            "facet" | "endfacet" => {
                if current.is_none() {
                    return Err(at("facet outside a solid"));
                }
            }
            "outer" => {
                if in_loop {
                    return Err(at("'outer loop' inside a loop"));
                }
                in_loop = true;
                loop_corners.clear();
            }
            "vertex" => {
                if !in_loop {
                    return Err(at("'vertex' outside 'outer loop'"));
                }
                let mut xyz = [0.0; 3];
                for value in &mut xyz {
                    let word = words
                        .next()
                        .ok_or_else(|| at("vertex needs three coordinates"))?;
                    *value = word
                        .parse::<f64>()
                        .map_err(|_| at(&format!("'{word}' is not a number")))?;
                }
                loop_corners.push(DVec3::from_array(xyz));
            }
            "endloop" => {
                if !in_loop {
                    return Err(at("'endloop' without 'outer loop'"));
                }
                in_loop = false;
                if loop_corners.len() < 3 {
                    return Err(at(&format!(
                        "a facet needs at least 3 vertices, this one has {}",
                        loop_corners.len()
                    )));
                }
                let part = current
                    .as_mut()
                    .ok_or_else(|| at("facet outside a solid"))?;
                let first = part.positions.len() as u32;
                part.positions.extend_from_slice(&loop_corners);
                for k in 1..loop_corners.len() as u32 - 1 {
                    part.triangles.push([first, first + k, first + k + 1]);
                }
            }
            other => return Err(at(&format!("unexpected '{other}'"))),
        }
    }
    if in_loop {
        anyhow::bail!("ASCII STL ends inside a facet loop (truncated)");
    }
    // A missing final 'endsolid' is common enough to accept when the facets are complete.
    if let Some(part) = current {
        parts.push(part);
    }
    if parts.len() > 1 {
        return Ok(parts);
    }
    // A single solid stands for the whole file: it takes the file's name, not the solid's.
    Ok(parts
        .into_iter()
        .map(|p| RawPart { name: None, ..p })
        .collect())
}

/// Writes binary STL (coordinates rounded to `f32`, facet normals from the corners).
pub(crate) fn write_binary(w: &mut dyn Write, mesh: &Mesh, count: u32) -> std::io::Result<()> {
    let mut header = [b' '; HEADER];
    let title = b"binary STL written by cutaway";
    header[..title.len()].copy_from_slice(title);
    w.write_all(&header)?;
    w.write_all(&count.to_le_bytes())?;
    let mut record = [0u8; TRIANGLE_RECORD as usize];
    for t in 0..mesh.triangles.len() {
        let normal = mesh.face_normal_scaled(t).normalize_or_zero();
        let corners = mesh.corners(t);
        let values = std::iter::once(normal).chain(corners);
        for (i, v) in values.enumerate() {
            for (k, c) in v.to_array().into_iter().enumerate() {
                let at = i * 12 + k * 4;
                record[at..at + 4].copy_from_slice(&(c as f32).to_le_bytes());
            }
        }
        w.write_all(&record)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn binary_with_header(header_text: &[u8], triangles: &[[[f32; 3]; 3]]) -> Vec<u8> {
        let mut bytes = vec![0u8; HEADER];
        bytes[..header_text.len()].copy_from_slice(header_text);
        bytes.extend_from_slice(&(triangles.len() as u32).to_le_bytes());
        for tri in triangles {
            bytes.extend_from_slice(&[0u8; 12]);
            for corner in tri {
                for c in corner {
                    bytes.extend_from_slice(&c.to_le_bytes());
                }
            }
            bytes.extend_from_slice(&[0u8; 2]);
        }
        bytes
    }

    #[test]
    fn binary_starting_with_solid_is_read_as_binary() {
        let tri = [[0.1f32, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
        let bytes = binary_with_header(b"solid this is really binary", &[tri]);
        let parts = parse(&bytes).unwrap();
        assert_eq!(parts.len(), 1);
        assert_eq!(parts[0].triangles, vec![[0, 1, 2]]);
        // f32 -> f64 exactly: 0.1f32 is not 0.1f64.
        assert_eq!(parts[0].positions[0].x, f64::from(0.1f32));
    }

    #[test]
    fn absurd_binary_count_is_an_error_before_allocation() {
        let mut bytes = binary_with_header(b"x", &[]);
        bytes[80..84].copy_from_slice(&4_000_000_000u32.to_le_bytes());
        bytes.extend_from_slice(&[0u8; 50]);
        let message = format!("{:#}", parse(&bytes).unwrap_err());
        assert!(message.contains("4000000000"), "{message}");
    }

    #[test]
    fn ascii_with_two_solids_gives_two_named_parts() {
        let text = b"solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid a\n\
solid b\nfacet normal 0 0 1\nouter loop\nvertex 0 0 1\nvertex 1 0 1\nvertex 1 1 1\nvertex 0 1 1\nendloop\nendfacet\nendsolid b\n";
        let parts = parse(text).unwrap();
        assert_eq!(parts.len(), 2);
        assert_eq!(parts[0].name.as_deref(), Some("a"));
        assert_eq!(parts[1].name.as_deref(), Some("b"));
        assert_eq!(parts[1].triangles, vec![[0, 1, 2], [0, 2, 3]]);
        assert_eq!(parts[0].positions[1], DVec3::new(1.0, 0.0, 0.0));
    }

    #[test]
    fn truncated_ascii_is_an_error() {
        let text = b"solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0";
        let message = format!("{:#}", parse(text).unwrap_err());
        assert!(message.contains("line 5"), "{message}");
    }
}
