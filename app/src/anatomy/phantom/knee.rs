//! The knee/thigh scene (default): a right knee with the distal thigh and proximal shank.
//!
//! Frame: millimetres, z up (proximal), -y anterior (the knee cap faces -y, toward a camera at
//! `(0, -300, 0)`), x lateral-medial. The knee joint line is at `z = 0`; the scene spans
//! `z = -90 .. 310` (400 mm) and is about 130 mm wide.
//!
//! Recipe (every number is a size or position in mm):
//! - `skin`: a vertical elliptic column whose semi-axes follow a smooth profile (thigh 72 x 66 at
//!   the top, knee 54 x 52, shank 50 x 50), rounded ends, plus a smooth prepatellar bulge.
//! - `fat`: the skin field offset 2.5 mm inward (the skin layer is the space between them).
//! - `femur`: tapered shaft (radius 16 to 13) blended with a metaphyseal flare and two condyles
//!   (ellipsoids), with the intercondylar notch and the trochlear groove carved out.
//! - `femur_marrow`: the medullary cavity, a capsule of radius 8.5 in the shaft.
//! - `patella`: an ellipsoid 42 x 18 x 46 in front of the trochlea.
//! - `tibia`: a plateau ellipsoid blended with a tapered shaft, 4 mm below the condyles.
//! - `quadriceps`: a spindle in front of and around the femur with a tendon toward the patella,
//!   clipped to 3.5 mm inside the fat and 3 mm away from bones and vessel.
//! - `popliteal_vessel`: a tube of radius 4 along a smooth path behind the femur and knee.

use glam::{DVec2, DVec3};

use super::sdf::{capsule, ellipsoid, elliptic_column, smax, smin, ssub, tapered_capsule, tube};
use super::{PartSpec, SceneSpec, lattice, profile};

fn v(x: f64, y: f64, z: f64) -> DVec3 {
    DVec3::new(x, y, z)
}

/// Outer body surface.
pub fn skin(p: DVec3) -> f64 {
    let column = elliptic_column(p, -90.0, 310.0, 40.0, |z| {
        let rx = profile(
            z,
            &[
                (-90.0, 50.0),
                (-20.0, 52.0),
                (20.0, 54.0),
                (120.0, 64.0),
                (310.0, 72.0),
            ],
        );
        let ry = profile(
            z,
            &[
                (-90.0, 50.0),
                (-20.0, 53.0),
                (20.0, 54.0),
                (120.0, 60.0),
                (310.0, 66.0),
            ],
        );
        let cy = profile(z, &[(-90.0, 4.0), (0.0, 3.0), (120.0, 0.0)]);
        (DVec2::new(0.0, cy), DVec2::new(rx, ry))
    });
    let prepatellar = ellipsoid(p, v(0.0, -40.0, 28.0), v(30.0, 16.0, 36.0));
    smin(column, prepatellar, 14.0)
}

/// Everything under the skin layer.
pub fn fat(p: DVec3) -> f64 {
    skin(p) + 2.5
}

/// Outer surface of the femur.
pub fn femur(p: DVec3) -> f64 {
    let shaft = tapered_capsule(p, v(0.0, 2.0, 60.0), v(0.0, -2.0, 285.0), 16.0, 13.0);
    let flare = ellipsoid(p, v(0.0, 5.0, 48.0), v(31.0, 22.0, 30.0));
    let lateral = ellipsoid(p, v(21.0, 8.0, 24.0), v(17.0, 27.0, 23.0));
    let medial = ellipsoid(p, v(-21.0, 8.0, 24.0), v(18.0, 27.0, 23.0));
    let mut f = smin(shaft, flare, 24.0);
    f = smin(f, smin(lateral, medial, 8.0), 12.0);
    let notch = ellipsoid(p, v(0.0, 24.0, 12.0), v(7.0, 18.0, 20.0));
    f = ssub(f, notch, 4.0);
    let trochlea = capsule(p, v(0.0, -30.0, 8.0), v(0.0, -28.0, 45.0), 5.0);
    ssub(f, trochlea, 6.0)
}

/// Medullary cavity of the femoral shaft.
pub fn femur_marrow(p: DVec3) -> f64 {
    capsule(p, v(0.0, 1.3, 95.0), v(0.0, -1.3, 255.0), 8.5)
}

pub fn patella(p: DVec3) -> f64 {
    ellipsoid(p, v(0.0, -37.0, 33.0), v(21.0, 9.0, 23.0))
}

pub fn tibia(p: DVec3) -> f64 {
    let plateau = ellipsoid(p, v(0.0, 4.0, -18.0), v(37.0, 27.0, 14.0));
    let shaft = tapered_capsule(p, v(0.0, 6.0, -28.0), v(0.0, 9.0, -66.0), 19.0, 13.0);
    let tuberosity = ellipsoid(p, v(0.0, -20.0, -34.0), v(12.0, 8.0, 12.0));
    smin(smin(plateau, shaft, 14.0), tuberosity, 8.0)
}

const VESSEL_PATH: [[f64; 3]; 7] = [
    [14.0, 27.0, 280.0],
    [9.0, 33.0, 170.0],
    [3.0, 40.0, 80.0],
    [0.0, 44.0, 30.0],
    [-1.0, 45.0, -10.0],
    [-3.0, 41.0, -45.0],
    [-5.0, 36.0, -72.0],
];

pub fn popliteal_vessel(p: DVec3) -> f64 {
    let path = VESSEL_PATH.map(DVec3::from_array);
    tube(p, &path, 4.0, 6.0)
}

pub fn quadriceps(p: DVec3) -> f64 {
    let belly = ellipsoid(p, v(0.0, -20.0, 180.0), v(52.0, 36.0, 118.0));
    let tendon = capsule(p, v(0.0, -32.0, 95.0), v(0.0, -40.0, 62.0), 9.0);
    let mut f = smin(belly, tendon, 20.0);
    f = smax(f, fat(p) + 3.5, 6.0);
    f = smax(f, -(femur(p) - 3.0), 6.0);
    f = smax(f, -(patella(p) - 3.0), 4.0);
    smax(f, -(popliteal_vessel(p) - 3.0), 4.0)
}

pub fn scene() -> SceneSpec {
    let part = |name, parent, field: fn(DVec3) -> f64, min, max, h| PartSpec {
        name,
        parent,
        field: Box::new(field),
        lattice: lattice(min, max, h),
    };
    SceneSpec {
        name: "knee",
        parts: vec![
            part(
                "skin",
                None,
                skin,
                [-78.0, -75.0, -95.0],
                [78.0, 75.0, 315.0],
                5.0,
            ),
            part(
                "fat",
                Some("skin"),
                fat,
                [-78.0, -75.0, -95.0],
                [78.0, 75.0, 315.0],
                5.0,
            ),
            part(
                "quadriceps",
                Some("fat"),
                quadriceps,
                [-70.0, -70.0, 40.0],
                [70.0, 40.0, 310.0],
                3.6,
            ),
            part(
                "femur",
                Some("fat"),
                femur,
                [-45.0, -40.0, -5.0],
                [45.0, 40.0, 302.0],
                2.7,
            ),
            part(
                "femur_marrow",
                Some("femur"),
                femur_marrow,
                [-15.0, -15.0, 80.0],
                [15.0, 15.0, 270.0],
                2.2,
            ),
            part(
                "patella",
                Some("fat"),
                patella,
                [-25.0, -50.0, 5.0],
                [25.0, -25.0, 60.0],
                1.5,
            ),
            part(
                "tibia",
                Some("fat"),
                tibia,
                [-42.0, -32.0, -82.0],
                [42.0, 35.0, 0.0],
                2.2,
            ),
            part(
                "popliteal_vessel",
                Some("fat"),
                popliteal_vessel,
                [-12.0, 20.0, -80.0],
                [22.0, 52.0, 288.0],
                1.9,
            ),
        ],
    }
}
