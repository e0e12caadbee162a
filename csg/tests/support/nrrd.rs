//! A minimal reader of attached gzip/raw NRRD label volumes, for the label-surface test and
//! bench only (csg sees no file format; the app has the real reader). It reads 8- and 16-bit
//! integer scalars, little endian, and builds the voxel → world RAS transform from `space
//! directions`, `space origin` and `space` (LPS is turned into RAS).

use std::io::Read;

use glam::{DAffine3, DMat3, DVec3};

/// A decoded label volume.
pub struct Volume {
    pub dims: [usize; 3],
    pub data: Vec<u16>,
    pub world_from_voxel: DAffine3,
}

/// Reads `path`; the error names the problem.
pub fn read(path: &std::path::Path) -> Result<Volume, String> {
    let bytes = std::fs::read(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let end = bytes
        .windows(2)
        .position(|w| w == b"\n\n")
        .ok_or("no blank line after the header")?;
    let header = std::str::from_utf8(&bytes[..end]).map_err(|e| e.to_string())?;
    let field = |name: &str| {
        header
            .lines()
            .find_map(|l| l.strip_prefix(name)?.strip_prefix(": "))
            .map(str::trim)
    };
    let numbers = |s: &str| -> Vec<f64> {
        s.split(|c: char| !(c.is_ascii_digit() || c == '.' || c == '-' || c == 'e' || c == '+'))
            .filter(|t| !t.is_empty())
            .filter_map(|t| t.parse().ok())
            .collect()
    };
    let sizes: Vec<usize> = field("sizes")
        .ok_or("no sizes")?
        .split_whitespace()
        .map(|t| t.parse().map_err(|_| format!("bad size {t}")))
        .collect::<Result<_, _>>()?;
    let dims: [usize; 3] = sizes.try_into().map_err(|_| "not 3-D")?;
    let width = match field("type").ok_or("no type")? {
        "uchar" | "unsigned char" | "uint8" | "uint8_t" => 1,
        "short" | "short int" | "int16" | "int16_t" | "ushort" | "unsigned short" | "uint16"
        | "uint16_t" => 2,
        t => return Err(format!("unsupported type {t}")),
    };
    if field("endian").is_some_and(|e| e != "little") {
        return Err("big endian is not supported".into());
    }
    let body = &bytes[end + 2..];
    let raw = match field("encoding").ok_or("no encoding")? {
        "gzip" | "gz" => {
            // Sized from the header (bounded: the check below refuses any other length), so
            // the decoder writes once instead of growing and copying the buffer.
            let expected = dims.iter().product::<usize>().saturating_mul(width);
            let mut out = Vec::with_capacity(expected.min(1 << 31));
            flate2::read::MultiGzDecoder::new(body)
                .read_to_end(&mut out)
                .map_err(|e| e.to_string())?;
            out
        }
        "raw" => body.to_vec(),
        e => return Err(format!("unsupported encoding {e}")),
    };
    let count = dims.iter().product::<usize>();
    if raw.len() != count * width {
        return Err(format!(
            "{} data bytes, expected {}",
            raw.len(),
            count * width
        ));
    }
    let data: Vec<u16> = if width == 1 {
        raw.iter().map(|&b| b as u16).collect()
    } else {
        raw.chunks_exact(2)
            .map(|c| u16::from_le_bytes([c[0], c[1]]))
            .collect()
    };
    let directions = numbers(field("space directions").ok_or("no space directions")?);
    let origin = numbers(field("space origin").unwrap_or("(0,0,0)"));
    if directions.len() != 9 || origin.len() != 3 {
        return Err("bad space directions or origin".into());
    }
    let mut matrix = DMat3::from_cols_slice(&directions);
    let mut origin = DVec3::from_slice(&origin);
    let space = field("space").unwrap_or("right-anterior-superior");
    if matches!(space, "left-posterior-superior" | "LPS") {
        let ras_from_lps = DMat3::from_diagonal(DVec3::new(-1.0, -1.0, 1.0));
        matrix = ras_from_lps * matrix;
        origin = ras_from_lps * origin;
    }
    Ok(Volume {
        dims,
        data,
        world_from_voxel: DAffine3::from_mat3_translation(matrix, origin),
    })
}
