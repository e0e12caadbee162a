//! What the window holds that scales with the scene, counted: the live cut's caches, the cut
//! picture kept between frames, the editor's and the picker's indexes, and the renderer's
//! uploads. The memory test prints it next to the resident size after every step, so growth can
//! be traced to what holds it rather than guessed from the allocator's totals.
//!
//! The count types of the parts live here too (the live cut's, the cut cache's, the renderer's),
//! so this module names what it counts without depending on the layers that hold it.

use std::fmt;

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
    /// Ray-pick trees, and the bytes they hold.
    pub pick_trees: usize,
    pub pick_bytes: u64,
    /// The renderer's uploads (None without a GPU renderer).
    pub gpu: Option<GpuCensus>,
}

impl fmt::Display for MemoryCensus {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let l = &self.live;
        write!(
            f,
            "live cut: {} indexes, {} prefixes, {} previews, {} face tables, {} model cuts; \
             preview: {}; camera copy: {}; editor indexes {}; pick trees {} ({:.1} MB)",
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
            self.pick_bytes as f64 / (1u64 << 20) as f64,
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

/// What the live-cut worker keeps between cuts (`crate::cutting::live_cut::LiveCut::census`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct LiveCensus {
    /// Indexes, cut prefixes and whole-model previews of models cut by several cutters.
    pub cuts: CacheCensus,
    /// Vertex-to-face tables of model meshes (for the deltas' normals).
    pub face_tables: usize,
    /// Live cuts of models cut by one cutter (walls, contour and kept delta each).
    pub model_cuts: usize,
}

/// How many entries the cut cache holds (`crate::cutting::cut_scene::CutCache`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct CacheCensus {
    /// Exact indexes of model meshes.
    pub indexes: usize,
    /// Closed results of leading runs of cutters (each with its own index).
    pub prefixes: usize,
    /// Whole-model previews.
    pub previews: usize,
}

/// The uploads the renderer keeps between frames, by kind (`crate::render::Renderer::census`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct GpuCensus {
    /// Whole model meshes, and their bytes.
    pub models: usize,
    pub model_bytes: u64,
    /// Wireframe edge buffers (of models and preview parts), and their bytes.
    pub edge_sets: usize,
    pub edge_bytes: u64,
    /// Parts of the preview or live cut being drawn, and their bytes (contours included).
    pub preview_parts: usize,
    pub preview_bytes: u64,
    /// Patches of deltas (live cut, scalpel), and their bytes.
    pub deltas: usize,
    pub delta_bytes: u64,
}
