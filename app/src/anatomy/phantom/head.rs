//! The head scene: skin (head and upper neck), skull, brain and ventricles.
//!
//! Frame: millimetres, z up, -y anterior (the face looks toward -y), x left-right; the origin is
//! near the centre of the head.
//!
//! Recipe:
//! - `skin`: cranium ellipsoid 148 x 188 x 168 blended with face, chin, nose, ears and a neck capsule.
//! - `skull`: a 7 mm shell (outer table minus inner table, one connected closed surface) blended with
//!   a solid facial mass, opened at the foramen magnum.
//! - `brain`: cerebrum ellipsoid with a longitudinal fissure carved on top, a cerebellum below the
//!   occipital lobes and a brainstem that passes through the foramen magnum into the neck, 3 mm or
//!   more from the bone everywhere.
//! - `ventricles`: two C-shaped lateral ventricles (tubes) joined to a slit-like third ventricle.

use glam::DVec3;

use super::sdf::{capsule, ellipsoid, smax, smin, ssub, tapered_capsule, tube};
use super::{PartSpec, SceneSpec, lattice};

fn v(x: f64, y: f64, z: f64) -> DVec3 {
    DVec3::new(x, y, z)
}

const CAVITY_CENTRE: DVec3 = DVec3::new(0.0, 5.0, 22.0);
const CAVITY_RADII: DVec3 = DVec3::new(61.0, 81.0, 71.0);

pub fn skin(p: DVec3) -> f64 {
    let cranium = ellipsoid(p, v(0.0, 5.0, 20.0), v(74.0, 94.0, 84.0));
    let face = ellipsoid(p, v(0.0, -32.0, -30.0), v(58.0, 62.0, 70.0));
    let chin = ellipsoid(p, v(0.0, -45.0, -78.0), v(38.0, 34.0, 26.0));
    let nose = tapered_capsule(p, v(0.0, -92.0, -2.0), v(0.0, -103.0, -30.0), 6.0, 9.0);
    let neck = capsule(p, v(0.0, 18.0, -80.0), v(0.0, 20.0, -140.0), 46.0);
    let mut f = smin(cranium, face, 30.0);
    f = smin(f, chin, 20.0);
    f = smin(f, nose, 10.0);
    f = smin(f, neck, 30.0);
    for s in [-1.0, 1.0] {
        let ear = ellipsoid(p, v(s * 74.0, 12.0, -2.0), v(9.0, 15.0, 26.0));
        f = smin(f, ear, 6.0);
    }
    f
}

pub fn skull(p: DVec3) -> f64 {
    let outer = ellipsoid(p, CAVITY_CENTRE, CAVITY_RADII + DVec3::splat(7.0));
    let facial = ellipsoid(p, v(0.0, -38.0, -22.0), v(44.0, 44.0, 40.0));
    let inner = ellipsoid(p, CAVITY_CENTRE, CAVITY_RADII);
    let shell = ssub(smin(outer, facial, 16.0), inner, 3.0);
    let foramen = capsule(p, v(0.0, 20.0, -90.0), v(0.0, 20.0, -30.0), 16.0);
    ssub(shell, foramen, 4.0)
}

pub fn brain(p: DVec3) -> f64 {
    let cerebrum = ellipsoid(p, v(0.0, 5.0, 25.0), v(57.0, 76.0, 63.0));
    // A 5 mm slab with an elliptic outline in the mid-sagittal plane: an honest distance bound,
    // unlike a thin ellipsoid whose scaled field would underestimate distances far below it.
    let outline = glam::DVec2::new((p.y - 2.0) / 84.0, (p.z - 82.0) / 44.0);
    let fissure = (p.x.abs() - 2.5).max((outline.length() - 1.0) * 44.0);
    let cerebellum = ellipsoid(p, v(0.0, 34.0, -16.0), v(36.0, 22.0, 15.0));
    let stem = tapered_capsule(p, v(0.0, 18.0, -10.0), v(0.0, 20.0, -105.0), 12.0, 10.0);
    let mut f = ssub(cerebrum, fissure, 2.0);
    f = smin(f, cerebellum, 8.0);
    smin(f, stem, 10.0)
}

pub fn ventricles(p: DVec3) -> f64 {
    let mut f = ellipsoid(p, v(0.0, 2.0, 14.0), v(3.0, 16.0, 11.0));
    for s in [-1.0, 1.0] {
        let c_shape = [
            v(s * 12.0, -32.0, 28.0),
            v(s * 14.0, -5.0, 36.0),
            v(s * 14.0, 25.0, 30.0),
            v(s * 17.0, 38.0, 12.0),
            v(s * 21.0, 22.0, -6.0),
        ];
        f = smin(f, tube(p, &c_shape, 4.5, 5.0), 3.0);
        let foramen = capsule(p, v(s * 12.0, -12.0, 30.0), v(0.0, -8.0, 18.0), 3.0);
        f = smin(f, foramen, 3.0);
    }
    // Keep the ventricles at least 3 mm inside the brain.
    smax(f, brain(p) + 3.0, 2.0)
}

pub fn scene() -> SceneSpec {
    let part = |name, parent, field: fn(DVec3) -> f64, min, max, h| PartSpec {
        name,
        parent,
        field: Box::new(field),
        lattice: lattice(min, max, h),
    };
    SceneSpec {
        name: "head",
        parts: vec![
            part(
                "skin",
                None,
                skin,
                [-86.0, -112.0, -190.0],
                [86.0, 102.0, 108.0],
                5.0,
            ),
            part(
                "skull",
                Some("skin"),
                skull,
                [-70.0, -85.0, -66.0],
                [70.0, 95.0, 102.0],
                3.4,
            ),
            part(
                "brain",
                Some("skin"),
                brain,
                [-60.0, -75.0, -118.0],
                [60.0, 83.0, 90.0],
                3.6,
            ),
            part(
                "ventricles",
                Some("brain"),
                ventricles,
                [-30.0, -40.0, -15.0],
                [30.0, 45.0, 45.0],
                1.8,
            ),
        ],
    }
}
