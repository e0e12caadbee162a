//! Paths inside a session: written relative to the session file's folder, so a session and its
//! files can move together (used by the session itself and by the image entry).

use std::path::{Component, Path, PathBuf};

/// `path` relative to `folder` when both can be made absolute and share a root; else `path` made
/// absolute (or as given).
pub fn relative_path(path: &Path, folder: &Path) -> PathBuf {
    let (Ok(path_abs), Ok(folder_abs)) = (std::path::absolute(path), std::path::absolute(folder))
    else {
        return path.to_path_buf();
    };
    let p: Vec<Component> = normalized(&path_abs);
    let f: Vec<Component> = normalized(&folder_abs);
    if p.first() != f.first() {
        return path_abs;
    }
    let common = p.iter().zip(&f).take_while(|(a, b)| a == b).count();
    let mut out = PathBuf::new();
    for _ in common..f.len() {
        out.push("..");
    }
    for c in &p[common..] {
        out.push(c.as_os_str());
    }
    out
}

/// Components with `.` dropped and `..` folded into their parent.
fn normalized(path: &Path) -> Vec<Component<'_>> {
    let mut out: Vec<Component> = Vec::new();
    for c in path.components() {
        match c {
            Component::CurDir => {}
            Component::ParentDir if matches!(out.last(), Some(Component::Normal(_))) => {
                out.pop();
            }
            other => out.push(other),
        }
    }
    out
}
