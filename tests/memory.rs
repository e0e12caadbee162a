//! The window's memory stays flat over a scripted session ([`memory_script`]: 10 cutters of 50
//! drag frames each, every view toggled, everything undone and redone) on a fixed scene, the
//! knee phantom's folder (`assets/knee`), so that it does not change with the default scene. It
//! fails when the resident size after loading is over 4× the loaded triangle data +
//! 300 MB, when any step after the first cut is more than 25 % (at least 64 MB) above the level
//! after the first cut, or when, once every cutter's every view, every model style and every mode was shown, any
//! later step (undo and redo of everything, each state drawn again) is more than 10 % (at least
//! 32 MB) above that level: repeating work must not pile memory up. It prints the highest level
//! after the first cut against the goal of +10 %, which is not met yet: on the earlier default scene (the head's
//! model files) 12 %, 13 % and 14 % in three runs (232 → 261 MB, 220 → 249 MB, 231 → 264 MB;
//! 16 % to 27 % before the caches below were bounded). What the window's caches hold stays flat at the worst steps (no live-cut index, one
//! preview, no copies), and so, within about 10 MB, do the allocator's bytes in use: the rest is
//! free space the allocator keeps resident in its arenas (40 MB after the first cut, 60 to 95 MB
//! later), once 27 MB in use that no counted cache holds (the software driver and egui are the
//! suspects). A trim of the live-cut worker's arena whenever it went idle did not change that.
//!
//! What keeps it flat is that each cache holds what the current view is made of and nothing
//! else: the live cut keeps a model's index only while its cutter is re-cut and drops all its
//! caches when Edit mode is left, a model cut by several cutters keeps one preview (so unchanged
//! models are not cut again and their indexes go), a preview the cutters no longer match is
//! dropped in Edit mode, Camera mode's copy of the cut lives only in Camera and Scalpel modes, and
//! wireframe edges go as soon as a frame does not draw them. Each step prints the allocator's totals
//! and the counts of what the window holds ([`cutaway::platform::memory_census`]); run with
//! `CUTAWAY_MEMORY_MAPS=1` to see the mappings per step.
//!
//! It is the only test of this binary, so no other test allocates in the process while it
//! measures. Skipped, with the reason printed, when no wgpu adapter exists (install
//! `mesa-vulkan-drivers` and set `WGPU_BACKEND=vulkan`; CI does). The same script on the real
//! anatomy, with peak figures: `cargo bench -p cutaway --bench memory`.

#[path = "support/memory_script.rs"]
mod memory_script;

use csg::testkit::{Resource, skip};
use memory_script::{Options, mb};

#[test]
fn window_memory_stays_flat_over_a_scripted_session() {
    if let Some(reason) = memory_script::no_adapter() {
        return skip(Resource::Gpu, reason);
    }
    let report = memory_script::run(Options {
        paths: vec![std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/knee")],
        cutters: 10,
        drag_frames: 50,
        save_session: None,
    });
    println!(
        "{} triangles ({:.1} MB): after loading {:.1} MB (bound {:.1} MB); after the first cut \
         {:.1} MB, highest later {:.1} MB at \"{}\" (goal +10 %: {:.1} MB); everything shown \
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
        report.worst.1 <= report.growth_guard(),
        "memory grew to {:.1} MB at \"{}\", over the {:.1} MB after the first cut + 25 % (at least 64 MB): {:.1} MB",
        mb(report.worst.1),
        report.worst.0,
        mb(report.first_cut),
        mb(report.growth_guard())
    );
    assert!(
        report.worst_after_all_shown.1 <= report.repeat_limit(),
        "memory grew to {:.1} MB at \"{}\", over the {:.1} MB once every view, style and mode was shown + 10 % (at least 32 MB): {:.1} MB",
        mb(report.worst_after_all_shown.1),
        report.worst_after_all_shown.0,
        mb(report.all_shown),
        mb(report.repeat_limit())
    );
}
