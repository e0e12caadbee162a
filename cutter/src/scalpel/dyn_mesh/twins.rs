//! The twin of every half-edge of a triangle list, for [`super::DynMesh::from_mesh`].
//!
//! Each half-edge is listed under its undirected edge (lower vertex, higher vertex), and one sort
//! puts an edge's half-edges in both directions next to each other; a pass over those runs then
//! pairs them. Finding each half-edge and its reverse by binary search in a sorted list of
//! directed edges instead was a third of making the scalpel's mesh on two million triangles
//! (four searches per half-edge, each a cache miss per probe).

use rayon::prelude::*;

use super::{NO_TWIN, NONMANIFOLD};

/// Per half-edge `3 t + k` (corner `k` to corner `k + 1` of triangle `t`), the half-edge that
/// runs the other way along the same edge: [`NO_TWIN`] when none does; [`NONMANIFOLD`] when the
/// edge joins a vertex to itself, or when more than one half-edge runs either way along it.
pub(super) fn twins(triangles: &[[u32; 3]]) -> Vec<u32> {
    let mut edges: Vec<(u64, u32)> = Vec::with_capacity(3 * triangles.len());
    for (t, tri) in triangles.iter().enumerate() {
        for k in 0..3 {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            let key = (u64::from(a.min(b)) << 32) | u64::from(a.max(b));
            edges.push((key, (3 * t + k) as u32));
        }
    }
    edges.par_sort_unstable_by_key(|e| e.0);
    // Whether half-edge `h` runs from the lower vertex of its edge to the higher.
    let upward = |h: u32| {
        let tri = triangles[(h / 3) as usize];
        let k = (h % 3) as usize;
        tri[k] < tri[(k + 1) % 3]
    };
    let mut twin = vec![NO_TWIN; 3 * triangles.len()];
    for run in edges.chunk_by(|x, y| x.0 == y.0) {
        let (lo, hi) = (run[0].0 >> 32, run[0].0 & u64::from(u32::MAX));
        if lo == hi {
            for &(_, h) in run {
                twin[h as usize] = NONMANIFOLD;
            }
            continue;
        }
        let up = run.iter().filter(|e| upward(e.1)).count();
        let down = run.len() - up;
        for &(_, h) in run {
            let (same, reverse) = if upward(h) { (up, down) } else { (down, up) };
            twin[h as usize] = if same != 1 || reverse > 1 {
                NONMANIFOLD
            } else if reverse == 1 {
                run.iter()
                    .map(|e| e.1)
                    .find(|&g| upward(g) != upward(h))
                    .expect("one half-edge runs the other way")
            } else {
                NO_TWIN
            };
        }
    }
    twin
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The rule of [`twins`], half-edge by half-edge over every other half-edge.
    fn plain(triangles: &[[u32; 3]]) -> Vec<u32> {
        let ends = |h: usize| {
            let tri = triangles[h / 3];
            (tri[h % 3], tri[(h % 3 + 1) % 3])
        };
        (0..3 * triangles.len())
            .map(|h| {
                let (a, b) = ends(h);
                let same = (0..3 * triangles.len())
                    .filter(|&g| ends(g) == (a, b))
                    .count();
                let reverse: Vec<usize> = (0..3 * triangles.len())
                    .filter(|&g| ends(g) == (b, a))
                    .collect();
                if a == b || same != 1 || reverse.len() > 1 {
                    NONMANIFOLD
                } else if let [g] = reverse[..] {
                    g as u32
                } else {
                    NO_TWIN
                }
            })
            .collect()
    }

    #[test]
    fn twins_follow_the_rule_on_closed_open_and_broken_meshes() {
        let tetra = vec![[0, 2, 1], [0, 1, 3], [1, 2, 3], [2, 0, 3]];
        let cases: Vec<Vec<[u32; 3]>> = vec![
            // Closed: every half-edge has its twin.
            tetra.clone(),
            // Open: the missing face leaves three boundary half-edges.
            tetra[..3].to_vec(),
            // A fin: three faces on edge 0-1.
            vec![[0, 1, 2], [1, 0, 3], [0, 1, 4]],
            // Two faces on one edge running the same way (inconsistent orientation).
            vec![[0, 1, 2], [0, 1, 3]],
            // A face listed twice, and a degenerate face joining a vertex to itself.
            vec![[0, 1, 2], [0, 1, 2], [2, 1, 3], [3, 3, 4]],
        ];
        for (n, triangles) in cases.iter().enumerate() {
            assert_eq!(twins(triangles), plain(triangles), "case {n}");
        }
        let closed = twins(&tetra);
        assert!(closed.iter().all(|&g| g < NONMANIFOLD));
        assert_eq!(
            twins(&tetra[..3]).iter().filter(|&&g| g == NO_TWIN).count(),
            3
        );
    }

    #[test]
    fn twins_follow_the_rule_on_a_sphere_with_flipped_and_repeated_faces() {
        let sphere = csg::testkit::icosphere(2, 1.0);
        let mut triangles = sphere.triangles.clone();
        triangles[5].swap(0, 1);
        triangles.push(triangles[17]);
        triangles.truncate(triangles.len() - 40);
        assert_eq!(twins(&triangles), plain(&triangles));
    }
}
