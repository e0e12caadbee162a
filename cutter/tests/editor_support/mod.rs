//! Shared scenes and checks of the editor tests: a sphere and a bumpy height field closed into a
//! solid, a fixed camera, gesture helpers, and the validator run after every edit.

#![allow(dead_code)]

use std::sync::Arc;

use glam::{DVec2, DVec3};

use csg::{Mesh, SpatialIndex};
use cutter::{Camera, CutKind, Cutter, Editor, EditorEvent, EditorSettings};

pub const VIEWPORT: DVec2 = DVec2::new(1280.0, 800.0);

/// A scene: target mesh, index, camera, δ.
pub struct Scene {
    pub mesh: Arc<Mesh>,
    pub index: Arc<SpatialIndex>,
    pub camera: Camera,
}

impl Scene {
    pub fn new(mesh: Mesh, camera: Camera) -> Scene {
        let index = Arc::new(SpatialIndex::build(&mesh));
        Scene {
            mesh: Arc::new(mesh),
            index,
            camera,
        }
    }

    /// A sphere of radius 50 (about 20k triangles) seen from −Y at distance 300.
    pub fn sphere() -> Scene {
        Scene::new(csg::testkit::icosphere(5, 50.0), front_camera())
    }

    /// A 100 × 100 slab, top z = 0 (flat), bottom z = −20, seen from above.
    pub fn slab() -> Scene {
        Scene::new(height_field(|_, _| 0.0, 40), top_camera())
    }

    /// A 100 × 100 solid whose top is hills and valleys along x (relief 6, slopes up to 20°), gently curved
    /// along y (a flat roller spanning y cannot follow strong curvature across it), seen from above.
    pub fn bumpy() -> Scene {
        Scene::new(
            height_field(|x, y| 3.0 * (x / 8.0).sin() + 0.5 * (y / 20.0).cos(), 100),
            top_camera(),
        )
    }

    /// Settings under the first rules (`cutaway-gesture/1`: 5δ deep, the wheel on the
    /// selected plane, boxes along the normal), which the thesis-mechanics tests were written
    /// for: they check those rules still hold.
    pub fn settings(&self, kind: CutKind) -> EditorSettings {
        EditorSettings::for_scene(&self.mesh.bbox(), self.camera.fov_y_deg)
            .with_kind(kind)
            .first_rules()
    }

    /// Settings under the current rules (a default depth that reaches behind the target, the
    /// wheel on the whole cutter, boxes along the view).
    pub fn current_settings(&self, kind: CutKind) -> EditorSettings {
        EditorSettings::for_scene(&self.mesh.bbox(), self.camera.fov_y_deg).with_kind(kind)
    }

    pub fn editor(&self, settings: EditorSettings) -> Editor {
        Editor::new(
            self.mesh.clone(),
            self.index.clone(),
            self.camera,
            VIEWPORT,
            settings,
        )
    }

    /// Distance from `p` to the surface.
    pub fn distance(&self, p: DVec3) -> f64 {
        self.index
            .closest_point(&self.mesh, p)
            .map_or(f64::INFINITY, |c| c.distance)
    }
}

pub fn front_camera() -> Camera {
    Camera {
        eye: DVec3::new(0.0, -300.0, 0.0),
        target: DVec3::ZERO,
        up: DVec3::Z,
        fov_y_deg: 30.0,
    }
}

pub fn top_camera() -> Camera {
    Camera {
        eye: DVec3::new(0.0, 0.0, 300.0),
        target: DVec3::ZERO,
        up: DVec3::Y,
        fov_y_deg: 30.0,
    }
}

/// A closed solid over [-50, 50]² with top `z = f(x, y)` and bottom `z = -20`, `n × n` cells,
/// outward oriented.
pub fn height_field(f: impl Fn(f64, f64) -> f64, n: usize) -> Mesh {
    let side = 100.0;
    let at = |i: usize| -50.0 + side * i as f64 / n as f64;
    let mut positions = Vec::new();
    let top = |i: usize, j: usize| (i * (n + 1) + j) as u32;
    for i in 0..=n {
        for j in 0..=n {
            let (x, y) = (at(i), at(j));
            positions.push(DVec3::new(x, y, f(x, y)));
        }
    }
    let base = positions.len() as u32;
    let bottom = |i: usize, j: usize| base + (i * (n + 1) + j) as u32;
    for i in 0..=n {
        for j in 0..=n {
            positions.push(DVec3::new(at(i), at(j), -20.0));
        }
    }
    let mut triangles = Vec::new();
    let mut quad = |a: u32, b: u32, c: u32, d: u32| {
        triangles.push([a, b, c]);
        triangles.push([a, c, d]);
    };
    for i in 0..n {
        for j in 0..n {
            // x along i, y along j: counter-clockwise seen from +z.
            quad(top(i, j), top(i + 1, j), top(i + 1, j + 1), top(i, j + 1));
            quad(
                bottom(i, j),
                bottom(i, j + 1),
                bottom(i + 1, j + 1),
                bottom(i + 1, j),
            );
        }
    }
    for k in 0..n {
        // Sides: y = -50 (j = 0), y = 50 (j = n), x = -50 (i = 0), x = 50 (i = n).
        quad(top(k, 0), bottom(k, 0), bottom(k + 1, 0), top(k + 1, 0));
        quad(top(k + 1, n), bottom(k + 1, n), bottom(k, n), top(k, n));
        quad(top(0, k + 1), bottom(0, k + 1), bottom(0, k), top(0, k));
        quad(top(n, k), bottom(n, k), bottom(n, k + 1), top(n, k + 1));
    }
    let mesh = Mesh::new(positions, triangles).expect("valid height field");
    assert!(mesh.volume() > 0.0, "height field must be outward");
    mesh
}

/// The validator of the issue, run after every edit: ≥ 2 planes, planar planes, consecutive
/// planes not crossing, closed outward mesh, no self-intersection (all in `sanity_check`), the
/// exact check the boolean makes of the surface it cuts with (`validate`: a smooth cutter's
/// subdivided surface, touching counted), plus the mesh facts checked independently here.
pub fn validate(c: &Cutter) {
    c.sanity_check()
        .unwrap_or_else(|e| panic!("invalid cutter: {e}\n{c:?}"));
    c.validate()
        .unwrap_or_else(|e| panic!("the exact cut would refuse the cutter: {e}\n{c:?}"));
    assert!(c.planes.len() >= 2);
    let q = c.quad_mesh();
    q.check_closed().expect("closed and consistently oriented");
    assert!(q.volume() > 0.0, "outward: volume {}", q.volume());
    let t = c.triangle_mesh();
    t.sanity_check().expect("triangle mesh structure");
    assert!(t.volume() > 0.0);
}

/// Feeds events, validating the cutter after each one that changed it.
pub fn feed(editor: &mut Editor, events: impl IntoIterator<Item = EditorEvent>) {
    for e in events {
        let r = editor.handle(e);
        if r.changed {
            validate(editor.cutter().expect("a changed editor has a cutter"));
        }
    }
}

/// Press A, drag to B in `steps`, release.
pub fn drag(a: DVec2, b: DVec2, steps: usize) -> Vec<EditorEvent> {
    let mut v = vec![EditorEvent::press(a.x, a.y)];
    for k in 1..=steps {
        let p = a.lerp(b, k as f64 / steps as f64);
        v.push(EditorEvent::move_to(p.x, p.y));
    }
    v.push(EditorEvent::release(b.x, b.y));
    v
}

/// Pixel of the leading plane's handle (middle of its projected front edge).
pub fn handle_px(editor: &Editor) -> DVec2 {
    let c = editor.cutter().expect("cutter");
    editor
        .camera()
        .project(editor.viewport(), c.leading().front_mid())
        .expect("handle in front of the camera")
}

/// Press on the handle, then move through `path` (pixels relative to the handle), release.
pub fn extrude(editor: &mut Editor, path: &[DVec2], shift: bool) {
    let h = handle_px(editor);
    let mut events = vec![EditorEvent::press(h.x, h.y)];
    for p in path {
        let q = h + *p;
        events.push(EditorEvent::Move {
            x: q.x,
            y: q.y,
            shift,
            ctrl: false,
        });
    }
    let last = h + path.last().copied().unwrap_or(DVec2::ZERO);
    events.push(EditorEvent::Release {
        x: last.x,
        y: last.y,
        shift,
        ctrl: false,
    });
    feed(editor, events);
}

/// An S-shaped path: `length` pixels to the right with a sideways swing of `amplitude`.
pub fn s_path(length: f64, amplitude: f64, steps: usize) -> Vec<DVec2> {
    (1..=steps)
        .map(|k| {
            let t = k as f64 / steps as f64;
            DVec2::new(length * t, -amplitude * (std::f64::consts::TAU * t).sin())
        })
        .collect()
}
