//! The surface point a ray meets on the scene **as drawn**: where the view shows a cut, that is
//! the cut's kept surface, walls, ribbons and slice walls, not the uncut model behind them. The
//! ruler and any other tool that places points on what the user sees go through here, so a point
//! never lands on a surface the cut has removed.

use glam::DVec3;

use crate::cutting::cut_scene::{PartKind, PreviewGeometry};
use crate::cutting::pick::ScenePicks;
use crate::scene::Scene;

/// The first point `ray` hits on the scene as drawn: a model's own surface, or, for a model the
/// cut `preview` draws by its parts, its kept surface, walls, ribbons and slice walls (not the
/// removed piece, which is see-through or hidden). `None` when nothing is hit.
pub fn first_hit(
    picks: &mut ScenePicks,
    scene: &Scene,
    preview: Option<&PreviewGeometry>,
    ray: &cutter::Ray,
) -> Option<DVec3> {
    let replaced = |m: usize| preview.is_some_and(|p| p.replaced.get(m).copied().unwrap_or(false));
    let mut whole = scene.clone();
    for (m, model) in whole.models.iter_mut().enumerate() {
        model.visible &= !replaced(m);
    }
    let mut best = picks.pick(&whole, ray).map(|(_, t)| t);
    for part in preview.map_or(&[][..], |p| &p.parts[..]) {
        let shown = scene.models.get(part.model).is_some_and(|m| m.visible);
        if !shown || part.kind == PartKind::Removed || part.mesh.triangles.is_empty() {
            continue;
        }
        let t_max = best.unwrap_or(f64::INFINITY);
        let tree = csg::PickIndex::build(&part.mesh);
        if let Some(hit) = tree.ray_cast(&part.mesh, ray.origin, ray.direction, t_max)
            && best.is_none_or(|b| hit.t < b)
        {
            best = Some(hit.t);
        }
    }
    best.map(|t| ray.at(t))
}
