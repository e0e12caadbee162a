//! The lumbar scene: two lumbar vertebrae (L4 above L5) and the intervertebral disc between them.
//!
//! Frame: millimetres, z up (cranial), -y anterior (vertebral bodies toward -y, spinous processes
//! toward +y), x left-right. L5's body is centred at the origin.
//!
//! Recipe of one vertebra centred at height `zc`:
//! - body: an elliptic column 48 x 34 x 27 with a slight waist and rounded rims;
//! - pedicles: capsules (radius 5) from the back of the body;
//! - laminae: capsules meeting behind the vertebral canal (the arch makes the vertebra a torus);
//! - spinous process: a tapered capsule pointing back and down, with a blunt tip;
//! - transverse processes: capsules (radius 4) pointing sideways;
//! - superior articular processes (outer, rising) and inferior ones (inner, descending), placed so
//!   that the facets of neighbouring vertebrae pass each other with a gap.
//!
//! The disc is an elliptic column 11 mm high with a gentle bulge, 1.5 mm from each endplate.

use glam::{DVec2, DVec3};

use super::sdf::{capsule, ellipsoid, elliptic_column, smin, tapered_capsule};
use super::{PartSpec, SceneSpec, lattice};

/// Half height of a vertebral body.
const BODY_HALF: f64 = 13.5;
/// Body centre heights.
const L5: f64 = 0.0;
const L4: f64 = 40.0;

fn v(x: f64, y: f64, z: f64) -> DVec3 {
    DVec3::new(x, y, z)
}

/// Field of a vertebra whose body is centred at height `zc`.
pub fn vertebra(p: DVec3, zc: f64) -> f64 {
    let body = elliptic_column(p, zc - BODY_HALF, zc + BODY_HALF, 6.0, |z| {
        let u = (z - zc) / BODY_HALF;
        let waist = 1.0 - 0.06 * (1.0 - u * u);
        (DVec2::ZERO, DVec2::new(24.0 * waist, 17.0 * waist))
    });
    let mut f = body;
    for s in [-1.0, 1.0] {
        let pedicle = capsule(
            p,
            v(s * 13.0, 12.0, zc + 4.0),
            v(s * 13.0, 25.0, zc + 4.0),
            5.0,
        );
        let lamina = capsule(p, v(s * 13.0, 27.0, zc + 2.0), v(0.0, 37.0, zc), 4.5);
        let transverse = capsule(
            p,
            v(s * 14.0, 23.0, zc + 4.0),
            v(s * 40.0, 27.0, zc + 7.0),
            4.0,
        );
        let superior = capsule(
            p,
            v(s * 17.0, 27.0, zc + 6.0),
            v(s * 21.0, 31.0, zc + 15.0),
            4.0,
        );
        let inferior = capsule(
            p,
            v(s * 10.0, 33.0, zc - 3.0),
            v(s * 8.0, 35.0, zc - 16.0),
            3.8,
        );
        f = smin(f, pedicle, 5.0);
        f = smin(f, lamina, 4.0);
        f = smin(f, transverse, 4.0);
        f = smin(f, superior, 3.0);
        f = smin(f, inferior, 3.0);
    }
    let spinous = tapered_capsule(p, v(0.0, 36.0, zc), v(0.0, 60.0, zc - 6.0), 5.0, 4.0);
    let tip = ellipsoid(p, v(0.0, 60.0, zc - 6.0), v(4.5, 6.0, 8.0));
    smin(f, smin(spinous, tip, 4.0), 4.0)
}

pub fn vertebra_l4(p: DVec3) -> f64 {
    vertebra(p, L4)
}

pub fn vertebra_l5(p: DVec3) -> f64 {
    vertebra(p, L5)
}

pub fn disc_l4_l5(p: DVec3) -> f64 {
    let z0 = L5 + BODY_HALF + 1.5;
    let z1 = L4 - BODY_HALF - 1.5;
    let mid = 0.5 * (z0 + z1);
    let half = 0.5 * (z1 - z0);
    elliptic_column(p, z0, z1, 3.0, |z| {
        let u = (z - mid) / half;
        let bulge = 1.0 + 0.04 * (1.0 - u * u);
        (DVec2::new(0.0, 0.5), DVec2::new(23.0 * bulge, 16.0 * bulge))
    })
}

pub fn scene() -> SceneSpec {
    let part = |name, field: fn(DVec3) -> f64, min, max, h| PartSpec {
        name,
        parent: None,
        field: Box::new(field),
        lattice: lattice(min, max, h),
    };
    SceneSpec {
        name: "lumbar",
        parts: vec![
            part(
                "vertebra_l4",
                vertebra_l4,
                [-46.0, -20.0, L4 - 28.0],
                [46.0, 70.0, L4 + 25.0],
                1.3,
            ),
            part(
                "disc_l4_l5",
                disc_l4_l5,
                [-27.0, -20.0, 13.0],
                [27.0, 20.0, 27.0],
                1.3,
            ),
            part(
                "vertebra_l5",
                vertebra_l5,
                [-46.0, -20.0, L5 - 28.0],
                [46.0, 70.0, L5 + 25.0],
                1.3,
            ),
        ],
    }
}
