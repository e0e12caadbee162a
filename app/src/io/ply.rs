//! PLY, ASCII and binary (both byte orders), read through `ply-rs-bw`; written as binary little
//! endian with `double` coordinates so that `f64` values round-trip exactly.
//!
//! Reading takes the `x`, `y`, `z` properties of the `vertex` element (any scalar type, converted
//! to `f64`; `float` converts exactly) and the `vertex_indices` (or `vertex_index`) list of the
//! `face` element (any integer type), fan-triangulating polygons. Faces of fewer than three
//! corners bound no surface and are skipped. Other elements and properties are ignored.
//! `ply-rs-bw` caps the memory it reserves from header counts, so a header that claims 4·10⁹
//! vertices in a small file fails at the end of the data instead of allocating.

use std::io::Write;

use csg::{DVec3, Mesh};
use ply_rs_bw::parser::Parser;
use ply_rs_bw::ply::{DefaultElement, Property};

use super::RawPart;

pub(crate) fn parse(bytes: &[u8]) -> anyhow::Result<Vec<RawPart>> {
    parse_marked(bytes).map(|(parts, _)| parts)
}

/// [`parse`], and the triangles (ids after fan triangulation) of the faces whose
/// [`WALL_PROPERTY`] is not 0: the incision walls of a scalpel-cut mesh this module wrote.
pub(crate) fn parse_marked(bytes: &[u8]) -> anyhow::Result<(Vec<RawPart>, Vec<u32>)> {
    let mut source = bytes;
    let ply = Parser::<DefaultElement>::new()
        .read_ply(&mut source)
        .map_err(|e| anyhow::anyhow!("malformed PLY: {e}"))?;
    let vertices = ply
        .payload
        .get("vertex")
        .ok_or_else(|| anyhow::anyhow!("PLY without a 'vertex' element"))?;
    let mut positions = Vec::with_capacity(vertices.len());
    for (v, vertex) in vertices.iter().enumerate() {
        let mut xyz = [0.0; 3];
        for (value, key) in xyz.iter_mut().zip(["x", "y", "z"]) {
            let property = vertex
                .get(key)
                .ok_or_else(|| anyhow::anyhow!("PLY vertex {v} has no '{key}' property"))?;
            *value = scalar(property).ok_or_else(|| {
                anyhow::anyhow!("PLY vertex property '{key}' is a list, not a number")
            })?;
        }
        positions.push(DVec3::from_array(xyz));
    }
    let faces = ply.payload.get("face").ok_or_else(|| {
        anyhow::anyhow!("PLY without a 'face' element (a point cloud, not a surface)")
    })?;
    let mut triangles = Vec::with_capacity(faces.len());
    let mut walls = Vec::new();
    let mut corners = Vec::new();
    for (f, face) in faces.iter().enumerate() {
        let list = face
            .get("vertex_indices")
            .or_else(|| face.get("vertex_index"))
            .ok_or_else(|| anyhow::anyhow!("PLY face {f} has no 'vertex_indices' list"))?;
        corners.clear();
        index_list(list, &mut corners).map_err(|what| anyhow::anyhow!("PLY face {f}: {what}"))?;
        let wall = face
            .get(WALL_PROPERTY)
            .and_then(scalar)
            .is_some_and(|w| w != 0.0);
        for k in 1..corners.len().saturating_sub(1) {
            if wall {
                walls.push(triangles.len() as u32);
            }
            triangles.push([corners[0], corners[k], corners[k + 1]]);
        }
    }
    let part = RawPart {
        name: None,
        positions,
        triangles,
    };
    Ok((vec![part], walls))
}

fn scalar(property: &Property) -> Option<f64> {
    Some(match *property {
        Property::Char(v) => v.into(),
        Property::UChar(v) => v.into(),
        Property::Short(v) => v.into(),
        Property::UShort(v) => v.into(),
        Property::Int(v) => v.into(),
        Property::UInt(v) => v.into(),
        Property::Float(v) => v.into(),
        Property::Double(v) => v,
        _ => return None,
    })
}

/// Appends a face's vertex indices as `u32`; negative or fractional indices are errors.
fn index_list(property: &Property, out: &mut Vec<u32>) -> Result<(), String> {
    fn push<T: Copy + TryInto<u32> + std::fmt::Display>(
        values: &[T],
        out: &mut Vec<u32>,
    ) -> Result<(), String> {
        for &v in values {
            out.push(
                v.try_into()
                    .map_err(|_| format!("vertex index {v} is negative"))?,
            );
        }
        Ok(())
    }
    match property {
        Property::ListChar(v) => push(v, out),
        Property::ListUChar(v) => push(v, out),
        Property::ListShort(v) => push(v, out),
        Property::ListUShort(v) => push(v, out),
        Property::ListInt(v) => push(v, out),
        Property::ListUInt(v) => push(v, out),
        _ => Err("'vertex_indices' is not a list of integers".to_owned()),
    }
}

/// The face property marking an incision wall (`uchar`, 1 on a wall): written only for a mesh
/// with walls, read back by [`parse_marked`]; other readers ignore a property they do not know.
pub(crate) const WALL_PROPERTY: &str = "cutaway_wall";

/// Writes binary little-endian PLY with `double` coordinates and `int` indices; the faces
/// `walls` (ascending) are marked with [`WALL_PROPERTY`] when there are any.
pub(crate) fn write_binary(w: &mut dyn Write, mesh: &Mesh, walls: &[u32]) -> std::io::Result<()> {
    let marked = !walls.is_empty();
    write!(
        w,
        "ply\nformat binary_little_endian 1.0\ncomment written by cutaway\n\
element vertex {}\nproperty double x\nproperty double y\nproperty double z\n\
element face {}\nproperty list uchar int vertex_indices\n{}end_header\n",
        mesh.positions.len(),
        mesh.triangles.len(),
        if marked {
            format!("property uchar {WALL_PROPERTY}\n")
        } else {
            String::new()
        }
    )?;
    for p in &mesh.positions {
        for c in p.to_array() {
            w.write_all(&c.to_le_bytes())?;
        }
    }
    let mut record = [0u8; 14];
    record[0] = 3;
    let size = if marked { 14 } else { 13 };
    let mut next_wall = walls.iter().peekable();
    for (t, tri) in mesh.triangles.iter().enumerate() {
        record[13] = u8::from(next_wall.next_if(|&&f| f as usize == t).is_some());
        for (k, &i) in tri.iter().enumerate() {
            // `Mesh::sanity_check` bounds indices by the vertex count, which PLY's `int` holds
            // for every mesh up to 2^31 vertices.
            let i = i32::try_from(i)
                .map_err(|_| std::io::Error::other("vertex index beyond PLY int range"))?;
            record[1 + 4 * k..5 + 4 * k].copy_from_slice(&i.to_le_bytes());
        }
        w.write_all(&record[..size])?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ascii_polygon_with_vertex_index_list_is_fanned() {
        let text = b"ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n\
element face 1\nproperty list uchar uint vertex_index\nend_header\n0 0 0\n1 0 0\n1 1 0\n0 1 0.1\n4 0 1 2 3\n";
        let parts = parse(text).unwrap();
        assert_eq!(parts[0].triangles, vec![[0, 1, 2], [0, 2, 3]]);
        assert_eq!(parts[0].positions[3].z, f64::from(0.1f32));
    }

    #[test]
    fn big_endian_binary_is_read() {
        let mut bytes = b"ply\nformat binary_big_endian 1.0\nelement vertex 3\nproperty double x\nproperty double y\nproperty double z\n\
element face 1\nproperty list uchar short vertex_indices\nend_header\n"
            .to_vec();
        for v in [0.5f64, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0] {
            bytes.extend_from_slice(&v.to_be_bytes());
        }
        bytes.push(3);
        for i in [0i16, 1, 2] {
            bytes.extend_from_slice(&i.to_be_bytes());
        }
        let parts = parse(&bytes).unwrap();
        assert_eq!(parts[0].positions[0], DVec3::new(0.5, 0.0, 0.0));
        assert_eq!(parts[0].triangles, vec![[0, 1, 2]]);
    }

    #[test]
    fn negative_index_and_absurd_count_are_errors() {
        let negative = b"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n\
element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n";
        assert!(format!("{:#}", parse(negative).unwrap_err()).contains("negative"));
        let absurd = b"ply\nformat ascii 1.0\nelement vertex 4000000000\nproperty float x\nproperty float y\nproperty float z\n\
element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n";
        assert!(parse(absurd).is_err());
    }

    /// Wall marks round-trip through the binary writer; a mesh without walls is written exactly
    /// as before (no property); an ASCII polygon marked as a wall marks all its triangles.
    #[test]
    fn wall_marks_round_trip_and_mark_every_triangle_of_a_polygon() {
        let mesh = csg::testkit::icosphere(1, 1.0);
        let walls = [2u32, 3, 17, 79];
        let mut bytes = Vec::new();
        write_binary(&mut bytes, &mesh, &walls).unwrap();
        let text = String::from_utf8_lossy(&bytes[..300]);
        assert!(text.contains("property uchar cutaway_wall"), "{text}");
        let (parts, marked) = parse_marked(&bytes).unwrap();
        assert_eq!(parts[0].triangles, mesh.triangles);
        assert_eq!(marked, walls);
        let mut plain = Vec::new();
        write_binary(&mut plain, &mesh, &[]).unwrap();
        assert!(!String::from_utf8_lossy(&plain[..300]).contains("cutaway_wall"));
        let property = format!("property uchar {WALL_PROPERTY}\n");
        assert_eq!(
            plain.len() + property.len() + mesh.triangles.len(),
            bytes.len()
        );
        assert!(parse_marked(&plain).unwrap().1.is_empty());
        let ascii = b"ply\nformat ascii 1.0\nelement vertex 5\nproperty float x\nproperty float y\nproperty float z\n\
element face 2\nproperty list uchar uint vertex_indices\nproperty uchar cutaway_wall\nend_header\n\
0 0 0\n1 0 0\n1 1 0\n0 1 0\n2 2 0\n3 1 4 2 0\n4 0 1 2 3 1\n";
        let (parts, marked) = parse_marked(ascii).unwrap();
        assert_eq!(parts[0].triangles.len(), 3);
        assert_eq!(marked, vec![1, 2]);
    }
}
