//! Legacy VTK `POLYDATA`, ASCII and binary (big endian, as the format defines): our own reader.
//!
//! Why our own: the one crate for the format (`vtkio`) has been a pre-release for years, and a
//! reader of its size cannot be checked for bounded allocation. This one reads only what Cutaway
//! needs and compares every count with the bytes left before it allocates anything for it.
//!
//! Layout: the version line `# vtk DataFile Version x.y`, a title line, `ASCII` or `BINARY`,
//! `DATASET POLYDATA`, then sections in any order:
//! - `POINTS n type`: `3n` numbers of any VTK scalar type (converted to `f64`; `float` exactly);
//! - `POLYGONS`, `TRIANGLE_STRIPS`, `VERTICES`, `LINES` as `n size` followed by `size` integers
//!   (`count i1 … icount` per cell), or in the VTK 5 layout as `OFFSETS type` and
//!   `CONNECTIVITY type` arrays;
//! - `METADATA` blocks (skipped up to the blank line that ends them);
//! - `POINT_DATA`, `CELL_DATA` or `FIELD` end the geometry: the rest of the file is not read.
//!
//! `POLYGONS` are fan-triangulated; `TRIANGLE_STRIPS` are triangulated here: strip
//! `v0 v1 v2 v3 …` gives `(v0 v1 v2)`, `(v2 v1 v3)`, `(v2 v3 v4)`, … (every odd triangle swaps its
//! first two corners so that all keep the strip's orientation), which is what VTK's
//! `vtkTriangleFilter` produces. Degenerate strip triangles (a repeated index, used to join
//! strips) are kept, as VTK keeps them; the validation report counts them. `VERTICES` and
//! `LINES` bound no surface and are skipped. Indices are not range-checked here (the mesh sanity
//! check does it with the vertex count), only for being non-negative.

use csg::DVec3;

use super::RawPart;

pub(crate) fn parse(bytes: &[u8]) -> anyhow::Result<Vec<RawPart>> {
    if !bytes.starts_with(b"# vtk DataFile") {
        anyhow::bail!("not a legacy VTK file (it must start with '# vtk DataFile')");
    }
    let mut r = Reader {
        bytes,
        at: 0,
        binary: false,
    };
    r.line()?; // version
    r.line()?; // title: free text
    let binary = match r.keyword_line()?.trim().to_ascii_uppercase().as_str() {
        "ASCII" => false,
        "BINARY" => true,
        other => anyhow::bail!("VTK encoding line is {other:?}, expected ASCII or BINARY"),
    };
    let dataset = r.keyword_line()?;
    let mut words = dataset.split_ascii_whitespace();
    if !words
        .next()
        .is_some_and(|w| w.eq_ignore_ascii_case("DATASET"))
    {
        anyhow::bail!("VTK: expected a DATASET line, found {dataset:?}");
    }
    let kind = words.next().unwrap_or("").to_ascii_uppercase();
    if kind != "POLYDATA" {
        anyhow::bail!("VTK {kind} data, not POLYDATA");
    }
    r.binary = binary;
    let mut part = RawPart::default();
    let mut points_seen = false;
    while let Some(line) = r.next_keyword_line()? {
        let mut words = line.split_ascii_whitespace();
        let keyword = words.next().unwrap_or("").to_ascii_uppercase();
        match keyword.as_str() {
            "POINTS" => {
                if points_seen {
                    anyhow::bail!("VTK: a second POINTS section");
                }
                points_seen = true;
                let n = count(words.next(), "POINTS")?;
                let scalar = Scalar::parse(words.next().unwrap_or(""))?;
                let values = n
                    .checked_mul(3)
                    .ok_or_else(|| anyhow::anyhow!("VTK POINTS {n}: count too large"))?;
                let coordinates = r.numbers(values, scalar, "POINTS")?;
                part.positions = coordinates
                    .chunks_exact(3)
                    .map(|p| DVec3::new(p[0], p[1], p[2]))
                    .collect();
            }
            "POLYGONS" | "TRIANGLE_STRIPS" | "VERTICES" | "LINES" => {
                let cells = count(words.next(), &keyword)?;
                let size = count(words.next(), &keyword)?;
                let cells = r.cells(cells, size, &keyword)?;
                match keyword.as_str() {
                    "POLYGONS" => cells.for_each(|cell| {
                        for k in 1..cell.len().saturating_sub(1) {
                            part.triangles.push([cell[0], cell[k], cell[k + 1]]);
                        }
                    }),
                    "TRIANGLE_STRIPS" => cells.for_each(|cell| {
                        for k in 0..cell.len().saturating_sub(2) {
                            part.triangles.push(if k % 2 == 0 {
                                [cell[k], cell[k + 1], cell[k + 2]]
                            } else {
                                [cell[k + 1], cell[k], cell[k + 2]]
                            });
                        }
                    }),
                    _ => {} // points and lines bound no surface
                }
            }
            "METADATA" => r.skip_metadata(),
            "POINT_DATA" | "CELL_DATA" | "FIELD" => break,
            other => anyhow::bail!("VTK: unexpected section {other:?} in POLYDATA"),
        }
    }
    if !points_seen {
        anyhow::bail!("VTK POLYDATA without POINTS");
    }
    Ok(vec![part])
}

/// A non-negative count from a section header.
fn count(word: Option<&str>, what: &str) -> anyhow::Result<usize> {
    let word = word.ok_or_else(|| anyhow::anyhow!("VTK {what}: missing count"))?;
    word.parse()
        .map_err(|_| anyhow::anyhow!("VTK {what}: count {word:?} is not a non-negative integer"))
}

/// A VTK scalar type: size in bytes in binary files, and how to decode it.
#[derive(Clone, Copy, Debug)]
enum Scalar {
    F32,
    F64,
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    I64,
    U64,
}

impl Scalar {
    fn parse(name: &str) -> anyhow::Result<Scalar> {
        Ok(match name.to_ascii_lowercase().as_str() {
            "float" => Scalar::F32,
            "double" => Scalar::F64,
            "char" => Scalar::I8,
            "unsigned_char" | "bit" => Scalar::U8,
            "short" => Scalar::I16,
            "unsigned_short" => Scalar::U16,
            "int" | "vtktypeint32" => Scalar::I32,
            "unsigned_int" | "vtktypeuint32" => Scalar::U32,
            "long" | "vtkidtype" | "vtktypeint64" => Scalar::I64,
            "unsigned_long" | "vtktypeuint64" => Scalar::U64,
            other => anyhow::bail!("VTK data type {other:?} is not a number type"),
        })
    }

    fn size(self) -> usize {
        match self {
            Scalar::I8 | Scalar::U8 => 1,
            Scalar::I16 | Scalar::U16 => 2,
            Scalar::F32 | Scalar::I32 | Scalar::U32 => 4,
            Scalar::F64 | Scalar::I64 | Scalar::U64 => 8,
        }
    }

    /// Decodes one big-endian value (`b` has exactly [`Scalar::size`] bytes).
    fn decode(self, b: &[u8]) -> f64 {
        let a = |n: usize| -> [u8; 8] {
            let mut out = [0u8; 8];
            out[..n].copy_from_slice(&b[..n]);
            out
        };
        let [b0, b1, b2, b3, b4, b5, b6, b7] = a(self.size());
        match self {
            Scalar::F32 => f32::from_be_bytes([b0, b1, b2, b3]).into(),
            Scalar::F64 => f64::from_be_bytes([b0, b1, b2, b3, b4, b5, b6, b7]),
            Scalar::I8 => i8::from_be_bytes([b0]).into(),
            Scalar::U8 => b0.into(),
            Scalar::I16 => i16::from_be_bytes([b0, b1]).into(),
            Scalar::U16 => u16::from_be_bytes([b0, b1]).into(),
            Scalar::I32 => i32::from_be_bytes([b0, b1, b2, b3]).into(),
            Scalar::U32 => u32::from_be_bytes([b0, b1, b2, b3]).into(),
            Scalar::I64 => i64::from_be_bytes([b0, b1, b2, b3, b4, b5, b6, b7]) as f64,
            Scalar::U64 => u64::from_be_bytes([b0, b1, b2, b3, b4, b5, b6, b7]) as f64,
        }
    }
}

/// The cells of one section as point indices: `starts[c]..starts[c + 1]` in `indices`.
struct Cells {
    indices: Vec<u32>,
    starts: Vec<usize>,
}

impl Cells {
    fn for_each(&self, mut f: impl FnMut(&[u32])) {
        for w in self.starts.windows(2) {
            f(&self.indices[w[0]..w[1]]);
        }
    }
}

/// A cursor over the file. Section headers are text lines; data is text numbers (ASCII) or
/// big-endian binary values that start right after the header line's newline.
struct Reader<'a> {
    bytes: &'a [u8],
    at: usize,
    binary: bool,
}

impl<'a> Reader<'a> {
    fn rest(&self) -> &'a [u8] {
        &self.bytes[self.at..]
    }

    /// The next line (without its `\n`/`\r\n`), as text.
    fn line(&mut self) -> anyhow::Result<&'a str> {
        let rest = self.rest();
        if rest.is_empty() {
            anyhow::bail!("VTK file ends in its header (truncated)");
        }
        let end = rest.iter().position(|&b| b == b'\n').unwrap_or(rest.len());
        self.at += (end + 1).min(rest.len());
        let line = &rest[..end];
        let line = line.strip_suffix(b"\r").unwrap_or(line);
        Ok(std::str::from_utf8(line).unwrap_or(""))
    }

    /// The next line that is not blank; an error at the end of the file.
    fn keyword_line(&mut self) -> anyhow::Result<&'a str> {
        self.next_keyword_line()?
            .ok_or_else(|| anyhow::anyhow!("VTK file ends in its header (truncated)"))
    }

    /// The next line that is not blank, or `None` at the end of the file.
    fn next_keyword_line(&mut self) -> anyhow::Result<Option<&'a str>> {
        let skip = self
            .rest()
            .iter()
            .take_while(|b| b.is_ascii_whitespace())
            .count();
        self.at += skip;
        if self.rest().is_empty() {
            return Ok(None);
        }
        let start = self.at;
        let line = self.line()?;
        if line.trim().is_empty() || !line.is_ascii() {
            let shown = String::from_utf8_lossy(&self.bytes[start..self.at.min(start + 40)]);
            anyhow::bail!("VTK: expected a section keyword at byte {start}, found {shown:?}");
        }
        Ok(Some(line))
    }

    /// Skips a `METADATA` block: lines up to and including the first blank one.
    fn skip_metadata(&mut self) {
        while !self.rest().is_empty() {
            match self.line() {
                Ok(line) if line.trim().is_empty() => return,
                Ok(_) => {}
                Err(_) => return,
            }
        }
    }

    /// `n` numbers of type `scalar`, checked against the bytes left before allocating.
    fn numbers(&mut self, n: usize, scalar: Scalar, what: &str) -> anyhow::Result<Vec<f64>> {
        // Binary: exactly `size` bytes each; ASCII: at least one digit and one separator each.
        let per_value = if self.binary { scalar.size() } else { 2 };
        let needed = n.saturating_mul(per_value);
        let left = self.rest().len();
        // The last ASCII value may end the file without a separator.
        if needed > left + usize::from(!self.binary) {
            anyhow::bail!(
                "VTK {what}: {n} values need at least {needed} bytes, but only {left} are left (truncated or a wrong count)"
            );
        }
        let mut out = Vec::with_capacity(n);
        if self.binary {
            let size = scalar.size();
            let data = &self.rest()[..n * size];
            out.extend(data.chunks_exact(size).map(|b| scalar.decode(b)));
            self.at += n * size;
        } else {
            for k in 0..n {
                let word = self.ascii_word().ok_or_else(|| {
                    anyhow::anyhow!("VTK {what}: the file ends after {k} of {n} values")
                })?;
                let value: f64 = word.parse().map_err(|_| {
                    anyhow::anyhow!("VTK {what}: value {} {word:?} is not a number", k + 1)
                })?;
                out.push(value);
            }
        }
        Ok(out)
    }

    /// The next whitespace-separated word of an ASCII section.
    fn ascii_word(&mut self) -> Option<&'a str> {
        let rest = self.rest();
        let skip = rest.iter().take_while(|b| b.is_ascii_whitespace()).count();
        let len = rest[skip..]
            .iter()
            .take_while(|b| !b.is_ascii_whitespace())
            .count();
        if len == 0 {
            return None;
        }
        self.at += skip + len;
        std::str::from_utf8(&rest[skip..skip + len]).ok()
    }

    /// Integers that must be non-negative indices or counts.
    fn indices(&mut self, n: usize, scalar: Scalar, what: &str) -> anyhow::Result<Vec<u32>> {
        self.numbers(n, scalar, what)?
            .into_iter()
            .enumerate()
            .map(|(k, v)| {
                if v.fract() == 0.0 && (0.0..=f64::from(u32::MAX)).contains(&v) {
                    Ok(v as u32)
                } else {
                    Err(anyhow::anyhow!(
                        "VTK {what}: value {} ({v}) is not an index",
                        k + 1
                    ))
                }
            })
            .collect()
    }

    /// A cell section whose header said `cells` and `size`: the legacy layout (`size` integers),
    /// or the VTK 5 layout (`OFFSETS` with `cells` entries, `CONNECTIVITY` with `size`).
    fn cells(&mut self, cells: usize, size: usize, what: &str) -> anyhow::Result<Cells> {
        if self.peek_keyword("OFFSETS") {
            let offsets_line = self.keyword_line()?;
            let scalar = Scalar::parse(offsets_line.split_ascii_whitespace().nth(1).unwrap_or(""))?;
            let offsets = self.indices(cells, scalar, what)?;
            let line = self.keyword_line()?;
            let mut words = line.split_ascii_whitespace();
            if !words
                .next()
                .is_some_and(|w| w.eq_ignore_ascii_case("CONNECTIVITY"))
            {
                anyhow::bail!("VTK {what}: OFFSETS without CONNECTIVITY");
            }
            let scalar = Scalar::parse(words.next().unwrap_or(""))?;
            let indices = self.indices(size, scalar, what)?;
            let mut starts = Vec::with_capacity(offsets.len());
            for (c, &o) in offsets.iter().enumerate() {
                let o = o as usize;
                if o > indices.len() || starts.last().is_some_and(|&s| o < s) {
                    anyhow::bail!(
                        "VTK {what}: offset {c} ({o}) is outside the connectivity or decreasing"
                    );
                }
                starts.push(o);
            }
            if starts.is_empty() {
                starts.push(0);
            }
            return Ok(Cells { indices, starts });
        }
        let list = self.indices(size, Scalar::I32, what)?;
        // Cells are at least their count, so more cells than integers cannot be.
        if cells > list.len() {
            anyhow::bail!(
                "VTK {what}: {cells} cells cannot fit in {} integers",
                list.len()
            );
        }
        let mut indices = Vec::with_capacity(list.len().saturating_sub(cells));
        let mut starts = Vec::with_capacity(cells + 1);
        starts.push(0);
        let mut at = 0usize;
        for c in 0..cells {
            let n = *list
                .get(at)
                .ok_or_else(|| anyhow::anyhow!("VTK {what}: cell {c} of {cells} is missing"))?
                as usize;
            let corners = list.get(at + 1..at + 1 + n).ok_or_else(|| {
                anyhow::anyhow!("VTK {what}: cell {c} claims {n} points past the end of the list")
            })?;
            indices.extend_from_slice(corners);
            starts.push(indices.len());
            at += 1 + n;
        }
        Ok(Cells { indices, starts })
    }

    /// True when the next non-blank line starts with `keyword` (nothing is consumed).
    fn peek_keyword(&self, keyword: &str) -> bool {
        let rest = self.rest();
        let skip = rest.iter().take_while(|b| b.is_ascii_whitespace()).count();
        rest[skip..]
            .get(..keyword.len())
            .is_some_and(|w| w.eq_ignore_ascii_case(keyword.as_bytes()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ascii_strip_alternates_winding() {
        let text = b"# vtk DataFile Version 3.0\nstrip\nASCII\nDATASET POLYDATA\nPOINTS 5 float\n\
0 0 0  1 0 0  0 1 0  1 1 0  0 2 0\nTRIANGLE_STRIPS 1 6\n5 0 1 2 3 4\n";
        let parts = parse(text).unwrap();
        assert_eq!(parts[0].triangles, vec![[0, 1, 2], [2, 1, 3], [2, 3, 4]]);
        // All three face the same way (+z).
        for t in &parts[0].triangles {
            let [a, b, c] = t.map(|i| parts[0].positions[i as usize]);
            assert!((b - a).cross(c - a).z > 0.0);
        }
    }

    #[test]
    fn ascii_polygons_are_fanned() {
        let text = b"# vtk DataFile Version 3.0\nquad\nASCII\nDATASET POLYDATA\nPOINTS 4 double\n\
0 0 0.1  1 0 0  1 1 0  0 1 0\nPOLYGONS 1 5\n4 0 1 2 3\n";
        let parts = parse(text).unwrap();
        assert_eq!(parts[0].triangles, vec![[0, 1, 2], [0, 2, 3]]);
        assert_eq!(parts[0].positions[0].z, 0.1);
    }

    #[test]
    fn vtk5_offsets_layout_lines_and_metadata() {
        let text = b"# vtk DataFile Version 5.1\nv5\nASCII\nDATASET POLYDATA\nPOINTS 4 float\n\
0 0 0 1 0 0 1 1 0 0 1 0\nMETADATA\nINFORMATION 0\n\nLINES 2 2\nOFFSETS vtktypeint64\n0 2\n\
CONNECTIVITY vtktypeint64\n0 1\nPOLYGONS 3 6\nOFFSETS vtktypeint64\n0 3 6\nCONNECTIVITY vtktypeint64\n\
0 1 2 0 2 3\nCELL_DATA 2\nSCALARS x float\n";
        let parts = parse(text).unwrap();
        assert_eq!(parts[0].triangles, vec![[0, 1, 2], [0, 2, 3]]);
    }

    #[test]
    fn cell_past_the_end_is_an_error() {
        let text = b"# vtk DataFile Version 3.0\nbad\nASCII\nDATASET POLYDATA\nPOINTS 3 float\n\
0 0 0  1 0 0  0 1 0\nPOLYGONS 1 4\n3 0 1 7\n";
        // Parses, but the index is out of range: caught by the mesh sanity check later.
        let parts = parse(text).unwrap();
        assert_eq!(parts[0].triangles, vec![[0, 1, 7]]);
        let absurd = b"# vtk DataFile Version 3.0\nbad\nASCII\nDATASET POLYDATA\nPOINTS 4000000000 float\n0 0 0\n";
        let e = format!("{:#}", parse(absurd).unwrap_err());
        assert!(e.contains("only 6 are left"), "{e}");
        let claims = b"# vtk DataFile Version 3.0\nbad\nASCII\nDATASET POLYDATA\nPOINTS 3 float\n\
0 0 0  1 0 0  0 1 0\nPOLYGONS 1 4\n9 0 1 2\n";
        let e = format!("{:#}", parse(claims).unwrap_err());
        assert!(e.contains("claims 9 points"), "{e}");
        let other = b"# vtk DataFile Version 3.0\nx\nASCII\nDATASET STRUCTURED_POINTS\n";
        let e = format!("{:#}", parse(other).unwrap_err());
        assert!(e.contains("STRUCTURED_POINTS data, not POLYDATA"), "{e}");
    }
}
