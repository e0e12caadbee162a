//! A binary little-endian PLY reader for the cutter's tests, which read the repository's meshes
//! (`assets/`) but cannot use the app's loaders (the app depends on `cutter`, not the other way
//! round). Only the layout those files use: `float` or `double` x y z (the first three vertex
//! properties, nothing else per vertex) and triangles as `list uchar uint`. `None` for
//! anything else or anything malformed.
//! Included with `#[path]` by `tests/scalpel/main.rs`.

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
