//! An image larger than the GPU's 3-D texture limit is shown at reduced resolution, never
//! dropped: each axis over the limit is averaged in blocks of the smallest whole number of voxels
//! that brings it under, and the caller says so ("image 4096 × 512 × 512 exceeds the GPU's 3-D
//! texture limit 2048: shown at half resolution …"). The window on a GL adapter has a limit of
//! 256, so a full-size CT needs this there.
//!
//! The reduced image keeps the stored type (int16 stays two bytes a voxel) and the world frame:
//! a block's voxel sits at the centre of the voxels it averages, and the few voxels past the last
//! whole block at the far edge are left out (less than one reduced voxel).

use std::sync::Arc;

use glam::{DAffine3, DVec3};

use super::{IntensityImage, SampleKind};

/// Voxels averaged per axis so every size is at most `limit` (1 where it already fits).
pub fn factors(dims: [usize; 3], limit: usize) -> [usize; 3] {
    dims.map(|d| d.div_ceil(limit.max(1)).max(1))
}

/// The message for an image over `limit`, or `None` when it fits.
pub fn notice(image: &IntensityImage, limit: usize) -> Option<String> {
    let f = factors(image.dims, limit);
    if f == [1, 1, 1] {
        return None;
    }
    let [a, b, c] = image.dims;
    let [x, y, z] = reduced_dims(image.dims, f);
    let most = f.iter().copied().max().unwrap_or(1);
    let how = if most == 2 {
        "half".to_owned()
    } else {
        format!("1/{most}")
    };
    Some(format!(
        "image {a} × {b} × {c} exceeds the GPU's 3-D texture limit {limit}: shown at {how} resolution ({x} × {y} × {z}, blocks of {} × {} × {} voxels averaged)",
        f[0], f[1], f[2]
    ))
}

fn reduced_dims(dims: [usize; 3], f: [usize; 3]) -> [usize; 3] {
    [0, 1, 2].map(|a| (dims[a] / f[a]).max(1))
}

/// `image` itself when it fits `limit`, else its block average (see the module documentation).
pub fn fit_to_limit(image: &Arc<IntensityImage>, limit: usize) -> Arc<IntensityImage> {
    let f = factors(image.dims, limit);
    if f == [1, 1, 1] {
        return image.clone();
    }
    let dims = reduced_dims(image.dims, f);
    let kind = image.kind();
    let mut bytes = Vec::with_capacity(dims.iter().product::<usize>() * kind.size());
    let [nx, ny, _] = image.dims;
    for k in 0..dims[2] {
        for j in 0..dims[1] {
            for i in 0..dims[0] {
                let (mut sum, mut count) = (0.0f64, 0usize);
                for kk in k * f[2]..((k + 1) * f[2]).min(image.dims[2]) {
                    for jj in j * f[1]..((j + 1) * f[1]).min(image.dims[1]) {
                        for ii in i * f[0]..((i + 1) * f[0]).min(image.dims[0]) {
                            let v = image.raw(ii + nx * (jj + ny * kk));
                            if !v.is_nan() {
                                sum += v;
                                count += 1;
                            }
                        }
                    }
                }
                let mean = if count == 0 {
                    f64::NAN
                } else {
                    sum / count as f64
                };
                push_sample(&mut bytes, kind, mean);
            }
        }
    }
    // Reduced voxel (i, j, k) is the centre of original voxels f·i … f·i + f − 1.
    let offset = DVec3::new(
        (f[0] - 1) as f64 * 0.5,
        (f[1] - 1) as f64 * 0.5,
        (f[2] - 1) as f64 * 0.5,
    );
    let scale = DVec3::new(f[0] as f64, f[1] as f64, f[2] as f64);
    let world_from_voxel =
        image.world_from_voxel * DAffine3::from_translation(offset) * DAffine3::from_scale(scale);
    let reduced = IntensityImage::new(
        image.source.clone(),
        dims,
        world_from_voxel,
        kind,
        bytes,
        image.scale(),
    )
    .expect("sizes match by construction");
    Arc::new(reduced)
}

/// Appends `v` (a stored value, unscaled) at `kind`, rounded and clamped for integer kinds.
fn push_sample(bytes: &mut Vec<u8>, kind: SampleKind, v: f64) {
    let round = |lo: f64, hi: f64| {
        if v.is_nan() {
            0.0
        } else {
            v.round().clamp(lo, hi)
        }
    };
    match kind {
        SampleKind::U8 => bytes.push(round(0.0, u8::MAX as f64) as u8),
        SampleKind::I16 => {
            bytes.extend_from_slice(&(round(i16::MIN as f64, i16::MAX as f64) as i16).to_le_bytes())
        }
        SampleKind::U16 => {
            bytes.extend_from_slice(&(round(0.0, u16::MAX as f64) as u16).to_le_bytes())
        }
        SampleKind::I32 => {
            bytes.extend_from_slice(&(round(i32::MIN as f64, i32::MAX as f64) as i32).to_le_bytes())
        }
        SampleKind::F32 => bytes.extend_from_slice(&(v as f32).to_le_bytes()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_image_over_the_limit_is_averaged_in_the_same_world_frame() {
        // A linear function of world position survives block averaging exactly (inside the
        // reduced grid), on a grid with a rotation and an offset.
        let world = DAffine3::from_mat3_translation(
            glam::DMat3::from_cols(
                DVec3::new(0.0, 0.5, 0.0),
                DVec3::new(-1.0, 0.0, 0.0),
                DVec3::new(0.0, 0.0, 2.0),
            ),
            DVec3::new(10.0, -4.0, 3.0),
        );
        let f = |p: DVec3| (2.0 * p.x - p.y + 0.5 * p.z) as f32;
        let image = Arc::new(IntensityImage::from_fn([37, 9, 16], world, f));
        assert!(notice(&image, 64).is_none());
        assert!(Arc::ptr_eq(&fit_to_limit(&image, 64), &image));
        let limit = 8;
        let reduced = fit_to_limit(&image, limit);
        assert_eq!(factors(image.dims, limit), [5, 2, 2]);
        assert_eq!(reduced.dims, [7, 4, 8]);
        assert!(reduced.dims.iter().all(|&d| d <= limit));
        assert_eq!(reduced.kind(), SampleKind::F32);
        for k in 0..8 {
            for j in 0..4 {
                for i in 0..7 {
                    let p = reduced
                        .world_from_voxel
                        .transform_point3(DVec3::new(i as f64, j as f64, k as f64));
                    let got = reduced.value(i, j, k);
                    assert!(
                        (got - f(p) as f64).abs() < 1e-3,
                        "({i}, {j}, {k}): {got} vs {}",
                        f(p)
                    );
                }
            }
        }
        let message = notice(&image, limit).unwrap();
        assert_eq!(
            message,
            "image 37 × 9 × 16 exceeds the GPU's 3-D texture limit 8: shown at 1/5 resolution (7 × 4 × 8, blocks of 5 × 2 × 2 voxels averaged)"
        );
    }

    #[test]
    fn integer_images_stay_at_their_type_rounded() {
        let mut bytes = Vec::new();
        for v in [-1000i16, -999, 3000, 3001] {
            bytes.extend_from_slice(&v.to_le_bytes());
        }
        let image = Arc::new(
            IntensityImage::new(
                "ct.nrrd".into(),
                [4, 1, 1],
                DAffine3::IDENTITY,
                SampleKind::I16,
                bytes,
                (1.0, 0.0),
            )
            .unwrap(),
        );
        let reduced = fit_to_limit(&image, 2);
        assert_eq!(reduced.kind(), SampleKind::I16);
        assert_eq!(reduced.bytes().len(), 4);
        assert_eq!(
            (reduced.value(0, 0, 0), reduced.value(1, 0, 0)),
            (-1000.0, 3001.0)
        );
        assert!(
            notice(&image, 2)
                .unwrap()
                .contains("shown at half resolution")
        );
    }
}
