//! Voxel samples: the integer and float types volume files store, decoded into label values.
//!
//! Every reader ends with the same step: a byte buffer of `count` samples of one [`SampleType`]
//! in one byte order becomes a [`LabelData`] of the narrowest unsigned type that holds its
//! values (`u8`, `u16` or `u32`), so a 256³ atlas stored as `short` costs 32 MB, not 64.
//!
//! Label values are non-negative integers. Rules for other data (each is an error naming the
//! first offending voxel, never a silent conversion):
//! - a negative value is not a label;
//! - a value above `u32::MAX` is not a label;
//! - float data is accepted only when every value is a whole number in `0..=u32::MAX` (tools
//!   such as nibabel write binary masks as `float32` 0/1); a fractional value means the file is
//!   an intensity image or a probability map, not a label map. NaN is never a label.

use super::LabelData;

/// The sample types of NRRD and NIfTI files.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SampleType {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    I64,
    U64,
    F32,
    F64,
}

impl SampleType {
    /// Bytes per sample.
    pub fn size(self) -> usize {
        match self {
            SampleType::I8 | SampleType::U8 => 1,
            SampleType::I16 | SampleType::U16 => 2,
            SampleType::I32 | SampleType::U32 | SampleType::F32 => 4,
            SampleType::I64 | SampleType::U64 | SampleType::F64 => 8,
        }
    }

    /// Name for messages, as C spells it.
    pub fn name(self) -> &'static str {
        match self {
            SampleType::I8 => "int8",
            SampleType::U8 => "uint8",
            SampleType::I16 => "int16",
            SampleType::U16 => "uint16",
            SampleType::I32 => "int32",
            SampleType::U32 => "uint32",
            SampleType::I64 => "int64",
            SampleType::U64 => "uint64",
            SampleType::F32 => "float32",
            SampleType::F64 => "float64",
        }
    }
}

/// Byte order of multi-byte samples.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Endian {
    Little,
    Big,
}

/// Where a bad sample is, for messages: the flat index turned into (i, j, k) by the caller's
/// dims (x fastest).
fn voxel_at(index: usize, dims: [usize; 3]) -> String {
    let i = index % dims[0];
    let j = (index / dims[0]) % dims[1];
    let k = index / (dims[0] * dims[1]);
    format!("({i}, {j}, {k})")
}

/// Decodes `bytes` (exactly `dims` product × sample size) into label values. `dims` only names
/// voxels in messages.
pub fn decode(
    bytes: &[u8],
    sample: SampleType,
    endian: Endian,
    dims: [usize; 3],
) -> anyhow::Result<LabelData> {
    debug_assert_eq!(bytes.len() % sample.size(), 0);
    let negative = |index: usize, value: i64| {
        anyhow::anyhow!(
            "negative value {value} at voxel {}: not a label map",
            voxel_at(index, dims)
        )
    };
    match sample {
        SampleType::U8 => Ok(LabelData::U8(bytes.to_vec())),
        SampleType::I8 => {
            if let Some(index) = bytes.iter().position(|&b| (b as i8) < 0) {
                return Err(negative(index, bytes[index] as i8 as i64));
            }
            Ok(LabelData::U8(bytes.to_vec()))
        }
        SampleType::U16 | SampleType::I16 => {
            let signed = sample == SampleType::I16;
            let mut values = Vec::with_capacity(bytes.len() / 2);
            for (index, pair) in bytes.chunks_exact(2).enumerate() {
                let pair = [pair[0], pair[1]];
                let value = match endian {
                    Endian::Little => u16::from_le_bytes(pair),
                    Endian::Big => u16::from_be_bytes(pair),
                };
                if signed && (value as i16) < 0 {
                    return Err(negative(index, value as i16 as i64));
                }
                values.push(value);
            }
            Ok(narrow_u16(values))
        }
        _ => {
            let values = decode_wide(bytes, sample, endian, dims)?;
            Ok(narrow_u32(values))
        }
    }
}

/// 32- and 64-bit integers and floats, checked one by one into `u32`.
fn decode_wide(
    bytes: &[u8],
    sample: SampleType,
    endian: Endian,
    dims: [usize; 3],
) -> anyhow::Result<Vec<u32>> {
    let size = sample.size();
    let mut values = Vec::with_capacity(bytes.len() / size);
    for (index, chunk) in bytes.chunks_exact(size).enumerate() {
        let mut raw = [0u8; 8];
        raw[..size].copy_from_slice(chunk);
        if endian == Endian::Big {
            raw[..size].reverse();
        }
        let value: Result<u32, String> = match sample {
            SampleType::I32 => {
                let v = i32::from_le_bytes([raw[0], raw[1], raw[2], raw[3]]);
                u32::try_from(v).map_err(|_| format!("negative value {v}"))
            }
            SampleType::U32 => Ok(u32::from_le_bytes([raw[0], raw[1], raw[2], raw[3]])),
            SampleType::I64 => {
                let v = i64::from_le_bytes(raw);
                u32::try_from(v).map_err(|_| format!("value {v}"))
            }
            SampleType::U64 => {
                let v = u64::from_le_bytes(raw);
                u32::try_from(v).map_err(|_| format!("value {v}"))
            }
            SampleType::F32 => {
                float_label(f32::from_le_bytes([raw[0], raw[1], raw[2], raw[3]]) as f64)
            }
            SampleType::F64 => float_label(f64::from_le_bytes(raw)),
            _ => unreachable!("narrow types are decoded by the caller"),
        };
        match value {
            Ok(v) => values.push(v),
            Err(what) => anyhow::bail!(
                "{what} at voxel {} in {} data: not a label map",
                voxel_at(index, dims),
                sample.name()
            ),
        }
    }
    Ok(values)
}

/// A float sample as a label: a whole number in `0..=u32::MAX`.
fn float_label(v: f64) -> Result<u32, String> {
    if v.is_finite() && v.fract() == 0.0 && (0.0..=u32::MAX as f64).contains(&v) {
        Ok(v as u32)
    } else {
        Err(format!("non-integer value {v}"))
    }
}

fn narrow_u16(values: Vec<u16>) -> LabelData {
    if values.iter().all(|&v| v <= u8::MAX as u16) {
        LabelData::U8(values.into_iter().map(|v| v as u8).collect())
    } else {
        LabelData::U16(values)
    }
}

fn narrow_u32(values: Vec<u32>) -> LabelData {
    let max = values.iter().copied().max().unwrap_or(0);
    if max <= u8::MAX as u32 {
        LabelData::U8(values.into_iter().map(|v| v as u8).collect())
    } else if max <= u16::MAX as u32 {
        LabelData::U16(values.into_iter().map(|v| v as u16).collect())
    } else {
        LabelData::U32(values)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const DIMS: [usize; 3] = [2, 2, 1];

    #[test]
    fn int16_both_byte_orders_narrow_to_the_smallest_type() {
        let le = [1u8, 0, 2, 0, 0, 0, 7, 0];
        let be = [0u8, 1, 0, 2, 0, 0, 0, 7];
        for (bytes, endian) in [(le, Endian::Little), (be, Endian::Big)] {
            let data = decode(&bytes, SampleType::I16, endian, DIMS).unwrap();
            assert_eq!(data, LabelData::U8(vec![1, 2, 0, 7]));
        }
        let wide = [0x2cu8, 0x01, 0, 0, 0, 0, 0, 0];
        let data = decode(&wide, SampleType::U16, Endian::Little, DIMS).unwrap();
        assert_eq!(data, LabelData::U16(vec![300, 0, 0, 0]));
    }

    #[test]
    fn negative_values_are_refused_with_the_voxel() {
        let bytes = [1u8, 0, 0, 0, 0xff, 0xff, 0, 0];
        let err = decode(&bytes, SampleType::I16, Endian::Little, DIMS).unwrap_err();
        assert_eq!(
            err.to_string(),
            "negative value -1 at voxel (0, 1, 0): not a label map"
        );
        let err = decode(&[0, 0x80, 0, 0], SampleType::I8, Endian::Little, DIMS).unwrap_err();
        assert!(err.to_string().contains("-128 at voxel (1, 0, 0)"), "{err}");
    }

    #[test]
    fn floats_with_whole_values_are_labels_fractions_are_not() {
        let whole: Vec<u8> = [0.0f32, 1.0, 70000.0, 3.0]
            .iter()
            .flat_map(|v| v.to_be_bytes())
            .collect();
        let data = decode(&whole, SampleType::F32, Endian::Big, DIMS).unwrap();
        assert_eq!(data, LabelData::U32(vec![0, 1, 70000, 3]));
        let fraction: Vec<u8> = [0.0f64, 0.25, 1.0, 1.0]
            .iter()
            .flat_map(|v| v.to_le_bytes())
            .collect();
        let err = decode(&fraction, SampleType::F64, Endian::Little, DIMS).unwrap_err();
        assert_eq!(
            err.to_string(),
            "non-integer value 0.25 at voxel (1, 0, 0) in float64 data: not a label map"
        );
        let nan: Vec<u8> = [f32::NAN, 0.0, 0.0, 0.0]
            .iter()
            .flat_map(|v| v.to_le_bytes())
            .collect();
        assert!(decode(&nan, SampleType::F32, Endian::Little, DIMS).is_err());
    }

    #[test]
    fn wide_integers_out_of_range_are_refused() {
        let big: Vec<u8> = [0u64, 1 << 40, 0, 0]
            .iter()
            .flat_map(|v| v.to_le_bytes())
            .collect();
        let err = decode(&big, SampleType::U64, Endian::Little, DIMS).unwrap_err();
        assert!(
            err.to_string()
                .contains("value 1099511627776 at voxel (1, 0, 0)"),
            "{err}"
        );
        let ok: Vec<u8> = [5i32, 0, 0, 2]
            .iter()
            .flat_map(|v| v.to_le_bytes())
            .collect();
        let data = decode(&ok, SampleType::I32, Endian::Little, DIMS).unwrap();
        assert_eq!(data, LabelData::U8(vec![5, 0, 0, 2]));
    }
}
