//! Scratch diagnostics (printing only); removed before delivery.
mod editor_support;
use glam::DVec2;
use cutter::CutKind;
use editor_support::*;

#[test]
fn debug_bumpy() {
    let scene = Scene::bumpy();
    let mut editor = scene.editor(scene.settings(CutKind::Curving));
    let a = DVec2::new(450.0, 430.0);
    feed(&mut editor, drag(a, a + DVec2::new(0.0, -60.0), 6));
    let h = handle_px(&editor);
    let path = s_path(320.0, 40.0, 120);
    editor.handle(cutter::EditorEvent::press(h.x, h.y));
    for (k, p) in path.iter().enumerate() {
        let q = h + *p;
        let r = editor.handle(cutter::EditorEvent::move_to(q.x, q.y));
        let c = editor.cutter().unwrap();
        let l = c.leading();
        let cam = editor.camera();
        let prev = c.planes[c.planes.len() - 2];
        let g = scene.distance(l.front_mid()) / editor.delta(); let ins = scene.index.closest_point(&scene.mesh, l.front_mid()).map(|c| (l.front_mid() - c.point).dot(scene.mesh.face_normal_scaled(c.face as usize)) < 0.0).unwrap(); eprintln!("gap {g:.2} inside {ins} move {k} mouse {:.1} n {} lead mid px {:.1} width/δ {:.2} back {:.2} face-n {:.2} changed {}", q, c.planes.len(), cam.project(editor.viewport(), l.front_mid()).unwrap(), (l.front_mid() - prev.front_mid()).length() / editor.delta(), l.back_direction(), prev.back_direction(), r.changed);
    }
}
