//! One model under the scalpel: the [`Scalpel`] with its half-edge copy of the model's mesh, the
//! mesh the scene shows for it, what the strokes so far replaced (for following undo), the rest
//! mesh's indexes for projecting the pointer, and the delta a stroke in progress is drawn with
//! (see the parent module's "Drawing a stroke in progress").
//!
//! Everything here that costs time proportional to the mesh is built off the UI thread: the
//! scalpel itself when the model is selected ([`super::Prepared`]), the rest mesh's indexes
//! when a stroke commits ([`ModelCut::index_rest`]), the vertex-to-face table when the shown
//! mesh changes.

use std::collections::HashSet;
use std::sync::Arc;

use glam::{DVec2, DVec3};

use csg::{Mesh, PickIndex, SpatialIndex};
use cutter::scalpel::live_opening::LiveOpening;
use cutter::scalpel::{OpenOptions, Scalpel, ScalpelOptions, dffd};

use crate::cutting::delta::{self, MeshDelta, VertexFaces};
use crate::platform::background::yield_to_foreground;
use crate::scene::Scene;

/// A scalpel working on one model of the scene.
pub(crate) struct ModelCut {
    /// Index into `Scene::models`.
    pub(crate) model: usize,
    pub(crate) scalpel: Scalpel,
    /// The mesh the scene shows for `model`, made from the scalpel's mesh.
    pub(crate) shown: Arc<Mesh>,
    /// `shown` before each committed stroke of this session, oldest first, with the opening it
    /// was shown with.
    pub(crate) before_strokes: Vec<(Arc<Mesh>, OpenOptions)>,
    /// Bumped whenever the scalpel's rest mesh changes at a stroke boundary (commit, undo).
    pub(crate) revision: u64,
    /// The rest mesh with its spatial index and ray-pick tree, and the `revision` they were
    /// built for. Splitting keeps the surface where it was, so they serve a whole stroke; built
    /// on a thread of their own when a stroke commits ([`ModelCut::index_rest`]).
    pub(crate) rest: Option<(u64, RestJob)>,
    /// The opening `shown` was made with (a stroke with another one redraws the whole mesh).
    pub(crate) shown_open: OpenOptions,
    /// The faces of each vertex of `shown`, for the deltas of a stroke; built on a thread of its
    /// own as soon as `shown` changes, so a stroke rarely waits for it.
    pub(crate) faces: Option<(Arc<Mesh>, FacesJob)>,
    /// The opening of the scalpel's mesh, kept between steps: a step recomputes only around
    /// what it changed.
    pub(crate) opening: LiveOpening,
}

/// The rest mesh and what finds points on it: the spatial index (closest points, the rays to the
/// layers below) and the ray-pick tree (the pointer's ray finds the stroke's samples).
#[derive(Clone)]
pub(crate) struct RestIndexes {
    pub(crate) mesh: Arc<Mesh>,
    pub(crate) index: Arc<SpatialIndex>,
    pub(crate) pick: Arc<PickIndex>,
}

impl RestIndexes {
    fn build(mesh: Arc<Mesh>) -> RestIndexes {
        RestIndexes {
            index: Arc::new(SpatialIndex::build(&mesh)),
            pick: Arc::new(PickIndex::build(&mesh)),
            mesh,
        }
    }
}

/// [`RestIndexes`], being built or built.
pub(crate) enum RestJob {
    Building(std::thread::JoinHandle<RestIndexes>, Arc<Mesh>),
    Built(RestIndexes),
}

/// [`VertexFaces`] of a mesh, being built or built.
pub(crate) enum FacesJob {
    Building(std::thread::JoinHandle<VertexFaces>),
    Built(Arc<VertexFaces>),
}

impl ModelCut {
    pub(crate) fn new(model: usize, mesh: &Arc<Mesh>) -> Result<ModelCut, String> {
        let scalpel = Scalpel::new(mesh, ScalpelOptions::default()).map_err(|e| e.to_string())?;
        let session = ModelCut {
            model,
            scalpel,
            shown: mesh.clone(),
            before_strokes: Vec::new(),
            revision: 0,
            // Made where the scalpel is (off the UI thread when prepared, see the parent module).
            rest: Some((0, RestJob::Built(RestIndexes::build(mesh.clone())))),
            shown_open: OpenOptions {
                width: 0.0,
                window: 0.0,
            },
            faces: None,
            opening: LiveOpening::new(),
        };
        Ok(session)
    }

    /// Starts building the vertex-to-face table of `shown` (when not done for it yet).
    pub(crate) fn start_faces(&mut self) {
        if self
            .faces
            .as_ref()
            .is_some_and(|(m, _)| Arc::ptr_eq(m, &self.shown))
        {
            return;
        }
        let mesh = self.shown.clone();
        let job = {
            let mesh = mesh.clone();
            std::thread::Builder::new()
                .name("cutaway scalpel faces".into())
                .spawn(move || {
                    yield_to_foreground();
                    VertexFaces::build(&mesh)
                })
        };
        self.faces = Some((
            mesh.clone(),
            match job {
                Ok(handle) => FacesJob::Building(handle),
                Err(_) => FacesJob::Built(Arc::new(VertexFaces::build(&mesh))),
            },
        ));
    }

    /// Builds the vertex-to-face table of `shown` on this thread (a thread preparing the cut).
    pub(crate) fn build_faces(&mut self) {
        let faces = Arc::new(VertexFaces::build(&self.shown));
        self.faces = Some((self.shown.clone(), FacesJob::Built(faces)));
    }

    /// The vertex-to-face table of `shown` (waits for its thread when still building).
    pub(crate) fn faces(&mut self) -> Arc<VertexFaces> {
        self.start_faces();
        let Some((mesh, job)) = self.faces.take() else {
            return Arc::new(VertexFaces::build(&self.shown));
        };
        let built = match job {
            FacesJob::Built(f) => f,
            FacesJob::Building(handle) => match handle.join() {
                Ok(f) => Arc::new(f),
                Err(_) => Arc::new(VertexFaces::build(&mesh)),
            },
        };
        self.faces = Some((mesh, FacesJob::Built(built.clone())));
        built
    }

    /// Starts building the indexes of the rest mesh `mesh` (the scalpel's mesh now) on a thread
    /// of its own, for the current revision: a stroke commits without waiting for them, and the
    /// next press rarely does.
    pub(crate) fn index_rest(&mut self, mesh: Arc<Mesh>) {
        let job = {
            let mesh = mesh.clone();
            std::thread::Builder::new()
                .name("cutaway scalpel rest".into())
                .spawn(move || {
                    yield_to_foreground();
                    RestIndexes::build(mesh)
                })
        };
        self.rest = Some((
            self.revision,
            match job {
                Ok(handle) => RestJob::Building(handle, mesh),
                Err(_) => RestJob::Built(RestIndexes::build(mesh)),
            },
        ));
    }

    /// The rest mesh and its indexes for the current revision (waits for their thread when still
    /// building; builds them when the rest mesh changed without [`ModelCut::index_rest`], as
    /// after an undo).
    pub(crate) fn rest_indexes(&mut self) -> RestIndexes {
        let built = match self.rest.take() {
            Some((revision, job)) if revision == self.revision => match job {
                RestJob::Built(r) => r,
                RestJob::Building(handle, mesh) => {
                    handle.join().unwrap_or_else(|_| RestIndexes::build(mesh))
                }
            },
            _ => RestIndexes::build(Arc::new(self.scalpel.mesh())),
        };
        self.rest = Some((self.revision, RestJob::Built(built.clone())));
        built
    }

    /// The rest mesh and its spatial index.
    pub(crate) fn rest(&mut self) -> (Arc<Mesh>, Arc<SpatialIndex>) {
        let r = self.rest_indexes();
        (r.mesh, r.index)
    }

    /// The rest mesh and its ray-pick tree.
    pub(crate) fn rest_pick(&mut self) -> (Arc<Mesh>, Arc<PickIndex>) {
        let r = self.rest_indexes();
        (r.mesh, r.pick)
    }

    /// The delta of the stroke so far against `shown` (see the module documentation). Cost:
    /// the stroke's segments, their fans and the opening's displaced vertices; never the mesh.
    pub(crate) fn stroke_delta(
        &mut self,
        open: &OpenOptions,
        stroke: &mut Stroke,
    ) -> Arc<MeshDelta> {
        let faces = self.faces();
        let base = self.shown.clone();
        let mesh = self.scalpel.dyn_mesh();
        let nb = base.triangles.len() as u32;
        let nv = base.positions.len() as u32;
        let segments = self.scalpel.segments();
        let from = stroke.segments_before.min(segments.len());
        let mut fan = Vec::new();
        let mut visit = |v: u32, touched: &mut HashSet<u32>, floors: &mut Vec<u32>| {
            if v as usize >= mesh.vertex_count() {
                return;
            }
            let mut copies = mesh.copies(v);
            copies.push(v);
            for c in copies {
                mesh.fan_into(c, &mut fan);
                for &h in &fan {
                    let t = h / 3;
                    touched.insert(t);
                    for &w in &mesh.triangles()[t as usize] {
                        if mesh.is_floor(w) {
                            floors.push(w);
                        }
                    }
                }
            }
        };
        let mut floors = Vec::new();
        for s in &segments[from..] {
            visit(s.a, &mut stroke.touched, &mut floors);
            visit(s.b, &mut stroke.touched, &mut floors);
        }
        floors.sort_unstable();
        floors.dedup();
        let mut more = Vec::new();
        for f in floors {
            visit(f, &mut stroke.touched, &mut more);
        }
        let no_opening = csg::fast_hash::FastMap::default();
        let displaced = if open.width > 0.0 {
            self.opening
                .update(&self.scalpel, open, self.scalpel.clock());
            self.opening.moved()
        } else {
            &no_opening
        };
        let position = |v: u32| {
            displaced
                .get(&v)
                .copied()
                .unwrap_or_else(|| mesh.positions()[v as usize])
        };
        // Base vertices that moved: displaced ones, and floor vertices a deeper cut lowered.
        let mut moved: Vec<u32> = displaced
            .keys()
            .chain(&stroke.base_displaced)
            .copied()
            .filter(|&v| v < nv && position(v) != base.positions[v as usize])
            .collect();
        let mut touched: Vec<u32> = stroke.touched.iter().copied().filter(|&t| t < nb).collect();
        touched.sort_unstable();
        for &t in &touched {
            for &v in &mesh.triangles()[t as usize] {
                if v < nv && position(v) != base.positions[v as usize] {
                    moved.push(v);
                }
            }
        }
        let current = |t: u32| Some(mesh.triangles()[t as usize]);
        let wall = |t: u32| (t as usize) < mesh.triangle_count() && mesh.is_wall(t);
        let added = &mesh.triangles()[(nb as usize).min(mesh.triangle_count())..];
        Arc::new(delta::build(&delta::Change {
            base: &base,
            faces: &faces,
            touched: &touched,
            current: &current,
            added,
            position: &position,
            moved: &moved,
            wall: &wall,
        }))
    }

    /// The mesh to show: the rest pose, opened by the DFFD at the tool's clock (the kept
    /// opening when it is up to date, see [`ModelCut::update_opening`]; else computed here).
    pub(crate) fn display(&self, open: &OpenOptions) -> Arc<Mesh> {
        let mut mesh = self.scalpel.mesh();
        let clock = self.scalpel.clock();
        if open.width > 0.0 {
            if self.opening.is_current(&self.scalpel, open, clock) {
                for (&v, &p) in self.opening.moved() {
                    mesh.positions[v as usize] = p;
                }
            } else {
                for (v, p) in dffd::open_displacements(&self.scalpel, open, clock) {
                    mesh.positions[v as usize] = p;
                }
            }
        }
        Arc::new(mesh)
    }

    /// Brings the opening up to the scalpel's mesh and clock; microseconds it took (0 without
    /// an opening).
    pub(crate) fn update_opening(&mut self, open: &OpenOptions) -> f64 {
        if open.width <= 0.0 {
            return 0.0;
        }
        let start = std::time::Instant::now();
        self.opening
            .update(&self.scalpel, open, self.scalpel.clock());
        start.elapsed().as_secs_f64() * 1e6
    }

    /// What identifies the scalpel's mesh between two steps (a step that leaves it changes
    /// nothing the user can see).
    pub(crate) fn signature(&self) -> (usize, usize, usize, [u64; 3]) {
        let m = self.scalpel.dyn_mesh();
        let last = m
            .positions()
            .last()
            .map_or([0; 3], |p| [p.x.to_bits(), p.y.to_bits(), p.z.to_bits()]);
        (
            m.triangle_count(),
            m.vertex_count(),
            self.scalpel.segments().len(),
            last,
        )
    }
}

/// The stroke in progress.
pub(crate) struct Stroke {
    /// The scene before the stroke: the undo snapshot.
    pub(crate) before: Scene,
    /// Pixel and surface point of the press.
    pub(crate) press_px: DVec2,
    pub(crate) press_point: DVec3,
    /// Pixel of the last sample fed to the scalpel.
    pub(crate) last_px: DVec2,
    /// Last surface point (misses are projected onto the view plane through it).
    pub(crate) last_point: DVec3,
    /// The scalpel stroke has begun (the pointer moved [`START_PIXELS`] from the press).
    pub(crate) begun: bool,
    /// The stroke could not begin: the rest of the drag is ignored.
    pub(crate) failed: bool,
    pub(crate) signature: (usize, usize, usize, [u64; 3]),
    /// Steps replace the scene's mesh (wireframe models, a changed opening) instead of making
    /// a delta.
    pub(crate) whole_mesh: bool,
    /// The scalpel's segment count before the stroke (its segments are the ones after).
    pub(crate) segments_before: usize,
    /// The opening the scene's mesh was shown with at the press.
    pub(crate) open_before: OpenOptions,
    /// Vertices that opening displaced in the scene's mesh.
    pub(crate) base_displaced: Vec<u32>,
    /// Triangles of the scene's mesh (and appended ones) the stroke's steps touched so far.
    pub(crate) touched: HashSet<u32>,
    /// What the view draws for the stroke so far (delta mode).
    pub(crate) delta: Option<Arc<MeshDelta>>,
    /// The samples fed to the scalpel that landed on the surface, in order; `None` marks a step
    /// off the surface (it splits the strokes on the layers below).
    pub(crate) samples: Vec<Option<DVec3>>,
    /// Every point fed to the scalpel in this stroke (the press point first), in order.
    pub(crate) points: Vec<DVec3>,
}
