//! Why a cut was refused: the boolean's one error type.

use crate::mesh::MeshError;

/// Why a cut was refused. Each variant names the sub-cutter and what to fix.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum CutError {
    /// The cutter has no triangles.
    #[error("cutter {sub_cutter} has no triangles")]
    EmptyCutter { sub_cutter: usize },
    /// Bad indices or a non-finite coordinate.
    #[error("cutter {sub_cutter}: {source}")]
    InvalidMesh {
        sub_cutter: usize,
        #[source]
        source: MeshError,
    },
    /// A cutter vertex is so far from the target that the two together span more than
    /// [`super::MAX_REACH`] target sizes.
    #[error(
        "cutter {sub_cutter}: vertex {vertex} at {position:?} is too far from the target (the cutter and the target together span more than 1024 target sizes)"
    )]
    OutOfRange {
        sub_cutter: usize,
        vertex: usize,
        position: [f64; 3],
    },
    /// A triangle uses one vertex twice.
    #[error("cutter {sub_cutter}: triangle {triangle} uses a vertex twice")]
    DegenerateTriangle { sub_cutter: usize, triangle: usize },
    /// An edge is not shared by exactly two triangles: the cutter is open (1) or non-manifold (3+).
    #[error(
        "cutter {sub_cutter} is not closed: edge ({a}, {b}) has {faces} triangle(s); a cutter must be a closed surface (every edge in exactly two triangles)"
    )]
    NotClosed {
        sub_cutter: usize,
        a: u32,
        b: u32,
        faces: usize,
    },
    /// The two triangles of an edge traverse it in the same direction.
    #[error(
        "cutter {sub_cutter} is not consistently oriented: both triangles of edge ({a}, {b}) run the same way"
    )]
    NotOriented { sub_cutter: usize, a: u32, b: u32 },
    /// Negative or zero enclosed volume (inward-facing or flat).
    #[error(
        "cutter {sub_cutter} encloses no positive volume (its triangles face inward, or it is flat); reverse its triangles or fix its shape"
    )]
    NotPositive { sub_cutter: usize },
    /// Two cutter triangles (of one sub-cutter, or of two sub-cutters) intersect.
    #[error(
        "cutter triangles {first} and {second} intersect (sub-cutters {first_sub} and {second_sub}); a cutter must not self-intersect and sub-cutters must be disjoint"
    )]
    SelfIntersecting {
        first: usize,
        second: usize,
        first_sub: usize,
        second_sub: usize,
    },
    /// An internal consistency check failed (a bug; the target is untouched).
    #[error("internal error in the boolean: {0}")]
    Internal(String),
}
