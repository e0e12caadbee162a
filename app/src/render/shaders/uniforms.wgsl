// The uniforms every mesh and line shader reads: the frame's (camera, light, viewport) and the
// draw's (colour and style). Put in front of mesh.wgsl and lines.wgsl by `shaders` (WGSL has no
// includes), so the two declarations cannot drift apart.

// Keep in sync with FrameUniform in gpu_data.rs.
struct Frame {
    clip_from_world: mat4x4<f32>,
    eye_in_world: vec4<f32>,
    light_in_world: vec4<f32>,
    // x, y: target size in pixels; z: near, w: far.
    viewport: vec4<f32>,
};

// Keep in sync with DrawUniform in gpu_data.rs.
struct Draw {
    // Linear RGB, straight opacity.
    color: vec4<f32>,
    // x: back-face brightness; y: 1 lit / 0 flat; z: line width px; w: offset toward the eye in
    // world units (negative: away; the cutter overlay yields to the walls it coincides with).
    params: vec4<f32>,
    // Linear RGB of the incision walls (vertices with `wall` 1).
    wall_color: vec4<f32>,
};

@group(0) @binding(0) var<uniform> frame: Frame;
@group(1) @binding(0) var<uniform> draw: Draw;

// A world point in clip space, moved `draw.params.w` toward the eye (see Draw), so a line or an
// overlay lying on a surface wins the depth test (or, negative, yields to it).
fn clip_position(position_in_world: vec3<f32>) -> vec4<f32> {
    let toward_eye = normalize(frame.eye_in_world.xyz - position_in_world);
    let moved = position_in_world + toward_eye * draw.params.w;
    return frame.clip_from_world * vec4<f32>(moved, 1.0);
}
