// Resolves weighted-blended order-independent transparency over the opaque image.

@group(0) @binding(0) var accum_texture: texture_2d<f32>;
@group(0) @binding(1) var revealage_texture: texture_2d<f32>;

@vertex
fn vs_main(@builtin(vertex_index) vertex_index: u32) -> @builtin(position) vec4<f32> {
    let uv = vec2<f32>(f32((vertex_index << 1u) & 2u), f32(vertex_index & 2u));
    return vec4<f32>(uv * 2.0 - 1.0, 0.0, 1.0);
}

@fragment
fn fs_main(@builtin(position) position: vec4<f32>) -> @location(0) vec4<f32> {
    let texel = vec2<i32>(position.xy);
    let revealage = textureLoad(revealage_texture, texel, 0).r;
    if revealage >= 0.9999 {
        discard;
    }
    let accum = textureLoad(accum_texture, texel, 0);
    let average = accum.rgb / max(accum.a, 1e-5);
    let alpha = 1.0 - revealage;
    // Premultiplied "over" (blend One, OneMinusSrcAlpha).
    return vec4<f32>(average * alpha, alpha);
}
