//! What a background job of the window ends as: one [`JobOutput`], handed to the app on the UI
//! thread (`app_jobs.rs`), the only place a finished job changes the window's state.

use std::path::PathBuf;
use std::sync::Arc;

use crate::scene::Scene;

use crate::gui::action::Purpose;

/// Result of a background job.
pub enum JobOutput {
    /// A file dialog closed; `paths` is empty when it was cancelled.
    Picked {
        purpose: Purpose,
        paths: Vec<PathBuf>,
        took: std::time::Duration,
    },
    /// Models were read.
    Models {
        models: Vec<crate::io::Model>,
        replace: bool,
        sources: Vec<PathBuf>,
        /// A volume among the files that holds an intensity image, not labels.
        image: Option<crate::scene::ImageLayer>,
    },
    /// A session was read (models included).
    Session { path: PathBuf, scene: Box<Scene> },
    /// An intensity image was read, to show on the walls.
    Image(crate::scene::ImageLayer),
    /// A target's spatial index was built.
    Index {
        model: usize,
        mesh: std::sync::Weak<csg::Mesh>,
        index: Arc<csg::SpatialIndex>,
    },
    /// Preview cut parts for the scene state `key`, and the wall time of the cut in ms.
    Preview {
        geometry: Arc<crate::cutting::cut_scene::PreviewGeometry>,
        key: crate::cutting::scene_cuts::PreviewKey,
        ms: f64,
    },
    /// "Remove All Cut Geometry": new meshes for the cut models, for the scene state `key`.
    CutsApplied {
        meshes: Vec<(usize, Arc<csg::Mesh>)>,
        key: crate::cutting::scene_cuts::PreviewKey,
    },
    /// Expose planned its cutters on the scene state `key` and measured what they remove (mm³).
    Exposed {
        key: crate::gui::expose_job::ExposeKey,
        exposed: Box<crate::expose::Exposed>,
        removed_mm3: Option<f64>,
    },
    /// Something finished that only needs a message.
    Done(String),
}
