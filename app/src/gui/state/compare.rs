//! The Compare view's state: the pictures shown, the update running and the worker's renderer and
//! cache of cut variants.

use std::sync::{Arc, Mutex};

use crate::cutting::cut_scene::PreviewGeometry;
use crate::metrics::MetricsOptions;
use crate::metrics::variants::VariantMetrics;
use crate::render::HeadlessRenderer;
use crate::scene::{Scene, SceneCutter};

use crate::gui::jobs::Job;

/// Most variants shown side by side.
pub const MAX_SHOWN: usize = 4;

/// Everything the pictures and measures depend on.
#[derive(Clone, Debug, PartialEq)]
pub(in crate::gui) struct Request {
    pub(in crate::gui) variants: Vec<(String, Vec<SceneCutter>)>,
    pub(in crate::gui) camera: [f64; 9],
    pub(in crate::gui) tile: [u32; 2],
    pub(in crate::gui) focus: Option<String>,
    pub(in crate::gui) critical: Vec<String>,
    pub(in crate::gui) models: Vec<(usize, bool, u32, [u32; 3])>,
}

impl Request {
    pub(in crate::gui) fn of(scene: &Scene, tile: [u32; 2], options: &MetricsOptions) -> Request {
        let c = scene.camera;
        let mut variants = crate::scene::variants::all(scene);
        variants.truncate(MAX_SHOWN);
        Request {
            variants,
            camera: [
                c.eye.x, c.eye.y, c.eye.z, c.target.x, c.target.y, c.target.z, c.up.x, c.up.y,
                c.up.z,
            ],
            tile,
            focus: options.focus.clone(),
            critical: options.critical.clone(),
            models: scene
                .models
                .iter()
                .map(|m| {
                    (
                        Arc::as_ptr(&m.model.mesh) as usize,
                        m.visible,
                        m.opacity.to_bits(),
                        m.color.map(f32::to_bits),
                    )
                })
                .collect(),
        }
    }
}

/// A variant's cut and measures, kept while its cutters and the models stay the same.
pub(in crate::gui) struct Cached {
    pub(in crate::gui) key: (Vec<SceneCutter>, Vec<usize>),
    pub(in crate::gui) geometry: Arc<PreviewGeometry>,
    /// Measures and the options (and camera, for exposure) they were taken with.
    pub(in crate::gui) metrics: Option<(MetricsOptions, [f64; 9], crate::metrics::Metrics)>,
}

#[derive(Default)]
pub(in crate::gui) struct Worker {
    pub(in crate::gui) renderer: Option<HeadlessRenderer>,
    pub(in crate::gui) cache: Vec<Cached>,
}

/// What one update produced.
pub struct Compared {
    pub images: Vec<image::RgbaImage>,
    pub variants: Vec<VariantMetrics>,
    /// Wall time of the update on the worker, ms.
    pub ms: f64,
}

/// The view's state.
#[derive(Default)]
pub struct CompareView {
    /// The view replaces the 3D view.
    pub open: bool,
    /// The newest finished update, or why it failed.
    pub shown: Option<Result<Compared, String>>,
    pub(in crate::gui) textures: Vec<egui::TextureHandle>,
    pub(in crate::gui) shown_request: Option<Request>,
    pub(in crate::gui) job: Option<(Request, Job<Compared>)>,
    pub(in crate::gui) worker: Arc<Mutex<Worker>>,
    /// Size of one viewport in pixels, from the last layout.
    pub(in crate::gui) tile: [u32; 2],
    /// How many viewports the shared camera was last framed for: the main view's camera is
    /// framed for a wide view, and seen through a narrow viewport it cuts the models off or
    /// leaves them off-centre, so opening the view (or changing the number shown) frames the
    /// scene for the viewports' shape, keeping the direction; closing frames it for the 3D
    /// view again.
    pub(in crate::gui) framed_for: Option<usize>,
}

impl CompareView {
    /// True while pictures are being made.
    pub fn busy(&self) -> bool {
        self.job.is_some()
    }
}
