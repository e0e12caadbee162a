//! Local validation of a scalpel step: the triangles a step touched are checked before it
//! commits (cost proportional to them, not to the mesh), so a configuration the cutting code
//! does not handle costs the user one refused step, never a broken mesh. The whole-mesh
//! validator used by the tests is [`super::invariants`].

use super::dyn_mesh::{DynMesh, NO_TWIN, is_real};

impl DynMesh {
    /// Local validation of triangles `tris` (what a step touched; cost proportional to them):
    /// indices valid and distinct, twins mutual and reversed, no boundary edge when `closed`,
    /// no directed edge used twice around a corner, and every corner's triangle in the fan its
    /// vertex names (no bow-tie made). The step fails and rolls back when this finds a problem,
    /// so a bug in a rare configuration costs the user one refused step, never a broken mesh.
    pub(crate) fn local_problem(&self, tris: &[u32], closed: bool) -> Option<String> {
        let nv = self.positions.len() as u32;
        // (corner vertex, its outgoing half-edge) of every touched triangle, grouped by vertex
        // so that each vertex's fan is walked once.
        let mut corners: Vec<(u32, u32)> = Vec::with_capacity(3 * tris.len());
        for &t in tris {
            let tri = self.triangles[t as usize];
            if tri.iter().any(|&v| v >= nv)
                || tri[0] == tri[1]
                || tri[1] == tri[2]
                || tri[0] == tri[2]
            {
                return Some(format!("triangle {t} {tri:?} has a bad index"));
            }
            for k in 0..3 {
                let h = 3 * t + k;
                let g = self.twin[h as usize];
                if is_real(g) {
                    if g as usize >= self.twin.len()
                        || self.twin[g as usize] != h
                        || self.origin(g) != self.dest(h)
                        || self.dest(g) != self.origin(h)
                    {
                        return Some(format!("half-edge {h} and its twin {g} disagree"));
                    }
                } else if g == NO_TWIN && closed {
                    return Some(format!("half-edge {h} of triangle {t} {tri:?} is open"));
                }
                corners.push((tri[k as usize], h));
            }
        }
        corners.sort_unstable();
        let mut fan = Vec::new();
        let mut dests = Vec::new();
        for group in corners.chunk_by(|x, y| x.0 == y.0) {
            let v = group[0].0;
            let start = self.vert_he[v as usize];
            if start == NO_TWIN || self.origin(start) != v {
                return Some(format!("vertex {v} has no outgoing half-edge"));
            }
            self.fan_from(start, &mut fan);
            if !self.singular[v as usize]
                && let Some(&(_, h)) = group.iter().find(|(_, h)| !fan.contains(h))
            {
                return Some(format!("vertex {v}: triangle {} is outside its fan", h / 3));
            }
            dests.clear();
            dests.extend(fan.iter().map(|&x| self.dest(x)));
            dests.sort_unstable();
            if let Some(w) = dests.windows(2).find(|w| w[0] == w[1]) {
                return Some(format!("directed edge {v} -> {} is used twice", w[0]));
            }
        }
        None
    }

    /// [`DynMesh::local_problem`] found nothing.
    pub(crate) fn local_check(&self, tris: &[u32], closed: bool) -> bool {
        self.local_problem(tris, closed).is_none()
    }
}
