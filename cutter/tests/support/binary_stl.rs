//! A binary STL reader for the cutter's tests and benches, which read real anatomy but cannot use
//! the app's loaders (the app depends on `cutter`, not the other way round). Bit-identical corners
//! are welded; triangles with a repeated corner are dropped. `None` for anything malformed.
//! Included with `#[path]` by `tests/scalpel/main.rs` and `benches/scalpel.rs`.

use glam::DVec3;

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
