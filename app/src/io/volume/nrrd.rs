//! NRRD label volumes (`.nrrd` with attached data, `.nhdr` with a detached data file, and 3D
//! Slicer's `.seg.nrrd`), after the format definition at teem.sourceforge.net/nrrd/format.html.
//!
//! Supported: `NRRD0001`–`NRRD0005`; every integer `type` and `float`/`double` (whole values
//! only, see [`super::samples`]); `encoding` `raw` and `gzip`; `endian` (little when absent);
//! `space` RAS, LAS, LPS, `scanner-xyz` (DICOM's LPS) and `3D-right-handed` (taken as RAS),
//! or `space dimension: 3`; `space directions` (any 3×3, permuted and flipped axes included),
//! `space origin`, `space units` (mm, cm, m, µm → mm); without a space, `spacings` (1 when absent)
//! and `axis mins`; `data file` (one file, relative to the header), `line skip`, `byte skip`
//! (`-1` for raw data at the end of the file). A 4-D file must have its non-spatial axis first:
//! that axis is the layer list of an overlapping Slicer segmentation. Key/value pairs (`key:=value`)
//! carry Slicer's segment names ([`super::segments`]).

use std::path::{Path, PathBuf};

use anyhow::Context as _;
use glam::DVec3;

use super::samples::{Endian, SampleType};
use super::{LabelData, RawSamples, RawVolume};

/// Largest header we look for the blank line in (Slicer writes a few hundred bytes per segment).
const MAX_HEADER: usize = 64 << 20;

/// The fields of a header that matter here, parsed.
#[derive(Debug, Default)]
struct Header {
    sample: Option<SampleType>,
    dimension: usize,
    sizes: Vec<u64>,
    endian: Option<Endian>,
    encoding: Option<Encoding>,
    /// Sign flips to RAS: (-1, -1, 1) for LPS.
    space_to_ras: Option<DVec3>,
    /// Per axis: `None` for a non-spatial axis.
    directions: Option<Vec<Option<DVec3>>>,
    origin: Option<DVec3>,
    unit_scale: f64,
    spacings: Option<Vec<f64>>,
    axis_mins: Option<Vec<f64>>,
    kinds: Option<Vec<String>>,
    data_file: Option<String>,
    line_skip: usize,
    byte_skip: i64,
    /// `key:=value` pairs, in file order.
    keys: Vec<(String, String)>,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Encoding {
    Raw,
    Gzip,
}

pub(crate) fn read(path: &Path) -> anyhow::Result<RawVolume> {
    let (header, data) = read_header_and_data(path)?;
    volume(&header, data)
}

/// [`read`] of a whole NRRD file already in memory, its data attached (the default scene's
/// embedded atlas): the same header parsing, size checks and decoding as a file on disk.
pub(crate) fn read_attached(mut bytes: Vec<u8>) -> anyhow::Result<RawVolume> {
    let (text, data_start) = split_header(&bytes)?;
    let header = parse_header(text)?;
    if header.data_file.is_some() {
        anyhow::bail!("a NRRD header with a separate 'data file' cannot be read from memory");
    }
    bytes.drain(..data_start);
    volume(&header, bytes)
}

/// The samples of a NRRD file at their own type (intensity images): the same header, geometry
/// and size checks as label maps, no decoding.
pub(crate) fn read_samples(path: &Path) -> anyhow::Result<RawSamples> {
    let (header, data) = read_header_and_data(path)?;
    samples(&header, data)
}

/// The parsed header and the still-encoded data bytes. The attached data is the file's buffer
/// with the header drained off in place, so a large file is held once.
fn read_header_and_data(path: &Path) -> anyhow::Result<(Header, Vec<u8>)> {
    let mut bytes = crate::io::bounded::read_bytes(path, crate::io::bounded::VOLUME_MAX_BYTES)?;
    let (text, data_start) = split_header(&bytes)?;
    let header = parse_header(text)?;
    let data = match &header.data_file {
        Some(name) => {
            let file = data_file_path(path, name)?;
            crate::io::bounded::read_bytes(&file, crate::io::bounded::VOLUME_MAX_BYTES)
                .with_context(|| format!("data file {}", file.display()))?
        }
        None => {
            bytes.drain(..data_start);
            bytes
        }
    };
    Ok((header, data))
}

/// The header text (up to the first empty line) and where the data starts.
fn split_header(bytes: &[u8]) -> anyhow::Result<(&str, usize)> {
    if !bytes.starts_with(b"NRRD000") {
        anyhow::bail!("not a NRRD file (it does not start with NRRD000)");
    }
    let search = &bytes[..bytes.len().min(MAX_HEADER)];
    let mut end = None;
    let mut line_start = 0;
    for (i, &b) in search.iter().enumerate() {
        if b == b'\n' {
            let line = &search[line_start..i];
            if line.is_empty() || line == b"\r" {
                end = Some((line_start, i + 1));
                break;
            }
            line_start = i + 1;
        }
    }
    // A detached header (.nhdr) may end at the end of the file without an empty line.
    let (header_end, data_start) = end.unwrap_or((search.len(), search.len()));
    if end.is_none() && search.len() == MAX_HEADER {
        anyhow::bail!("no end of the NRRD header in the first {MAX_HEADER} bytes");
    }
    let text = std::str::from_utf8(&bytes[..header_end])
        .map_err(|e| anyhow::anyhow!("the NRRD header is not text (byte {})", e.valid_up_to()))?;
    Ok((text, data_start))
}

fn parse_header(text: &str) -> anyhow::Result<Header> {
    let mut header = Header {
        unit_scale: 1.0,
        ..Header::default()
    };
    let mut lines = text.lines().enumerate();
    let (_, magic) = lines.next().unwrap_or((0, ""));
    let version = magic.trim().strip_prefix("NRRD000").unwrap_or("");
    if !matches!(version, "1" | "2" | "3" | "4" | "5") {
        anyhow::bail!("unsupported NRRD version '{}'", magic.trim());
    }
    for (number, line) in lines {
        let line = line.trim_end_matches('\r');
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let at = || format!("NRRD header line {}", number + 1);
        if let Some((key, value)) = line.split_once(":=") {
            header.keys.push((key.to_owned(), value.to_owned()));
            continue;
        }
        let (field, value) = line
            .split_once(": ")
            .ok_or_else(|| anyhow::anyhow!("{}: expected 'field: value', got '{line}'", at()))?;
        parse_field(&mut header, &field.to_ascii_lowercase(), value.trim())
            .with_context(|| format!("{} ('{field}')", at()))?;
    }
    Ok(header)
}

fn parse_field(h: &mut Header, field: &str, value: &str) -> anyhow::Result<()> {
    match field {
        "type" => h.sample = Some(sample_type(value)?),
        "dimension" => {
            h.dimension = value
                .parse()
                .map_err(|_| anyhow::anyhow!("not a number: '{value}'"))?;
            if !(3..=4).contains(&h.dimension) {
                anyhow::bail!(
                    "dimension {} (a label volume is 3-D, or 4-D with layers first)",
                    h.dimension
                );
            }
        }
        "sizes" => {
            h.sizes = value
                .split_whitespace()
                .map(|s| {
                    s.parse::<u64>()
                        .map_err(|_| anyhow::anyhow!("not a size: '{s}'"))
                })
                .collect::<anyhow::Result<_>>()?;
        }
        "endian" => {
            h.endian = Some(match value {
                "little" => Endian::Little,
                "big" => Endian::Big,
                _ => anyhow::bail!("unknown endian '{value}'"),
            })
        }
        "encoding" => {
            h.encoding = Some(match value {
                "raw" => Encoding::Raw,
                "gzip" | "gz" => Encoding::Gzip,
                _ => anyhow::bail!("unsupported encoding '{value}' (raw and gzip are read)"),
            })
        }
        "space" => h.space_to_ras = Some(space_to_ras(value)?),
        "space dimension" => {
            if value != "3" {
                anyhow::bail!("space dimension {value} (only 3-D space is supported)");
            }
            h.space_to_ras.get_or_insert(DVec3::ONE);
        }
        "space directions" => {
            h.directions = Some(
                vectors(value)?
                    .into_iter()
                    .map(|v| v.map(|v| DVec3::new(v[0], v[1], v[2])))
                    .collect(),
            )
        }
        "space origin" => {
            let v = vectors(value)?;
            match v.as_slice() {
                [Some(v)] => h.origin = Some(DVec3::new(v[0], v[1], v[2])),
                _ => anyhow::bail!("expected one vector (x,y,z)"),
            }
        }
        "space units" => {
            let units: Vec<&str> = value
                .split_whitespace()
                .map(|u| u.trim_matches('"'))
                .collect();
            let scale = |u: &str| match u {
                "mm" | "millimeter" | "millimeters" => Some(1.0),
                "cm" => Some(10.0),
                "m" | "meter" | "meters" => Some(1000.0),
                "um" | "µm" | "micron" | "microns" => Some(0.001),
                _ => None,
            };
            let first = units.first().copied().unwrap_or("mm");
            match scale(first) {
                Some(s) if units.iter().all(|u| *u == first) => h.unit_scale = s,
                _ => anyhow::bail!(
                    "unsupported space units '{value}' (mm, cm, m or µm, the same on every axis)"
                ),
            }
        }
        "spacings" => h.spacings = Some(numbers(value)?),
        "axis mins" | "axismins" => h.axis_mins = Some(numbers(value)?),
        "kinds" => h.kinds = Some(value.split_whitespace().map(str::to_owned).collect()),
        "data file" | "datafile" => {
            if value.starts_with("LIST") || value.split_whitespace().count() > 1 {
                anyhow::bail!(
                    "several data files ('{value}') are not supported; write one data file"
                );
            }
            h.data_file = Some(value.to_owned());
        }
        "line skip" | "lineskip" => {
            h.line_skip = value
                .parse()
                .map_err(|_| anyhow::anyhow!("not a count: '{value}'"))?
        }
        "byte skip" | "byteskip" => {
            h.byte_skip = value
                .parse()
                .map_err(|_| anyhow::anyhow!("not a count: '{value}'"))?;
            if h.byte_skip < -1 {
                anyhow::bail!("byte skip {value} (must be -1 or more)");
            }
        }
        // Fields that do not change the labels or their place.
        _ => {}
    }
    Ok(())
}

fn sample_type(value: &str) -> anyhow::Result<SampleType> {
    Ok(match value {
        "signed char" | "int8" | "int8_t" => SampleType::I8,
        "uchar" | "unsigned char" | "uint8" | "uint8_t" => SampleType::U8,
        "short" | "short int" | "signed short" | "signed short int" | "int16" | "int16_t" => {
            SampleType::I16
        }
        "ushort" | "unsigned short" | "unsigned short int" | "uint16" | "uint16_t" => {
            SampleType::U16
        }
        "int" | "signed int" | "int32" | "int32_t" => SampleType::I32,
        "uint" | "unsigned int" | "uint32" | "uint32_t" => SampleType::U32,
        "longlong"
        | "long long"
        | "long long int"
        | "signed long long"
        | "signed long long int"
        | "int64"
        | "int64_t" => SampleType::I64,
        "ulonglong" | "unsigned long long" | "unsigned long long int" | "uint64" | "uint64_t" => {
            SampleType::U64
        }
        "float" => SampleType::F32,
        "double" => SampleType::F64,
        _ => anyhow::bail!("unsupported type '{value}' (a label volume holds integers)"),
    })
}

/// The sign flips that take a NRRD space to RAS.
fn space_to_ras(value: &str) -> anyhow::Result<DVec3> {
    Ok(match value.to_ascii_lowercase().as_str() {
        "right-anterior-superior" | "ras" | "3d-right-handed" => DVec3::ONE,
        "left-anterior-superior" | "las" => DVec3::new(-1.0, 1.0, 1.0),
        "left-posterior-superior" | "lps" | "scanner-xyz" => DVec3::new(-1.0, -1.0, 1.0),
        _ => anyhow::bail!(
            "unsupported space '{value}' (RAS, LAS, LPS, scanner-xyz or 3D-right-handed)"
        ),
    })
}

/// `(a,b,c) none (d,e,f)` → one entry per token; `none` is `None`.
fn vectors(value: &str) -> anyhow::Result<Vec<Option<[f64; 3]>>> {
    let mut out = Vec::new();
    let mut rest = value.trim();
    while !rest.is_empty() {
        if let Some(after) = rest.strip_prefix("none") {
            out.push(None);
            rest = after.trim_start();
            continue;
        }
        let inner = rest
            .strip_prefix('(')
            .and_then(|r| r.split_once(')'))
            .ok_or_else(|| anyhow::anyhow!("expected '(x,y,z)' or 'none', got '{rest}'"))?;
        let parts: Vec<f64> = inner
            .0
            .split(',')
            .map(|s| parse_f64(s.trim()))
            .collect::<anyhow::Result<_>>()?;
        let v: [f64; 3] = parts.try_into().map_err(|p: Vec<f64>| {
            anyhow::anyhow!("a vector of {} numbers, expected 3", p.len())
        })?;
        out.push(Some(v));
        rest = inner.1.trim_start();
    }
    Ok(out)
}

fn numbers(value: &str) -> anyhow::Result<Vec<f64>> {
    value.split_whitespace().map(parse_f64).collect()
}

fn parse_f64(s: &str) -> anyhow::Result<f64> {
    match s.to_ascii_lowercase().as_str() {
        "nan" => Ok(f64::NAN),
        _ => s
            .parse()
            .map_err(|_| anyhow::anyhow!("not a number: '{s}'")),
    }
}

fn data_file_path(header_path: &Path, name: &str) -> anyhow::Result<PathBuf> {
    let name = Path::new(name);
    if name.is_absolute() {
        return Ok(name.to_path_buf());
    }
    let dir = header_path.parent().unwrap_or(Path::new("."));
    Ok(dir.join(name))
}

/// The file as labels or as an intensity image (`super::content_rule`), read once.
pub(crate) fn read_content(path: &Path) -> anyhow::Result<super::content_rule::RawContent> {
    let (header, data) = read_header_and_data(path)?;
    let raw = samples(&header, data)?;
    super::content_rule::classify(raw, |raw| labels_of(&header, raw))
}

/// Builds the volume from a parsed header and its data bytes (still encoded).
fn volume(h: &Header, data: Vec<u8>) -> anyhow::Result<RawVolume> {
    labels_of(h, &samples(h, data)?)
}

/// Decodes the samples of a label map and its segment names.
fn labels_of(h: &Header, raw: &RawSamples) -> anyhow::Result<RawVolume> {
    let dims = raw.dims;
    let layers_data = if raw.layers == 1 {
        vec![super::samples::decode(
            &raw.bytes, raw.sample, raw.endian, dims,
        )?]
    } else {
        deinterleave(&raw.bytes, raw.layers, raw.sample.size())
            .iter()
            .enumerate()
            .map(|(l, layer)| {
                super::samples::decode(layer, raw.sample, raw.endian, dims)
                    .with_context(|| format!("layer {l}"))
            })
            .collect::<anyhow::Result<Vec<LabelData>>>()?
    };
    let names = super::segments::from_keys(&h.keys, raw.layers)?;
    Ok(RawVolume {
        dims,
        world_from_voxel: raw.world_from_voxel,
        layers: layers_data,
        names,
    })
}

/// Checks a parsed header against its data bytes (still encoded) and returns exactly the
/// samples, decompressed, at their own type: the data buffer itself with skipped bytes drained
/// off, so raw data is never copied.
fn samples(h: &Header, mut data: Vec<u8>) -> anyhow::Result<RawSamples> {
    let sample = h
        .sample
        .ok_or_else(|| anyhow::anyhow!("the header has no 'type' field"))?;
    if h.dimension == 0 {
        anyhow::bail!("the header has no 'dimension' field");
    }
    if h.sizes.len() != h.dimension {
        anyhow::bail!(
            "'sizes' has {} numbers for dimension {}",
            h.sizes.len(),
            h.dimension
        );
    }
    let encoding = h
        .encoding
        .ok_or_else(|| anyhow::anyhow!("the header has no 'encoding' field"))?;
    let layered = h.dimension == 4;
    let first_spatial = usize::from(layered);
    if layered && !first_axis_is_list(h) {
        anyhow::bail!("a 4-D NRRD must have its non-spatial (layer) axis first");
    }
    let layers = if layered { h.sizes[0] } else { 1 };
    if layers == 0 || layers > 256 {
        anyhow::bail!("{layers} layers on the first axis (1..=256)");
    }
    let spatial = [
        h.sizes[first_spatial],
        h.sizes[first_spatial + 1],
        h.sizes[first_spatial + 2],
    ];
    let voxels = super::check_dims(spatial, layers)?;
    let dims = spatial.map(|n| n as usize);
    let world_from_voxel = geometry(h, first_spatial)?;

    let sample_size = sample.size();
    let expected = voxels * layers as usize * sample_size;
    let skipped = data.len() - skip_lines(&data, h.line_skip)?.len();
    data.drain(..skipped);
    let bytes = match encoding {
        Encoding::Raw => {
            let start = match h.byte_skip {
                -1 => data.len().checked_sub(expected),
                skip => Some(skip as usize),
            };
            match start {
                Some(s) if data.len().checked_sub(s) == Some(expected) => {
                    data.drain(..s);
                    data
                }
                _ => anyhow::bail!(
                    "voxel data is {} bytes, but sizes {} × {} need {expected}",
                    data.len().saturating_sub(h.byte_skip.max(0) as usize),
                    join(&h.sizes),
                    sample.name()
                ),
            }
        }
        Encoding::Gzip => {
            if h.byte_skip == -1 {
                anyhow::bail!("byte skip -1 is only meaningful for raw encoding");
            }
            let skip = h.byte_skip as usize;
            let mut inflated = super::gzip::inflate_exact(&data, expected + skip, "voxel data")?;
            drop(data);
            inflated.drain(..skip);
            inflated
        }
    };
    Ok(RawSamples {
        dims,
        world_from_voxel,
        layers: layers as usize,
        sample,
        endian: h.endian.unwrap_or(Endian::Little),
        bytes,
        scale: (1.0, 0.0),
    })
}

fn join(values: &[u64]) -> String {
    values
        .iter()
        .map(u64::to_string)
        .collect::<Vec<_>>()
        .join(" ")
}

/// Whether the first axis of a 4-D header is non-spatial (`none` direction, or a list kind).
fn first_axis_is_list(h: &Header) -> bool {
    if let Some(directions) = &h.directions {
        return directions.first().is_some_and(Option::is_none);
    }
    if let Some(kinds) = &h.kinds {
        let kind = kinds.first().map(|k| k.to_ascii_lowercase());
        return !matches!(kind.as_deref(), Some("domain" | "space"));
    }
    h.spacings
        .as_ref()
        .and_then(|s| s.first())
        .is_some_and(|s| s.is_nan())
}

/// The voxel-to-world matrix in RAS millimetres.
fn geometry(h: &Header, first_spatial: usize) -> anyhow::Result<glam::DAffine3> {
    let to_ras = h.space_to_ras;
    let (columns, origin) = match (&h.directions, to_ras) {
        (Some(directions), _) => {
            if directions.len() != h.dimension {
                anyhow::bail!(
                    "'space directions' has {} entries for dimension {}",
                    directions.len(),
                    h.dimension
                );
            }
            let mut columns = [DVec3::ZERO; 3];
            for (axis, column) in columns.iter_mut().enumerate() {
                *column = directions[first_spatial + axis].ok_or_else(|| {
                    anyhow::anyhow!(
                        "'space directions' is none for spatial axis {}",
                        first_spatial + axis
                    )
                })?;
            }
            (columns, h.origin.unwrap_or(DVec3::ZERO))
        }
        (None, Some(_)) => anyhow::bail!("the header names a space but has no 'space directions'"),
        (None, None) => {
            let spacing = |axis: usize| -> anyhow::Result<f64> {
                let s = h
                    .spacings
                    .as_ref()
                    .map(|s| s.get(first_spatial + axis).copied().unwrap_or(f64::NAN))
                    .unwrap_or(1.0);
                if !s.is_finite() || s == 0.0 {
                    anyhow::bail!("spacing {s} on spatial axis {}", first_spatial + axis);
                }
                Ok(s)
            };
            let min = |axis: usize| {
                h.axis_mins
                    .as_ref()
                    .and_then(|m| m.get(first_spatial + axis).copied())
                    .filter(|m| m.is_finite())
                    .unwrap_or(0.0)
            };
            (
                [
                    DVec3::X * spacing(0)?,
                    DVec3::Y * spacing(1)?,
                    DVec3::Z * spacing(2)?,
                ],
                DVec3::new(min(0), min(1), min(2)),
            )
        }
    };
    let flip = to_ras.unwrap_or(DVec3::ONE) * h.unit_scale;
    super::affine(columns.map(|c| c * flip), origin * flip)
}

/// Drops `count` lines (each ending in `\n`) from the start of the data.
fn skip_lines(data: &[u8], count: usize) -> anyhow::Result<&[u8]> {
    let mut rest = data;
    for line in 0..count {
        let end = rest
            .iter()
            .position(|&b| b == b'\n')
            .ok_or_else(|| anyhow::anyhow!("line skip {count}: the data has only {line} lines"))?;
        rest = &rest[end + 1..];
    }
    Ok(rest)
}

/// Splits samples stored layer-fastest into one buffer per layer.
fn deinterleave(bytes: &[u8], layers: usize, sample_size: usize) -> Vec<Vec<u8>> {
    let voxels = bytes.len() / (layers * sample_size);
    let mut out = vec![Vec::with_capacity(voxels * sample_size); layers];
    for voxel in bytes.chunks_exact(layers * sample_size) {
        for (layer, sample) in voxel.chunks_exact(sample_size).enumerate() {
            out[layer].extend_from_slice(sample);
        }
    }
    out
}

/// Writes a label volume as NRRD (tests and tools: synthetic volumes in any axis order and
/// encoding). `directions` are the columns in the file's `space`; `gzip` picks the encoding.
#[cfg(test)]
pub(crate) fn write_for_test(
    space: &str,
    type_name: &str,
    sizes: &[usize],
    directions: &str,
    origin: DVec3,
    samples: &[u8],
    gzip: bool,
    extra: &str,
) -> Vec<u8> {
    use std::io::Write as _;
    let mut out = format!(
        "NRRD0004\ntype: {type_name}\ndimension: {}\nspace: {space}\nsizes: {}\nspace directions: {directions}\nendian: little\nencoding: {}\nspace origin: ({},{},{})\n{extra}{}\n",
        sizes.len(),
        sizes.iter().map(|s| s.to_string()).collect::<Vec<_>>().join(" "),
        if gzip { "gzip" } else { "raw" },
        origin.x,
        origin.y,
        origin.z,
        if extra.is_empty() { "" } else { "\n" }
    )
    .into_bytes();
    if gzip {
        let mut e = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::fast());
        e.write_all(samples).unwrap();
        out.extend(e.finish().unwrap());
    } else {
        out.extend_from_slice(samples);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str, data: &[u8]) -> anyhow::Result<RawVolume> {
        volume(&parse_header(text)?, data.to_vec())
    }

    #[test]
    fn lps_header_gives_a_ras_matrix() {
        let text = "NRRD0004\ntype: unsigned char\ndimension: 3\nspace: left-posterior-superior\nsizes: 2 1 1\nspace directions: (0,1,0) (0,0,-1) (1,0,0)\nencoding: raw\nspace origin: (-128,-128,128)\n";
        let v = parse(text, &[0, 3]).unwrap();
        assert_eq!(v.dims, [2, 1, 1]);
        let m = v.world_from_voxel;
        assert_eq!(
            m.transform_point3(DVec3::ZERO),
            DVec3::new(128.0, 128.0, 128.0)
        );
        assert_eq!(
            m.transform_point3(DVec3::X),
            DVec3::new(128.0, 127.0, 128.0)
        );
        assert_eq!(
            m.transform_point3(DVec3::Y),
            DVec3::new(128.0, 128.0, 127.0)
        );
        assert_eq!(
            m.transform_point3(DVec3::Z),
            DVec3::new(127.0, 128.0, 128.0)
        );
        assert_eq!(v.layers, vec![LabelData::U8(vec![0, 3])]);
    }

    #[test]
    fn no_space_uses_spacings_and_axis_mins() {
        let text = "NRRD0005\ntype: ushort\ndimension: 3\nsizes: 1 1 2\nspacings: 0.5 2 3\naxis mins: 1 2 3\nendian: big\nencoding: raw\n";
        let v = parse(text, &[0, 1, 1, 0]).unwrap();
        assert_eq!(v.layers, vec![LabelData::U16(vec![1, 256])]);
        let m = v.world_from_voxel;
        assert_eq!(m.transform_point3(DVec3::ONE), DVec3::new(1.5, 4.0, 6.0));
        let nan = text.replace("spacings: 0.5 2 3", "spacings: 0.5 nan 3");
        let err = parse(&nan, &[0, 1, 1, 0]).unwrap_err();
        assert_eq!(err.to_string(), "spacing NaN on spatial axis 1");
    }

    #[test]
    fn layered_4d_splits_the_first_axis_into_layers() {
        let text = "NRRD0004\ntype: uint8\ndimension: 4\nspace: RAS\nsizes: 2 3 1 1\nspace directions: none (1,0,0) (0,1,0) (0,0,1)\nkinds: list domain domain domain\nencoding: raw\n";
        let v = parse(text, &[1, 0, 2, 1, 0, 0]).unwrap();
        assert_eq!(v.dims, [3, 1, 1]);
        assert_eq!(
            v.layers,
            vec![LabelData::U8(vec![1, 2, 0]), LabelData::U8(vec![0, 1, 0])]
        );
        let spatial_first = text.replace(
            "none (1,0,0) (0,1,0) (0,0,1)",
            "(1,0,0) (0,1,0) (0,0,1) none",
        );
        assert!(parse(&spatial_first, &[0; 6]).is_err());
    }

    #[test]
    fn sizes_data_and_matrix_are_checked() {
        let base = "NRRD0004\ntype: uint8\ndimension: 3\nspace: RAS\nsizes: 2 2 1\nspace directions: (1,0,0) (0,1,0) (0,0,1)\nencoding: raw\n";
        let err = parse(base, &[1, 2, 3]).unwrap_err();
        assert_eq!(
            err.to_string(),
            "voxel data is 3 bytes, but sizes 2 2 1 × uint8 need 4"
        );
        let zero = base.replace("sizes: 2 2 1", "sizes: 2 0 1");
        assert!(
            parse(&zero, &[])
                .unwrap_err()
                .to_string()
                .contains("size 0 of axis 1")
        );
        let huge = base.replace("sizes: 2 2 1", "sizes: 2049 1 1");
        assert!(
            parse(&huge, &[])
                .unwrap_err()
                .to_string()
                .contains("outside 1..=2048")
        );
        let many = base.replace("sizes: 2 2 1", "sizes: 2048 2048 1000");
        assert!(
            parse(&many, &[])
                .unwrap_err()
                .to_string()
                .contains("more than the limit")
        );
        let singular = base.replace("(0,1,0) (0,0,1)", "(2,0,0) (0,0,1)");
        let err = parse(&singular, &[0; 4]).unwrap_err();
        assert!(
            err.to_string().starts_with("singular direction matrix"),
            "{err}"
        );
        let float = base.replace("uint8", "float");
        let bytes: Vec<u8> = [0.5f32, 0.0, 0.0, 0.0]
            .iter()
            .flat_map(|f| f.to_le_bytes())
            .collect();
        assert!(
            parse(&float, &bytes)
                .unwrap_err()
                .to_string()
                .contains("not a label map")
        );
    }

    #[test]
    fn header_split_and_skips() {
        let file = b"NRRD0004\ntype: uint8\r\n\r\n\x01\x02";
        let (text, start) = split_header(file).unwrap();
        assert_eq!(text, "NRRD0004\ntype: uint8\r\n");
        assert_eq!(&file[start..], b"\x01\x02");
        assert!(split_header(b"PLY\n").is_err());
        assert_eq!(skip_lines(b"a\nbc\nxyz", 2).unwrap(), b"xyz");
        assert!(skip_lines(b"a\n", 2).is_err());
    }
}
