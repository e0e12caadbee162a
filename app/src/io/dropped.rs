//! What dropping files and folders onto the window does, decided outside the GUI so the rule is
//! one function the window calls and tests check: a session opens as File → Open… opens it;
//! meshes, label volumes and folders open as File → Open does (replacing an empty scene) or are
//! added to the models already there (as File → Add does).

use std::path::{Path, PathBuf};

/// What a drop asks for.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum DropIntent {
    /// Open this session (the first session among the dropped files; the others are ignored,
    /// as one window holds one session).
    Session(PathBuf),
    /// Load these files and folders as the scene's models (the scene was empty).
    Open(Vec<PathBuf>),
    /// Add these files and folders to the models already shown.
    Add(Vec<PathBuf>),
}

/// True for a session file (`.json`, the session format's extension).
pub fn is_session_path(path: &Path) -> bool {
    path.extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("json"))
}

/// The intent of dropping `paths` on a window whose scene has no models when `scene_empty`;
/// `None` for an empty drop.
pub fn intent_of_drop(paths: Vec<PathBuf>, scene_empty: bool) -> Option<DropIntent> {
    if paths.is_empty() {
        return None;
    }
    if let Some(session) = paths.iter().find(|p| is_session_path(p)) {
        return Some(DropIntent::Session(session.clone()));
    }
    Some(if scene_empty {
        DropIntent::Open(paths)
    } else {
        DropIntent::Add(paths)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn paths(names: &[&str]) -> Vec<PathBuf> {
        names.iter().map(PathBuf::from).collect()
    }

    #[test]
    fn a_session_opens_meshes_open_or_add_and_nothing_does_nothing() {
        assert_eq!(intent_of_drop(Vec::new(), true), None);
        assert_eq!(
            intent_of_drop(paths(&["a.stl", "scan.JSON", "b.json"]), false),
            Some(DropIntent::Session(PathBuf::from("scan.JSON")))
        );
        assert_eq!(
            intent_of_drop(paths(&["knee", "a.vtk"]), true),
            Some(DropIntent::Open(paths(&["knee", "a.vtk"])))
        );
        assert_eq!(
            intent_of_drop(paths(&["labels.nrrd"]), false),
            Some(DropIntent::Add(paths(&["labels.nrrd"])))
        );
    }
}
