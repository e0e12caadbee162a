//! The geometry Preview mode draws: for every cutter, the kept part of its target, the walls, the
//! removed piece, the contour, and the ribbons and slices of its thin sub-cutters (thesis 3.4).
//!
//! This is the adapter between the scene and the boolean. It speaks only in plain meshes
//! ([`CutParts`]), so the renderer does not care which boolean produced them.
//!
//! The cuts use `csg`'s exact local boolean ([`csg::subtract`], [`csg::subtract_many`]) on the
//! cutter surface of the `cutter` crate ([`cutter::Cutter::surface`], smooth cutters subdivided:
//! the same surface the Edit overlay draws), and the ribbon/slice sub-cutters of
//! [`cutter::subcutters`] (thin boxes evenly spaced or centred on the planes, or horizontal layers
//! at depth steps, thesis 3.4.2).
//!
//! Several cutters on one model ([`cut_in_turn`]): each cuts the *closed* result of the ones
//! before it (their kept part welded to their walls), not just the kept surface, so the walls of
//! an earlier cutter that lie inside a later one are removed and a later cutter gets no walls where
//! an earlier one already took the material away. The result is T ∖ (K1 ∪ … ∪ Kn) for overlapping
//! cutters too (which `subtract_many` refuses). A tag per triangle (model surface, or the cutter
//! whose wall it is) survives every step, so the walls keep their colour and the contour is read
//! off the final mesh where the surface meets the walls. [`CutCache`] keeps the exact index of
//! each model and the closed results of earlier cutters, so re-cutting while one cutter is edited
//! (the live cut of Edit mode) costs one boolean.
//!
//! There is no approximate cut. When the boolean refuses a cutter (the editor only hands over
//! cutters that pass the same exact check, so this is a cutter loaded from a file or a target that
//! cannot be indexed), that cutter cuts nothing, the reason goes to [`PreviewGeometry::notes`]
//! (the GUI shows it in the status bar, `cutaway render` exits non-zero) and
//! [`PreviewGeometry::reports`] marks the cutter not exact.

use std::collections::HashMap;
use std::sync::Arc;

use csg::{Mesh, TargetIndex};
use glam::DVec3;

use crate::scene::{Scene, SceneCutter};

use super::cut_parts::{chain_edges, push_part};
pub use super::cut_parts::{
    contour_polylines, cut_exact, cutter_mesh, cutter_surface, select, sub_cuts,
};
pub use super::cut_results::{
    CutParts, CutReport, INCISION, PartKind, PreviewGeometry, PreviewPart, SURFACE, Step,
};

/// A model cut by several cutters in turn.
#[derive(Clone, Debug)]
pub struct SequenceResult {
    /// T ∖ (K1 ∪ … ∪ Kn): the kept surface closed by the walls, welded (closed and manifold when
    /// the model is and every cut was exact).
    pub closed: Arc<Mesh>,
    /// Tag of every triangle of `closed`: [`SURFACE`], or the cutter whose wall it is.
    pub tags: Arc<Vec<u32>>,
    /// Why a cutter could not cut (one line each); it cut nothing.
    pub notes: Vec<String>,
    /// Every cutter of the sequence with how its cut went.
    pub reports: Vec<(usize, CutReport)>,
}

/// The state between two steps of [`cut_in_turn`]: a closed mesh, its tags, (when it could be
/// built) its exact index, and how the cutters so far went.
#[derive(Clone)]
struct Stage {
    mesh: Arc<Mesh>,
    tags: Arc<Vec<u32>>,
    index: Option<Arc<TargetIndex>>,
    reports: Vec<(usize, CutReport)>,
}

/// The geometry of the cutters cutting a model, as a cache key (views left out).
type PrefixKey = (usize, Vec<(usize, cutter::Cutter)>);

/// One model's preview, as a cache key: the mesh and its cutters with their views.
type ModelKey = (usize, Vec<(usize, SceneCutter)>);

/// The cached output of one model in [`preview_geometry_with`].
#[derive(Clone, Default)]
struct ModelPreview {
    parts: Vec<PreviewPart>,
    contours: Vec<(usize, Vec<DVec3>)>,
    notes: Vec<String>,
    reports: Vec<(usize, CutReport)>,
}

/// Caches that make re-cutting while the user edits one cutter cheap: the exact index of every
/// model mesh (built once per mesh), the closed intermediate results of cutter prefixes (so
/// earlier cutters of a model are not re-cut when only the last one moves), and whole-model
/// previews (so models whose cutters did not change are not cut again). Entries hold only weak
/// references to the model meshes' identity through their address plus a `Weak`, so a replaced
/// mesh never matches a stale entry.
#[derive(Default)]
pub struct CutCache {
    /// Per target mesh: its exact index, and whether a cut used it since the last
    /// [`CutCache::forget_unused`].
    indexes: Vec<(std::sync::Weak<Mesh>, Arc<TargetIndex>, bool)>,
    /// Closed results of leading runs of cutters, and whether a cut used them since the last
    /// [`CutCache::forget_unused`].
    prefixes: std::collections::VecDeque<(PrefixKey, std::sync::Weak<Mesh>, Stage, bool)>,
    /// Preview parts per model, and whether a cut used them since the last `forget_unused`.
    models: std::collections::VecDeque<(ModelKey, std::sync::Weak<Mesh>, ModelPreview, bool)>,
}

/// Cut prefixes kept by [`CutCache`] (each holds a model-sized mesh and its index).
const CACHE_ENTRIES: usize = 4;

/// How many entries a [`CutCache`] holds.
pub use crate::platform::memory_census::CacheCensus;

impl CutCache {
    /// The exact index of `mesh`, built on first use.
    pub fn index(&mut self, mesh: &Arc<Mesh>) -> Result<Arc<TargetIndex>, csg::MeshError> {
        self.indexes.retain(|(w, _, _)| w.strong_count() > 0);
        if let Some((_, index, used)) = self
            .indexes
            .iter_mut()
            .find(|(w, _, _)| w.upgrade().is_some_and(|m| Arc::ptr_eq(&m, mesh)))
        {
            *used = true;
            return Ok(index.clone());
        }
        let index = Arc::new(TargetIndex::build(mesh.clone())?);
        self.indexes
            .push((Arc::downgrade(mesh), index.clone(), true));
        Ok(index)
    }

    /// What the cache holds now (the memory test prints it per step).
    pub fn census(&self) -> CacheCensus {
        CacheCensus {
            indexes: self.indexes.len(),
            prefixes: self.prefixes.len(),
            previews: self.models.len(),
        }
    }

    /// True when the index of `mesh` is cached.
    pub fn has_index(&self, mesh: &Arc<Mesh>) -> bool {
        self.indexes
            .iter()
            .any(|(w, _, _)| w.upgrade().is_some_and(|m| Arc::ptr_eq(&m, mesh)))
    }

    /// Drops the indexes, cut prefixes and model previews that no cut used since the previous
    /// call. A long-lived cache (the live cut's) calls this after each request, so it holds
    /// what the current cutters need, not every model or cutter state ever cut: an index costs
    /// several times its mesh, a prefix or a preview a model-sized mesh, and a model whose
    /// cutters did not change is not cut again. (Without calls, each list stays bounded:
    /// [`CACHE_ENTRIES`] prefixes, a preview and an index per live target mesh.)
    pub fn forget_unused(&mut self) {
        self.indexes
            .retain(|(w, _, used)| *used && w.strong_count() > 0);
        self.prefixes
            .retain(|(_, w, _, used)| *used && w.strong_count() > 0);
        self.models
            .retain(|(_, w, _, used)| *used && w.strong_count() > 0);
        for (_, _, used) in &mut self.indexes {
            *used = false;
        }
        for (_, _, _, used) in &mut self.prefixes {
            *used = false;
        }
        for (_, _, _, used) in &mut self.models {
            *used = false;
        }
    }

    fn prefix(&mut self, mesh: &Arc<Mesh>, key: &PrefixKey) -> Option<Stage> {
        let (_, _, stage, used) = self
            .prefixes
            .iter_mut()
            .find(|(k, w, _, _)| k == key && w.upgrade().is_some_and(|m| Arc::ptr_eq(&m, mesh)))?;
        *used = true;
        Some(stage.clone())
    }

    fn store_prefix(&mut self, mesh: &Arc<Mesh>, key: PrefixKey, stage: Stage) {
        self.prefixes
            .retain(|(k, w, _, _)| w.strong_count() > 0 && *k != key);
        if self.prefixes.len() >= CACHE_ENTRIES {
            self.prefixes.pop_front();
        }
        self.prefixes
            .push_back((key, Arc::downgrade(mesh), stage, true));
    }

    fn model(&mut self, mesh: &Arc<Mesh>, key: &ModelKey) -> Option<ModelPreview> {
        let (_, _, preview, used) = self
            .models
            .iter_mut()
            .find(|(k, w, _, _)| k == key && w.upgrade().is_some_and(|m| Arc::ptr_eq(&m, mesh)))?;
        *used = true;
        Some(preview.clone())
    }

    /// Keeps one preview per model mesh (the newest): older states of an edited model's cutters
    /// are never asked for again, and a big model's parts are large. Not bounded by a count: a
    /// model whose preview was pushed out would be cut again on the next request, its index built
    /// again and kept, so a scene of more cut models than a bound re-cut most of them on every
    /// change; one preview per live mesh is what the current picture is made of anyway.
    fn store_model(&mut self, mesh: &Arc<Mesh>, key: ModelKey, preview: ModelPreview) {
        self.models
            .retain(|(k, w, _, _)| w.strong_count() > 0 && k.0 != key.0);
        self.models
            .push_back((key, Arc::downgrade(mesh), preview, true));
    }
}

fn prefix_key(mesh: &Arc<Mesh>, cutters: &[(usize, &SceneCutter)]) -> PrefixKey {
    (
        Arc::as_ptr(mesh) as usize,
        cutters
            .iter()
            .map(|(i, c)| (*i, c.cutter.clone()))
            .collect(),
    )
}

/// Cuts `cutters` (scene index and cutter, in order) out of the model `mesh` one after another.
/// Each cutter cuts the closed result of the ones before it (their kept part welded to their
/// walls), so the walls of an earlier cutter that lie inside a later one are removed, and a later
/// cutter has no walls where an earlier one already removed the material: the result is
/// T ∖ (K1 ∪ … ∪ Kn) whether the cutters overlap or not. Every triangle carries a tag (the
/// model's [`SURFACE`] or the cutter whose wall it is) through all the steps.
///
/// `on_step` sees every step. `may_skip(cutter)` says that nobody needs that cutter's step (only
/// its effect on the result): a run of such cutters at the start whose closed result is cached
/// is then not cut again.
pub fn cut_in_turn(
    cache: &mut CutCache,
    mesh: &Arc<Mesh>,
    cutters: &[(usize, &SceneCutter)],
    may_skip: impl Fn(usize) -> bool,
    on_step: impl FnMut(&Step),
) -> SequenceResult {
    cut_in_turn_marked(cache, mesh, &[], cutters, may_skip, on_step)
}

/// [`cut_in_turn`] on a model whose faces `incisions` (ascending) are scalpel walls: they start
/// tagged [`INCISION`] instead of [`SURFACE`] and keep that tag through the cuts, so the preview
/// draws what is left of them as walls. Such a model's cut prefixes are neither cached nor read
/// from the cache (a cached prefix holds the tags of whoever cut it).
pub fn cut_in_turn_marked(
    cache: &mut CutCache,
    mesh: &Arc<Mesh>,
    incisions: &[u32],
    cutters: &[(usize, &SceneCutter)],
    may_skip: impl Fn(usize) -> bool,
    mut on_step: impl FnMut(&Step),
) -> SequenceResult {
    let mut notes = Vec::new();
    let cached = incisions.is_empty();
    // The longest cached prefix of skippable cutters.
    let mut start = 0;
    let mut stage = None;
    for k in (1..=cutters.len()).rev().filter(|_| cached) {
        if !cutters[..k].iter().all(|(i, _)| may_skip(*i)) {
            continue;
        }
        if let Some(s) = cache.prefix(mesh, &prefix_key(mesh, &cutters[..k])) {
            start = k;
            stage = Some(s);
            break;
        }
    }
    let mut stage = match stage {
        Some(s) => s,
        None => {
            let index = match cache.index(mesh) {
                Ok(index) => Some(index),
                Err(e) => {
                    notes.push(format!("the model cannot be cut: {e}"));
                    None
                }
            };
            let mut tags = vec![SURFACE; mesh.triangle_count()];
            for &f in incisions {
                if let Some(t) = tags.get_mut(f as usize) {
                    *t = INCISION;
                }
            }
            Stage {
                mesh: mesh.clone(),
                tags: Arc::new(tags),
                index,
                reports: Vec::new(),
            }
        }
    };
    for k in start..cutters.len() {
        let (c, cutter) = cutters[k];
        let Some(index) = stage.index.clone() else {
            stage.reports.push((c, CutReport::default()));
            continue;
        };
        let surface = cutter_mesh(cutter);
        if surface.is_empty() {
            stage.reports.push((c, CutReport::default()));
            continue;
        }
        if !surface.bbox().overlaps(&stage.mesh.bbox()) {
            // Exactly nothing to cut (and the boolean would refuse a cutter far out of range).
            let nothing = CutReport {
                exact: true,
                cut_ms: 0.0,
            };
            stage.reports.push((c, nothing));
            continue;
        }
        let tag = c as u32;
        let started = std::time::Instant::now();
        let exact = csg::subtract(&index, &surface);
        let cut_ms = started.elapsed().as_secs_f64() * 1000.0;
        let result = match exact {
            Ok(result) => result,
            Err(why) => {
                notes.push(format!("cutter {} cannot cut: {why}", c + 1));
                stage.reports.push((
                    c,
                    CutReport {
                        exact: false,
                        cut_ms,
                    },
                ));
                continue;
            }
        };
        // Each region's kept part welded to its own walls (nested solids stay apart).
        let (after, after_tags) = closed_by_region(&index, &stage.tags, &result, tag);
        // The removed piece is built only when someone looks at this step.
        let removed = if may_skip(c) {
            Mesh::default()
        } else {
            let part = result.removed.part();
            select(&part.mesh, |t| {
                matches!(part.provenance[t],
                    csg::Provenance::Target(f) if stage.tags[f as usize] == SURFACE)
            })
        };
        on_step(&Step {
            cutter: c,
            before: &index,
            before_mesh: &stage.mesh,
            before_tags: &stage.tags,
            removed: &removed,
            after: &after,
            after_tags: &after_tags,
        });
        let after = Arc::new(after);
        let next_index = if k + 1 < cutters.len() {
            match TargetIndex::build(after.clone()) {
                Ok(index) => Some(Arc::new(index)),
                Err(e) => {
                    notes.push(format!(
                        "after cutter {}: {e}; the cutters after it cannot cut",
                        c + 1
                    ));
                    None
                }
            }
        } else {
            None
        };
        let mut reports = std::mem::take(&mut stage.reports);
        reports.push((
            c,
            CutReport {
                exact: true,
                cut_ms,
            },
        ));
        stage = Stage {
            mesh: after,
            tags: Arc::new(after_tags),
            index: next_index,
            reports,
        };
        if cached && k + 1 < cutters.len() && stage.index.is_some() {
            let mut cached = stage.clone();
            // A cached prefix is not cut again: its time is not this cut's.
            for (_, r) in &mut cached.reports {
                r.cut_ms = 0.0;
            }
            cache.store_prefix(mesh, prefix_key(mesh, &cutters[..=k]), cached);
        }
    }
    SequenceResult {
        closed: stage.mesh,
        tags: stage.tags,
        notes,
        reports: stage.reports,
    }
}

/// The closed result of cutting `index`'s mesh (triangle tags `tags`) with `result`: per region
/// solid, its kept part and its walls (tagged `wall_tag`) welded into one closed surface (walls
/// share the contour's vertices bit for bit, so welding closes the seam), the solids one after
/// another. Each region is welded on its own: where regions are nested their walls overlap, and
/// welding across them would join the solids through the shared cutter vertices.
pub fn closed_by_region(
    index: &TargetIndex,
    tags: &[u32],
    result: &csg::CutResult,
    wall_tag: u32,
) -> (Mesh, Vec<u32>) {
    let (kept, provenance) = result.materialize_with_provenance(index.mesh());
    let region_closed = index.regions_closed();
    // The solid of a kept face: its region when that is closed, else the open regions together
    // (as the walls' solids are numbered).
    let solid = |f: u32| {
        let r = index.region_of_face(f);
        if region_closed[r as usize] {
            r
        } else {
            csg::solids::OPEN_PART
        }
    };
    let mut groups: Vec<u32> = provenance
        .iter()
        .map(|&f| solid(f))
        .chain(result.walls_solid.iter().copied())
        .collect();
    groups.sort_unstable();
    groups.dedup();
    if groups.len() <= 1 {
        // One solid (the common case): no split, no extra copy of a large kept part.
        let mut closed_tags: Vec<u32> = provenance.iter().map(|&f| tags[f as usize]).collect();
        let mut closed = kept;
        closed.append(&result.walls.mesh);
        closed_tags.resize(closed.triangle_count(), wall_tag);
        return (csg::weld::weld_exact(&closed).compacted(), closed_tags);
    }
    let mut closed = Mesh::default();
    let mut closed_tags =
        Vec::with_capacity(kept.triangle_count() + result.walls.mesh.triangle_count());
    for group in groups {
        let mut part = select(&kept, |t| solid(provenance[t]) == group);
        let mut part_tags: Vec<u32> = provenance
            .iter()
            .filter(|&&f| solid(f) == group)
            .map(|&f| tags[f as usize])
            .collect();
        let walls = select(&result.walls.mesh, |t| result.walls_solid[t] == group);
        part.append(&walls);
        part_tags.resize(part.triangle_count(), wall_tag);
        closed.append(&csg::weld::weld_exact(&part).compacted());
        closed_tags.extend(part_tags);
    }
    (closed, closed_tags)
}

/// The contour of a cut read off a welded, tagged result: the edges where a [`SURFACE`] triangle
/// meets a wall triangle whose tag `wall(tag)` accepts, chained into polylines (closed loops
/// repeat their first point). The edges of the walls are gathered first, so the cost is one hash
/// probe per surface edge.
pub fn tag_contours(mesh: &Mesh, tags: &[u32], wall: impl Fn(u32) -> bool) -> Vec<Vec<DVec3>> {
    let mut wall_edges: HashMap<(u32, u32), bool> = HashMap::new();
    for (t, tri) in mesh.triangles.iter().enumerate() {
        if tags[t] != SURFACE && wall(tags[t]) {
            for k in 0..3 {
                let (a, b) = (tri[k], tri[(k + 1) % 3]);
                wall_edges.insert((a.min(b), a.max(b)), false);
            }
        }
    }
    if wall_edges.is_empty() {
        return Vec::new();
    }
    for (t, tri) in mesh.triangles.iter().enumerate() {
        if tags[t] == SURFACE {
            for k in 0..3 {
                let (a, b) = (tri[k], tri[(k + 1) % 3]);
                if let Some(hit) = wall_edges.get_mut(&(a.min(b), a.max(b))) {
                    *hit = true;
                }
            }
        }
    }
    let edges: Vec<(u32, u32)> = wall_edges
        .into_iter()
        .filter(|&(_, hit)| hit)
        .map(|(e, _)| e)
        .collect();
    chain_edges(mesh, edges)
}

/// Executes every cutter of `scene` whose views show anything (see [`preview_geometry_with`]),
/// once: each model is cut with a cache of its own, dropped as soon as its parts are made. A
/// one-off cut (`cutaway render`, exports, Preview's job) asks nothing again, so an index (several
/// times its mesh) or a cut prefix kept past its model would only add to the peak: every cut
/// model's index would live until the last model is cut, and each model's parts would be copied
/// into a cache nobody reads.
pub fn preview_geometry(scene: &Scene) -> PreviewGeometry {
    scene_preview(scene, None)
}

/// Executes every cutter of `scene` whose views show anything. The cutters of one model cut it
/// in turn ([`cut_in_turn`]): the kept part and the walls are those of T ∖ (K1 ∪ … ∪ Kn), the
/// contour is where the kept surface meets the walls, and each cutter's removed piece, ribbons
/// and slices come from the surface it cut. `cache` makes repeated calls cheap while one cutter
/// is edited.
pub fn preview_geometry_with(scene: &Scene, cache: &mut CutCache) -> PreviewGeometry {
    scene_preview(scene, Some(cache))
}

/// [`preview_geometry_with`] with `cache`, or, with none, a cache per model that goes with it
/// (see [`preview_geometry`]).
fn scene_preview(scene: &Scene, mut cache: Option<&mut CutCache>) -> PreviewGeometry {
    let mut out = PreviewGeometry {
        replaced: vec![false; scene.models.len()],
        ..PreviewGeometry::default()
    };
    for (model_index, model) in scene.models.iter().enumerate() {
        let cutters: Vec<(usize, &SceneCutter)> = scene
            .cutters
            .iter()
            .enumerate()
            .filter(|(_, c)| c.target == model_index && c.views.any())
            .collect();
        if cutters.is_empty() {
            continue;
        }
        out.replaced[model_index] = true;
        let preview = match cache.as_deref_mut() {
            Some(cache) => {
                let key: ModelKey = (
                    Arc::as_ptr(&model.model.mesh) as usize,
                    cutters.iter().map(|(i, c)| (*i, (*c).clone())).collect(),
                );
                match cache.model(&model.model.mesh, &key) {
                    Some(p) => p,
                    None => {
                        let p = model_preview(scene, model_index, &cutters, cache);
                        cache.store_model(&model.model.mesh, key, p.clone());
                        p
                    }
                }
            }
            None => model_preview(scene, model_index, &cutters, &mut CutCache::default()),
        };
        out.parts.extend(preview.parts);
        out.contours.extend(preview.contours);
        out.notes.extend(preview.notes);
        out.reports.extend(preview.reports);
    }
    out.reports.sort_by_key(|(c, _)| *c);
    out
}

/// The preview parts of one model cut by `cutters`.
fn model_preview(
    scene: &Scene,
    model_index: usize,
    cutters: &[(usize, &SceneCutter)],
    cache: &mut CutCache,
) -> ModelPreview {
    let model = &scene.models[model_index];
    let mut out = PreviewGeometry::default();
    let mut refused: Vec<usize> = Vec::new();
    let needs_step = |c: usize| {
        let v = &scene.cutters[c].views;
        v.transparency.is_some() || v.ribbons.is_some() || v.slices.is_some()
    };
    let sequence = cut_in_turn_marked(
        cache,
        &model.model.mesh,
        model.wall_faces(),
        cutters,
        |c| !needs_step(c),
        |step| {
            let c = step.cutter;
            let cutter = &scene.cutters[c];
            let views = cutter.views;
            if let Some(opacity) = views.transparency {
                push_part(
                    &mut out,
                    model_index,
                    c,
                    PartKind::Removed,
                    opacity,
                    step.removed.clone(),
                );
            }
            for (view, with_walls) in [(views.ribbons, false), (views.slices, true)] {
                let Some(view) = view else { continue };
                let (ribbons, walls) = match sub_cuts(step, cutter, &view, with_walls) {
                    Ok(pieces) => pieces,
                    Err(e) => {
                        let what = if with_walls { "slices" } else { "ribbons" };
                        out.notes
                            .push(format!("cutter {} {what} cannot be cut: {e}", c + 1));
                        refused.push(c);
                        continue;
                    }
                };
                push_part(&mut out, model_index, c, PartKind::Ribbon, 1.0, ribbons);
                if with_walls {
                    // The slice is closed by the sub-cutters' walls, turned to face out of it.
                    push_part(
                        &mut out,
                        model_index,
                        c,
                        PartKind::SliceWall,
                        1.0,
                        walls.reversed(),
                    );
                }
            }
        },
    );
    let shows_walls = |tag: u32| scene.cutters.get(tag as usize).is_some_and(|c| c.views.cut);
    let closed = &sequence.closed;
    let tags = &sequence.tags;
    for &(c, cutter) in cutters {
        if cutter.views.cut {
            let walls = select(closed, |t| tags[t] == c as u32);
            push_part(&mut out, model_index, c, PartKind::Wall, 1.0, walls);
        }
    }
    for line in tag_contours(closed, tags, shows_walls) {
        out.contours.push((model_index, line));
    }
    // What is left of the model's scalpel incisions: walls on their own (a hard edge at the lips).
    let incisions = select(closed, |t| tags[t] == INCISION);
    push_part(
        &mut out,
        model_index,
        usize::MAX,
        PartKind::Wall,
        1.0,
        incisions,
    );
    let kept = select(closed, |t| tags[t] == SURFACE);
    push_part(&mut out, model_index, usize::MAX, PartKind::Kept, 1.0, kept);
    let mut notes = sequence.notes;
    notes.extend(out.notes);
    let reports = sequence
        .reports
        .into_iter()
        .map(|(c, mut r)| {
            r.exact &= !refused.contains(&c);
            (c, r)
        })
        .collect();
    ModelPreview {
        parts: out.parts,
        contours: out.contours,
        notes,
        reports,
    }
}

#[cfg(test)]
mod tests;

#[cfg(test)]
pub(crate) mod incision_tests;
