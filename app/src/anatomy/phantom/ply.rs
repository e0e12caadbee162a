//! The phantom's storage format: binary little-endian PLY with `float` positions and `uint`
//! triangle indices, written and read by this module only.
//!
//! Why a private writer and reader: the embedded scene must load without depending on the general
//! loaders in [`crate::io`], and `f32` positions keep the committed files small (`f32 -> f64` is
//! exact, so what the app sees is exactly what is stored). Any standard PLY reader opens the
//! files. The reader accepts exactly the layout the writer produces (comments aside) and checks
//! every count against the bytes present before allocating.

use anyhow::Context;
use glam::DVec3;

use csg::Mesh;

/// The header lines after the comments, with the two counts to fill in.
fn header(comment: &str, vertices: usize, triangles: usize) -> String {
    let mut h = String::from("ply\nformat binary_little_endian 1.0\n");
    for line in comment.lines() {
        h.push_str("comment ");
        h.push_str(line);
        h.push('\n');
    }
    h.push_str(&format!(
        "element vertex {vertices}\nproperty float x\nproperty float y\nproperty float z\n\
         element face {triangles}\nproperty list uchar uint vertex_indices\nend_header\n"
    ));
    h
}

/// Encodes `mesh` (positions rounded to `f32`) with `comment` lines in the header.
pub fn encode(mesh: &Mesh, comment: &str) -> Vec<u8> {
    let mut bytes = header(comment, mesh.positions.len(), mesh.triangles.len()).into_bytes();
    bytes.reserve(mesh.positions.len() * 12 + mesh.triangles.len() * 13);
    for p in &mesh.positions {
        for c in p.to_array() {
            bytes.extend_from_slice(&(c as f32).to_le_bytes());
        }
    }
    for t in &mesh.triangles {
        bytes.push(3);
        for i in t {
            bytes.extend_from_slice(&i.to_le_bytes());
        }
    }
    bytes
}

/// Parses bytes produced by [`encode`]. Errors name the problem; the caller adds the file name.
pub fn decode(bytes: &[u8]) -> anyhow::Result<Mesh> {
    const END: &[u8] = b"end_header\n";
    let end = bytes
        .windows(END.len())
        .position(|w| w == END)
        .context("not a PLY file: no end_header line")?;
    let text = std::str::from_utf8(&bytes[..end]).context("PLY header is not UTF-8")?;
    let mut lines = text.lines().filter(|l| !l.starts_with("comment"));
    let mut expect = |want: &str| -> anyhow::Result<String> {
        let line = lines.next().unwrap_or_default().trim_end().to_string();
        anyhow::ensure!(
            line.starts_with(want),
            "PLY header line {line:?} where {want:?} was expected"
        );
        Ok(line)
    };
    expect("ply")?;
    expect("format binary_little_endian 1.0")?;
    let vertices = count(&expect("element vertex ")?)?;
    expect("property float x")?;
    expect("property float y")?;
    expect("property float z")?;
    let triangles = count(&expect("element face ")?)?;
    expect("property list uchar uint vertex_indices")?;
    let body = &bytes[end + END.len()..];
    let need = vertices as u128 * 12 + triangles as u128 * 13;
    anyhow::ensure!(
        body.len() as u128 == need,
        "PLY body has {} bytes, but {vertices} vertices and {triangles} triangles need {need}",
        body.len()
    );
    let (vertex_bytes, face_bytes) = body.split_at(vertices * 12);
    let f32_at = |chunk: &[u8], i: usize| {
        f32::from_le_bytes([chunk[i], chunk[i + 1], chunk[i + 2], chunk[i + 3]])
    };
    let positions: Vec<DVec3> = vertex_bytes
        .chunks_exact(12)
        .map(|c| {
            DVec3::new(
                f32_at(c, 0) as f64,
                f32_at(c, 4) as f64,
                f32_at(c, 8) as f64,
            )
        })
        .collect();
    let mut tris = Vec::with_capacity(triangles);
    for (t, c) in face_bytes.chunks_exact(13).enumerate() {
        anyhow::ensure!(
            c[0] == 3,
            "face {t} has {} corners; only triangles are stored",
            c[0]
        );
        let u = |i: usize| u32::from_le_bytes([c[i], c[i + 1], c[i + 2], c[i + 3]]);
        tris.push([u(1), u(5), u(9)]);
    }
    Ok(Mesh::new(positions, tris)?)
}

fn count(line: &str) -> anyhow::Result<usize> {
    let word = line.split_whitespace().nth(2).unwrap_or_default();
    word.parse::<usize>()
        .with_context(|| format!("bad element count in PLY header line {line:?}"))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tetrahedron() -> Mesh {
        Mesh {
            positions: vec![
                DVec3::new(0.0, 0.0, 0.0),
                DVec3::new(1.5, 0.0, 0.0),
                DVec3::new(0.0, 2.25, 0.0),
                DVec3::new(0.0, 0.0, -3.125),
            ],
            triangles: vec![[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]],
        }
    }

    #[test]
    fn round_trip_is_exact_for_f32_values() {
        let mesh = tetrahedron();
        let bytes = encode(&mesh, "synthetic phantom\nsecond line");
        assert_eq!(decode(&bytes).expect("decodes"), mesh);
    }

    #[test]
    fn truncated_and_garbled_files_are_errors() {
        let bytes = encode(&tetrahedron(), "x");
        for cut in [0, 10, bytes.len() / 2, bytes.len() - 1] {
            assert!(decode(&bytes[..cut]).is_err(), "cut at {cut}");
        }
        let huge = String::from_utf8_lossy(&bytes)
            .replace("element vertex 4", "element vertex 4000000000");
        let huge = [
            huge.split("end_header\n")
                .next()
                .unwrap_or_default()
                .as_bytes(),
            b"end_header\n",
        ]
        .concat();
        let err = decode(&huge).expect_err("absurd count");
        assert!(err.to_string().contains("need"), "{err}");
        let mut bad_index = bytes.clone();
        let n = bad_index.len();
        bad_index[n - 4..].copy_from_slice(&99u32.to_le_bytes());
        assert!(decode(&bad_index).is_err());
    }
}
