// Thick screen-space lines: each segment instance is a quad of `draw.params.z` pixels width,
// extended by half the width at both ends so consecutive segments join without gaps.

// Keep in sync with FrameUniform in gpu_data.rs.
struct Frame {
    clip_from_world: mat4x4<f32>,
    eye_in_world: vec4<f32>,
    light_in_world: vec4<f32>,
    viewport: vec4<f32>,
};

// Keep in sync with DrawUniform in gpu_data.rs.
struct Draw {
    color: vec4<f32>,
    params: vec4<f32>,
    wall_color: vec4<f32>,
};

@group(0) @binding(0) var<uniform> frame: Frame;
@group(1) @binding(0) var<uniform> draw: Draw;

// Keep in sync with Segment in gpu_data.rs.
struct SegmentIn {
    @location(0) a_in_world: vec3<f32>,
    @location(1) b_in_world: vec3<f32>,
};

struct VertexOut {
    @builtin(position) position_in_clip: vec4<f32>,
};

fn to_clip(p: vec3<f32>) -> vec4<f32> {
    // Pull the point toward the eye so a line lying on a surface wins the depth test.
    let offset = normalize(frame.eye_in_world.xyz - p) * draw.params.w;
    return frame.clip_from_world * vec4<f32>(p + offset, 1.0);
}

@vertex
fn vs_main(@builtin(vertex_index) vertex_index: u32, s: SegmentIn) -> VertexOut {
    // Two triangles: (0,-1) (1,-1) (1,1) / (0,-1) (1,1) (0,1) as (along, across).
    let i = vertex_index % 6u;
    let along = select(0.0, 1.0, i == 1u || i == 2u || i == 4u);
    let across = select(-1.0, 1.0, i == 2u || i == 4u || i == 5u);

    var ca = to_clip(s.a_in_world);
    var cb = to_clip(s.b_in_world);
    // Clip the segment to the space in front of the eye.
    let min_w = 1e-4;
    var out: VertexOut;
    if ca.w < min_w && cb.w < min_w {
        out.position_in_clip = vec4<f32>(2.0, 2.0, 2.0, 1.0);
        return out;
    }
    if ca.w < min_w {
        ca = mix(ca, cb, (min_w - ca.w) / (cb.w - ca.w));
    } else if cb.w < min_w {
        cb = mix(cb, ca, (min_w - cb.w) / (ca.w - cb.w));
    }
    let half_size = 0.5 * frame.viewport.xy;
    let sa = ca.xy / ca.w * half_size;
    let sb = cb.xy / cb.w * half_size;
    var dir = sb - sa;
    if dot(dir, dir) < 1e-12 {
        dir = vec2<f32>(1.0, 0.0);
    }
    dir = normalize(dir);
    let perp = vec2<f32>(-dir.y, dir.x);
    let half_width = 0.5 * draw.params.z;
    let offset_px = perp * across * half_width + dir * (along * 2.0 - 1.0) * half_width;
    let c = select(ca, cb, along > 0.5);
    out.position_in_clip = vec4<f32>(c.xy + offset_px / half_size * c.w, c.z, c.w);
    return out;
}

@fragment
fn fs_main() -> @location(0) vec4<f32> {
    // Premultiplied.
    return vec4<f32>(draw.color.rgb * draw.color.a, draw.color.a);
}
