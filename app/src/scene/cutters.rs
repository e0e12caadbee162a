//! A cutter of the scene (the `cutter` crate's cutter aimed at one model) and the views Preview
//! shows it with.

/// A cutter's ribbons or slices: the `cutter` crate's request, kept as it is.
pub use cutter::subcutters::SubCutterSpec;

/// Which context-preserving views a cutter shows in Preview mode (thesis 3.4).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CutterViews {
    /// Normal cut: the kept part with the walls in their own colour and a thick contour line.
    pub cut: bool,
    /// The removed piece drawn with this opacity (0..=1) by order-independent transparency.
    pub transparency: Option<f32>,
    /// Ribbons: the removed surface inside thin sub-cutters, no walls.
    pub ribbons: Option<SubCutterSpec>,
    /// Solid slices: ribbons closed by their walls.
    pub slices: Option<SubCutterSpec>,
}

impl Default for CutterViews {
    /// Normal cut only.
    fn default() -> CutterViews {
        CutterViews {
            cut: true,
            transparency: None,
            ribbons: None,
            slices: None,
        }
    }
}

impl CutterViews {
    /// True when the cutter changes the picture at all in Preview mode.
    pub fn any(&self) -> bool {
        self.cut || self.transparency.is_some() || self.ribbons.is_some() || self.slices.is_some()
    }
}

/// A cutter of the scene: the `cutter` crate's [`cutter::Cutter`] (kind, smoothing and the
/// bounded planes the editor produced), aimed at one model, with how Preview shows it.
///
/// The cutter is held as the editor, the boolean and the overlay know it, never as a copy in
/// another form: the session reader makes it once from the file's names and points, and every
/// reader (live cut, Preview, undo, `extrude`, `render`) takes its surface from
/// [`cutter::Cutter::surface`].
#[derive(Clone, Debug, PartialEq)]
pub struct SceneCutter {
    /// Index into [`Scene::models`] of the model this cutter cuts.
    pub target: usize,
    /// At least one plane; consecutive planes bound one box of the cutter.
    pub cutter: cutter::Cutter,
    pub views: CutterViews,
}

impl SceneCutter {
    /// `cutter` aimed at model `target`, shown as a Normal Cut.
    pub fn new(target: usize, cutter: cutter::Cutter) -> SceneCutter {
        SceneCutter {
            target,
            cutter,
            views: CutterViews::default(),
        }
    }
}
