// Thick screen-space lines: each segment instance is a quad of `draw.params.z` pixels width,
// extended by half the width at both ends so consecutive segments join without gaps. Follows
// uniforms.wgsl (Frame, Draw and their bindings).

// Keep in sync with Segment in gpu_data.rs.
struct SegmentIn {
    @location(0) a_in_world: vec3<f32>,
    @location(1) b_in_world: vec3<f32>,
};

struct VertexOut {
    @builtin(position) position_in_clip: vec4<f32>,
};

@vertex
fn vs_main(@builtin(vertex_index) vertex_index: u32, s: SegmentIn) -> VertexOut {
    // Two triangles: (0,-1) (1,-1) (1,1) / (0,-1) (1,1) (0,1) as (along, across).
    let i = vertex_index % 6u;
    let along = select(0.0, 1.0, i == 1u || i == 2u || i == 4u);
    let across = select(-1.0, 1.0, i == 2u || i == 4u || i == 5u);

    var ca = clip_position(s.a_in_world);
    var cb = clip_position(s.b_in_world);
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
