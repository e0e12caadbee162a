//! Every mesh file of the shared real-anatomy folder loads, and its triangle, region and
//! watertightness figures match those of an independent reader.
//!
//! The reference is the tables of `anatomy/SOURCES.md`, computed with trimesh (PLY/STL/OBJ) and
//! VTK's `vtkPolyDataReader` + `vtkTriangleFilter` (legacy VTK), with coincident vertices merged:
//! `tris` = triangles (strips expanded), `comps` = face-connected components, `watertight` =
//! every edge shared by exactly two faces. Ours: the triangles of all parts, the regions of
//! [`csg::Mesh::report`] (edge-connected components), and `report.closed`.
//!
//! Triangles and watertightness must match exactly on every file. Components match exactly on
//! every closed mesh; on 13 open SPL/HuBMAP meshes with non-manifold edges trimesh counts more
//! pieces, because it joins faces only through edges with exactly two faces while our regions
//! also join the faces around a non-manifold edge. For those the test recounts with trimesh's
//! rule (an independent union–find here) and requires that count to equal the reference, and
//! ours to be smaller. No triangle is dropped anywhere (strips have no degenerate triangles in
//! this data; VTK's triangle filter and ours expand them the same way).
//!
//! The folder is `$CUTAWAY_ANATOMY` (a relative path is taken from the workspace root, where CI
//! runs), else `../shared/anatomy` next to the workspace; when neither exists the test prints why
//! and passes without checking.

use csg::testkit::{Resource, skip};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use rayon::prelude::*;

/// The reference figures of one table row.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Expected {
    tris: usize,
    comps: usize,
    watertight: bool,
}

/// Measured figures: ours, and the component count under trimesh's rule.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Measured {
    figures: Expected,
    /// Components when only edges with exactly two faces join faces. trimesh's `split` (which
    /// made the reference `comps`) builds face adjacency from such edges only, whereas our regions
    /// also join the faces around a non-manifold edge (three or more faces), so on open,
    /// non-manifold meshes the reference can count more pieces than we do. On closed meshes the
    /// two rules coincide (every edge has two faces).
    comps_two_face_edges: usize,
    /// Regions (components with their cavities joined to them): the models the file gives.
    regions: usize,
}

fn anatomy_dir() -> Result<PathBuf, String> {
    let workspace = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    match std::env::var_os("CUTAWAY_ANATOMY") {
        Some(dir) => {
            let dir = PathBuf::from(dir);
            let candidates = if dir.is_absolute() {
                vec![dir.clone()]
            } else {
                vec![workspace.join(&dir), dir.clone()]
            };
            candidates
                .into_iter()
                .find(|c| c.join("SOURCES.md").is_file())
                .ok_or_else(|| format!("CUTAWAY_ANATOMY={} has no SOURCES.md", dir.display()))
        }
        None => {
            let dir = workspace.join("../shared/anatomy");
            if dir.join("SOURCES.md").is_file() {
                Ok(dir)
            } else {
                Err(format!(
                    "CUTAWAY_ANATOMY is unset and {} does not exist",
                    dir.display()
                ))
            }
        }
    }
}

fn cells(line: &str) -> Vec<String> {
    line.trim()
        .trim_matches('|')
        .split('|')
        .map(|c| c.trim().to_owned())
        .collect()
}

fn number(cell: &str) -> usize {
    cell.replace(',', "")
        .parse()
        .unwrap_or_else(|_| panic!("'{cell}' is not a count"))
}

/// Parses the per-folder tables: key `folder/file` or `folder/file#part`.
fn reference_table(sources: &str) -> BTreeMap<String, Expected> {
    let mut table = BTreeMap::new();
    let mut folder = String::new();
    let mut columns: Option<(usize, usize, usize)> = None;
    for line in sources.lines() {
        if let Some(heading) = line.strip_prefix("## `") {
            folder = heading
                .split('`')
                .next()
                .unwrap_or_default()
                .trim_end_matches('/')
                .to_owned();
            columns = None;
            continue;
        }
        if !line.starts_with('|') {
            columns = None;
            continue;
        }
        let row = cells(line);
        if row.first().is_some_and(|c| c == "file") {
            let at = |name: &str| row.iter().position(|c| c == name);
            columns = at("tris")
                .zip(at("comps"))
                .zip(at("watertight"))
                .map(|((t, c), w)| (t, c, w));
            continue;
        }
        let Some((tris, comps, watertight)) = columns else {
            continue;
        };
        if row[0].starts_with("---") {
            continue;
        }
        let file = row[0].trim_matches('`');
        table.insert(
            format!("{folder}/{file}"),
            Expected {
                tris: number(&row[tris]),
                comps: number(&row[comps]),
                watertight: row[watertight] == "yes",
            },
        );
    }
    table
}

/// One loaded file: each part's name and figures, and how many models it gives.
type FileFigures = (Vec<(String, Measured)>, usize);

fn measure(mesh: &csg::Mesh) -> Measured {
    let report = mesh.report();
    Measured {
        figures: Expected {
            tris: mesh.triangle_count(),
            comps: report.components,
            watertight: report.closed,
        },
        comps_two_face_edges: if report.closed {
            report.components
        } else {
            components_through_two_face_edges(mesh)
        },
        regions: report.regions,
    }
}

/// Face components joined only through edges used by exactly two faces (trimesh's rule), by
/// union–find: an implementation independent of `csg::regions`.
fn components_through_two_face_edges(mesh: &csg::Mesh) -> usize {
    let mut faces_of_edge: std::collections::HashMap<(u32, u32), Vec<usize>> = Default::default();
    for (t, tri) in mesh.triangles.iter().enumerate() {
        for k in 0..3 {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            faces_of_edge
                .entry((a.min(b), a.max(b)))
                .or_default()
                .push(t);
        }
    }
    let mut parent: Vec<usize> = (0..mesh.triangles.len()).collect();
    fn root(parent: &mut [usize], mut x: usize) -> usize {
        while parent[x] != x {
            parent[x] = parent[parent[x]];
            x = parent[x];
        }
        x
    }
    for faces in faces_of_edge.values() {
        if let [f, g] = faces[..] {
            let (rf, rg) = (root(&mut parent, f), root(&mut parent, g));
            parent[rf] = rg;
        }
    }
    (0..parent.len())
        .filter(|&t| root(&mut parent, t) == t)
        .count()
}

#[test]
fn every_anatomy_file_matches_the_independent_reader() {
    let dir = match anatomy_dir() {
        Ok(dir) => dir,
        Err(why) => return skip(Resource::Data, why),
    };
    let sources = std::fs::read_to_string(dir.join("SOURCES.md")).unwrap();
    let table = reference_table(&sources);
    assert!(
        table.len() > 100,
        "parsed only {} rows of SOURCES.md",
        table.len()
    );

    let files = cutaway::io::mesh_files(&dir).unwrap();
    let results: Vec<(String, anyhow::Result<FileFigures>)> = files
        .par_iter()
        .map(|file| {
            let key = file
                .strip_prefix(&dir)
                .unwrap()
                .to_string_lossy()
                .replace('\\', "/");
            let result = cutaway::io::read_parts(file).map(|parts| {
                let models = cutaway::io::models_of_parts(file, &parts).len();
                let measured = parts
                    .iter()
                    .map(|p| (p.name.clone(), measure(&p.mesh)))
                    .collect();
                (measured, models)
            });
            (key, result)
        })
        .collect();

    let mut problems = Vec::new();
    let mut checked_rows = 0;
    let mut expected_models = 0;
    let mut models = 0;
    let mut explained = 0;
    for (key, result) in &results {
        let (parts, model_count) = match result {
            Ok(ok) => ok,
            Err(e) => {
                problems.push(format!(
                    "{key}: does not load: {}",
                    cutaway::cli::error_line(e)
                ));
                continue;
            }
        };
        models += model_count;
        // A row per part (`file#part`) when the table lists parts, else one row for the file.
        let per_part: Vec<(&String, &Measured)> = parts.iter().map(|(n, m)| (n, m)).collect();
        let rows: Vec<(String, Measured)> = if table.contains_key(key) {
            let mut whole = Measured {
                figures: Expected {
                    tris: 0,
                    comps: 0,
                    watertight: true,
                },
                comps_two_face_edges: 0,
                regions: 0,
            };
            for (_, m) in &per_part {
                whole.figures.tris += m.figures.tris;
                whole.figures.comps += m.figures.comps;
                whole.figures.watertight &= m.figures.watertight;
                whole.comps_two_face_edges += m.comps_two_face_edges;
                whole.regions += m.regions;
            }
            vec![(key.clone(), whole)]
        } else {
            per_part
                .iter()
                .map(|(n, m)| (format!("{key}#{n}"), **m))
                .collect()
        };
        for (row, measured) in rows {
            match table.get(&row) {
                None => problems.push(format!("{row}: loaded, but SOURCES.md has no row for it")),
                Some(expected) => {
                    checked_rows += 1;
                    expected_models += measured.regions;
                    let ours = measured.figures;
                    // Triangles and watertightness must match exactly. Components too, except
                    // that on open meshes with non-manifold edges the reference (trimesh's rule,
                    // see `Measured`) may count more: then it must equal our own count under its
                    // rule, and ours may only be smaller.
                    let comps_ok = ours.comps == expected.comps
                        || (!expected.watertight
                            && measured.comps_two_face_edges == expected.comps
                            && ours.comps < expected.comps);
                    if ours.tris != expected.tris
                        || ours.watertight != expected.watertight
                        || !comps_ok
                    {
                        problems.push(format!(
                            "{row}: SOURCES.md says {expected:?}, we read {measured:?}"
                        ));
                    }
                    if ours.comps != expected.comps {
                        explained += 1;
                    }
                }
            }
        }
    }
    if checked_rows != table.len() {
        problems.push(format!(
            "{} rows of SOURCES.md were not matched by a loaded file or part",
            table.len() - checked_rows
        ));
    }
    assert!(
        problems.is_empty(),
        "{} problems:\n{}",
        problems.len(),
        problems.join("\n")
    );
    // One model per region.
    assert_eq!(models, expected_models);
    eprintln!(
        "checked {checked_rows} rows, {} files, {models} models; {explained} open meshes where non-manifold edges join pieces the reference splits",
        results.len()
    );
}

#[test]
fn reference_table_parser_reads_files_and_parts() {
    let text = "## `knee/` - Knee\n\n| file | source | tris | comps | watertight | extent |\n|---|---|---|---|---|---|\n\
| `a.stl` | a | 59,456 | 1 | yes | 1 mm |\n| `s.obj#disc` | b | 1,608 | 2 | no | 2 mm |\n\nprose\n| folder | what |\n| `x/` | y |\n";
    let table = reference_table(text);
    assert_eq!(table.len(), 2);
    assert_eq!(
        table["knee/a.stl"],
        Expected {
            tris: 59_456,
            comps: 1,
            watertight: true
        }
    );
    assert_eq!(
        table["knee/s.obj#disc"],
        Expected {
            tris: 1_608,
            comps: 2,
            watertight: false
        }
    );
}
