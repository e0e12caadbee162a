use glam::{DAffine3, DMat3, DVec3};

use super::*;

fn image_i16(dims: [usize; 3], m: DAffine3, values: &[i16]) -> IntensityImage {
    let bytes = values.iter().flat_map(|v| v.to_le_bytes()).collect();
    IntensityImage::new("t".into(), dims, m, SampleKind::I16, bytes, (1.0, 0.0)).unwrap()
}

#[test]
fn trilinear_sampling_reproduces_a_linear_function_in_world_space() {
    // A permuted, flipped, anisotropic grid (j runs along -x, k along +y, i along +z).
    let m = DAffine3::from_mat3_translation(
        DMat3::from_cols(DVec3::Z * 2.0, DVec3::NEG_X * 0.5, DVec3::Y * 3.0),
        DVec3::new(10.0, -4.0, 1.0),
    );
    let f = |p: DVec3| (3.0 * p.x - 2.0 * p.y + 0.5 * p.z) as f32;
    let image = IntensityImage::from_fn([5, 9, 4], m, f);
    for q in [
        DVec3::new(0.3, 2.7, 1.2),
        DVec3::new(3.9, 7.5, 2.99),
        DVec3::new(2.0, 4.0, 0.0),
    ] {
        let p = m.transform_point3(q);
        let got = image.sample_world(p).unwrap();
        assert!((got - f(p) as f64).abs() < 1e-3, "{q}: {got} vs {}", f(p));
    }
    // Half a voxel past the last centre still samples (edge value), further out does not.
    assert!(
        image
            .sample_world(m.transform_point3(DVec3::new(-0.49, 0.0, 0.0)))
            .is_some()
    );
    assert!(
        image
            .sample_world(m.transform_point3(DVec3::new(-0.51, 0.0, 0.0)))
            .is_none()
    );
    assert!(
        image
            .sample_world(m.transform_point3(DVec3::new(0.0, 8.6, 0.0)))
            .is_none()
    );
}

#[test]
fn stored_types_and_scaling() {
    let img = image_i16([2, 1, 1], DAffine3::IDENTITY, &[-1000, 3000]);
    assert_eq!(img.value(0, 0, 0), -1000.0);
    assert_eq!(img.value(1, 0, 0), 3000.0);
    assert_eq!(img.range(), (-1000.0, 3000.0));
    assert_eq!(img.bytes().len(), 4, "int16 stays two bytes a voxel");
    assert_eq!(img.sample_world(DVec3::new(0.25, 0.0, 0.0)), Some(0.0));
    let scaled = IntensityImage::new(
        "t".into(),
        [2, 1, 1],
        DAffine3::IDENTITY,
        SampleKind::U8,
        vec![0, 200],
        (2.0, -1024.0),
    )
    .unwrap();
    assert_eq!(scaled.value(1, 0, 0), -624.0);
    assert_eq!(scaled.range(), (-1024.0, -624.0));
    let short = IntensityImage::new(
        "t".into(),
        [2, 1, 1],
        DAffine3::IDENTITY,
        SampleKind::F32,
        vec![0; 4],
        (1.0, 0.0),
    );
    assert!(short.unwrap_err().to_string().contains("need 8"));
}

#[test]
fn disjoint_boxes_are_refused() {
    let img = image_i16([4, 4, 4], DAffine3::IDENTITY, &[0; 64]);
    let near = csg::Aabb::from_points(&[DVec3::splat(1.0), DVec3::splat(2.0)]);
    check_overlap(&img, near).unwrap();
    let far = csg::Aabb::from_points(&[DVec3::splat(100.0), DVec3::splat(120.0)]);
    let err = check_overlap(&img, far).unwrap_err().to_string();
    assert!(err.contains("disjoint"), "{err}");
}
