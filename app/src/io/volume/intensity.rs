//! Intensity images (CT, MR) from NRRD and NIfTI files, through the same header, geometry (RAS
//! millimetres) and size checks as label maps, into an [`IntensityImage`].
//!
//! The voxels stay at their own type when it is one the renderer keeps as is (`uint8`, `int16`,
//! `uint16`, `int32`, `float32`): the file's buffer becomes the image's buffer, byte-swapped in
//! place when big-endian, so a 300 MB `int16` CT is held once. Other types are converted:
//! `int8` to `int16`, and `uint32`, 64-bit integers and `float64` to `float32` (a scan in those
//! types is rare; the conversion is the one copy).

use std::path::Path;

use anyhow::Context as _;

use super::samples::{Endian, SampleType};
use super::{RawSamples, VolumeFormat};
use crate::io::intensity::{IntensityImage, SampleKind};

/// Reads an intensity image. Errors are one line naming the file.
pub fn read_image(path: &Path) -> anyhow::Result<IntensityImage> {
    read(path).with_context(|| path.display().to_string())
}

fn read(path: &Path) -> anyhow::Result<IntensityImage> {
    if std::fs::metadata(path)?.is_dir() {
        anyhow::bail!("an image is one .nrrd, .nhdr, .nii or .nii.gz file, not a folder");
    }
    let raw = match super::file_format(path)? {
        VolumeFormat::Nrrd => super::nrrd::read_samples(path)?,
        VolumeFormat::Nifti => super::nifti::read_samples(path)?,
    };
    from_samples(path, raw)
}

/// An image from samples a reader has handed over (no second read of the file).
pub(crate) fn from_samples(path: &Path, raw: RawSamples) -> anyhow::Result<IntensityImage> {
    if raw.layers != 1 {
        anyhow::bail!(
            "{} layers: an intensity image has one 3-D volume (this looks like a segmentation)",
            raw.layers
        );
    }
    let RawSamples {
        dims,
        world_from_voxel,
        sample,
        endian,
        mut bytes,
        scale,
        ..
    } = raw;
    let kind = match sample {
        SampleType::U8 => SampleKind::U8,
        SampleType::I16 => SampleKind::I16,
        SampleType::U16 => SampleKind::U16,
        SampleType::I32 => SampleKind::I32,
        SampleType::F32 => SampleKind::F32,
        SampleType::I8 => {
            bytes = bytes
                .iter()
                .flat_map(|&b| (b as i8 as i16).to_le_bytes())
                .collect();
            return IntensityImage::new(
                path.to_path_buf(),
                dims,
                world_from_voxel,
                SampleKind::I16,
                bytes,
                scale,
            );
        }
        SampleType::U32 | SampleType::I64 | SampleType::U64 | SampleType::F64 => {
            let floats = widest_to_f32(&bytes, sample, endian);
            drop(bytes);
            return IntensityImage::new(
                path.to_path_buf(),
                dims,
                world_from_voxel,
                SampleKind::F32,
                floats,
                scale,
            );
        }
    };
    if endian == Endian::Big && kind.size() > 1 {
        for chunk in bytes.chunks_exact_mut(kind.size()) {
            chunk.reverse();
        }
    }
    IntensityImage::new(
        path.to_path_buf(),
        dims,
        world_from_voxel,
        kind,
        bytes,
        scale,
    )
}

/// 32-bit unsigned and 64-bit samples as little-endian `f32` bytes.
fn widest_to_f32(bytes: &[u8], sample: SampleType, endian: Endian) -> Vec<u8> {
    let size = sample.size();
    let mut out = Vec::with_capacity(bytes.len() / size * 4);
    for chunk in bytes.chunks_exact(size) {
        let mut raw = [0u8; 8];
        raw[..size].copy_from_slice(chunk);
        if endian == Endian::Big {
            raw[..size].reverse();
        }
        let v = match sample {
            SampleType::U32 => u32::from_le_bytes([raw[0], raw[1], raw[2], raw[3]]) as f32,
            SampleType::I64 => i64::from_le_bytes(raw) as f32,
            SampleType::U64 => u64::from_le_bytes(raw) as f32,
            _ => f64::from_le_bytes(raw) as f32,
        };
        out.extend_from_slice(&v.to_le_bytes());
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    fn tempdir(name: &str) -> std::path::PathBuf {
        let dir = std::env::temp_dir().join(format!("cutaway-image-{name}-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    fn write(dir: &Path, name: &str, bytes: &[u8]) -> std::path::PathBuf {
        let path = dir.join(name);
        std::fs::write(&path, bytes).unwrap();
        path
    }

    #[test]
    fn nrrd_int16_lps_is_kept_at_its_type_in_ras() {
        let dir = tempdir("nrrd");
        let values: Vec<i16> = vec![-1000, -500, 0, 40, 400, 1000, 2000, 3000];
        let samples: Vec<u8> = values.iter().flat_map(|v| v.to_le_bytes()).collect();
        for gzip in [false, true] {
            let file = super::super::nrrd::write_for_test(
                "left-posterior-superior",
                "short",
                &[2, 2, 2],
                "(1,0,0) (0,1,0) (0,0,2)",
                DVec3::new(10.0, 20.0, 30.0),
                &samples,
                gzip,
                "",
            );
            let path = write(&dir, &format!("ct{gzip}.nrrd"), &file);
            let img = read_image(&path).unwrap();
            assert_eq!(img.kind(), SampleKind::I16);
            assert_eq!(img.bytes().len(), 16);
            assert_eq!(img.value(1, 1, 1), 3000.0);
            assert_eq!(img.value(0, 1, 0), 0.0);
            // LPS (10, 20, 30) is RAS (-10, -20, 30); i runs toward -x in RAS.
            let p = img
                .world_from_voxel
                .transform_point3(DVec3::new(1.0, 0.0, 1.0));
            assert_eq!(p, DVec3::new(-11.0, -20.0, 32.0));
            assert_eq!(img.sample_world(p), Some(1000.0));
        }
    }

    #[test]
    fn nifti_big_endian_and_wide_types() {
        let dir = tempdir("nifti");
        let srow: [[f32; 4]; 3] = [
            [2.0, 0.0, 0.0, -5.0],
            [0.0, 2.0, 0.0, 0.0],
            [0.0, 0.0, 2.0, 0.0],
        ];
        let values = [1.5f32, -2.0, 7.25, 0.0];
        let samples: Vec<u8> = values.iter().flat_map(|v| v.to_le_bytes()).collect();
        let file = super::super::nifti::write_for_test([2, 2, 1], 16, srow, &samples);
        let img = read_image(&write(&dir, "mr.nii", &file)).unwrap();
        assert_eq!(img.kind(), SampleKind::F32);
        assert_eq!(img.value(0, 1, 0), 7.25);
        assert_eq!(img.sample_world(DVec3::new(-5.0, 0.0, 0.0)), Some(1.5));
        // Big-endian uint16 is swapped in place; float64 becomes float32.
        let be: Vec<u8> = [1u16, 300, 65535, 2]
            .iter()
            .flat_map(|v| v.to_be_bytes())
            .collect();
        let raw = RawSamples {
            dims: [2, 2, 1],
            world_from_voxel: glam::DAffine3::IDENTITY,
            layers: 1,
            sample: SampleType::U16,
            endian: Endian::Big,
            bytes: be,
            scale: (1.0, 0.0),
        };
        let img = from_samples(Path::new("be.nrrd"), raw).unwrap();
        assert_eq!(img.value(0, 1, 0), 65535.0);
        let doubles: Vec<u8> = [0.5f64, 1.0, 2.0, 3.0]
            .iter()
            .flat_map(|v| v.to_le_bytes())
            .collect();
        let raw = RawSamples {
            dims: [2, 2, 1],
            world_from_voxel: glam::DAffine3::IDENTITY,
            layers: 1,
            sample: SampleType::F64,
            endian: Endian::Little,
            bytes: doubles,
            scale: (1.0, 0.0),
        };
        let img = from_samples(Path::new("d.nii"), raw).unwrap();
        assert_eq!((img.kind(), img.value(0, 0, 0)), (SampleKind::F32, 0.5));
    }

    #[test]
    fn bad_images_name_the_file_and_the_problem() {
        let dir = tempdir("bad");
        let file = super::super::nrrd::write_for_test(
            "RAS",
            "short",
            &[2, 2, 2],
            "(1,0,0) (0,1,0) (0,0,1)",
            DVec3::ZERO,
            &[0; 10],
            false,
            "",
        );
        let path = write(&dir, "short.nrrd", &file);
        let err = format!("{:#}", read_image(&path).unwrap_err());
        assert!(err.starts_with(&path.display().to_string()), "{err}");
        assert!(err.contains("need 16"), "{err}");
        let layered = super::super::nrrd::write_for_test(
            "RAS",
            "uchar",
            &[2, 1, 1, 1],
            "none (1,0,0) (0,1,0) (0,0,1)",
            DVec3::ZERO,
            &[0, 1],
            false,
            "kinds: list domain domain domain",
        );
        let path = write(&dir, "seg.seg.nrrd", &layered);
        let err = format!("{:#}", read_image(&path).unwrap_err());
        assert!(err.contains("2 layers"), "{err}");
        let text = write(&dir, "notes.txt", b"hello");
        assert!(format!("{:#}", read_image(&text).unwrap_err()).contains("not a volume"));
    }
}
