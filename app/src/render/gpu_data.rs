//! Every struct the GPU reads, `#[repr(C)]` and `Pod`. Keep each in sync with the WGSL struct
//! of the same name (named on each struct); the naga validation test checks the sizes.

use bytemuck::{Pod, Zeroable};

/// One mesh vertex, made by the cutting layer (`crate::cutting::vertices`), which builds the
/// vertices of deltas and walls. Keep in sync with `VertexIn` in `mesh.wgsl`.
pub use crate::cutting::vertices::Vertex;

/// One vertex of a wall coloured by the risk map. Keep in sync with `RiskIn` in `risk.wgsl`.
/// Laid out as [`Vertex`] (the same buffer layout), with the ramp position in the last place.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct RiskVertex {
    pub position_in_world: [f32; 3],
    /// The smooth normal of the wall it was refined from, interpolated at this point (not unit
    /// length; the shader normalizes per fragment).
    pub normal_in_world: [f32; 3],
    /// Where the corner's distance lies on the ramp (the map's settings' `ramp_position`): ≤ 0
    /// red, 0..1 graded, ≥ 1 beyond.
    pub ramp: f32,
}

/// One line segment, drawn as a screen-space quad of the draw's width. Keep in sync with
/// `SegmentIn` in `lines.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct Segment {
    pub a_in_world: [f32; 3],
    pub b_in_world: [f32; 3],
}

/// Per-view values. Keep in sync with `Frame` in `uniforms.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct FrameUniform {
    /// World → clip (tile-adjusted when rendering a tile of a larger image).
    pub clip_from_world: [[f32; 4]; 4],
    /// xyz: eye position; w: unused.
    pub eye_in_world: [f32; 4],
    /// xyz: unit direction toward the key light (a headlight above-left of the eye); w: unused.
    pub light_in_world: [f32; 4],
    /// x, y: render-target size in pixels; z: near, w: far distance (view depth range, for the
    /// order-independent-transparency weights).
    pub viewport: [f32; 4],
}

/// Per-draw values, bound with a dynamic offset ([`DRAW_UNIFORM_STRIDE`] apart). Keep in sync
/// with `Draw` in `mesh.wgsl` and `lines.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct DrawUniform {
    /// Linear-light RGB and opacity (straight, not premultiplied).
    pub color: [f32; 4],
    /// x: brightness factor of back faces (two-sided lighting); y: 1 = lit, 0 = flat colour;
    /// z: line width in pixels (lines only); w: world-space offset toward the eye (lines only,
    /// keeps lines lying on a surface in front of it).
    pub params: [f32; 4],
    /// Linear-light RGB of the incision walls of a mesh drawn with this uniform (vertices with
    /// `wall` 1); w unused.
    pub wall_color: [f32; 4],
}

/// Blit settings. Keep in sync with `Blit` in `blit.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct BlitUniform {
    /// 0: show `left`; 1: red/blue anaglyph of `left` (red) and `right` (blue).
    pub mode: u32,
    /// 1 when the output format is not sRGB, so the shader must gamma-encode itself.
    pub encode_srgb: u32,
    /// 1: write straight alpha (PNG); 0: premultiplied (egui).
    pub straight_alpha: u32,
    pub _pad: u32,
}

/// Dynamic uniform offsets must be multiples of the device's alignment (256 on every backend
/// wgpu supports is the maximum), so per-draw and per-view uniforms are this far apart.
pub const DRAW_UNIFORM_STRIDE: u64 = 256;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn uniform_sizes_match_the_wgsl_layouts() {
        // WGSL sizes: mat4x4<f32> 64 + 3 × vec4<f32> 48 = 112; Draw 3 × vec4 = 48; Blit 4 × u32.
        assert_eq!(size_of::<FrameUniform>(), 112);
        assert_eq!(size_of::<DrawUniform>(), 48);
        assert_eq!(size_of::<BlitUniform>(), 16);
        assert_eq!(size_of::<Vertex>(), 28);
        assert_eq!(size_of::<RiskVertex>(), size_of::<Vertex>());
        assert_eq!(size_of::<Segment>(), 24);
        assert!(size_of::<FrameUniform>() as u64 <= DRAW_UNIFORM_STRIDE);
    }
}
