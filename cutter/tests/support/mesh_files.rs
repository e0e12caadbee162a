//! The mesh files the cutter's tests and benches read (the repository's binary PLY assets, the
//! real anatomy's binary STL), in one place: the cutter never sees a file format in its library
//! code and cannot use the app's loaders (the app depends on `cutter`, not the other way round),
//! so its dev-only code reads them here. Included with `#[path]` by `tests/scalpel/main.rs` and
//! `benches/scalpel.rs`; `None` for anything malformed.
//!
//! - [`read_binary_ply`]: binary little-endian PLY, only the layout those files use: `float` or
//!   `double` x y z (the first three vertex properties, nothing else per vertex) and triangles as
//!   `list uchar uint`.
//! - [`read_binary_stl`]: binary STL; bit-identical corners are welded, triangles with a
//!   repeated corner dropped.

use glam::DVec3;

/// Reads the binary PLY at `path` (see the module doc).
pub fn read_binary_ply(path: &std::path::Path) -> Option<csg::Mesh> {
    let bytes = std::fs::read(path).ok()?;
    let end = bytes.windows(11).position(|w| w == b"end_header\n")? + 11;
    let header = std::str::from_utf8(&bytes[..end]).ok()?;
    if !header.contains("format binary_little_endian 1.0") {
        return None;
    }
    let count = |element: &str| -> Option<usize> {
        header
            .lines()
            .find_map(|l| l.strip_prefix(&format!("element {element} ")))?
            .trim()
            .parse()
            .ok()
    };
    let (nv, nf) = (count("vertex")?, count("face")?);
    let props: Vec<&str> = header
        .lines()
        .skip_while(|l| !l.starts_with("element vertex"))
        .skip(1)
        .take_while(|l| l.starts_with("property"))
        .collect();
    let double = match props.as_slice() {
        [x, y, z] if [x, y, z].iter().all(|p| p.starts_with("property float ")) => false,
        [x, y, z] if [x, y, z].iter().all(|p| p.starts_with("property double ")) => true,
        _ => return None,
    };
    let size = if double { 8 } else { 4 };
    let mut positions = Vec::with_capacity(nv);
    for v in 0..nv {
        let mut c = [0.0f64; 3];
        for (a, x) in c.iter_mut().enumerate() {
            let o = end + (3 * v + a) * size;
            let b = bytes.get(o..o + size)?;
            *x = if double {
                f64::from_le_bytes(b.try_into().ok()?)
            } else {
                f32::from_le_bytes(b.try_into().ok()?) as f64
            };
        }
        positions.push(DVec3::from_array(c));
    }
    let mut at = end + 3 * nv * size;
    let mut triangles = Vec::with_capacity(nf);
    for _ in 0..nf {
        if *bytes.get(at)? != 3 {
            return None;
        }
        let mut tri = [0u32; 3];
        for (k, i) in tri.iter_mut().enumerate() {
            let o = at + 1 + 4 * k;
            *i = u32::from_le_bytes(bytes.get(o..o + 4)?.try_into().ok()?);
        }
        triangles.push(tri);
        at += 13;
    }
    csg::Mesh::new(positions, triangles).ok()
}

/// Reads the binary STL at `path` (see the module doc).
pub fn read_binary_stl(path: &std::path::Path) -> Option<csg::Mesh> {
    let bytes = std::fs::read(path).ok()?;
    let n = u32::from_le_bytes(bytes.get(80..84)?.try_into().ok()?) as usize;
    let mut map = std::collections::HashMap::new();
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    for t in 0..n {
        let base = 84 + 50 * t + 12;
        let mut tri = [0u32; 3];
        for (k, corner) in tri.iter_mut().enumerate() {
            let mut c = [0f32; 3];
            for (a, x) in c.iter_mut().enumerate() {
                let o = base + 12 * k + 4 * a;
                *x = f32::from_le_bytes(bytes.get(o..o + 4)?.try_into().ok()?);
            }
            *corner = *map.entry(c.map(f32::to_bits)).or_insert_with(|| {
                positions.push(DVec3::new(c[0] as f64, c[1] as f64, c[2] as f64));
                positions.len() as u32 - 1
            });
        }
        if tri[0] != tri[1] && tri[1] != tri[2] && tri[0] != tri[2] {
            triangles.push(tri);
        }
    }
    csg::Mesh::new(positions, triangles).ok()
}
