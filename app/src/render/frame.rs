//! What one frame draws, in the renderer's own terms: the models as meshes with a colour and a
//! style, the cut as parts that replace some of them, cutter overlays, deltas, the look and the
//! image. The renderer knows nothing of the scene it came from; the caller (`crate::view::frame`
//! for the window and for headless renders alike) makes a frame from a scene and hands over the
//! cut it computed, as `re_renderer` takes draw data.

use std::fmt;
use std::sync::Arc;

use csg::Mesh;
use cutter::Camera;
use glam::DVec3;

use crate::cutting::delta::MeshDelta;
use crate::cutting::wall_risk::WallRisk;
use crate::io::intensity::{IntensityImage, Window};

/// A cutter as the editor shows it in Edit mode (built by `crate::cutting::overlay`).
pub use crate::cutting::overlay::CutterOverlay;

/// What the view shows (the GUI's mode buttons; Scalpel draws like Camera).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum ViewMode {
    /// The models as they are; cutters hidden.
    #[default]
    Camera,
    /// The models as they are and the cutters of [`FrameInputs::overlays`], semi-transparent;
    /// with [`FrameInputs::cut`] (the GUI's live cut) the cut models are drawn by its parts.
    Edit,
    /// Cuts executed: [`FrameInputs::cut`] replaces the cut models; cutters hidden.
    Preview,
}

/// How a model's surface is drawn.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum DrawStyle {
    #[default]
    Solid,
    /// Edges only, one pixel wide.
    Wireframe,
}

/// One model to draw. The renderer uploads `mesh` once and again only when the `Arc` (or the
/// `walls` list) is replaced.
#[derive(Clone, Debug)]
pub struct ModelDraw {
    /// For the GPU objects' labels.
    pub name: String,
    pub mesh: Arc<Mesh>,
    /// Faces of `mesh` that are incision walls (ascending), drawn in the wall colour with a hard
    /// edge at the lips (`crate::cutting::wall_split`).
    pub walls: Option<Arc<[u32]>>,
    /// sRGB, 0..=1.
    pub color: [f32; 3],
    /// 0..=1; below 1 drawn by order-independent transparency, 0 not drawn.
    pub opacity: f32,
    pub style: DrawStyle,
    pub visible: bool,
}

impl ModelDraw {
    /// The wall faces, empty for none.
    pub fn wall_faces(&self) -> &[u32] {
        self.walls.as_deref().unwrap_or(&[])
    }
}

/// The frame's look: the Rendering menu's settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Look {
    /// sRGB with straight alpha; alpha 0 gives a transparent image.
    pub background: [f32; 4],
    /// 2×2 supersampling (unless [`FrameInputs::deterministic`]).
    pub antialias: bool,
    /// Red/blue anaglyph of two eye cameras.
    pub anaglyph: bool,
}

impl Default for Look {
    /// White, antialiased, one eye.
    fn default() -> Look {
        Look {
            background: [1.0, 1.0, 1.0, 1.0],
            antialias: true,
            anaglyph: false,
        }
    }
}

/// The intensity image shown on walls, slices and ribbons.
#[derive(Clone, Debug)]
pub struct ImageDraw {
    /// Uploaded once as a 3-D texture, again only when the `Arc` is replaced.
    pub image: Arc<IntensityImage>,
    pub window: Window,
    /// Walls (and slices' walls) show the image.
    pub on_walls: bool,
    /// Slices and ribbons show the image on their outer surface.
    pub on_slices: bool,
    /// How much of the image goes into a wall's colour: 0 (the structure colour) to 1.
    pub image_weight: f32,
}

/// How a part of a cut is drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PartLook {
    /// The model outside every cutter: the model's colour, opacity and style.
    Kept,
    /// Cutter surface inside the model: the wall colour, opaque; shows the image on walls.
    Wall,
    /// The removed piece: the model's colour at the part's opacity, transparent.
    Removed,
    /// Removed surface inside a thin sub-cutter: the model's colour, opaque; shows the image on
    /// slices.
    Ribbon,
    /// Walls of a solid slice: the wall colour, opaque; shows the image on walls or slices.
    SliceWall,
    /// What a cut left of a model's scalpel incisions, every face an incision wall: the model's
    /// colour, shaded as the uncut model's incisions are; shows the image on walls.
    Incisions,
}

/// One mesh of a cut.
#[derive(Clone, Copy, Debug)]
pub struct PartDraw<'a> {
    /// Index into [`FrameInputs::models`] of the model the part belongs to (its colour).
    pub model: usize,
    pub look: PartLook,
    /// For [`PartLook::Removed`]; 1 for the others.
    pub opacity: f32,
    pub mesh: &'a Mesh,
}

/// A computed cut as the renderer draws it: parts that replace their models, and contour lines.
/// The renderer uploads a cut once and keeps it while the same `Arc` is handed in, so the
/// caller computes it off the UI thread and passes the same `Arc` every frame.
pub trait CutDrawing: fmt::Debug + Send + Sync {
    /// Whether model `model` is drawn by its parts instead of its own mesh.
    fn replaced(&self, model: usize) -> bool;
    /// How many parts there are.
    fn part_count(&self) -> usize;
    /// Part `index` (< [`CutDrawing::part_count`]).
    fn part(&self, index: usize) -> PartDraw<'_>;
    /// Thick contour lines: (model index, polyline).
    fn contours(&self) -> &[(usize, Vec<DVec3>)];
    /// The index into `risk.walls` of the refined wall computed for part `index`, if any.
    fn risk_wall(&self, risk: &WallRisk, index: usize) -> Option<usize> {
        let _ = (risk, index);
        None
    }
}

/// A rectangle of a larger image, for rendering exports bigger than the device's maximum texture
/// size tile by tile. The camera still frames the full image.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Tile {
    /// Size of the full image in pixels.
    pub full_size: [u32; 2],
    /// Top-left pixel of this tile in the full image (y down); the tile's size is
    /// [`FrameInputs::size`].
    pub origin: [u32; 2],
}

/// Everything that may change from one frame to the next. `Send + Sync + 'static`, so it can
/// live in an egui paint callback.
#[derive(Clone, Debug)]
pub struct FrameInputs {
    /// The models, in order (parts, contours and deltas name them by index or mesh).
    pub models: Vec<ModelDraw>,
    pub look: Look,
    /// The image on walls, slices and ribbons (`None`: no image).
    pub image: Option<ImageDraw>,
    /// The camera to render with.
    pub camera: Camera,
    /// Output size in physical pixels, each at least 1.
    pub size: [u32; 2],
    pub mode: ViewMode,
    /// The cut for Preview mode (and the live cut under the overlays in Edit mode); `None`
    /// draws the models uncut.
    pub cut: Option<Arc<dyn CutDrawing>>,
    /// Cutters to draw in Edit mode.
    pub overlays: Vec<CutterOverlay>,
    /// No supersampling whatever [`Look::antialias`] says (golden-image tests).
    pub deterministic: bool,
    /// Render only this part of a larger image (`None`: the whole image is `size`).
    pub tile: Option<Tile>,
    /// Models drawn as their uploaded mesh plus a small change (the live cut's kept part, a
    /// scalpel stroke in progress): a delta applies to the model whose mesh is its `base` (same
    /// `Arc`), replaced by the cut or not. See [`crate::cutting::delta`].
    pub deltas: Vec<Arc<MeshDelta>>,
    /// The risk map of `cut`'s walls ([`crate::cutting::wall_risk`]): a wall part it has a
    /// refined wall for ([`CutDrawing::risk_wall`]) is drawn coloured by distance instead.
    /// `None`: walls as usual.
    pub risk: Option<Arc<WallRisk>>,
}

impl FrameInputs {
    /// A frame of `models` from `camera`, in `mode`, with the default look and no image, cut,
    /// overlays or deltas.
    pub fn new(models: Vec<ModelDraw>, camera: Camera, size: [u32; 2], mode: ViewMode) -> Self {
        FrameInputs {
            models,
            look: Look::default(),
            image: None,
            camera,
            size,
            mode,
            cut: None,
            overlays: Vec::new(),
            deterministic: false,
            tile: None,
            deltas: Vec::new(),
            risk: None,
        }
    }

    /// Shows `cut` (or none): any [`CutDrawing`] behind an `Arc`, kept by identity.
    pub fn show_cut<C: CutDrawing + 'static>(&mut self, cut: Option<Arc<C>>) {
        self.cut = cut.map(|c| c as Arc<dyn CutDrawing>);
    }

    /// Pixels rendered per output pixel along each axis: 2 with antialiasing, 1 without.
    pub fn supersample(&self) -> u32 {
        if self.look.antialias && !self.deterministic {
            2
        } else {
            1
        }
    }
}
