//! # Cutting a scene: everything between the cutter editor and the pictures, without a window
//!
//! The window (`gui/`), the CLI and the tests drive the same code here, so what a user does in
//! the window can be replayed and checked headless. Nothing in this module knows egui or wgpu:
//! it speaks scenes, `cutter` cutters and `csg` meshes, and reports progress through
//! [`crate::platform::jobs::Progress`].
//!
//! - [`cut_scene`]: the scene-cutting model: every cutter of a model cut in turn, the parts
//!   Preview draws, and the cache that makes re-cutting one edited cutter cost one boolean;
//!   [`cut_parts`] is one cutter against one target (surface, exact cut, ribbons, slices);
//!   [`cut_results`] the types both speak (a cut's parts, Preview's parts, each cutter's report).
//! - [`live_cut`]: the live re-cut of Edit mode on its own worker, newest request wins.
//! - [`mesh_cut`]: one cutter cut out of a whole target mesh (`cutaway subtract`, Python).
//! - [`scene_cuts`]: the whole scene cut off the UI thread (Preview, Remove All Cut Geometry,
//!   exports) and the key that says when a result is stale.
//! - [`editing`]: the editor slot around `cutter::Editor` and the settings a new cutter starts
//!   with.
//! - [`overlay`]: the cutter as Edit mode draws it, the surface the boolean cuts with.
//! - [`obstacles`]: what lies behind a cutter's target (the scene's other visible structures),
//!   which a new cutter's default depth reaches for.
//! - [`pick`]: which model a ray meets first, through each model's BVH; [`drawn_hit`]: the point
//!   a ray meets on the scene as drawn (cut walls and kept parts where a cut is shown).
//! - [`wall_risk`]: the risk map's distances from the cut walls to the critical structures, on
//!   walls refined so the colours never make a wall look safer than it is.
//! - [`risk_worker`]: that map for the cut on screen, on a worker, one job at a time, given
//!   only for the cut and the settings it was computed for.

pub mod cut_parts;
pub mod cut_results;
pub mod cut_scene;
pub mod delta;
pub mod drawn_hit;
pub mod editing;
pub mod live_cut;
pub mod mesh_cut;
pub mod obstacles;
pub mod overlay;
pub mod pick;
pub mod risk_worker;
pub mod scene_cuts;
pub mod vertices;
pub mod wall_pick;
pub mod wall_risk;
pub mod wall_split;
