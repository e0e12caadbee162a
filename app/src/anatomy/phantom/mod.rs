//! # The synthetic anatomy phantom
//!
//! Cutaway ships three small segmented scenes so that it opens on something anatomical without any
//! patient data: a knee/thigh (the default), a lumbar segment and a head. They are **synthetic**:
//! every structure is an implicit shape written in [`knee`], [`lumbar`] and [`head`] (capsules,
//! ellipsoids, tapered sections, smooth unions and subtractions; no noise, no random numbers), turned
//! into a closed triangle mesh by [`extract`] (marching tetrahedra) and stored as one binary PLY per
//! structure under `assets/<scene>/<part>.ply` by `cutaway phantom --out assets`.
//!
//! ## Representation: nested closed surfaces
//! A label-map segmentation gives one closed surface per label. Here every part is one closed,
//! outward-oriented surface that bounds what a radiologist would outline **including what lies
//! inside it**: `skin` is the body outline, `fat` the outline of everything under the skin (the skin
//! layer is the space between the two), `femur` the outer surface of the bone and
//! `femur_marrow` its medullary cavity, nested inside it as a separate part (so every part has a
//! positive volume and can be cut on its own). The `skull` is a true shell: its inner table and
//! outer table are one connected closed surface, joined at the foramen magnum, with the brain in
//! the cavity outside the bone. [`NESTING`] records which part lies inside which; parts that share
//! a parent are disjoint. Generation checks every relation with a clearance (see [`generate`]).
//!
//! ## Determinism
//! A part is a pure function of the constants in its scene file: the lattice is fixed, blocks are
//! merged in a fixed order whatever the number of threads, and the writer emits vertices in first-use
//! order. Regenerating gives byte-identical files (`phantom_is_deterministic`).

use std::path::Path;
use std::time::Instant;

use anyhow::Context;
use glam::DVec3;
use rayon::prelude::*;

use csg::Mesh;

pub mod extract;
pub mod head;
pub mod knee;
pub mod lumbar;
pub mod ply;
pub mod sdf;

use extract::{Lattice, extract};
use sdf::Field;

/// Most triangles one part may have (foundation issue, point 6).
pub const MAX_TRIANGLES: usize = 200_000;

/// One structure of a scene: its field and the lattice it is sampled on.
pub struct PartSpec {
    /// File stem: `assets/<scene>/<name>.ply`.
    pub name: &'static str,
    /// The part this one lies inside (`None`: a top-level part). See [`NESTING`].
    pub parent: Option<&'static str>,
    /// Negative inside, 1-Lipschitz (see [`sdf`]).
    pub field: Field<'static>,
    /// Must strictly contain the shape.
    pub lattice: Lattice,
}

/// A scene to generate: parts in display order.
pub struct SceneSpec {
    pub name: &'static str,
    pub parts: Vec<PartSpec>,
}

/// The scenes in menu order (knee first: the default).
pub fn scene_specs() -> Vec<SceneSpec> {
    vec![knee::scene(), lumbar::scene(), head::scene()]
}

/// Which part lies inside which, per scene: `(scene, part, parent)`. Parts of a scene with the same
/// parent (or both top-level) are disjoint. Kept in sync with the scene files by
/// `nesting_table_matches_the_scenes`.
pub const NESTING: &[(&str, &str, Option<&str>)] = &[
    ("knee", "skin", None),
    ("knee", "fat", Some("skin")),
    ("knee", "quadriceps", Some("fat")),
    ("knee", "femur", Some("fat")),
    ("knee", "femur_marrow", Some("femur")),
    ("knee", "patella", Some("fat")),
    ("knee", "tibia", Some("fat")),
    ("knee", "popliteal_vessel", Some("fat")),
    ("lumbar", "vertebra_l4", None),
    ("lumbar", "disc_l4_l5", None),
    ("lumbar", "vertebra_l5", None),
    ("head", "skin", None),
    ("head", "skull", Some("skin")),
    ("head", "brain", Some("skin")),
    ("head", "ventricles", Some("brain")),
];

/// Smallest clearance (mm) between the surfaces of a part and its parent or siblings, measured at
/// the vertices of each against the field of the other.
pub const MIN_CLEARANCE: f64 = 0.8;

/// A generated part.
#[derive(Clone, Debug)]
pub struct GeneratedPart {
    pub name: &'static str,
    pub mesh: Mesh,
}

/// Extracts one part and checks it (closed, oriented, within budget).
pub fn generate_part(spec: &PartSpec) -> anyhow::Result<Mesh> {
    let mesh = extract(&spec.field, &spec.lattice).with_context(|| spec.name.to_string())?;
    let defects = extract::directed_edge_defects(&mesh);
    anyhow::ensure!(
        defects == 0,
        "{}: {defects} edges are not shared by exactly two opposite faces",
        spec.name
    );
    anyhow::ensure!(
        mesh.triangles.len() <= MAX_TRIANGLES,
        "{}: {} triangles exceed the budget of {MAX_TRIANGLES}",
        spec.name,
        mesh.triangles.len()
    );
    anyhow::ensure!(mesh.volume() > 0.0, "{}: volume is not positive", spec.name);
    // Round to f32 now, as stored, so that the checks below see the stored geometry.
    let mesh = Mesh {
        positions: mesh
            .positions
            .iter()
            .map(|p| p.as_vec3().as_dvec3())
            .collect(),
        triangles: mesh.triangles,
    };
    Ok(mesh)
}

/// The smallest signed clearance of `mesh`'s vertices against `field`, times `sign` (+1: the
/// vertices must be outside the field's shape; -1: inside).
fn clearance(mesh: &Mesh, field: &Field<'static>, sign: f64) -> f64 {
    mesh.positions
        .par_iter()
        .map(|&p| sign * field(p))
        .reduce(|| f64::INFINITY, f64::min)
}

/// Generates every part of `scene` and checks the nesting relations: each part lies inside its
/// parent and siblings lie outside each other, all with at least [`MIN_CLEARANCE`] measured at
/// vertices in both directions. Returns the parts and the smallest clearance found.
pub fn generate(scene: &SceneSpec) -> anyhow::Result<(Vec<GeneratedPart>, f64)> {
    let meshes = scene
        .parts
        .iter()
        .map(|spec| generate_part(spec).with_context(|| scene.name.to_string()))
        .collect::<anyhow::Result<Vec<Mesh>>>()?;
    let mut smallest = f64::INFINITY;
    for (i, a) in scene.parts.iter().enumerate() {
        for (j, b) in scene.parts.iter().enumerate().skip(i + 1) {
            // Inside: a's vertices inside b and b's outside a when b is a's parent (or vice versa).
            let (ca, cb) = if a.parent == Some(b.name) {
                (
                    clearance(&meshes[i], &b.field, -1.0),
                    clearance(&meshes[j], &a.field, 1.0),
                )
            } else if b.parent == Some(a.name) {
                (
                    clearance(&meshes[i], &b.field, 1.0),
                    clearance(&meshes[j], &a.field, -1.0),
                )
            } else if a.parent == b.parent {
                (
                    clearance(&meshes[i], &b.field, 1.0),
                    clearance(&meshes[j], &a.field, 1.0),
                )
            } else {
                continue; // Related through their parents.
            };
            let c = ca.min(cb);
            anyhow::ensure!(
                c >= MIN_CLEARANCE,
                "{}: {} and {} are only {c:.3} mm apart (need {MIN_CLEARANCE})",
                scene.name,
                a.name,
                b.name
            );
            smallest = smallest.min(c);
        }
    }
    let parts = scene
        .parts
        .iter()
        .zip(meshes)
        .map(|(s, mesh)| GeneratedPart { name: s.name, mesh })
        .collect();
    Ok((parts, smallest))
}

/// The header comment of every phantom file.
pub const PLY_COMMENT: &str = "SYNTHETIC PHANTOM, not patient data. Generated by `cutaway phantom --out assets` (app/src/phantom). Units mm, z up, -y anterior.";

/// Regenerates every scene into `out/<scene>/<part>.ply` and prints one line per part.
pub fn write_all(out: &Path) -> anyhow::Result<()> {
    let start = Instant::now();
    for scene in scene_specs() {
        let scene_start = Instant::now();
        let (parts, smallest) = generate(&scene)?;
        let dir = out.join(scene.name);
        std::fs::create_dir_all(&dir).with_context(|| format!("{}", dir.display()))?;
        for part in &parts {
            let path = dir.join(format!("{}.ply", part.name));
            let bytes = ply::encode(&part.mesh, PLY_COMMENT);
            crate::io::write_file(&path, &bytes)?;
            println!(
                "{}: {} triangles, {} vertices, {} bytes, volume {:.0} mm3",
                path.display(),
                part.mesh.triangles.len(),
                part.mesh.positions.len(),
                bytes.len(),
                part.mesh.volume()
            );
        }
        println!(
            "{}: {} parts in {:.2} s, smallest clearance {smallest:.2} mm",
            scene.name,
            parts.len(),
            scene_start.elapsed().as_secs_f64()
        );
    }
    println!("all scenes in {:.2} s", start.elapsed().as_secs_f64());
    Ok(())
}

/// A lattice around the box `[min, max]` (mm) with spacing `h`, padded by two spacings.
pub fn lattice(min: [f64; 3], max: [f64; 3], h: f64) -> Lattice {
    Lattice {
        min: DVec3::from_array(min) - DVec3::splat(2.0 * h),
        max: DVec3::from_array(max) + DVec3::splat(2.0 * h),
        h,
    }
}

/// A smooth profile through `(z, value)` knots sorted by `z`: smoothstep between neighbours,
/// constant beyond the ends.
pub fn profile(z: f64, knots: &[(f64, f64)]) -> f64 {
    let Some(first) = knots.first() else {
        return 0.0;
    };
    if z <= first.0 {
        return first.1;
    }
    for w in knots.windows(2) {
        if z <= w[1].0 {
            return sdf::lerp(w[0].1, w[1].1, sdf::smoothstep(w[0].0, w[1].0, z));
        }
    }
    knots[knots.len() - 1].1
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nesting_table_matches_the_scenes() {
        let mut listed = Vec::new();
        for scene in scene_specs() {
            for part in &scene.parts {
                listed.push((scene.name, part.name, part.parent));
                if let Some(parent) = part.parent {
                    assert!(
                        scene.parts.iter().any(|p| p.name == parent),
                        "{}: {parent}",
                        scene.name
                    );
                }
            }
        }
        assert_eq!(listed, NESTING.to_vec());
    }

    #[test]
    fn phantom_is_deterministic() {
        // The patella is small enough to generate twice in a debug test.
        let a = generate_part(
            &knee::scene()
                .parts
                .into_iter()
                .find(|p| p.name == "patella")
                .expect("patella"),
        )
        .expect("generates");
        let b = generate_part(
            &knee::scene()
                .parts
                .into_iter()
                .find(|p| p.name == "patella")
                .expect("patella"),
        )
        .expect("generates");
        assert!(a.triangles.len() > 1000);
        assert_eq!(ply::encode(&a, PLY_COMMENT), ply::encode(&b, PLY_COMMENT));
        // And on a single thread the bytes are the same again.
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .expect("pool");
        let c = pool.install(|| {
            generate_part(
                &knee::scene()
                    .parts
                    .into_iter()
                    .find(|p| p.name == "patella")
                    .expect("patella"),
            )
            .expect("generates")
        });
        assert_eq!(ply::encode(&a, PLY_COMMENT), ply::encode(&c, PLY_COMMENT));
    }

    #[test]
    fn profile_interpolates_smoothly() {
        let knots = [(0.0, 10.0), (10.0, 20.0), (30.0, 0.0)];
        assert_eq!(profile(-5.0, &knots), 10.0);
        assert_eq!(profile(5.0, &knots), 15.0);
        assert_eq!(profile(10.0, &knots), 20.0);
        assert_eq!(profile(40.0, &knots), 0.0);
        assert!(profile(20.0, &knots) < 20.0 && profile(20.0, &knots) > 0.0);
    }
}
