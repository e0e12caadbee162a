//! The region rule: which connected components are cavities of another.
//!
//! A segmentation surface often has nested shells: a bone's outer and inner surface, a hollow
//! organ, or separate structures one inside the other (a brain inside the skin). Treating all
//! shells of a file as one solid under the even-odd rule makes every inner outward shell a hole
//! of its container, which is wrong for nested structures. The rule used everywhere instead
//! (the boolean, the region split, the region count):
//!
//! > a **closed** component oriented **inward** (negative enclosed volume) that lies inside
//! > another closed component is a **cavity** of the innermost such component and belongs to
//! > its region; every other component is a region of its own.
//!
//! Each region is then one solid under the non-zero winding rule: its outer shell is outward,
//! its cavities inward, so the winding number is 1 inside its material and 0 elsewhere.
//!
//! "Lies inside" is decided exactly on the lattice points (the same predicates and tie-break as
//! the boolean): a ray along +x from one vertex of the inward component, perturbed like a cutter
//! point, crosses each closed component an odd number of times exactly when the vertex is inside
//! it. A vertex that lies exactly on another closed component's surface (touching shells) says
//! nothing, so the next vertex is tried. The innermost container is the one with the smallest
//! enclosed volume: closed shells that do not cross are nested, so their enclosed volumes are
//! ordered. Components that cross each other are outside this contract (the boolean's contract
//! says the same of self-intersecting targets).
//!
//! Cost: one exact volume pass over the faces when the mesh has several components, then one
//! ray per inward closed component (more only where vertices touch other shells).

use crate::aabb::Aabb;
use crate::adjacency::EdgeAdjacency;
use crate::exact::{self, LPoint};
use crate::lattice::Lattice;
use crate::lattice_bvh::{Bvh, IBox};
use crate::mesh::Mesh;
use crate::regions::{Regions, union};

/// Regions are components with their cavities joined: the rule of this module applied to
/// [`Regions::components`] (kept here so that `regions` stays the plain union-find it builds on).
impl Regions {
    /// Labels the regions of `mesh`: its edge-connected components, each cavity (a closed inward
    /// component inside another closed component) joined to the innermost component around it
    /// (the rule above).
    ///
    /// `adjacency` must be [`EdgeAdjacency::build`] of `mesh`.
    pub fn build(mesh: &Mesh, adjacency: &EdgeAdjacency) -> Regions {
        Self::of_components(mesh, adjacency, Self::components(mesh, adjacency))
    }

    /// [`Regions::build`] from the components ([`Regions::components`]) already labelled.
    pub fn of_components(mesh: &Mesh, adjacency: &EdgeAdjacency, components: Regions) -> Regions {
        if components.count <= 1 {
            return components;
        }
        let mut closed = vec![true; components.count];
        for e in 0..adjacency.edge_count() as u32 {
            let faces = adjacency.faces_of_edge(e);
            if faces.len() != 2 {
                for &f in faces {
                    closed[components.region_of_triangle[f as usize] as usize] = false;
                }
            }
        }
        if closed.iter().all(|&c| !c) {
            return components;
        }
        let lpoints = lattice_points(mesh);
        let boxes: Vec<IBox> = mesh
            .triangles
            .iter()
            .map(|t| IBox::of_triangle(t.map(|v| &lpoints[v as usize])))
            .collect();
        let bounds = boxes.iter().fold(IBox::EMPTY, |acc, b| acc.union(b));
        let bvh = Bvh::build(&boxes);
        let faces_in_box =
            |query: &IBox, visit: &mut dyn FnMut(u32)| bvh.query(query, &boxes, visit);
        let solids = solid_regions(mesh, &lpoints, &bounds, &components, &closed, &faces_in_box);
        solids.label(&components)
    }
}

impl Regions {
    /// The number of regions ([`Regions::build`]'s count) of a mesh that is closed, oriented,
    /// vertex-manifold and free of self-intersection, as a label surface is by construction:
    /// there its components by shared vertices are its edge-connected ones, and every inward
    /// component is a cavity of an outward one around it, so the regions are the components
    /// enclosing a positive exact volume. One union-find over the vertices and one exact volume
    /// pass: no edge adjacency, no spatial index and no ray. On any other mesh the count means
    /// nothing (the caller states the guarantee).
    pub fn count_of_valid_closed(mesh: &Mesh) -> usize {
        let mut parent: Vec<u32> = (0..mesh.positions.len() as u32).collect();
        for t in &mesh.triangles {
            union(&mut parent, t[0], t[1]);
            union(&mut parent, t[0], t[2]);
        }
        // Components numbered in order of their first triangle (vertices no triangle uses, if
        // any, form none).
        let root_of = |mut v: u32| {
            while parent[v as usize] != v {
                v = parent[v as usize];
            }
            v
        };
        let mut id_of_root = vec![u32::MAX; mesh.positions.len()];
        let mut count = 0u32;
        let region_of_triangle: Vec<u32> = mesh
            .triangles
            .iter()
            .map(|t| {
                let id = &mut id_of_root[root_of(t[0]) as usize];
                if *id == u32::MAX {
                    *id = count;
                    count += 1;
                }
                *id
            })
            .collect();
        if count <= 1 {
            return count as usize;
        }
        let components = Regions {
            region_of_triangle,
            count: count as usize,
        };
        let lpoints = lattice_points(mesh);
        let closed = vec![true; components.count];
        component_volumes(mesh, &lpoints, &components, &closed)
            .iter()
            .filter(|&&v| v > 0)
            .count()
    }
}

/// The mesh's vertices on the lattice of its own box (the boolean's exact coordinates).
fn lattice_points(mesh: &Mesh) -> Vec<LPoint> {
    let lattice = Lattice::for_box(&Aabb::from_points(&mesh.positions));
    mesh.positions
        .iter()
        .map(|&p| lattice.quantize(p).unwrap_or([0, 0, 0]))
        .collect()
}

/// How many vertices of an inward component are tried before it is left as its own region
/// (every one lying exactly on another shell: a degenerate, touching configuration).
const VERTEX_TRIES: usize = 64;

/// The regions of a mesh in terms of its connected components.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct SolidRegions {
    /// Region of each component, regions numbered in order of their first triangle.
    pub region_of_component: Vec<u32>,
    /// Number of regions.
    pub count: usize,
    /// Per component: the component whose cavity it is (`None`: it starts its own region).
    pub cavity_of: Vec<Option<u32>>,
    /// Per region: the sign of its exact enclosed volume (lattice units) when the mesh has
    /// several components and the region is closed; 0 otherwise (a lone component or an open
    /// one has no other region's winding to be told apart from).
    pub volume_sign: Vec<i8>,
}

impl SolidRegions {
    /// Every component its own region (a mesh with at most one component, or no cavity).
    fn identity(components: usize, volume_sign: Vec<i8>) -> SolidRegions {
        SolidRegions {
            region_of_component: (0..components as u32).collect(),
            count: components,
            cavity_of: vec![None; components],
            volume_sign,
        }
    }

    /// The regions of every triangle, from the components of every triangle.
    pub fn label(&self, components: &Regions) -> Regions {
        Regions {
            region_of_triangle: components
                .region_of_triangle
                .iter()
                .map(|&c| self.region_of_component[c as usize])
                .collect(),
            count: self.count,
        }
    }
}

/// Calls its second argument for every face whose lattice box overlaps the first (at least).
pub(crate) type FacesInBox<'a> = &'a dyn Fn(&IBox, &mut dyn FnMut(u32));

/// The regions of `mesh` under the cavity rule (module doc).
///
/// `lpoints` are the lattice points of `mesh`'s vertices, `bounds` their box, `components` its
/// edge-connected components with `component_closed` per component, and `faces_in_box` calls
/// its argument for every face whose lattice box overlaps the query (at least).
pub(crate) fn solid_regions(
    mesh: &Mesh,
    lpoints: &[LPoint],
    bounds: &IBox,
    components: &Regions,
    component_closed: &[bool],
    faces_in_box: FacesInBox<'_>,
) -> SolidRegions {
    let n = components.count;
    if n <= 1 {
        return SolidRegions::identity(n, vec![0; n]);
    }
    let comp = |t: u32| components.region_of_triangle[t as usize] as usize;
    let volumes = component_volumes(mesh, lpoints, components, component_closed);
    let sign = |v: i128| v.signum() as i8;
    let inward: Vec<usize> = (0..n)
        .filter(|&c| component_closed[c] && volumes[c] < 0)
        .collect();
    if inward.is_empty() {
        return SolidRegions::identity(n, volumes.iter().map(|&v| sign(v)).collect());
    }
    // A few vertices of each inward component, in order of first use.
    let mut slot = vec![usize::MAX; n];
    for (i, &c) in inward.iter().enumerate() {
        slot[c] = i;
    }
    let mut tries: Vec<Vec<u32>> = vec![Vec::new(); inward.len()];
    for (t, tri) in mesh.triangles.iter().enumerate() {
        let s = slot[comp(t as u32)];
        if s == usize::MAX || tries[s].len() >= VERTEX_TRIES {
            continue;
        }
        for &v in tri {
            if tries[s].len() < VERTEX_TRIES && !tries[s].contains(&v) {
                tries[s].push(v);
            }
        }
    }
    let usable = |t: u32, c: usize| {
        let tri = mesh.triangles[t as usize];
        let k = comp(t);
        k != c && component_closed[k] && tri[0] != tri[1] && tri[1] != tri[2] && tri[2] != tri[0]
    };
    let corners = |t: u32| mesh.triangles[t as usize].map(|v| &lpoints[v as usize]);
    let mut cavity_of: Vec<Option<u32>> = vec![None; n];
    for (&c, vertices) in inward.iter().zip(&tries) {
        for &v in vertices {
            let p = &lpoints[v as usize];
            let mut on_other = false;
            faces_in_box(&IBox { min: *p, max: *p }, &mut |t| {
                if !on_other && usable(t, c) {
                    let [a, b, cc] = corners(t);
                    on_other = exact::point_on_triangle(p, a, b, cc);
                }
            });
            if on_other {
                continue;
            }
            let far = [bounds.max[0] + 1, p[1], p[2]];
            let ray = IBox { min: *p, max: far };
            let mut hits: Vec<u32> = Vec::new();
            faces_in_box(&ray, &mut |t| {
                if usable(t, c) {
                    let [a, b, cc] = corners(t);
                    if exact::cutter_edge_crosses_target_face(p, &far, a, b, cc).is_some() {
                        hits.push(comp(t) as u32);
                    }
                }
            });
            hits.sort_unstable();
            // Components crossed an odd number of times contain the vertex; the innermost is
            // the one enclosing the least volume.
            cavity_of[c] = hits
                .chunk_by(|a, b| a == b)
                .filter(|run| run.len() % 2 == 1)
                .map(|run| run[0])
                .min_by_key(|&k| (volumes[k as usize].unsigned_abs(), k));
            break;
        }
    }
    // Join each cavity with its container; the smallest component id of a group is its root,
    // so numbering roots in ascending order numbers regions by their first triangle.
    let mut parent: Vec<u32> = (0..n as u32).collect();
    for (c, container) in cavity_of.iter().enumerate() {
        if let Some(k) = container {
            union(&mut parent, c as u32, *k);
        }
    }
    let grouped = Regions::from_parents(parent);
    let mut region_volume = vec![0i128; grouped.count];
    let mut region_closed = vec![true; grouped.count];
    for c in 0..n {
        let r = grouped.region_of_triangle[c] as usize;
        region_volume[r] = region_volume[r].saturating_add(volumes[c]);
        region_closed[r] &= component_closed[c];
    }
    SolidRegions {
        count: grouped.count,
        region_of_component: grouped.region_of_triangle,
        cavity_of,
        volume_sign: region_volume
            .iter()
            .zip(&region_closed)
            .map(|(&v, &closed)| if closed { sign(v) } else { 0 })
            .collect(),
    }
}

/// Exact enclosed volume (six times, lattice units) of every closed component; 0 for open ones.
fn component_volumes(
    mesh: &Mesh,
    lpoints: &[LPoint],
    components: &Regions,
    component_closed: &[bool],
) -> Vec<i128> {
    use rayon::prelude::*;
    let n = components.count;
    let origin = [0i64; 3];
    let mut volumes = (0..mesh.triangles.len())
        .into_par_iter()
        .with_min_len(1 << 15)
        .fold(
            || vec![0i128; n],
            |mut acc, t| {
                let c = components.region_of_triangle[t] as usize;
                if component_closed[c] {
                    let [a, b, cc] = mesh.triangles[t].map(|v| &lpoints[v as usize]);
                    acc[c] = acc[c].saturating_add(exact::orient3d(&origin, a, b, cc));
                }
                acc
            },
        )
        .reduce(
            || vec![0i128; n],
            |a, b| {
                a.iter()
                    .zip(&b)
                    .map(|(x, y)| x.saturating_add(*y))
                    .collect()
            },
        );
    volumes.truncate(n);
    volumes
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::*;
    use crate::testkit;

    fn sphere(centre: DVec3, radius: f64) -> Mesh {
        let mut m = testkit::icosphere(2, radius);
        for p in &mut m.positions {
            *p += centre;
        }
        m
    }

    fn joined(parts: &[Mesh]) -> Mesh {
        let mut out = Mesh::default();
        for p in parts {
            out.append(p);
        }
        out
    }

    /// The count without adjacency or rays agrees with the full rule on every nesting a label
    /// surface can have: apart, a cavity, a structure inside another's cavity, an island.
    #[test]
    fn count_of_valid_closed_agrees_with_the_region_rule() {
        let big = sphere(DVec3::ZERO, 10.0);
        let cavity = sphere(DVec3::ZERO, 6.0).reversed();
        let inner = sphere(DVec3::ZERO, 3.0);
        let apart = sphere(DVec3::new(30.0, 0.0, 0.0), 2.0);
        let other = sphere(DVec3::new(-30.0, 0.0, 0.0), 2.0);
        let cases = [
            (Mesh::default(), 0),
            (big.clone(), 1),
            (joined(&[big.clone(), apart.clone()]), 2),
            (joined(&[big.clone(), cavity.clone()]), 1),
            (joined(&[big.clone(), cavity.clone(), inner.clone()]), 2),
            (
                joined(&[apart.clone(), big.clone(), cavity, inner, other]),
                4,
            ),
        ];
        for (i, (mesh, expected)) in cases.iter().enumerate() {
            let full = Regions::build(mesh, &EdgeAdjacency::build(mesh)).count;
            assert_eq!(full, *expected, "case {i}: the full rule");
            assert_eq!(Regions::count_of_valid_closed(mesh), *expected, "case {i}");
        }
    }
}
