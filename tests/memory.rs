//! The window's memory stays flat over a scripted session ([`memory_script`]: 10 cutters of 50
//! drag frames each, every view toggled, everything undone and redone) on a fixed scene, the
//! knee phantom's folder (`assets/knee`), so that it does not change with the default scene. It
//! fails when the resident size after loading is over 4× the loaded triangle data + 300 MB, or
//! when, once every cutter's every view, every model style and every mode was shown,
//! any later step (undo and redo of everything, each state drawn again) is more than 10 % above
//! that level: repeating work must not pile memory up. It prints the level after the first cut and
//! the highest level after it, against the stricter target of +10 % over the whole
//! session, which is not met yet: with free arena pages handed back the highest later level was
//! 16 % to 27 % above the first cut's in three runs (215 → 251 MB, 205 → 259 MB, and 213 → 269 MB
//! with glibc capped at two arenas, which changed nothing); most of the difference is memory in
//! use, not kept by the allocator — the cut indexes and previews of the nine models cut after the
//! first, wireframe edges (run with
//! `CUTAWAY_MEMORY_MAPS=1` to see the mappings per step).
//!
//! It is the only test of this binary, so no other test allocates in the process while it
//! measures. Skipped, with the reason printed, when no wgpu adapter exists (install
//! `mesa-vulkan-drivers` and set `WGPU_BACKEND=vulkan`; CI does). The same script on the real
//! anatomy, with peak figures: `cargo bench -p cutaway --bench memory`.

#[path = "memory_script.rs"]
mod memory_script;

use memory_script::{Options, mb};

#[test]
fn window_memory_stays_flat_over_a_scripted_session() {
    if let Some(reason) = memory_script::no_adapter() {
        println!("skipped: {reason}");
        return;
    }
    let report = memory_script::run(Options {
        paths: vec![std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/knee")],
        cutters: 10,
        drag_frames: 50,
        save_session: None,
    });
    println!(
        "{} triangles ({:.1} MB): after loading {:.1} MB (bound {:.1} MB); after the first cut \
         {:.1} MB, highest later {:.1} MB at \"{}\" (+10 % target {:.1} MB); everything shown \
         {:.1} MB, highest after {:.1} MB at \"{}\" (limit +10 %: {:.1} MB); peak {:.1} MB; {:.0} s",
        report.triangles,
        mb(report.data_bytes),
        mb(report.loaded),
        mb(report.load_bound()),
        mb(report.first_cut),
        mb(report.worst.1),
        report.worst.0,
        mb(report.growth_limit()),
        mb(report.all_shown),
        mb(report.worst_after_all_shown.1),
        report.worst_after_all_shown.0,
        mb(report.repeat_limit()),
        mb(report.peak),
        report.seconds
    );
    assert!(
        report.cutters_made >= 8,
        "only {} of 10 cutters were made",
        report.cutters_made
    );
    assert!(
        report.loaded <= report.load_bound(),
        "after loading the window holds {:.1} MB, over 4 × {:.1} MB of triangle data + 300 MB",
        mb(report.loaded),
        mb(report.data_bytes)
    );
    assert!(
        report.worst_after_all_shown.1 <= report.repeat_limit(),
        "memory grew to {:.1} MB at \"{}\", over the {:.1} MB once every view, style and mode was shown + 10 %",
        mb(report.worst_after_all_shown.1),
        report.worst_after_all_shown.0,
        mb(report.all_shown)
    );
}
