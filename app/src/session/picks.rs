//! Which structures of each file a session picks, so that its reader surfaces only those: a
//! session saved from the default scene names the embedded atlas (312 labels) and picks the 59
//! the scene showed, and surfacing all of them took most of its opening time.
//!
//! A reader given the picks may return just those structures, each with its position in the
//! file's full list as `index`; [`at_position`] finds a pick in either kind of list.

use std::path::{Path, PathBuf};

use crate::io::Model;
use crate::session::format::SessionFile;

/// Per file that session entries read as structures: the positions they pick, or `None` when an
/// entry takes every structure of the file.
pub type StructurePicks = Vec<(PathBuf, Option<Vec<usize>>)>;

/// The structures each file of `file` is asked for; paths are resolved against `folder` as the
/// session's reader resolves them.
pub fn structure_picks(file: &SessionFile, folder: &Path) -> StructurePicks {
    let mut picks: StructurePicks = Vec::new();
    if file.format == crate::session::format::FORMAT_V1 {
        return picks;
    }
    for entry in file
        .models
        .iter()
        .filter(|e| !e.exact && e.region.is_none())
    {
        let source = folder.join(&entry.path);
        let slot = match picks.iter().position(|(p, _)| *p == source) {
            Some(k) => k,
            None => {
                picks.push((source, Some(Vec::new())));
                picks.len() - 1
            }
        };
        let wanted = &mut picks[slot].1;
        match (entry.structure, wanted.as_mut()) {
            (Some(k), Some(list)) if !list.contains(&k) => list.push(k),
            (Some(_), _) => {}
            (None, _) => *wanted = None,
        }
    }
    for (_, wanted) in &mut picks {
        if let Some(list) = wanted {
            list.sort_unstable();
        }
    }
    picks
}

/// The positions picked from `source`, if the session picks some rather than all.
pub fn picks_of<'a>(picks: &'a StructurePicks, source: &Path) -> Option<&'a [usize]> {
    picks
        .iter()
        .find(|(p, _)| p == source)
        .and_then(|(_, wanted)| wanted.as_deref())
}

/// The model at position `r` of a file's list, from the whole list or from the picks only: the
/// model at `r` when its `index` says so, else the one whose `index` is `r`, else (a list whose
/// models do not carry their positions) the model at `r`.
pub fn at_position(models: &[Model], r: usize) -> Option<&Model> {
    models
        .get(r)
        .filter(|m| m.index == r)
        .or_else(|| models.iter().find(|m| m.index == r))
        .or_else(|| models.get(r))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn model(index: usize) -> Model {
        Model {
            name: format!("m{index}"),
            source: PathBuf::from("a.nrrd"),
            index,
            color: None,
            group: String::new(),
            mesh: csg::Mesh::default().into(),
        }
    }

    #[test]
    fn a_pick_is_found_in_the_whole_list_and_in_the_picks_only() {
        let whole: Vec<Model> = (0..5).map(model).collect();
        let picked = vec![model(1), model(3)];
        assert_eq!(at_position(&whole, 3).unwrap().index, 3);
        assert_eq!(at_position(&picked, 3).unwrap().index, 3);
        assert_eq!(at_position(&picked, 1).unwrap().index, 1);
        assert!(at_position(&picked, 4).is_none());
        // Models that do not carry their positions are taken by position, as before.
        let unnumbered = vec![model(0), model(0)];
        assert_eq!(at_position(&unnumbered, 1).unwrap().name, "m0");
        assert!(std::ptr::eq(
            at_position(&unnumbered, 1).unwrap(),
            &unnumbered[1]
        ));
    }

    #[test]
    fn picks_gather_per_file_and_an_entry_taking_all_wins() {
        let text = r#"{"format": "cutaway-session/2", "models": [
            {"path": "atlas.nrrd", "structure": 40},
            {"path": "atlas.nrrd", "structure": 3},
            {"path": "atlas.nrrd", "structure": 40},
            {"path": "other.nrrd", "structure": 1},
            {"path": "other.nrrd"},
            {"path": "mesh.obj", "region": 2}
        ], "cutters": []}"#;
        let file = crate::session::parse(text).unwrap();
        let picks = structure_picks(&file, Path::new("/s"));
        assert_eq!(
            picks_of(&picks, Path::new("/s/atlas.nrrd")),
            Some(&[3, 40][..])
        );
        assert_eq!(picks_of(&picks, Path::new("/s/other.nrrd")), None);
        assert_eq!(picks_of(&picks, Path::new("/s/mesh.obj")), None);
    }
}
