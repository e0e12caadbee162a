//! The rule that tells labels from intensities, decided from a volume's samples before any
//! label is decoded; the readers apply it to what they read, [`super::content`] acts on it.
//!
//! # The rule
//! A file with more than one layer (a Slicer segmentation) is always labels. A one-layer file
//! is an **intensity image** when any of these holds, checked in one pass over the samples:
//! - a float value with a fractional part (or NaN, or infinite): label maps hold whole numbers
//!   (masks written as `float32` 0/1 stay labels);
//! - a negative value: labels are never negative, CT is (air is -1000 HU);
//! - more than [`MAX_LABEL_VALUES`] distinct values: a segmentation has tens to hundreds of
//!   labels, a scan thousands of grey values.
//!
//! Otherwise it is a label map. An 8-bit scan without negative values (at most 256 values) is
//! therefore read as labels; open it with `--image` / File → Open Image… instead.
//!
//! # Deciding without a pass of its own
//! [`classify`] applies the rule exactly, but reads every sample only where it must. A scan
//! shows its nature in any sample (CT air is negative everywhere, MR floats have fractions, a
//! scan's grey values are thousands), so the rule first runs on an evenly spread sample
//! ([`SAMPLE`] values): whatever it finds there is a fact about the file, and the file is an
//! image. Otherwise the samples are decoded as labels, a pass needed anyway, which refuses a
//! negative or fractional value on its own; only then does the full rule run, to tell an image
//! from a broken label map. The distinct-value limit is checked on the labels' counts, which
//! reading a label map makes anyway ([`super::content`]).

use std::collections::HashSet;

use super::RawSamples;
use super::samples::{Endian, SampleType};

/// More distinct values than this make a one-layer volume an intensity image.
pub const MAX_LABEL_VALUES: usize = 1000;

/// What a reader found in a file before decoding labels.
pub(crate) enum RawContent {
    Labels(super::RawVolume),
    Image(RawSamples, String),
}

/// Values of a one-layer file the rule looks at before decoding (see the module doc).
pub const SAMPLE: usize = 1 << 16;

/// The rule applied to `raw` (see the module doc): an image with its reason, or the label map
/// `labels_of` decodes. `labels_of`'s error is returned when the whole file passes the rule.
pub(crate) fn classify(
    raw: RawSamples,
    labels_of: impl FnOnce(&RawSamples) -> anyhow::Result<super::RawVolume>,
) -> anyhow::Result<RawContent> {
    if let Some(reason) = sampled_intensity_reason(&raw) {
        return Ok(RawContent::Image(raw, reason));
    }
    match labels_of(&raw) {
        Ok(volume) => Ok(RawContent::Labels(volume)),
        Err(error) => match intensity_reason(&raw) {
            Some(reason) => Ok(RawContent::Image(raw, reason)),
            None => Err(error),
        },
    }
}

/// [`intensity_reason`] on at most [`SAMPLE`] values spread evenly over the file: `Some` is
/// exact (the value it names is in the file), `None` says nothing about the values not read.
fn sampled_intensity_reason(raw: &RawSamples) -> Option<String> {
    let size = raw.sample.size();
    let count = raw.bytes.len() / size;
    if count <= SAMPLE {
        return intensity_reason(raw);
    }
    let stride = count.div_ceil(SAMPLE);
    let mut bytes = Vec::with_capacity(SAMPLE * size);
    for index in (0..count).step_by(stride) {
        bytes.extend_from_slice(&raw.bytes[index * size..(index + 1) * size]);
    }
    let sampled = RawSamples {
        dims: [bytes.len() / size, 1, 1],
        world_from_voxel: raw.world_from_voxel,
        layers: raw.layers,
        sample: raw.sample,
        endian: raw.endian,
        bytes,
        scale: raw.scale,
    };
    intensity_reason(&sampled)
}

/// Why `raw` is an intensity image, or `None` for a label map (see [the rule](self)); reads
/// every sample.
pub(crate) fn intensity_reason(raw: &RawSamples) -> Option<String> {
    if raw.layers != 1 {
        return None;
    }
    let size = raw.sample.size();
    let name = raw.sample.name();
    // 16-bit values: a bitmap of the 65 536 possible values; wider: a set that stops growing
    // past the limit.
    let mut seen16 = vec![0u64; if size == 2 { 1024 } else { 0 }];
    let mut seen = HashSet::new();
    let mut distinct = 0usize;
    for chunk in raw.bytes.chunks_exact(size) {
        let mut b = [0u8; 8];
        b[..size].copy_from_slice(chunk);
        if raw.endian == Endian::Big {
            b[..size].reverse();
        }
        let value = match raw.sample {
            SampleType::U8 => b[0] as f64,
            SampleType::I8 => b[0] as i8 as f64,
            SampleType::U16 => u16::from_le_bytes([b[0], b[1]]) as f64,
            SampleType::I16 => i16::from_le_bytes([b[0], b[1]]) as f64,
            SampleType::U32 => u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f64,
            SampleType::I32 => i32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f64,
            SampleType::U64 => u64::from_le_bytes(b) as f64,
            SampleType::I64 => i64::from_le_bytes(b) as f64,
            SampleType::F32 => f32::from_le_bytes([b[0], b[1], b[2], b[3]]) as f64,
            SampleType::F64 => f64::from_le_bytes(b),
        };
        if !value.is_finite() || value.fract() != 0.0 {
            return Some(format!("{name} values with fractions, such as {value}"));
        }
        if value < 0.0 {
            return Some(format!("negative {name} values, such as {value}"));
        }
        let new = match size {
            1 => false,
            2 => {
                let bits = u16::from_le_bytes([b[0], b[1]]) as usize;
                let word = &mut seen16[bits / 64];
                let fresh = *word & (1 << (bits % 64)) == 0;
                *word |= 1 << (bits % 64);
                fresh
            }
            _ => seen.insert(u64::from_le_bytes(b)),
        };
        if new {
            distinct += 1;
            if distinct > MAX_LABEL_VALUES {
                return Some(format!(
                    "more than {MAX_LABEL_VALUES} distinct {name} values"
                ));
            }
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    fn raw(sample: SampleType, bytes: Vec<u8>, layers: usize) -> RawSamples {
        let voxels = bytes.len() / sample.size() / layers;
        RawSamples {
            dims: [voxels, 1, 1],
            world_from_voxel: glam::DAffine3::IDENTITY,
            layers,
            sample,
            endian: Endian::Little,
            bytes,
            scale: (1.0, 0.0),
        }
    }

    fn le<T: Copy, const N: usize>(values: &[T], f: impl Fn(T) -> [u8; N]) -> Vec<u8> {
        values.iter().flat_map(|&v| f(v)).collect()
    }

    #[test]
    fn labels_stay_labels() {
        // Whole floats (a nibabel mask), a few int16 labels, 1000 distinct uint16 values.
        let mask = le(&[0f32, 1.0, 1.0, 0.0], f32::to_le_bytes);
        assert_eq!(intensity_reason(&raw(SampleType::F32, mask, 1)), None);
        let few = le(&[0i16, 3, 7, 3], i16::to_le_bytes);
        assert_eq!(intensity_reason(&raw(SampleType::I16, few, 1)), None);
        let many: Vec<u16> = (0..MAX_LABEL_VALUES as u16).collect();
        let many = le(&many, u16::to_le_bytes);
        assert_eq!(intensity_reason(&raw(SampleType::U16, many, 1)), None);
        // A layered file is a segmentation whatever its values.
        let layered = le(&[-1i16, 2], i16::to_le_bytes);
        assert_eq!(intensity_reason(&raw(SampleType::I16, layered, 2)), None);
    }

    fn decode(raw: &RawSamples) -> anyhow::Result<super::super::RawVolume> {
        let layer = super::super::samples::decode(&raw.bytes, raw.sample, raw.endian, raw.dims)?;
        Ok(super::super::RawVolume {
            dims: raw.dims,
            world_from_voxel: raw.world_from_voxel,
            layers: vec![layer],
            names: Vec::new(),
        })
    }

    #[test]
    fn classify_decides_from_a_sample_and_stays_exact() {
        let n = 4 * SAMPLE + 3;
        // A CT: negative everywhere, decided by the sample alone (no decoding).
        let ct: Vec<i16> = (0..n).map(|i| (i % 3000) as i16 - 1000).collect();
        let ct = raw(SampleType::I16, le(&ct, i16::to_le_bytes), 1);
        match classify(ct, |_| panic!("a scan is not decoded")).unwrap() {
            RawContent::Image(_, why) => assert!(why.starts_with("negative int16"), "{why}"),
            RawContent::Labels(_) => panic!("a CT read as labels"),
        }
        // Labels: decoded.
        let labels: Vec<i16> = (0..n).map(|i| (i / 1000 % 7) as i16).collect();
        let labels = raw(SampleType::I16, le(&labels, i16::to_le_bytes), 1);
        assert!(matches!(
            classify(labels, decode).unwrap(),
            RawContent::Labels(_)
        ));
        // One negative value between the sampled ones: the decode refuses it and the full rule
        // names it, as the full scan did.
        let mut hidden: Vec<i16> = vec![2; n];
        hidden[1] = -5;
        let hidden = raw(SampleType::I16, le(&hidden, i16::to_le_bytes), 1);
        assert!(sampled_intensity_reason(&hidden).is_none());
        match classify(hidden, decode).unwrap() {
            RawContent::Image(_, why) => assert_eq!(why, "negative int16 values, such as -5"),
            RawContent::Labels(_) => panic!("a negative value read as a label"),
        }
    }

    #[test]
    fn scans_are_images_with_the_reason() {
        let ct = le(&[0i16, -1000, 40], i16::to_le_bytes);
        let why = intensity_reason(&raw(SampleType::I16, ct, 1)).unwrap();
        assert_eq!(why, "negative int16 values, such as -1000");
        let mr = le(&[0.0f32, 12.5], f32::to_le_bytes);
        let why = intensity_reason(&raw(SampleType::F32, mr, 1)).unwrap();
        assert!(why.starts_with("float32 values with fractions"), "{why}");
        let nan = le(&[f64::NAN], f64::to_le_bytes);
        assert!(intensity_reason(&raw(SampleType::F64, nan, 1)).is_some());
        for (sample, bytes) in [
            (
                SampleType::U16,
                le(
                    &(0..=MAX_LABEL_VALUES as u16).collect::<Vec<_>>(),
                    u16::to_le_bytes,
                ),
            ),
            (
                SampleType::U32,
                le(
                    &(0..=MAX_LABEL_VALUES as u32).collect::<Vec<_>>(),
                    u32::to_le_bytes,
                ),
            ),
        ] {
            let why = intensity_reason(&raw(sample, bytes, 1)).unwrap();
            assert!(why.starts_with("more than 1000 distinct"), "{why}");
        }
        // Big-endian samples are read in their order: 0xFC18 is -1000.
        let mut big = raw(SampleType::I16, vec![0xFC, 0x18], 1);
        big.endian = Endian::Big;
        assert!(intensity_reason(&big).unwrap().contains("-1000"));
    }
}
