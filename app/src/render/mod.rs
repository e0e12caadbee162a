//! # The renderer: one for the window and for headless PNG export
//!
//! A long-lived [`Renderer`] owns the pipelines, the offscreen targets and a cache of uploaded
//! meshes; everything that changes per frame comes in a [`FrameInputs`] and lives in per-frame
//! draw data ([`draw_data`]). The 3D view is always rendered offscreen ([`Renderer::prepare`])
//! and then composited into whatever target the caller has ([`Renderer::paint`]): egui's render
//! pass in the window, a plain texture in [`headless`]. So the window and `cutaway render` produce
//! the same pixels.
//!
//! ## Using it from an egui paint callback (offscreen in `prepare`, blit in `paint`)
//!
//! ```ignore
//! // Once, at startup (eframe's CreationContext):
//! let rs = cc.wgpu_render_state.as_ref().unwrap();
//! let renderer = Renderer::new(&rs.device, OutputTarget::egui(rs.target_format));
//! rs.renderer.write().callback_resources.insert(renderer);
//!
//! // Each frame, for the viewport rect:
//! struct ViewCallback { inputs: FrameInputs }      // FrameInputs is Send + Sync + 'static
//! impl egui_wgpu::CallbackTrait for ViewCallback {
//!     fn prepare(&self, device, queue, _screen, encoder, resources) -> Vec<wgpu::CommandBuffer> {
//!         resources.get_mut::<Renderer>().unwrap().prepare(device, queue, encoder, &self.inputs);
//!         Vec::new()
//!     }
//!     fn paint(&self, _info, pass, resources) {
//!         resources.get::<Renderer>().unwrap().paint(pass);
//!     }
//! }
//! // inputs.size = rect size in physical pixels (rect.size() * pixels_per_point, rounded).
//! ui.painter().add(egui_wgpu::Callback::new_paint_callback(rect, ViewCallback { inputs }));
//! ```
//!
//! The renderer draws what it is given and knows no scene: a [`FrameInputs`] lists the models
//! (a mesh behind an `Arc`, a colour, a style), the look, the image and the cut to show, and the
//! caller makes it from its scene (`crate::view::frame`). The renderer uploads a mesh once and
//! re-uploads only when the `Arc` is replaced. A model that changes a little at a time (the live
//! cut while painting, a scalpel stroke) comes as a [`crate::cutting::delta::MeshDelta`] in
//! [`FrameInputs::deltas`] instead: the uploaded mesh stays, some of its faces are hidden in
//! place and a small patch is drawn with it, so a change uploads only what changed
//! ([`Renderer::last_frame_uploads`] counts it). The cut ([`FrameInputs::cut`], a
//! [`CutDrawing`]) is computed by the caller, on a worker thread in the window; the renderer
//! runs no boolean and keeps a cut's uploads while the same `Arc` comes every frame.
//!
//! ## What is drawn (thesis 3.4)
//! - Models: per-model colour, opacity (< 1 → order-independent transparency), solid or
//!   wireframe, visibility. Two-sided headlight shading; back faces darker.
//! - With [`FrameInputs::risk`], the cut walls it covers coloured by their distance to the
//!   critical structures (red, graded, then the wall's own look; `shaders/risk.wgsl`).
//! - [`ViewMode::Edit`]: the cutters of [`FrameInputs::overlays`] semi-transparent, plane outlines
//!   on top, the highlighted plane in orange.
//! - [`ViewMode::Preview`] with [`FrameInputs::cut`]: per cutter the kept part, the walls in
//!   their own colour, a thick screen-space contour line, the removed piece by weighted-blended
//!   order-independent transparency (McGuire and Bavoil 2013; correct for any number of
//!   overlapping layers without sorting), ribbons and solid slices.
//! - Anti-aliasing: 2×2 supersampling (the blit's bilinear tap averages each 2×2 block exactly).
//!   [`FrameInputs::deterministic`] turns it off for golden images.
//! - Red/blue anaglyph: the scene rendered from two eye cameras, combined in the blit.
//!
//! Colour pipeline: sRGB colours → linear light → shaded into `Rgba16Float`
//! premultiplied targets → gamma-encoded by the blit shader when the output format is not sRGB
//! (egui's `Bgra8Unorm` surface is not), so lighting never looks dark.

pub mod device_memory;
pub mod draw_data;
pub mod frame;
pub mod gpu_data;
pub mod headless;
pub mod image_layer;
mod pipelines;
mod renderer;
pub mod risk_layer;

pub use frame::{
    CutDrawing, CutterOverlay, DrawStyle, FrameInputs, ImageDraw, Look, ModelDraw, PartDraw,
    PartLook, Tile, ViewMode,
};
pub use headless::HeadlessRenderer;
pub use renderer::{
    BACK_FACE, CONTOUR_COLOR, CONTOUR_OFFSET, CONTOUR_WIDTH_PX, GpuCensus, Renderer, UploadStats,
    WALL_MIX, WALL_TINT,
};

/// The render target [`Renderer::paint`] draws into.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct OutputTarget {
    pub format: wgpu::TextureFormat,
    /// Sample count of the render pass `paint` is called in.
    pub sample_count: u32,
    /// Depth format of that pass, if it has a depth attachment (egui's has none by default).
    pub depth_format: Option<wgpu::TextureFormat>,
    /// Write straight alpha (for PNG files) instead of premultiplied alpha (for egui).
    pub straight_alpha: bool,
}

impl OutputTarget {
    /// egui's render pass: its target format, no MSAA, no depth buffer, premultiplied alpha.
    /// (If the app sets `NativeOptions::multisampling` or `depth_buffer`, fill the fields in.)
    pub fn egui(format: wgpu::TextureFormat) -> OutputTarget {
        OutputTarget {
            format,
            sample_count: 1,
            depth_format: None,
            straight_alpha: false,
        }
    }

    /// A PNG export: `Rgba8Unorm`, straight alpha.
    pub fn png() -> OutputTarget {
        OutputTarget {
            format: wgpu::TextureFormat::Rgba8Unorm,
            sample_count: 1,
            depth_format: None,
            straight_alpha: true,
        }
    }
}

/// sRGB-encoded component (0..=1) → linear light.
pub fn srgb_to_linear(c: f32) -> f32 {
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

/// Linear light (0..=1) → sRGB-encoded component.
pub fn linear_to_srgb(c: f32) -> f32 {
    if c <= 0.003_130_8 {
        c * 12.92
    } else {
        1.055 * c.powf(1.0 / 2.4) - 0.055
    }
}

/// The WGSL sources, for the pipelines and for the naga validation test.
pub mod shaders {
    /// `uniforms.wgsl` (the frame and draw uniforms both read) with `mesh.wgsl`, and with
    /// `lines.wgsl` (WGSL has no includes).
    pub const MESH: &str = concat!(
        include_str!("shaders/uniforms.wgsl"),
        include_str!("shaders/mesh.wgsl")
    );
    pub const LINES: &str = concat!(
        include_str!("shaders/uniforms.wgsl"),
        include_str!("shaders/lines.wgsl")
    );
    pub const COMPOSITE: &str = include_str!("shaders/composite.wgsl");
    pub const BLIT: &str = include_str!("shaders/blit.wgsl");
    pub const SCATTER: &str = include_str!("shaders/scatter.wgsl");
    /// [`MESH`] with the image fragment stage of `image.wgsl` appended (walls showing the
    /// intensity image).
    pub const MESH_IMAGE: &str = concat!(
        include_str!("shaders/uniforms.wgsl"),
        include_str!("shaders/mesh.wgsl"),
        include_str!("shaders/image.wgsl")
    );
    pub const RISK: &str = include_str!("shaders/risk.wgsl");
    pub const RISK_IMAGE: &str = include_str!("shaders/risk_image.wgsl");

    /// The risk map's shader: the colours of `ramp` (the map's, in linear light) as WGSL
    /// constants, `mesh.wgsl`, with `image.wgsl` when the walls show the image, and `risk.wgsl`
    /// (+ `risk_image.wgsl`).
    pub fn risk(with_image: bool, ramp: &crate::cutting::wall_risk::RiskRamp) -> String {
        let constant = |name: &str, srgb: [f32; 3]| {
            let [r, g, b] = srgb.map(super::srgb_to_linear);
            format!("const {name}: vec3<f32> = vec3<f32>({r:.8}, {g:.8}, {b:.8});\n")
        };
        let mut source = constant("RISK_NEAR_COLOR", ramp.near)
            + &constant("RISK_BAND_START", ramp.band_start)
            + &constant("RISK_BAND_END", ramp.band_end)
            + MESH;
        if with_image {
            source += include_str!("shaders/image.wgsl");
        }
        source += RISK;
        if with_image {
            source += RISK_IMAGE;
        }
        source
    }

    /// Every shader with its file name.
    pub const ALL: [(&str, &str); 6] = [
        ("mesh.wgsl", MESH),
        ("lines.wgsl", LINES),
        ("composite.wgsl", COMPOSITE),
        ("blit.wgsl", BLIT),
        ("scatter.wgsl", SCATTER),
        ("mesh.wgsl + image.wgsl", MESH_IMAGE),
    ];
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cutting::wall_risk::RiskRamp;

    /// Every WGSL shader parses and validates with naga, so a broken shader cannot hide behind a
    /// GPU-less CI machine.
    #[test]
    fn shaders_validate_with_naga() {
        let risk = [
            ("risk.wgsl", shaders::risk(false, &RiskRamp::SCENE)),
            ("risk.wgsl + image", shaders::risk(true, &RiskRamp::SCENE)),
        ];
        let assembled = risk.iter().map(|(n, s)| (*n, s.as_str()));
        for (name, source) in shaders::ALL.into_iter().chain(assembled) {
            let module = naga::front::wgsl::parse_str(source)
                .unwrap_or_else(|e| panic!("{name}: {}", e.emit_to_string(source)));
            let mut validator = naga::valid::Validator::new(
                naga::valid::ValidationFlags::all(),
                naga::valid::Capabilities::default(),
            );
            if let Err(e) = validator.validate(&module) {
                panic!("{name}: {}", e.emit_to_string(source));
            }
        }
    }

    #[test]
    fn srgb_round_trip() {
        for i in 0..=20 {
            let c = i as f32 / 20.0;
            assert!((linear_to_srgb(srgb_to_linear(c)) - c).abs() < 1e-5, "{c}");
        }
        assert!(srgb_to_linear(0.5) < 0.25 && srgb_to_linear(0.5) > 0.2);
    }
}
