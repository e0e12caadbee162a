//! NIfTI-1 and NIfTI-2 label volumes (`.nii`, `.nii.gz`; single file, magic `n+1`/`n+2`), with
//! a header reader of our own: a label map needs a dozen fields, and reading them ourselves lets
//! us check every size before the voxel data is inflated.
//!
//! Geometry, as the standard says: the sform when `sform_code > 0`, else the qform (quaternion,
//! `pixdim`, `qfac`) when `qform_code > 0`, else `pixdim` on the diagonal. Spatial units from
//! `xyzt_units` (m, mm, µm; unknown = mm). `scl_slope`/`scl_inter` are ignored: label values
//! are stored values. Dimensions beyond the third must be 1 (a time series is not a label map).
//! Both byte orders are read (the header size, 348 or 540, tells which).

use std::io::Read;
use std::path::Path;

use glam::{DMat3, DQuat, DVec3};

use super::samples::{Endian, SampleType};
use super::{RawSamples, RawVolume};

/// Whether `bytes` start with an uncompressed NIfTI-1/2 header.
pub fn sniff(bytes: &[u8]) -> bool {
    header_kind(bytes).is_some()
}

/// (NIfTI version, byte order) from the first bytes.
fn header_kind(bytes: &[u8]) -> Option<(u8, Endian)> {
    let size = <[u8; 4]>::try_from(bytes.get(..4)?).ok()?;
    for endian in [Endian::Little, Endian::Big] {
        let n = match endian {
            Endian::Little => i32::from_le_bytes(size),
            Endian::Big => i32::from_be_bytes(size),
        };
        if n == 348
            && bytes
                .get(344..347)
                .is_some_and(|m| m == b"n+1" || m == b"ni1")
        {
            return Some((1, endian));
        }
        if n == 540 && bytes.get(4..7).is_some_and(|m| m == b"n+2" || m == b"ni2") {
            return Some((2, endian));
        }
    }
    None
}

/// Little helpers reading header fields in the file's byte order.
struct Fields<'a> {
    bytes: &'a [u8],
    endian: Endian,
}

impl Fields<'_> {
    fn raw<const N: usize>(&self, at: usize) -> [u8; N] {
        let mut b: [u8; N] = self.bytes[at..at + N]
            .try_into()
            .expect("header field in range");
        if self.endian == Endian::Big {
            b.reverse();
        }
        b
    }
    fn i16(&self, at: usize) -> i64 {
        i16::from_le_bytes(self.raw(at)) as i64
    }
    fn i32(&self, at: usize) -> i64 {
        i32::from_le_bytes(self.raw(at)) as i64
    }
    fn i64(&self, at: usize) -> i64 {
        i64::from_le_bytes(self.raw(at))
    }
    fn f32(&self, at: usize) -> f64 {
        f32::from_le_bytes(self.raw(at)) as f64
    }
    fn f64(&self, at: usize) -> f64 {
        f64::from_le_bytes(self.raw(at))
    }
}

/// The header fields a label map needs, version-independent.
#[derive(Debug)]
struct Header {
    endian: Endian,
    dim: [i64; 8],
    datatype: i64,
    pixdim: [f64; 8],
    vox_offset: f64,
    qform_code: i64,
    sform_code: i64,
    quatern: [f64; 3],
    qoffset: [f64; 3],
    srow: [[f64; 4]; 3],
    xyzt_units: i64,
    scl_slope: f64,
    scl_inter: f64,
}

fn parse_header(bytes: &[u8], version: u8, endian: Endian) -> Header {
    let f = Fields { bytes, endian };
    if version == 1 {
        Header {
            endian,
            dim: std::array::from_fn(|i| f.i16(40 + 2 * i)),
            datatype: f.i16(70),
            pixdim: std::array::from_fn(|i| f.f32(76 + 4 * i)),
            vox_offset: f.f32(108),
            qform_code: f.i16(252),
            sform_code: f.i16(254),
            quatern: std::array::from_fn(|i| f.f32(256 + 4 * i)),
            qoffset: std::array::from_fn(|i| f.f32(268 + 4 * i)),
            srow: std::array::from_fn(|r| std::array::from_fn(|c| f.f32(280 + 16 * r + 4 * c))),
            xyzt_units: bytes[123] as i64,
            scl_slope: f.f32(112),
            scl_inter: f.f32(116),
        }
    } else {
        Header {
            endian,
            dim: std::array::from_fn(|i| f.i64(16 + 8 * i)),
            datatype: f.i16(12),
            pixdim: std::array::from_fn(|i| f.f64(104 + 8 * i)),
            vox_offset: f.i64(168) as f64,
            qform_code: f.i32(344),
            sform_code: f.i32(348),
            quatern: std::array::from_fn(|i| f.f64(352 + 8 * i)),
            qoffset: std::array::from_fn(|i| f.f64(376 + 8 * i)),
            srow: std::array::from_fn(|r| std::array::from_fn(|c| f.f64(400 + 32 * r + 8 * c))),
            xyzt_units: f.i32(500),
            scl_slope: f.f64(176),
            scl_inter: f.f64(184),
        }
    }
}

pub(crate) fn read(path: &Path) -> anyhow::Result<RawVolume> {
    labels_of(&read_samples(path)?)
}

/// The file as labels or as an intensity image (`super::content_rule`), read once.
pub(crate) fn read_content(path: &Path) -> anyhow::Result<super::content_rule::RawContent> {
    super::content_rule::classify(read_samples(path)?, labels_of)
}

fn labels_of(raw: &RawSamples) -> anyhow::Result<RawVolume> {
    let layer = super::samples::decode(&raw.bytes, raw.sample, raw.endian, raw.dims)?;
    Ok(RawVolume {
        dims: raw.dims,
        world_from_voxel: raw.world_from_voxel,
        layers: vec![layer],
        names: Vec::new(),
    })
}

/// The samples of a NIfTI file at their own type with the file's `scl_slope`/`scl_inter`
/// (intensity images; label maps ignore the scaling): the same header, geometry and size checks
/// as label maps, no decoding.
pub(crate) fn read_samples(path: &Path) -> anyhow::Result<RawSamples> {
    let opened = SampleStream::open(path)?;
    let (h, dims, world_from_voxel, sample, expected) = (
        opened.header,
        opened.dims,
        opened.world_from_voxel,
        opened.sample,
        opened.expected,
    );
    let data = match opened.source {
        Source::Plain { mut file, offset } => {
            // Uncompressed: the voxels are the file's own buffer, the header drained off in
            // place, so a large image is held once.
            file.drain(..offset);
            file.truncate(expected);
            file
        }
        Source::Gzip {
            first,
            mut reader,
            compressed,
        } => {
            let mut data = first;
            let more = expected - data.len();
            super::gzip::read_exact_limited_onto(
                &mut reader,
                more,
                compressed,
                "voxel data",
                &mut data,
            )?;
            data
        }
    };
    Ok(samples_of(&h, dims, world_from_voxel, sample, data))
}

/// A NIfTI file opened at its voxels: the header read and checked (sizes against the bytes
/// present, geometry), the data not yet inflated. [`SampleStream::chunks`] hands the voxel bytes
/// over a bounded piece at a time, so a reader that keeps little of them (a mask's non-zero runs)
/// never holds the whole inflated image.
pub(crate) struct SampleStream {
    header: Header,
    pub dims: [u64; 3],
    pub world_from_voxel: glam::DAffine3,
    pub sample: SampleType,
    /// Voxel bytes in all.
    pub expected: usize,
    source: Source,
}

enum Source {
    /// Uncompressed: the file's bytes, the voxels from `offset`.
    Plain { file: Vec<u8>, offset: usize },
    /// Gzip: the voxel bytes inflated with the header, then the decoder at the next one.
    Gzip {
        first: Vec<u8>,
        /// Boxed: the decoder's state is large beside the other variant.
        reader: Box<flate2::read::MultiGzDecoder<std::io::Cursor<Vec<u8>>>>,
        compressed: usize,
    },
}

impl SampleStream {
    pub(crate) fn open(path: &Path) -> anyhow::Result<SampleStream> {
        let file = crate::io::bounded::read_bytes(path, crate::io::bounded::VOLUME_MAX_BYTES)?;
        let gz = file.starts_with(&[0x1f, 0x8b]);
        let compressed = file.len();
        let (mut head, mut reader) = if gz {
            let mut reader = Box::new(flate2::read::MultiGzDecoder::new(std::io::Cursor::new(
                file,
            )));
            let mut head = Vec::new();
            (&mut reader)
                .take(540)
                .read_to_end(&mut head)
                .map_err(|e| anyhow::anyhow!("corrupt or truncated gzip header ({e})"))?;
            (head, Some(reader))
        } else {
            (file, None)
        };
        let (version, endian) = header_kind(&head).ok_or_else(|| {
            anyhow::anyhow!("not a NIfTI-1/2 file (no header size 348/540 with magic n+1/n+2)")
        })?;
        let header_size = if version == 1 { 348 } else { 540 };
        if head.len() < header_size {
            anyhow::bail!(
                "the NIfTI header is cut short ({} of {header_size} bytes)",
                head.len()
            );
        }
        let h = parse_header(&head, version, endian);
        let sample = sample_type(h.datatype)?;
        let dims = spatial_dims(&h.dim)?;
        let voxels = super::check_dims(dims, 1)?;
        let world_from_voxel = geometry(&h)?;
        if !(h.vox_offset >= header_size as f64 && h.vox_offset <= (64 << 20) as f64) {
            anyhow::bail!(
                "vox_offset {} is not past the header (or absurd)",
                h.vox_offset
            );
        }
        let offset = h.vox_offset as usize;
        let expected = voxels * sample.size();
        let source = match reader.take() {
            None => {
                if head.len() < offset + expected {
                    anyhow::bail!(
                        "voxel data is {} bytes, but dims {} {} {} × {} need {expected}",
                        head.len().saturating_sub(offset),
                        dims[0],
                        dims[1],
                        dims[2],
                        sample.name()
                    );
                }
                Source::Plain { file: head, offset }
            }
            Some(mut reader) => {
                // Skip the extensions between the header and the voxels.
                let mut skipped = head.len();
                let mut sink = [0u8; 4096];
                while skipped < offset {
                    let n = (offset - skipped).min(sink.len());
                    reader.read_exact(&mut sink[..n]).map_err(|e| {
                        anyhow::anyhow!("the file ends before vox_offset {offset} ({e})")
                    })?;
                    skipped += n;
                }
                // Voxel data may start inside the 540 bytes read (a NIfTI-1 file's 352-byte
                // offset).
                let first = if skipped > offset {
                    head.drain(..offset);
                    head.truncate(expected);
                    head
                } else {
                    Vec::new()
                };
                Source::Gzip {
                    first,
                    reader,
                    compressed,
                }
            }
        };
        Ok(SampleStream {
            header: h,
            dims,
            world_from_voxel,
            sample,
            expected,
            source,
        })
    }

    /// Hands the voxel bytes to `visit` in order, with each piece's offset in the voxel data,
    /// `chunk` bytes at a time at most (an uncompressed file's all at once: it is in memory
    /// already). Fewer bytes than the header needs is an error.
    pub(crate) fn chunks(
        self,
        chunk: usize,
        visit: &mut dyn FnMut(usize, &[u8]),
    ) -> anyhow::Result<()> {
        match self.source {
            Source::Plain { file, offset } => visit(0, &file[offset..offset + self.expected]),
            Source::Gzip {
                first, mut reader, ..
            } => {
                visit(0, &first);
                let mut done = first.len();
                let mut buffer = vec![0u8; chunk.max(1)];
                while done < self.expected {
                    let want = (self.expected - done).min(buffer.len());
                    let mut filled = 0;
                    while filled < want {
                        match reader.read(&mut buffer[filled..want]) {
                            Ok(0) => anyhow::bail!(
                                "voxel data is {} bytes after gzip, but the header's sizes and type need {}",
                                done + filled,
                                self.expected
                            ),
                            Ok(n) => filled += n,
                            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => {}
                            Err(e) => {
                                anyhow::bail!("corrupt or truncated gzip voxel data ({e})")
                            }
                        }
                    }
                    visit(done, &buffer[..filled]);
                    done += filled;
                }
            }
        }
        Ok(())
    }
}

fn samples_of(
    h: &Header,
    dims: [u64; 3],
    world_from_voxel: glam::DAffine3,
    sample: SampleType,
    bytes: Vec<u8>,
) -> RawSamples {
    // A slope of 0 means "no scaling" (NIfTI-1 standard).
    let scale = if h.scl_slope.is_finite() && h.scl_slope != 0.0 && h.scl_inter.is_finite() {
        (h.scl_slope, h.scl_inter)
    } else {
        (1.0, 0.0)
    };
    RawSamples {
        dims: dims.map(|d| d as usize),
        world_from_voxel,
        layers: 1,
        sample,
        endian: h.endian,
        bytes,
        scale,
    }
}

fn sample_type(datatype: i64) -> anyhow::Result<SampleType> {
    Ok(match datatype {
        2 => SampleType::U8,
        4 => SampleType::I16,
        8 => SampleType::I32,
        16 => SampleType::F32,
        64 => SampleType::F64,
        256 => SampleType::I8,
        512 => SampleType::U16,
        768 => SampleType::U32,
        1024 => SampleType::I64,
        1280 => SampleType::U64,
        _ => anyhow::bail!(
            "NIfTI datatype {datatype} is not a label type (integers, or floats holding whole numbers)"
        ),
    })
}

/// dim[1..=3]; dim[0] says how many are used; dims 4.. must be 1.
fn spatial_dims(dim: &[i64; 8]) -> anyhow::Result<[u64; 3]> {
    let used = dim[0];
    if !(1..=7).contains(&used) {
        anyhow::bail!("dim[0] = {used} (expected 1..=7)");
    }
    let size = |i: usize| if (i as i64) <= used { dim[i] } else { 1 };
    for i in 4..=used as usize {
        if size(i) != 1 {
            anyhow::bail!(
                "dim[{i}] = {} volumes: a label map has one 3-D volume",
                size(i)
            );
        }
    }
    let out = [size(1), size(2), size(3)];
    if let Some(bad) = out.iter().find(|&&d| d < 0) {
        anyhow::bail!("negative dimension {bad}");
    }
    Ok(out.map(|d| d as u64))
}

/// sform, else qform, else pixdim; scaled to millimetres.
fn geometry(h: &Header) -> anyhow::Result<glam::DAffine3> {
    let mm = match h.xyzt_units & 7 {
        1 => 1000.0,
        3 => 0.001,
        _ => 1.0,
    };
    let (columns, origin) = if h.sform_code > 0 {
        let s = &h.srow;
        (
            [0, 1, 2].map(|c| DVec3::new(s[0][c], s[1][c], s[2][c])),
            DVec3::new(s[0][3], s[1][3], s[2][3]),
        )
    } else if h.qform_code > 0 {
        let [b, c, d] = h.quatern;
        let a = (1.0 - (b * b + c * c + d * d)).max(0.0).sqrt();
        let rotation = DMat3::from_quat(DQuat::from_xyzw(b, c, d, a).normalize());
        let qfac = if h.pixdim[0] < 0.0 { -1.0 } else { 1.0 };
        let scale = DVec3::new(h.pixdim[1], h.pixdim[2], qfac * h.pixdim[3]);
        (
            [
                rotation.x_axis * scale.x,
                rotation.y_axis * scale.y,
                rotation.z_axis * scale.z,
            ],
            DVec3::from_array(h.qoffset),
        )
    } else {
        let p = &h.pixdim;
        for (axis, s) in p[1..=3].iter().enumerate() {
            if !s.is_finite() || *s <= 0.0 {
                anyhow::bail!("pixdim[{}] = {s}: not a voxel size", axis + 1);
            }
        }
        (
            [DVec3::X * p[1], DVec3::Y * p[2], DVec3::Z * p[3]],
            DVec3::ZERO,
        )
    };
    super::affine(columns.map(|c| c * mm), origin * mm)
}

/// Writes a NIfTI-1 file (tests: synthetic volumes in any orientation). `srow` is the sform.
#[cfg(test)]
pub(crate) fn write_for_test(
    dims: [usize; 3],
    datatype: i16,
    srow: [[f32; 4]; 3],
    samples: &[u8],
) -> Vec<u8> {
    let mut h = vec![0u8; 352];
    h[0..4].copy_from_slice(&348i32.to_le_bytes());
    let dim = [
        3i16,
        dims[0] as i16,
        dims[1] as i16,
        dims[2] as i16,
        1,
        1,
        1,
        1,
    ];
    for (i, d) in dim.iter().enumerate() {
        h[40 + 2 * i..42 + 2 * i].copy_from_slice(&d.to_le_bytes());
    }
    h[70..72].copy_from_slice(&datatype.to_le_bytes());
    for i in 0..8 {
        h[76 + 4 * i..80 + 4 * i].copy_from_slice(&1f32.to_le_bytes());
    }
    h[108..112].copy_from_slice(&352f32.to_le_bytes());
    h[123] = 2;
    h[254..256].copy_from_slice(&1i16.to_le_bytes());
    for (r, row) in srow.iter().enumerate() {
        for (c, v) in row.iter().enumerate() {
            h[280 + 16 * r + 4 * c..284 + 16 * r + 4 * c].copy_from_slice(&v.to_le_bytes());
        }
    }
    h[344..348].copy_from_slice(b"n+1\0");
    h.extend_from_slice(samples);
    h
}

#[cfg(test)]
mod tests {
    use super::*;

    fn header(bytes: &[u8]) -> Header {
        let (version, endian) = header_kind(bytes).unwrap();
        parse_header(bytes, version, endian)
    }

    #[test]
    fn sform_is_used_and_sniffed() {
        let srow = [
            [2.0, 0.0, 0.0, -10.0],
            [0.0, -3.0, 0.0, 5.0],
            [0.0, 0.0, 1.0, 0.0],
        ];
        let bytes = write_for_test([2, 2, 2], 2, srow, &[0; 8]);
        assert!(sniff(&bytes));
        let h = header(&bytes);
        assert_eq!(h.dim[..4], [3, 2, 2, 2]);
        let m = geometry(&h).unwrap();
        assert_eq!(m.transform_point3(DVec3::ONE), DVec3::new(-8.0, 2.0, 1.0));
    }

    #[test]
    fn qform_with_negative_qfac_flips_k() {
        let mut bytes = write_for_test([2, 2, 2], 2, [[0.0; 4]; 3], &[0; 8]);
        bytes[254..256].copy_from_slice(&0i16.to_le_bytes());
        bytes[252..254].copy_from_slice(&1i16.to_le_bytes());
        bytes[76..80].copy_from_slice(&(-1f32).to_le_bytes());
        bytes[88..92].copy_from_slice(&2.5f32.to_le_bytes());
        // Quaternion (b, c, d) = (0, 0, 1): 180° about z, so x and y flip.
        bytes[264..268].copy_from_slice(&1f32.to_le_bytes());
        bytes[268..272].copy_from_slice(&7f32.to_le_bytes());
        let m = geometry(&header(&bytes)).unwrap();
        let p = m.transform_point3(DVec3::ONE);
        assert!((p - DVec3::new(6.0, -1.0, -2.5)).length() < 1e-12, "{p}");
    }

    #[test]
    fn time_series_and_bad_types_are_refused() {
        let mut dim = [4, 2, 2, 2, 3, 1, 1, 1];
        assert!(
            spatial_dims(&dim)
                .unwrap_err()
                .to_string()
                .contains("dim[4] = 3")
        );
        dim[4] = 1;
        assert_eq!(spatial_dims(&dim).unwrap(), [2, 2, 2]);
        assert!(sample_type(32).is_err());
        assert_eq!(sample_type(512).unwrap(), SampleType::U16);
    }
}
