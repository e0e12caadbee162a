//! The cutter as Edit mode draws it: its plane outlines and its closed surface, the very mesh the
//! boolean cuts with ([`super::cut_parts::cutter_surface`]), so what the user edits is what cuts.
//! The window and headless renders both build their overlays here.
//!
//! A smooth cutter's surface costs a subdivision, so the surfaces of the last few cutters drawn
//! are kept (per thread) between frames.

use std::cell::RefCell;
use std::collections::VecDeque;
use std::sync::Arc;

use csg::Mesh;

use super::cut_parts::cutter_surface;
use crate::scene::SceneCutter;

/// A cutter as the editor shows it in Edit mode.
#[derive(Clone, Debug, Default)]
pub struct CutterOverlay {
    /// The corners of each bounded cutting plane (front-top, back-top, back-bottom,
    /// front-bottom), for the outline and the highlighted plane.
    pub planes: Vec<[glam::DVec3; 4]>,
    /// The closed cutter surface, exactly the one the boolean cuts with
    /// ([`cutter_surface`], smooth cutters subdivided).
    pub surface: Arc<csg::Mesh>,
    /// Index into `planes` of the plane under the mouse or selected; drawn in orange.
    pub highlighted_plane: Option<usize>,
    /// The cutter being edited (drawn a little stronger than the others).
    pub active: bool,
}

/// Surfaces kept between frames (the cutters a scene usually shows at once).
const KEPT_SURFACES: usize = 8;

/// The overlay of a scene cutter: plane outlines and the cutting surface, not highlighted, not
/// active (the window sets those for the cutter being edited).
pub fn cutter_overlay(cutter: &SceneCutter) -> CutterOverlay {
    CutterOverlay {
        planes: cutter.cutter.planes.iter().map(|p| p.corners()).collect(),
        surface: overlay_surface(&cutter.cutter),
        highlighted_plane: None,
        active: false,
    }
}

/// [`cutter_surface`] of `cutter`, from the per-thread cache when the same cutter was drawn
/// lately.
pub fn overlay_surface(cutter: &cutter::Cutter) -> Arc<Mesh> {
    thread_local! {
        static SURFACES: RefCell<VecDeque<(cutter::Cutter, Arc<Mesh>)>> = Default::default();
    }
    SURFACES.with(|cache| {
        let mut cache = cache.borrow_mut();
        if let Some((_, mesh)) = cache.iter().find(|(k, _)| k == cutter) {
            return mesh.clone();
        }
        let mesh = Arc::new(cutter_surface(cutter));
        if cache.len() >= KEPT_SURFACES {
            cache.pop_front();
        }
        cache.push_back((cutter.clone(), mesh.clone()));
        mesh
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_support::scene_with_cube_cut;

    /// The overlay draws exactly the surface the cut subtracts, plain and smooth.
    #[test]
    fn the_overlay_draws_the_surface_the_boolean_cuts_with() {
        let mut scene = scene_with_cube_cut(crate::scene::CutterViews::default());
        for smooth in [false, true] {
            scene.cutters[0].cutter.smooth = smooth;
            let overlay = cutter_overlay(&scene.cutters[0]);
            let cut_with = crate::cutting::cut_scene::cutter_mesh(&scene.cutters[0]);
            assert!(!cut_with.is_empty());
            assert_eq!(*overlay.surface, cut_with, "smooth: {smooth}");
            assert_eq!(overlay.planes.len(), scene.cutters[0].cutter.planes.len());
        }
    }
}
