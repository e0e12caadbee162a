// Copies the offscreen image into the output: 2x2 supersampling resolve by one bilinear tap,
// red/blue anaglyph combination, gamma encoding for non-sRGB targets, straight or premultiplied
// alpha.

// Keep in sync with BlitUniform in gpu_data.rs.
struct Blit {
    mode: u32,
    encode_srgb: u32,
    straight_alpha: u32,
    _pad: u32,
};

@group(0) @binding(0) var left_texture: texture_2d<f32>;
@group(0) @binding(1) var right_texture: texture_2d<f32>;
@group(0) @binding(2) var linear_sampler: sampler;
@group(0) @binding(3) var<uniform> blit: Blit;

struct VertexOut {
    @builtin(position) position: vec4<f32>,
    @location(0) uv: vec2<f32>,
};

@vertex
fn vs_main(@builtin(vertex_index) vertex_index: u32) -> VertexOut {
    let uv = vec2<f32>(f32((vertex_index << 1u) & 2u), f32(vertex_index & 2u));
    var out: VertexOut;
    out.position = vec4<f32>(uv.x * 2.0 - 1.0, 1.0 - uv.y * 2.0, 0.0, 1.0);
    out.uv = uv;
    return out;
}

fn encode(linear: vec3<f32>) -> vec3<f32> {
    let c = clamp(linear, vec3<f32>(0.0), vec3<f32>(1.0));
    let low = c * 12.92;
    let high = 1.055 * pow(c, vec3<f32>(1.0 / 2.4)) - 0.055;
    return select(high, low, c <= vec3<f32>(0.0031308));
}

@fragment
fn fs_main(in: VertexOut) -> @location(0) vec4<f32> {
    // Premultiplied linear colour.
    var color = textureSample(left_texture, linear_sampler, in.uv);
    if blit.mode == 1u {
        let right = textureSample(right_texture, linear_sampler, in.uv);
        let weights = vec3<f32>(0.2126, 0.7152, 0.0722);
        let alpha = max(color.a, right.a);
        color = vec4<f32>(dot(color.rgb, weights), 0.0, dot(right.rgb, weights), alpha);
    }
    let alpha = color.a;
    var straight = color.rgb / max(alpha, 1e-6);
    if blit.encode_srgb == 1u {
        straight = encode(straight);
    }
    if blit.straight_alpha == 1u {
        return vec4<f32>(straight, alpha);
    }
    return vec4<f32>(straight * alpha, alpha);
}
