//! What the window holds that scales with the scene, counted: the live cut's caches, the cut
//! picture kept between frames, the editor's and the picker's indexes, and the renderer's
//! uploads. The memory test prints it next to the resident size after every step, so growth can
//! be traced to what holds it rather than guessed from the allocator's totals.

use std::fmt;

use crate::cutting::live_cut::LiveCensus;
use crate::render::GpuCensus;

/// Counts of what the window holds (see the module documentation).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct MemoryCensus {
    /// The live-cut worker's caches.
    pub live: LiveCensus,
    /// Triangles of the computed cut (Preview's parts) the window keeps, if it keeps one.
    pub preview_triangles: Option<usize>,
    /// Whether Camera mode's copy of the cut without the removed-piece views is held.
    pub derived_cut: bool,
    /// The editor's spatial indexes.
    pub editor_indexes: usize,
    /// Ray-pick trees.
    pub pick_trees: usize,
    /// The renderer's uploads (None without a GPU renderer).
    pub gpu: Option<GpuCensus>,
}

impl fmt::Display for MemoryCensus {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let l = &self.live;
        write!(
            f,
            "live cut: {} indexes, {} prefixes, {} previews, {} face tables, {} model cuts; \
             preview: {}; camera copy: {}; editor indexes {}; pick trees {}",
            l.cuts.indexes,
            l.cuts.prefixes,
            l.cuts.previews,
            l.face_tables,
            l.model_cuts,
            self.preview_triangles
                .map_or("none".to_string(), |t| format!("{t} triangles")),
            if self.derived_cut { "yes" } else { "no" },
            self.editor_indexes,
            self.pick_trees,
        )?;
        if let Some(g) = &self.gpu {
            let mb = |b: u64| b as f64 / (1u64 << 20) as f64;
            write!(
                f,
                "; GPU: {} models {:.1} MB, {} edge sets {:.1} MB, {} cut parts {:.1} MB, \
                 {} patches {:.1} MB",
                g.models,
                mb(g.model_bytes),
                g.edge_sets,
                mb(g.edge_bytes),
                g.preview_parts,
                mb(g.preview_bytes),
                g.deltas,
                mb(g.delta_bytes)
            )?;
        }
        Ok(())
    }
}
