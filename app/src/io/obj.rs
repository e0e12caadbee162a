//! Wavefront OBJ: reading through `tobj` (built with `use_f64`, so coordinates are parsed straight
//! to `f64`), writing with Rust's shortest round-trip formatting (`{}` on `f64` prints the fewest
//! digits that parse back to the same bits), so written values read back exactly.
//!
//! Reading options: `single_index` (one index per corner; tobj splits a position used with
//! different normals or texture coordinates, and our weld merges it back), `triangulate`
//! (polygons become fans), points and lines ignored (they bound no surface). Each OBJ object or
//! group (`o`/`g`) is a part; tobj's placeholder name for faces before any `o`/`g` becomes "the
//! file". Materials are not loaded.
//!
//! A vertex's optional fourth value `w` is a weight for rational curves and surfaces; the OBJ
//! specification says it is not used for polygonal geometry. tobj divides `x y z` by it (and
//! refuses `w = 0`), so `w` is removed from `v` lines before tobj sees them ([`without_vertex_w`])
//! and the fast path skips it: `v 1 2 3 0.5` is the point (1, 2, 3).

use std::io::{BufReader, Write};

use csg::{DVec3, Mesh};

use super::RawPart;

/// tobj's name for faces that come before any `o`/`g` line.
const TOBJ_UNNAMED: &str = "unnamed_object";

pub(crate) fn parse(bytes: &[u8]) -> anyhow::Result<Vec<RawPart>> {
    match parse_plain(bytes) {
        Some(parts) => Ok(parts),
        None => parse_with_tobj(bytes),
    }
}

fn parse_with_tobj(bytes: &[u8]) -> anyhow::Result<Vec<RawPart>> {
    let bytes = without_vertex_w(bytes);
    let bytes = &bytes[..];
    // `LoadOptions` has more fields when tobj's optional features (`merging`, `reordering`) are
    // on, so the update is needed in such builds although it is not in ours.
    #[allow(clippy::needless_update)]
    let options = tobj::LoadOptions {
        single_index: true,
        triangulate: true,
        ignore_points: true,
        ignore_lines: true,
        ..Default::default()
    };
    let mut reader = BufReader::new(bytes);
    let (models, _materials) = tobj::load_obj_buf(&mut reader, &options, |_| {
        Err(tobj::LoadError::OpenFileFailed)
    })
    .map_err(|e| match e {
        tobj::LoadError::ReadError => {
            anyhow::anyhow!("not a text OBJ file (unreadable line or a non-UTF-8 byte)")
        }
        other => anyhow::anyhow!("malformed OBJ: {other}"),
    })?;
    models
        .into_iter()
        .map(|model| {
            let mesh = model.mesh;
            if !mesh.indices.len().is_multiple_of(3) {
                anyhow::bail!(
                    "malformed OBJ: object '{}' has an incomplete triangle",
                    model.name
                );
            }
            let positions = mesh
                .positions
                .chunks_exact(3)
                .map(|p| DVec3::new(p[0], p[1], p[2]))
                .collect();
            let triangles = mesh
                .indices
                .chunks_exact(3)
                .map(|t| [t[0], t[1], t[2]])
                .collect();
            let name = (model.name != TOBJ_UNNAMED && !model.name.is_empty()).then_some(model.name);
            Ok(RawPart {
                name,
                positions,
                triangles,
            })
        })
        .collect()
}

/// `bytes` with the fourth value of every `v` line that has exactly four values removed (see the
/// module doc); borrowed unchanged when no line has one. Lines with colours (`v x y z r g b`) and
/// everything else are kept byte for byte, so tobj's errors and line numbers stay the same.
fn without_vertex_w(bytes: &[u8]) -> std::borrow::Cow<'_, [u8]> {
    let has_w = |line: &[u8]| {
        let mut words = line
            .split(|b| b.is_ascii_whitespace())
            .filter(|w| !w.is_empty());
        words.next() == Some(b"v".as_slice()) && words.count() == 4
    };
    if !bytes.split(|&b| b == b'\n').any(has_w) {
        return std::borrow::Cow::Borrowed(bytes);
    }
    let mut out = Vec::with_capacity(bytes.len());
    for (i, line) in bytes.split(|&b| b == b'\n').enumerate() {
        if i > 0 {
            out.push(b'\n');
        }
        if !has_w(line) {
            out.extend_from_slice(line);
            continue;
        }
        // Keep everything up to the end of the third value: drop the last word only.
        let trimmed = line.trim_ascii_end();
        let last_start = trimmed
            .iter()
            .rposition(|b| b.is_ascii_whitespace())
            .map_or(0, |p| p + 1);
        out.extend_from_slice(trimmed[..last_start].trim_ascii_end());
        if line.ends_with(b"\r") {
            out.push(b'\r');
        }
    }
    std::borrow::Cow::Owned(out)
}

/// The fast path for plain triangle OBJ (what our writer and most mesh tools produce): ASCII text
/// whose geometry is only `v x y z`, `f a b c` with plain (possibly negative) position indices
/// that refer to vertices already read, and `o`/`g` names. Anything else (texture or normal
/// references, polygons, colours, lines, points, an index that is out of range,
/// malformed numbers) returns `None` and the whole file goes to tobj, which also words the
/// errors. On the files it accepts the result equals tobj's after welding and compaction.
///
/// Why: tobj allocates a `String` per line and hashes every corner; on a 2M-triangle OBJ that
/// alone took most of `cutaway info`'s 2 s budget (see `app/benches/load.rs`).
fn parse_plain(bytes: &[u8]) -> Option<Vec<RawPart>> {
    if !bytes.is_ascii() {
        return None;
    }
    let text = std::str::from_utf8(bytes).ok()?;
    let mut positions: Vec<DVec3> = Vec::new();
    // (name, triangles in file-wide position indices)
    let mut parts: Vec<(Option<String>, Vec<[u32; 3]>)> = vec![(None, Vec::new())];
    for line in text.lines() {
        let mut words = line.split_ascii_whitespace();
        let Some(keyword) = words.next() else {
            continue;
        };
        match keyword {
            "v" => {
                let mut xyz = [0.0; 3];
                for value in &mut xyz {
                    *value = words.next()?.parse().ok()?;
                }
                // An optional weight `w`, not used by polygons (see the module doc).
                if let Some(w) = words.next() {
                    w.parse::<f64>().ok()?;
                    if words.next().is_some() {
                        return None;
                    }
                }
                positions.push(DVec3::from_array(xyz));
            }
            "f" => {
                let count = positions.len() as i64;
                let mut tri = [0u32; 3];
                for corner in &mut tri {
                    let index: i64 = words.next()?.parse().ok()?;
                    let resolved = if index < 0 { count + index } else { index - 1 };
                    if !(0..count).contains(&resolved) {
                        return None;
                    }
                    *corner = u32::try_from(resolved).ok()?;
                }
                if words.next().is_some() {
                    return None;
                }
                parts.last_mut()?.1.push(tri);
            }
            "o" | "g" => {
                if !line.starts_with(keyword) {
                    return None; // indented: tobj names it differently; let tobj decide
                }
                let name = line[1..].trim();
                let name = (!name.is_empty()).then(|| name.to_owned());
                match parts.last_mut() {
                    Some(last) if last.1.is_empty() => last.0 = name,
                    _ => parts.push((name, Vec::new())),
                }
            }
            "vt" | "vn" | "l" | "p" => return None,
            _ => {} // comments, `s`, `usemtl`, `mtllib`, …: no geometry (tobj ignores them too)
        }
    }
    let parts: Vec<_> = parts.into_iter().filter(|(_, t)| !t.is_empty()).collect();
    if parts.len() == 1 {
        let (name, triangles) = parts.into_iter().next()?;
        return Some(vec![RawPart {
            name,
            positions,
            triangles,
        }]);
    }
    // Several parts: give each only the positions it uses (in order of first use).
    let mut local = vec![u32::MAX; positions.len()];
    let mut owner = vec![usize::MAX; positions.len()];
    Some(
        parts
            .into_iter()
            .enumerate()
            .map(|(p, (name, triangles))| {
                let mut part_positions = Vec::new();
                let triangles = triangles
                    .into_iter()
                    .map(|tri| {
                        tri.map(|i| {
                            let i = i as usize;
                            if owner[i] != p {
                                owner[i] = p;
                                local[i] = part_positions.len() as u32;
                                part_positions.push(positions[i]);
                            }
                            local[i]
                        })
                    })
                    .collect();
                RawPart {
                    name,
                    positions: part_positions,
                    triangles,
                }
            })
            .collect(),
    )
}

fn write_vertices(w: &mut dyn Write, positions: &[DVec3]) -> std::io::Result<()> {
    for p in positions {
        writeln!(w, "v {} {} {}", p.x, p.y, p.z)?;
    }
    Ok(())
}

/// Writes `mesh` as `v` and `f` records (1-based indices).
pub(crate) fn write_mesh(w: &mut dyn Write, mesh: &Mesh) -> std::io::Result<()> {
    writeln!(
        w,
        "# written by cutaway: {} vertices, {} triangles",
        mesh.positions.len(),
        mesh.triangles.len()
    )?;
    write_vertices(w, &mesh.positions)?;
    for [a, b, c] in &mesh.triangles {
        writeln!(w, "f {} {} {}", a + 1, b + 1, c + 1)?;
    }
    Ok(())
}

/// Checks polygon faces before anything is written: at least 3 corners, indices in range.
pub(crate) fn check_polygons(positions: &[DVec3], faces: &[Vec<u32>]) -> anyhow::Result<()> {
    if let Some((v, p)) = positions.iter().enumerate().find(|(_, p)| !p.is_finite()) {
        anyhow::bail!("vertex {v} has a non-finite coordinate {p}");
    }
    for (f, face) in faces.iter().enumerate() {
        if face.len() < 3 {
            anyhow::bail!(
                "face {f} has {} corners; a polygon needs at least 3",
                face.len()
            );
        }
        if let Some(&i) = face.iter().find(|&&i| i as usize >= positions.len()) {
            anyhow::bail!(
                "face {f} uses vertex {i}, but there are only {} vertices",
                positions.len()
            );
        }
    }
    Ok(())
}

/// Writes general polygons (`f a b c d …`).
pub(crate) fn write_polygons(
    w: &mut dyn Write,
    positions: &[DVec3],
    faces: &[Vec<u32>],
) -> std::io::Result<()> {
    writeln!(
        w,
        "# written by cutaway: {} vertices, {} polygons",
        positions.len(),
        faces.len()
    )?;
    write_vertices(w, positions)?;
    for face in faces {
        w.write_all(b"f")?;
        for i in face {
            write!(w, " {}", i + 1)?;
        }
        w.write_all(b"\n")?;
    }
    Ok(())
}

/// Checks polylines before anything is written: at least 2 points each, all finite.
pub(crate) fn check_polylines(polylines: &[Vec<DVec3>]) -> anyhow::Result<()> {
    for (l, line) in polylines.iter().enumerate() {
        if line.len() < 2 {
            anyhow::bail!(
                "polyline {l} has {} points; a polyline needs at least 2",
                line.len()
            );
        }
        if let Some(p) = line.iter().find(|p| !p.is_finite()) {
            anyhow::bail!("polyline {l} has a non-finite point {p}");
        }
    }
    Ok(())
}

/// True when a polyline ends where it starts (bit for bit): it is written as a closed loop.
fn is_closed(line: &[DVec3]) -> bool {
    line.len() > 2
        && line.first().map(|p| p.to_array().map(f64::to_bits))
            == line.last().map(|p| p.to_array().map(f64::to_bits))
}

/// Writes polylines: each point once as `v`, then one `l` record per polyline.
pub(crate) fn write_polylines(w: &mut dyn Write, polylines: &[Vec<DVec3>]) -> std::io::Result<()> {
    writeln!(w, "# written by cutaway: {} polylines", polylines.len())?;
    for line in polylines {
        let points = if is_closed(line) {
            &line[..line.len() - 1]
        } else {
            &line[..]
        };
        write_vertices(w, points)?;
    }
    let mut next = 1usize;
    for line in polylines {
        let closed = is_closed(line);
        let count = if closed { line.len() - 1 } else { line.len() };
        w.write_all(b"l")?;
        for i in next..next + count {
            write!(w, " {i}")?;
        }
        if closed {
            write!(w, " {next}")?;
        }
        w.write_all(b"\n")?;
        next += count;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn groups_become_named_parts_and_polygons_fans() {
        let text = b"v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\n\
o first\ng first\nf 1 2 3 4\no second\nf 1 2 5\n";
        let parts = parse(text).unwrap();
        assert_eq!(parts.len(), 2);
        assert_eq!(parts[0].name.as_deref(), Some("first"));
        assert_eq!(parts[0].triangles.len(), 2);
        assert_eq!(parts[1].name.as_deref(), Some("second"));
        assert_eq!(parts[1].triangles.len(), 1);
        assert_eq!(parts[1].positions[2], DVec3::new(0.0, 0.0, 1.0));
    }

    #[test]
    fn faces_before_any_group_belong_to_the_file() {
        let parts = parse(b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
        assert_eq!(parts.len(), 1);
        assert_eq!(parts[0].name, None);
    }

    #[test]
    fn decimal_text_is_parsed_to_f64_not_f32() {
        let parts = parse(b"v 0.1 0.2 0.3\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
        assert_eq!(parts[0].positions[0], DVec3::new(0.1, 0.2, 0.3));
    }

    #[test]
    fn out_of_range_face_index_is_an_error() {
        assert!(parse(b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n").is_err());
    }

    /// The fast path and tobj agree, after the common welding and compaction, on plain files.
    #[test]
    fn fast_path_matches_tobj_on_plain_files() {
        let files: [&[u8]; 4] = [
            b"v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n",
            b"# unused vertex and negative indices\nv 9 9 9\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\ns off\nusemtl x\nv 0 0 0.5\nf 2 3 -1\n",
            b"v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\no a\ng a\nf 1 2 3\no b\nf 4 2 1\nf 4 3 2\no a\nf 1 3 4\n",
            b"v 0.1 -0.0 1e-300\r\nv 1e11 3.141592653589793 0\r\nv 0 1 0\r\nf 1 2 3\r\n",
        ];
        for bytes in files {
            let fast = parse_plain(bytes).expect("plain file takes the fast path");
            let slow = parse_with_tobj(bytes).unwrap();
            let fast = crate::io::finish_parts(fast, "x").unwrap();
            let slow = crate::io::finish_parts(slow, "x").unwrap();
            assert_eq!(fast.len(), slow.len());
            for (f, s) in fast.iter().zip(&slow) {
                assert_eq!(f.name, s.name);
                assert_eq!(f.mesh, s.mesh, "{}", String::from_utf8_lossy(bytes));
            }
        }
    }

    #[test]
    fn anything_unusual_goes_to_tobj() {
        for bytes in [
            &b"v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3 4\n"[..],
            b"v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\n",
            b"v 0 0 0 2 1 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
            b"f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n",
            b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 0\n",
            b"v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2\nf 1 2 3\n",
            "v 0 0 0\nv 1 0 0\nv 0 1 0\no caf\u{e9}\nf 1 2 3\n".as_bytes(),
        ] {
            assert!(
                parse_plain(bytes).is_none(),
                "{}",
                String::from_utf8_lossy(bytes)
            );
        }
    }

    #[test]
    fn vertex_w_is_ignored_not_divided_by() {
        let expected = [
            DVec3::new(2.0, 4.0, 6.0),
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(0.0, 1.0, 0.0),
        ];
        // Fast path, tobj path (a normal reference sends the file there), w = 0, CRLF.
        for text in [
            &b"v 2 4 6 0.5\nv 1 0 0\nv 0 1 0 1\nf 1 2 3\n"[..],
            b"v 2 4 6 0.5\nv 1 0 0\nv 0 1 0 1\nvn 0 0 1\nf 1//1 2//1 3//1\n",
            b"v 2 4 6 0\r\nv 1 0 0\r\nv 0 1 0\r\nvn 0 0 1\r\nf 1//1 2//1 3//1\r\n",
        ] {
            let parts = parse(text).unwrap();
            let fin = crate::io::finish_parts(parts, "x").unwrap();
            let mut got = fin[0].mesh.positions.clone();
            got.sort_by(|a, b| a.to_array().partial_cmp(&b.to_array()).unwrap());
            let mut want = expected.to_vec();
            want.sort_by(|a, b| a.to_array().partial_cmp(&b.to_array()).unwrap());
            assert_eq!(got, want, "{}", String::from_utf8_lossy(text));
        }
        // Colours (three extra values) are not a weight: kept for tobj, which ignores them.
        let colour = b"v 2 4 6 1 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
        assert_eq!(&without_vertex_w(colour)[..], &colour[..]);
        assert_eq!(
            &without_vertex_w(b"v 1 2 3 0.5\r\nf 1 2 3")[..],
            b"v 1 2 3\r\nf 1 2 3"
        );
    }

    #[test]
    fn closed_polyline_reuses_its_first_vertex() {
        let square = vec![DVec3::ZERO, DVec3::X, DVec3::ONE, DVec3::ZERO];
        let open = vec![DVec3::Z, DVec3::Y];
        let mut out = Vec::new();
        write_polylines(&mut out, &[square, open]).unwrap();
        let text = String::from_utf8(out).unwrap();
        let records: Vec<&str> = text.lines().filter(|l| l.starts_with('l')).collect();
        assert_eq!(records, ["l 1 2 3 1", "l 4 5"]);
        assert_eq!(text.lines().filter(|l| l.starts_with("v ")).count(), 5);
    }
}
