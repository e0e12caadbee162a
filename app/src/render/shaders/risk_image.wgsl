// Walls coloured by the risk map on a scene whose walls show the intensity image (appended to
// mesh.wgsl, image.wgsl and risk.wgsl): within the far distance the ramp replaces the image, so
// the warning reads the same on any scan; beyond it the wall shows the image as fs_image does.

@fragment
fn fs_risk_image(in: RiskOut, @builtin(front_facing) front_facing: bool) -> @location(0) vec4<f32> {
    let v = risk_as_vertex_out(in);
    let flat_normal = face_normal(in.position_in_world);
    let wall = image_wall_color(v, front_facing, flat_normal);
    let r = risk_ramp(in.ramp);
    let warned = risk_shaded(r.rgb, v, front_facing, flat_normal);
    return vec4<f32>(mix(wall, warned, r.a), 1.0);
}
