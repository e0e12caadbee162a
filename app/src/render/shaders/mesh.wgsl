// Shaded triangle meshes: opaque (fs_opaque) and weighted-blended order-independent
// transparency (fs_oit, McGuire and Bavoil 2013). Two-sided headlight shading in linear light.
// Follows uniforms.wgsl (Frame, Draw and their bindings).

// Keep in sync with Vertex in gpu_data.rs.
struct VertexIn {
    @location(0) position_in_world: vec3<f32>,
    @location(1) normal_in_world: vec3<f32>,
    // 1 on an incision wall, 0 elsewhere (the same at the three corners of a triangle).
    @location(2) wall: f32,
};

struct VertexOut {
    @builtin(position) position_in_clip: vec4<f32>,
    @location(0) position_in_world: vec3<f32>,
    @location(1) normal_in_world: vec3<f32>,
    @location(2) wall: f32,
};

@vertex
fn vs_main(v: VertexIn) -> VertexOut {
    var out: VertexOut;
    out.position_in_clip = clip_position(v.position_in_world);
    out.position_in_world = v.position_in_world;
    out.normal_in_world = v.normal_in_world;
    out.wall = v.wall;
    return out;
}

// Screen-space derivatives are only defined in uniform control flow, so the face normal is
// computed before any branch that depends on the fragment.
fn face_normal(p: vec3<f32>) -> vec3<f32> {
    let n = cross(dpdx(p), dpdy(p));
    return n / max(length(n), 1e-30);
}

// No branch depends on a uniform alone (the flat colour is chosen with `select` at the end):
// a software rasterizer (lavapipe) compiles a shader variant per value of a uniform that decides
// a branch, and with one draw uniform per model those variants pile up frame after frame.
fn shade(in: VertexOut, front_facing: bool, flat_normal: vec3<f32>) -> vec3<f32> {
    let wall = clamp(in.wall, 0.0, 1.0);
    let base = mix(draw.color.rgb, draw.wall_color.rgb, wall);
    let lit = shade_color(base, in, front_facing, flat_normal);
    return mix(lit, lit * incision_shadow(in, flat_normal), wall);
}

// How much light reaches an incision wall: it lies inside the tissue, so it is in shadow, most
// where it is seen edge-on. A groove's walls are steep, so from the front they meet the view at
// a grazing angle along both lips: the incision shows as a dark line with dark rims at its lips,
// a cut into the surface, never a light ridge standing on it; from an angle the wall facing the
// eye stays darker than the surface around it.
fn incision_shadow(in: VertexOut, flat_normal: vec3<f32>) -> f32 {
    let to_eye = normalize(frame.eye_in_world.xyz - in.position_in_world);
    var n = in.normal_in_world;
    n = select(flat_normal, n / max(length(n), 1e-30), dot(n, n) >= 1e-12);
    let facing = abs(dot(n, to_eye));
    return mix(0.22, 0.6, facing * facing);
}

// `shade` with a base colour of the fragment's own (the image on a wall, image.wgsl).
fn shade_color(base: vec3<f32>, in: VertexOut, front_facing: bool, flat_normal: vec3<f32>) -> vec3<f32> {
    let to_eye = normalize(frame.eye_in_world.xyz - in.position_in_world);
    var n = in.normal_in_world;
    var brightness = 1.0;
    if dot(n, n) < 1e-12 {
        // No vertex normal: the face normal, turned toward the eye.
        n = flat_normal;
        n = n * sign(dot(n, to_eye) + 1e-20);
        if !front_facing {
            brightness = draw.params.x;
        }
    } else {
        n = normalize(n);
        if !front_facing {
            n = -n;
            brightness = draw.params.x;
        }
    }
    let l = frame.light_in_world.xyz;
    let diffuse = max(dot(n, l), 0.0);
    // A weak fill light from the eye keeps faces turned away from the key light readable.
    let fill = max(dot(n, to_eye), 0.0);
    let h = normalize(l + to_eye);
    let specular = pow(max(dot(n, h), 0.0), 40.0) * 0.18;
    let lit = base * (0.18 + 0.6 * diffuse + 0.24 * fill) * brightness + vec3<f32>(specular * brightness);
    return select(base, lit, draw.params.y >= 0.5);
}

@fragment
fn fs_opaque(in: VertexOut, @builtin(front_facing) front_facing: bool) -> @location(0) vec4<f32> {
    let flat_normal = face_normal(in.position_in_world);
    return vec4<f32>(shade(in, front_facing, flat_normal), 1.0);
}

struct OitOut {
    // Premultiplied colour and opacity, both multiplied by the depth weight; summed.
    @location(0) accum: vec4<f32>,
    // Opacity; the target keeps the product of (1 - opacity) over all layers.
    @location(1) revealage: vec4<f32>,
};

@fragment
fn fs_oit(in: VertexOut, @builtin(front_facing) front_facing: bool) -> OitOut {
    let flat_normal = face_normal(in.position_in_world);
    let color = shade(in, front_facing, flat_normal);
    let alpha = clamp(draw.color.a, 0.0, 1.0);
    let near = frame.viewport.z;
    let far = frame.viewport.w;
    let depth = clamp((distance(frame.eye_in_world.xyz, in.position_in_world) - near) / max(far - near, 1e-6), 0.0, 1.0);
    // Nearer layers weigh more; the clamp keeps the f16 sums finite.
    let weight = alpha * clamp(0.03 / (1e-5 + pow(depth, 4.0)), 1e-2, 1e3);
    var out: OitOut;
    out.accum = vec4<f32>(color * alpha, alpha) * weight;
    out.revealage = vec4<f32>(alpha, alpha, alpha, alpha);
    return out;
}
