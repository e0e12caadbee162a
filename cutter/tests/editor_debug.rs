//! Scratch diagnostics (printing only); removed before delivery.
mod editor_support;
use glam::DVec2;
use cutter::CutKind;
use editor_support::*;

fn run(scene: &Scene, a: DVec2, amp: f64) {
    let mut editor = scene.editor(scene.settings(CutKind::Curving));
    feed(&mut editor, drag(a, a + DVec2::new(0.0, -60.0), 6));
    let h = handle_px(&editor);
    let path = s_path(220.0, amp, 80);
    editor.handle(cutter::EditorEvent::press(h.x, h.y));
    for (k, p) in path.iter().enumerate() {
        let q = h + *p;
        let r = editor.handle(cutter::EditorEvent::move_to(q.x, q.y));
        let c = editor.cutter().unwrap();
        let l = c.leading();
        let cam = editor.camera();
        eprintln!("move {k} mouse {:.1} n {} lead mid px {:.1} valid {:?} changed {}", q, c.planes.len(), cam.project(editor.viewport(), l.front_mid()).unwrap(), c.sanity_check().err(), r.changed);
    }
    let c = editor.cutter().unwrap();
    let cam = editor.camera();
    for p in &c.planes { eprintln!("mid px {:.1}  ft px {:.1} fb px {:.1}", cam.project(editor.viewport(), p.front_mid()).unwrap(), cam.project(editor.viewport(), p.front_top).unwrap(), cam.project(editor.viewport(), p.front_bottom).unwrap()); }
    eprintln!("mouse end px {:.1}", h + *path.last().unwrap());
}

#[test]
fn debug_slab_s() { run(&Scene::slab(), DVec2::new(500.0, 430.0), 60.0); }
#[test]
fn debug_sphere_s() { run(&Scene::sphere(), DVec2::new(560.0, 430.0), 60.0); }
