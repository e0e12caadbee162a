// Walls coloured by the risk map (appended to mesh.wgsl, whose shading it uses; the ramp's
// colours come first, the map's (`RiskRamp`), written by `shaders::risk`). Each vertex carries
// its ramp position: ≤ 0 within the near distance (red), 0..1 the graded band (orange to
// yellow), ≥ 1 beyond it (the wall's own look). The position is interpolated linearly and mapped
// per fragment, so the near and far lines stay sharp across a triangle. The distances behind it
// are computed on the CPU (`crate::cutting::wall_risk`); nothing here measures anything.

// Keep in sync with RiskVertex in gpu_data.rs.
struct RiskIn {
    @location(0) position_in_world: vec3<f32>,
    @location(1) normal_in_world: vec3<f32>,
    @location(2) ramp: f32,
};

struct RiskOut {
    @builtin(position) position_in_clip: vec4<f32>,
    @location(0) position_in_world: vec3<f32>,
    @location(1) normal_in_world: vec3<f32>,
    @location(2) ramp: f32,
};

@vertex
fn vs_risk(v: RiskIn) -> RiskOut {
    var out: RiskOut;
    out.position_in_clip = clip_position(v.position_in_world);
    out.position_in_world = v.position_in_world;
    out.normal_in_world = v.normal_in_world;
    out.ramp = v.ramp;
    return out;
}

// The fragment as mesh.wgsl's shading takes it (not an incision wall: the draw colour is the
// wall colour already).
fn risk_as_vertex_out(in: RiskOut) -> VertexOut {
    var v: VertexOut;
    v.position_in_clip = in.position_in_clip;
    v.position_in_world = in.position_in_world;
    v.normal_in_world = in.normal_in_world;
    v.wall = 0.0;
    return v;
}

// rgb: the ramp's linear colour at position s; a: 1 where the ramp colours the wall, 0 beyond.
fn risk_ramp(s: f32) -> vec4<f32> {
    let band = mix(RISK_BAND_START, RISK_BAND_END, clamp(s, 0.0, 1.0));
    let rgb = select(band, RISK_NEAR_COLOR, s <= 0.0);
    return vec4<f32>(rgb, select(0.0, 1.0, s < 1.0));
}

// The ramp's colour shaded without the specular highlight (the shading less that of black, which
// is the highlight alone), so red reads red under the headlight.
fn risk_shaded(rgb: vec3<f32>, v: VertexOut, front_facing: bool, flat_normal: vec3<f32>) -> vec3<f32> {
    let highlight = shade_color(vec3<f32>(0.0), v, front_facing, flat_normal);
    return shade_color(rgb, v, front_facing, flat_normal) - highlight;
}

@fragment
fn fs_risk(in: RiskOut, @builtin(front_facing) front_facing: bool) -> @location(0) vec4<f32> {
    let v = risk_as_vertex_out(in);
    let flat_normal = face_normal(in.position_in_world);
    let r = risk_ramp(in.ramp);
    let wall = shade(v, front_facing, flat_normal);
    let warned = risk_shaded(r.rgb, v, front_facing, flat_normal);
    return vec4<f32>(mix(wall, warned, r.a), 1.0);
}
