//! A folder of masks opened in the window arrives structure by structure: the first structures
//! are drawn while the other files are read, in file order at their final places, with the
//! progress and Cancel in the status bar; Cancel brings back the scene the user had.

use std::path::PathBuf;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;

use super::CutawayApp;
use super::state::folder::{FolderWork, Outcome};
use super::volume_jobs_tests::step_until;
use crate::io::Model;

/// A window on the skin alone, settled.
fn window(name: &str) -> Harness<'static, CutawayApp> {
    let mut h = super::volume_jobs_tests::window(
        &format!("folder-{name}"),
        vec![super::volume_jobs_tests::skin_file()],
    );
    step_until(&mut h, "the skin", |app| !app.busy());
    h
}

/// Opens a folder of masks whose outcomes `work` sends.
fn start(h: &mut Harness<'static, CutawayApp>, work: impl FolderWork) {
    let ctx = h.ctx.clone();
    h.state_mut()
        .folder
        .start_with(&ctx, "/masks".into(), "Opening masks".into(), work);
}

fn structure(name: &str, x: f64) -> Option<Model> {
    let mesh = csg::testkit::cube(
        glam::DVec3::new(x, 0.0, 0.0),
        glam::DVec3::new(x + 1.0, 1.0, 1.0),
    );
    Some(Model {
        source: PathBuf::from("/masks"),
        group: "masks".into(),
        ..Model::part(name, Some([0.5, 0.5, 0.5]), mesh)
    })
}

fn names(app: &CutawayApp) -> Vec<(String, usize)> {
    app.scene
        .models
        .iter()
        .map(|m| (m.model.name.clone(), m.model.index))
        .collect()
}

/// Outcomes that come out of order are shown in file order at their final index; the scene
/// shows the first structures while the worker still reads, with the status bar's progress.
#[test]
fn structures_are_shown_in_file_order_while_the_rest_arrive() {
    let mut h = window("order");
    let gate = Arc::new(AtomicBool::new(false));
    let open = gate.clone();
    start(&mut h, move |progress, send| {
        send((1, structure("b", 2.0)));
        send((0, structure("a", 0.0)));
        send((3, structure("d", 6.0)));
        while !open.load(Ordering::Relaxed) {
            progress.check()?;
            std::thread::sleep(Duration::from_millis(5));
        }
        send((2, None));
        send((4, structure("e", 8.0)));
        Ok(4)
    });
    step_until(&mut h, "the first structures", |app| {
        app.scene.models.len() == 2
    });
    h.run_steps(2);
    assert_eq!(
        names(h.state()),
        [("a".to_owned(), 0), ("b".to_owned(), 1)],
        "d waits on file 2"
    );
    assert!(h.state().folder.busy());
    assert!(
        h.query_by_label_contains("2 structures shown").is_some(),
        "the status bar's progress"
    );
    gate.store(true, Ordering::Relaxed);
    step_until(&mut h, "the folder", |app| !app.busy());
    h.run_steps(2);
    let app = h.state();
    assert_eq!(
        names(app),
        [
            ("a".to_owned(), 0),
            ("b".to_owned(), 1),
            ("d".to_owned(), 2),
            ("e".to_owned(), 3)
        ]
    );
    assert!(!app.status.is_error, "{}", app.status.message);
    assert!(
        app.status.message.contains("4 structures"),
        "{}",
        app.status.message
    );
    assert!(
        h.query_by_label_contains("structures shown").is_none(),
        "no progress after the end"
    );
}

/// Cancel while structures are shown: the worker stops and the scene is the one before.
#[test]
fn cancel_restores_the_scene_the_user_had() {
    let mut h = window("cancel");
    let before = names(h.state());
    let stopped = Arc::new(AtomicBool::new(false));
    let seen = stopped.clone();
    start(&mut h, move |progress, send| {
        send((0, structure("a", 0.0)));
        let waited = progress.check().and_then(|()| {
            loop {
                progress.check()?;
                std::thread::sleep(Duration::from_millis(5));
            }
        });
        seen.store(true, Ordering::Relaxed);
        waited
    });
    step_until(&mut h, "the first structure", |app| {
        app.scene.models.len() == 1 && app.scene.models[0].model.name == "a"
    });
    h.get_by_label("Cancel").click();
    h.run_steps(2);
    step_until(&mut h, "the worker to stop", |_| {
        stopped.load(Ordering::Relaxed)
    });
    h.run_steps(2);
    let app = h.state();
    assert_eq!(names(app), before, "the scene before the folder");
    assert!(
        app.status.message.contains("cancelled"),
        "{}",
        app.status.message
    );
    assert!(!app.folder.busy());
}

/// The chest's mask folder opened as a user opens it: its seven structures, named after their
/// files, in file order, the same meshes as the folder read whole; then added to that scene.
#[test]
fn a_real_mask_folder_opens_structure_by_structure() {
    let Some(dir) = std::env::var_os("CUTAWAY_ANATOMY")
        .map(|d| PathBuf::from(d).join("volumes/nifti_chest/per_structure"))
        .filter(|d| d.is_dir())
    else {
        println!("skipped: set CUTAWAY_ANATOMY to the anatomy folder to open its chest masks");
        return;
    };
    let mut h = window("chest");
    let ctx = h.ctx.clone();
    h.state_mut().open_paths(&ctx, vec![dir.clone()], true);
    step_until(&mut h, "the chest masks", |app| !app.busy());
    h.run_steps(2);
    let whole = crate::io::read_parts(&dir).unwrap();
    // Among other paths, the folder is read whole as one volume, not searched for meshes.
    let (added, _) =
        crate::scene::open::load_paths(std::slice::from_ref(&dir), &Default::default()).unwrap();
    assert_eq!(added.len(), whole.len());
    let app = h.state();
    assert!(!app.status.is_error, "{}", app.status.message);
    assert_eq!(app.scene.models.len(), whole.len());
    for (i, (shown, read)) in app.scene.models.iter().zip(&whole).enumerate() {
        assert_eq!((&shown.model.name, shown.model.index), (&read.name, i));
        assert_eq!(shown.model.group, "per_structure");
        assert_eq!(
            shown.model.mesh.triangles.len(),
            read.mesh.triangles.len(),
            "{}",
            read.name
        );
    }
    // Added to the scene (File → Add Model… or a drop): the same structures again, after the
    // ones there, one undo step.
    h.state_mut().open_paths(&ctx, vec![dir.clone()], false);
    step_until(&mut h, "the chest masks added", |app| !app.busy());
    h.run_steps(2);
    let app = h.state();
    assert!(!app.status.is_error, "{}", app.status.message);
    assert_eq!(app.scene.models.len(), 2 * whole.len());
    for (shown, read) in app.scene.models[whole.len()..].iter().zip(&whole) {
        assert_eq!(&shown.model.name, &read.name);
        assert_eq!(shown.model.mesh.triangles.len(), read.mesh.triangles.len());
    }
    h.state_mut().undo();
    assert_eq!(h.state().scene.models.len(), whole.len(), "one Undo");
}

/// Adds a folder of masks whose outcomes `work` sends to the window's scene (File → Add Model…).
fn add(h: &mut Harness<'static, CutawayApp>, work: impl FolderWork) {
    let ctx = h.ctx.clone();
    super::folder_arrival::add_with(h.state_mut(), &ctx, "/masks".into(), work);
}

/// A worker that sends `first`, waits for `gate` (stopping when cancelled), then sends `rest`;
/// `stopped` is set when it ends either way.
fn gated(
    first: Vec<Outcome>,
    gate: Arc<AtomicBool>,
    rest: Vec<Outcome>,
    stopped: Arc<AtomicBool>,
) -> impl FolderWork {
    move |progress, send| {
        // The structures, as the worker counts them (an empty mask gives none).
        let count = first.iter().chain(&rest).filter(|o| o.1.is_some()).count();
        for o in first {
            send(o);
        }
        let waited = (|| {
            while !gate.load(Ordering::Relaxed) {
                progress.check()?;
                std::thread::sleep(Duration::from_millis(5));
            }
            Ok(())
        })();
        if waited.is_ok() {
            for o in rest {
                send(o);
            }
        }
        stopped.store(true, Ordering::Relaxed);
        waited.map(|()| count)
    }
}

/// Added to a scene, a folder's structures come after the models there, the camera stays, and
/// the whole folder is one undo step: an edit made while it arrives is undone on its own and
/// keeps them, the next Undo removes them all, Redo brings them back.
#[test]
fn a_folder_added_to_the_scene_arrives_as_one_undo_step() {
    let mut h = window("add");
    let before = names(h.state());
    assert_eq!(before.len(), 1, "the skin");
    let camera = h.state().scene.camera;
    let (gate, stopped) = (
        Arc::new(AtomicBool::new(false)),
        Arc::new(AtomicBool::new(false)),
    );
    add(
        &mut h,
        gated(
            vec![(0, structure("a", 0.0))],
            gate.clone(),
            vec![
                (1, structure("b", 2.0)),
                (2, None),
                (3, structure("d", 6.0)),
            ],
            stopped,
        ),
    );
    step_until(&mut h, "the first structure", |app| {
        app.scene.models.len() == 2
    });
    // Each structure's index is its place in the folder, as a session names it.
    assert_eq!(names(h.state())[1], ("a".to_owned(), 0));
    assert!(
        h.query_by_label_contains("Adding masks: 1 structures shown")
            .is_some(),
        "the status bar's progress"
    );
    // An edit while the folder arrives: the skin's colour.
    let edit_before = h.state().scene.clone();
    h.state_mut().scene.models[0].color = [1.0, 0.0, 0.0];
    h.state_mut().record("colour change", edit_before);
    gate.store(true, Ordering::Relaxed);
    step_until(&mut h, "the folder", |app| !app.busy());
    h.run_steps(2);
    let all = [
        ("skin".to_owned(), 0),
        ("a".to_owned(), 0),
        ("b".to_owned(), 1),
        ("d".to_owned(), 2),
    ];
    let app = h.state();
    assert_eq!(names(app)[1..], all[1..]);
    assert_eq!(app.scene.camera, camera, "the camera stays");
    assert!(
        app.status.message.contains("Added masks: 3 structures"),
        "{}",
        app.status.message
    );
    h.state_mut().undo();
    assert_eq!(
        names(h.state())[1..],
        all[1..],
        "undoing the edit keeps them"
    );
    assert_ne!(h.state().scene.models[0].color, [1.0, 0.0, 0.0]);
    h.state_mut().undo();
    assert_eq!(names(h.state()), before, "one Undo removes the folder");
    h.state_mut().redo();
    assert_eq!(names(h.state())[1..], all[1..], "Redo brings it back");
}

/// Cancel, or an Undo, while a folder is added: the worker stops, what has come stays, and one
/// Undo removes it.
#[test]
fn a_folder_being_added_stops_on_cancel_or_undo_and_keeps_what_came() {
    for how in ["Cancel", "Undo"] {
        let mut h = window(&format!("add-{how}"));
        let before = names(h.state());
        let stopped = Arc::new(AtomicBool::new(false));
        add(
            &mut h,
            gated(
                vec![(0, structure("a", 0.0)), (1, structure("b", 2.0))],
                Arc::new(AtomicBool::new(false)),
                Vec::new(),
                stopped.clone(),
            ),
        );
        step_until(&mut h, "the first structures", |app| {
            app.scene.models.len() == 3
        });
        match how {
            "Cancel" => {
                h.get_by_label("Cancel").click();
                h.run_steps(2);
                assert!(
                    h.state().status.message.contains("2 structures added"),
                    "{}",
                    h.state().status.message
                );
                assert_eq!(names(h.state()).len(), 3, "what came stays");
                h.state_mut().undo();
            }
            _ => h.state_mut().undo(),
        }
        step_until(&mut h, "the worker to stop", |_| {
            stopped.load(Ordering::Relaxed)
        });
        h.run_steps(2);
        assert!(!h.state().folder.busy(), "{how}");
        assert_eq!(names(h.state()), before, "{how}: the folder undone");
        h.state_mut().redo();
        assert_eq!(
            names(h.state()).len(),
            3,
            "{how}: Redo brings back what came"
        );
    }
}
