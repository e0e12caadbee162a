// Walls, slices and ribbons that show the intensity image (appended to mesh.wgsl, whose vertex
// stage and shading it uses). The image is an integer 3-D texture holding the file's samples
// bit for bit (R8Uint, R16Uint or R32Uint), decoded here by the sample kind, interpolated by
// hand (trilinear over eight textureLoads: integer textures are not filterable), scaled,
// windowed and mixed with the structure colour. `crate::intensity::IntensityImage::sample_world`
// is the CPU twin of `sample_image`.

// Keep in sync with ImageUniform in image_layer.rs.
struct ImageParams {
    voxel_from_world: mat4x4<f32>,
    // xyz: grid size; w: sample kind (0 uint8, 1 int16, 2 uint16, 3 int32, 4 float32).
    dims: vec4<f32>,
    // x: slope, y: intercept (stored → real value); z: window low; w: 1 / window width.
    values: vec4<f32>,
    // x: weight of the image against the structure colour (0, ½ or 1).
    mix: vec4<f32>,
};

@group(2) @binding(0) var<uniform> image: ImageParams;
@group(2) @binding(1) var volume: texture_3d<u32>;

// A stored sample as a number; `select`, not branches (see `shade` in mesh.wgsl).
fn stored_value(raw: u32, kind: u32) -> f32 {
    let as_i16 = f32(bitcast<i32>(raw << 16u) >> 16u);
    let as_i32 = f32(bitcast<i32>(raw));
    let as_f32 = bitcast<f32>(raw);
    var v = f32(raw);
    v = select(v, as_i16, kind == 1u);
    v = select(v, as_i32, kind == 3u);
    v = select(v, as_f32, kind == 4u);
    return v;
}

fn voxel(i: vec3<i32>, kind: u32) -> f32 {
    return stored_value(textureLoad(volume, i, 0).r, kind);
}

// x: the real value at world point p; y: 1 inside the grid (within half a voxel), else 0.
fn sample_image(p: vec3<f32>) -> vec2<f32> {
    let q = (image.voxel_from_world * vec4<f32>(p, 1.0)).xyz;
    let n = image.dims.xyz;
    let inside = all(q >= vec3<f32>(-0.5)) && all(q <= n - vec3<f32>(0.5));
    let c = clamp(q, vec3<f32>(0.0), n - vec3<f32>(1.0));
    let f = floor(c);
    let t = c - f;
    let last = vec3<i32>(n) - vec3<i32>(1);
    let b = min(vec3<i32>(f), last);
    let e = min(b + vec3<i32>(1), last);
    let kind = u32(image.dims.w);
    let x00 = mix(voxel(vec3<i32>(b.x, b.y, b.z), kind), voxel(vec3<i32>(e.x, b.y, b.z), kind), t.x);
    let x10 = mix(voxel(vec3<i32>(b.x, e.y, b.z), kind), voxel(vec3<i32>(e.x, e.y, b.z), kind), t.x);
    let x01 = mix(voxel(vec3<i32>(b.x, b.y, e.z), kind), voxel(vec3<i32>(e.x, b.y, e.z), kind), t.x);
    let x11 = mix(voxel(vec3<i32>(b.x, e.y, e.z), kind), voxel(vec3<i32>(e.x, e.y, e.z), kind), t.x);
    let v = mix(mix(x00, x10, t.y), mix(x01, x11, t.y), t.z);
    return vec2<f32>(v * image.values.x + image.values.y, select(0.0, 1.0, inside));
}

fn srgb_to_linear_1(c: f32) -> f32 {
    return select(pow((c + 0.055) / 1.055, 2.4), c / 12.92, c <= 0.04045);
}

// The shaded colour of a wall showing the image at this fragment (fs_image's colour, also the
// wall beyond the risk map's far distance in risk_image.wgsl).
fn image_wall_color(in: VertexOut, front_facing: bool, flat_normal: vec3<f32>) -> vec3<f32> {
    let s = sample_image(in.position_in_world);
    // The window maps to display grey (as a viewer shows it), so the grey is sRGB-encoded.
    let grey = srgb_to_linear_1(clamp((s.x - image.values.z) * image.values.w, 0.0, 1.0));
    let weight = image.mix.x * s.y;
    let structure = shade(in, front_facing, flat_normal);
    // The image is lit gently: enough to read the wall's shape, not enough to change its greys
    // much across a flat wall.
    let light = dot(shade_color(vec3<f32>(1.0), in, front_facing, flat_normal), vec3<f32>(1.0 / 3.0));
    let scan = vec3<f32>(grey) * mix(1.0, clamp(light, 0.0, 1.2), 0.3);
    return mix(structure, scan, weight);
}

@fragment
fn fs_image(in: VertexOut, @builtin(front_facing) front_facing: bool) -> @location(0) vec4<f32> {
    let flat_normal = face_normal(in.position_in_world);
    return vec4<f32>(image_wall_color(in, front_facing, flat_normal), 1.0);
}
