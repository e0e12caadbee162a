//! The mesh files csg's tests and benches read: csg never sees a file format in its library code,
//! so its dev-only code reads them here. Included with `#[path]`.
//!
//! - [`read_obj`]: the `v` and `f` lines of an OBJ (polygons fanned into triangles; texture and
//!   normal indices ignored), panicking on anything malformed; for the boolean bench's cases.

use csg::Mesh;
use glam::DVec3;

/// The boolean bench's peer files (`v` and `f` records, polygons fanned); the bench cannot use
/// the app's readers, and these files are plain.
pub fn read_obj(path: &str) -> Mesh {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{path}: {e}"));
    let mut m = Mesh::default();
    for line in text.lines() {
        let mut it = line.split_whitespace();
        match it.next() {
            Some("v") => {
                let c: Vec<f64> = it.take(3).map(|x| x.parse().expect("coordinate")).collect();
                m.positions.push(DVec3::new(c[0], c[1], c[2]));
            }
            Some("f") => {
                let idx: Vec<u32> = it
                    .map(|x| {
                        x.split('/')
                            .next()
                            .unwrap_or("")
                            .parse::<u32>()
                            .expect("index")
                            - 1
                    })
                    .collect();
                for k in 1..idx.len() - 1 {
                    m.triangles.push([idx[0], idx[k], idx[k + 1]]);
                }
            }
            _ => {}
        }
    }
    m
}
