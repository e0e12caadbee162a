//! Legacy VTK `POLYDATA`, ASCII and binary (big endian, as the format defines), read through
//! `vtkio`. `POLYGONS` are fan-triangulated; `TRIANGLE_STRIPS` are triangulated here: strip
//! `v0 v1 v2 v3 …` gives `(v0 v1 v2)`, `(v2 v1 v3)`, `(v2 v3 v4)`, … (every odd triangle swaps its
//! first two corners so that all keep the strip's orientation), which is what VTK's
//! `vtkTriangleFilter` produces. Degenerate strip triangles (a repeated index, used to join
//! strips) are kept, as VTK keeps them; the validation report counts them. `VERTICES` and
//! `LINES` bound no surface and are ignored.

use csg::DVec3;
use vtkio::model::{DataSet, Piece, VertexNumbers};

use super::RawPart;

pub(crate) fn parse(bytes: &[u8]) -> anyhow::Result<Vec<RawPart>> {
    if !bytes.starts_with(b"# vtk DataFile") {
        anyhow::bail!("not a legacy VTK file (it must start with '# vtk DataFile')");
    }
    let vtk =
        vtkio::Vtk::parse_legacy_be(bytes).map_err(|e| anyhow::anyhow!("malformed VTK: {e}"))?;
    let pieces = match vtk.data {
        DataSet::PolyData { pieces, .. } => pieces,
        DataSet::ImageData { .. } => anyhow::bail!("VTK STRUCTURED_POINTS data, not POLYDATA"),
        DataSet::StructuredGrid { .. } => anyhow::bail!("VTK STRUCTURED_GRID data, not POLYDATA"),
        DataSet::RectilinearGrid { .. } => anyhow::bail!("VTK RECTILINEAR_GRID data, not POLYDATA"),
        DataSet::UnstructuredGrid { .. } => {
            anyhow::bail!("VTK UNSTRUCTURED_GRID data, not POLYDATA")
        }
        DataSet::Field { .. } => anyhow::bail!("VTK FIELD data, not POLYDATA"),
    };
    let mut part = RawPart::default();
    for piece in pieces {
        let Piece::Inline(piece) = piece else {
            anyhow::bail!("VTK piece stored outside the file (not supported)");
        };
        let base = u32::try_from(part.positions.len())
            .map_err(|_| anyhow::anyhow!("too many VTK points"))?;
        let coordinates: Vec<f64> = piece
            .points
            .cast_into::<f64>()
            .ok_or_else(|| anyhow::anyhow!("VTK POINTS of a type that is not a number"))?;
        if !coordinates.len().is_multiple_of(3) {
            anyhow::bail!(
                "VTK POINTS holds {} numbers, not a multiple of 3",
                coordinates.len()
            );
        }
        part.positions.extend(
            coordinates
                .chunks_exact(3)
                .map(|p| DVec3::new(p[0], p[1], p[2])),
        );
        if let Some(polys) = &piece.polys {
            for_each_cell(polys, "POLYGONS", |cell| {
                for k in 1..cell.len().saturating_sub(1) {
                    part.triangles
                        .push(offset([cell[0], cell[k], cell[k + 1]], base)?);
                }
                Ok(())
            })?;
        }
        if let Some(strips) = &piece.strips {
            for_each_cell(strips, "TRIANGLE_STRIPS", |cell| {
                for k in 0..cell.len().saturating_sub(2) {
                    let corners = if k % 2 == 0 {
                        [cell[k], cell[k + 1], cell[k + 2]]
                    } else {
                        [cell[k + 1], cell[k], cell[k + 2]]
                    };
                    part.triangles.push(offset(corners, base)?);
                }
                Ok(())
            })?;
        }
    }
    Ok(vec![part])
}

fn offset(corners: [u64; 3], base: u32) -> anyhow::Result<[u32; 3]> {
    let mut out = [0u32; 3];
    for (o, c) in out.iter_mut().zip(corners) {
        *o = u32::try_from(c)
            .ok()
            .and_then(|c| c.checked_add(base))
            .ok_or_else(|| anyhow::anyhow!("VTK cell uses point {c}, beyond any point index"))?;
    }
    Ok(out)
}

/// Calls `f` with each cell's point indices, for both the legacy (`n i1 … in`) and the offsets
/// (`OFFSETS`/`CONNECTIVITY`, VTK 5) layouts, checking the cell structure as it goes.
fn for_each_cell(
    cells: &VertexNumbers,
    what: &str,
    mut f: impl FnMut(&[u64]) -> anyhow::Result<()>,
) -> anyhow::Result<()> {
    let mut cell = Vec::new();
    match cells {
        VertexNumbers::Legacy {
            num_cells,
            vertices,
        } => {
            let mut at = 0usize;
            for c in 0..*num_cells {
                let n = *vertices.get(at).ok_or_else(|| {
                    anyhow::anyhow!("VTK {what}: cell {c} of {num_cells} is missing")
                })? as usize;
                let corners = vertices.get(at + 1..at + 1 + n).ok_or_else(|| {
                    anyhow::anyhow!(
                        "VTK {what}: cell {c} claims {n} points past the end of the list"
                    )
                })?;
                cell.clear();
                cell.extend(corners.iter().map(|&i| u64::from(i)));
                f(&cell)?;
                at += 1 + n;
            }
        }
        VertexNumbers::XML {
            connectivity,
            offsets,
        } => {
            let mut start = 0u64;
            for (c, &end) in offsets.iter().enumerate() {
                if end == 0 && c == 0 {
                    continue; // leading zero of the VTK 5 layout
                }
                let corners = usize::try_from(start)
                    .ok()
                    .zip(usize::try_from(end).ok())
                    .and_then(|(s, e)| connectivity.get(s..e))
                    .ok_or_else(|| anyhow::anyhow!("VTK {what}: cell {c} has offsets {start}..{end} outside the connectivity"))?;
                f(corners)?;
                start = end;
            }
        }
    }
    Ok(())
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
    fn cell_past_the_end_is_an_error() {
        let text = b"# vtk DataFile Version 3.0\nbad\nASCII\nDATASET POLYDATA\nPOINTS 3 float\n\
0 0 0  1 0 0  0 1 0\nPOLYGONS 1 4\n3 0 1 7\n";
        // Parses, but the index is out of range: caught by the mesh sanity check later.
        let parts = parse(text).unwrap();
        assert_eq!(parts[0].triangles, vec![[0, 1, 7]]);
        let absurd = b"# vtk DataFile Version 3.0\nbad\nASCII\nDATASET POLYDATA\nPOINTS 4000000000 float\n0 0 0\n";
        assert!(parse(absurd).is_err());
    }
}
