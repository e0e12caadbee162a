//! `cutaway info MESH --json`: facts about one mesh file (see `../shared/CONTRACT.md`).
//!
//! The file is read as one mesh ([`crate::io::read_mesh`]: every part welded on its own, then
//! concatenated) and described by [`csg::Mesh::report`]. `volume` is the signed enclosed volume;
//! it is meaningful only when `closed` is true.

use std::io::Write as _;
use std::path::{Path, PathBuf};

use serde::Serialize;

#[derive(Debug, clap::Args)]
pub struct InfoArgs {
    /// The mesh file (.obj, .stl, .ply, .vtk).
    pub mesh: PathBuf,
    /// Print one JSON object (see CONTRACT.md).
    #[arg(long)]
    pub json: bool,
}

/// The `info --json` object. Field order is the contract's order.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Info {
    pub vertices: usize,
    pub triangles: usize,
    pub regions: usize,
    pub closed: bool,
    pub manifold: bool,
    pub bbox_min: [f64; 3],
    pub bbox_max: [f64; 3],
    pub volume: f64,
}

/// Reads `path` and computes its [`Info`] (all the work of `cutaway info` except printing).
pub fn info(path: &Path) -> anyhow::Result<Info> {
    let mesh = crate::io::read_mesh(path)?;
    let report = mesh.report();
    let bbox = mesh.bbox();
    Ok(Info {
        vertices: report.vertices,
        triangles: report.triangles,
        regions: report.regions,
        closed: report.closed,
        manifold: report.manifold,
        bbox_min: bbox.min.to_array(),
        bbox_max: bbox.max.to_array(),
        volume: mesh.volume(),
    })
}

pub fn run(args: &InfoArgs) -> anyhow::Result<()> {
    let info = info(&args.mesh)?;
    let text = if args.json {
        format!("{}\n", serde_json::to_string(&info)?)
    } else {
        table(&args.mesh, &info)
    };
    // `print!` would panic on a closed pipe (`cutaway info … | head -0`); report it instead.
    let mut stdout = std::io::stdout().lock();
    stdout
        .write_all(text.as_bytes())
        .and_then(|()| stdout.flush())?;
    Ok(())
}

/// The human-readable form: one fact per line, names aligned.
fn table(path: &Path, info: &Info) -> String {
    let yes_no = |b: bool| if b { "yes" } else { "no" };
    let xyz = |v: [f64; 3]| format!("{} {} {}", v[0], v[1], v[2]);
    let size = [0, 1, 2].map(|k| info.bbox_max[k] - info.bbox_min[k]);
    let volume = if info.closed {
        info.volume.to_string()
    } else {
        format!("{} (not meaningful: the mesh is open)", info.volume)
    };
    let rows = [
        ("file", path.display().to_string()),
        ("vertices", info.vertices.to_string()),
        ("triangles", info.triangles.to_string()),
        ("regions", info.regions.to_string()),
        ("closed", yes_no(info.closed).to_owned()),
        ("manifold", yes_no(info.manifold).to_owned()),
        ("bbox min", xyz(info.bbox_min)),
        ("bbox max", xyz(info.bbox_max)),
        ("bbox size", xyz(size)),
        ("volume", volume),
    ];
    rows.iter()
        .map(|(name, value)| format!("{name:<10} {value}\n"))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn json_fields_are_in_contract_order() {
        let info = Info {
            vertices: 8,
            triangles: 12,
            regions: 1,
            closed: true,
            manifold: true,
            bbox_min: [0.0, 0.0, 0.0],
            bbox_max: [1.0, 2.0, 3.5],
            volume: 7.0,
        };
        assert_eq!(
            serde_json::to_string(&info).unwrap(),
            r#"{"vertices":8,"triangles":12,"regions":1,"closed":true,"manifold":true,"bbox_min":[0.0,0.0,0.0],"bbox_max":[1.0,2.0,3.5],"volume":7.0}"#
        );
        let text = table(Path::new("cube.obj"), &info);
        assert!(text.contains("triangles  12\n"), "{text}");
        assert!(text.contains("bbox size  1 2 3.5\n"), "{text}");
    }
}
