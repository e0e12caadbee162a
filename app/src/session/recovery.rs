//! Crash recovery and the recent-files list: the small state the window keeps between runs.
//!
//! While the window is open, the scene is autosaved as a normal session file (`crate::session`)
//! into the state folder every [`AUTOSAVE_EVERY`] when something changed. A clean exit deletes it, so a
//! recovery file found at start-up means the last run ended without one (crash, kill, power loss)
//! and the window offers to reopen it. The file records the process that owns it: a second window
//! started while the first still runs does not offer the first one's live autosave.
//!
//! The state folder is `$CUTAWAY_STATE_DIR`, else `$XDG_STATE_HOME/cutaway`, else
//! `~/.local/state/cutaway`, else a folder under the system temp dir. Tests point
//! `CUTAWAY_STATE_DIR` at a private folder.

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use anyhow::Context as _;

/// Minimum time between two autosaves.
pub const AUTOSAVE_EVERY: Duration = Duration::from_secs(20);
/// How many recent files the File menu lists.
pub const RECENT_LIMIT: usize = 10;

/// The folder holding the recovery session, its owner marker and the recent-files list.
pub fn state_dir() -> PathBuf {
    if let Some(dir) = std::env::var_os("CUTAWAY_STATE_DIR").filter(|d| !d.is_empty()) {
        return PathBuf::from(dir);
    }
    if let Some(dir) = std::env::var_os("XDG_STATE_HOME").filter(|d| !d.is_empty()) {
        return PathBuf::from(dir).join("cutaway");
    }
    if let Some(home) = std::env::var_os("HOME").filter(|d| !d.is_empty()) {
        return PathBuf::from(home).join(".local/state/cutaway");
    }
    std::env::temp_dir().join("cutaway-state")
}

/// Autosave bookkeeping for one window.
#[derive(Debug)]
pub struct Recovery {
    /// Folder of the files below; created on first save.
    dir: PathBuf,
    /// When the last autosave happened (or the window started).
    last_save: Instant,
    /// True when the scene changed since the last autosave.
    dirty: bool,
    /// True when the scene changed since it was opened or saved by the user (opening over it
    /// asks to save first).
    unsaved: bool,
}

impl Recovery {
    pub fn new(dir: PathBuf) -> Recovery {
        Recovery {
            dir,
            last_save: Instant::now(),
            dirty: false,
            unsaved: false,
        }
    }

    /// The autosaved session.
    pub fn session_path(&self) -> PathBuf {
        self.dir.join("recovery-session.json")
    }

    fn owner_path(&self) -> PathBuf {
        self.dir.join("recovery-owner.pid")
    }

    /// The recovery session left behind by a run that did not exit cleanly, if any.
    pub fn pending(&self) -> Option<PathBuf> {
        let session = self.session_path();
        if !session.is_file() {
            return None;
        }
        if let Ok(text) = std::fs::read_to_string(self.owner_path())
            && let Ok(pid) = text.trim().parse::<u32>()
            && pid != std::process::id()
            && Path::new(&format!("/proc/{pid}")).exists()
        {
            // Another window is alive and owns this autosave.
            return None;
        }
        Some(session)
    }

    /// Notes that the scene changed; the next [`Recovery::tick`] after the interval saves it.
    pub fn mark_dirty(&mut self) {
        self.dirty = true;
        self.unsaved = true;
    }

    /// The scene is as the user opened or saved it: nothing to lose by replacing it.
    pub fn mark_saved(&mut self) {
        self.unsaved = false;
    }

    /// True when the scene has changes the user has not saved.
    pub fn has_unsaved(&self) -> bool {
        self.unsaved
    }

    /// True when the scene changed and the autosave interval has passed.
    pub fn due(&self) -> bool {
        self.dirty && self.last_save.elapsed() >= AUTOSAVE_EVERY
    }

    /// Starts an autosave: records this process as the owner and returns the path the caller
    /// writes the session to.
    pub fn begin_save(&mut self) -> anyhow::Result<PathBuf> {
        self.last_save = Instant::now();
        self.dirty = false;
        std::fs::create_dir_all(&self.dir).with_context(|| format!("{}", self.dir.display()))?;
        std::fs::write(self.owner_path(), std::process::id().to_string())
            .with_context(|| format!("{}", self.owner_path().display()))?;
        Ok(self.session_path())
    }

    /// A clean exit (or the user declined recovery): the autosave is no longer needed.
    pub fn discard(&mut self) {
        let _ = std::fs::remove_file(self.session_path());
        // The autosave's cut meshes (`recovery-session.meshes/`, see `crate::session::meshes`).
        let _ = std::fs::remove_dir_all(crate::session::meshes::mesh_dir(&self.session_path()));
        let _ = std::fs::remove_file(self.owner_path());
        self.dirty = false;
    }
}

/// Recently opened files and sessions, most recent first, stored as JSON in the state folder.
#[derive(Debug, Default)]
pub struct RecentFiles {
    /// At most [`RECENT_LIMIT`] entries, no duplicates, most recent first.
    pub paths: Vec<PathBuf>,
    /// Where the list is stored; `None` keeps it in memory only.
    file: Option<PathBuf>,
}

impl RecentFiles {
    /// Reads the list from `dir/recent.json`; a missing or unreadable file gives an empty list.
    pub fn load(dir: &Path) -> RecentFiles {
        let file = dir.join("recent.json");
        let paths = std::fs::read_to_string(&file)
            .ok()
            .and_then(|text| serde_json::from_str::<Vec<PathBuf>>(&text).ok())
            .unwrap_or_default();
        let mut list = RecentFiles {
            paths: Vec::new(),
            file: Some(file),
        };
        for p in paths.into_iter().rev() {
            list.insert(p);
        }
        list
    }

    fn insert(&mut self, path: PathBuf) {
        self.paths.retain(|p| p != &path);
        self.paths.insert(0, path);
        self.paths.truncate(RECENT_LIMIT);
    }

    /// Moves `path` to the front and stores the list (errors are ignored: the list is a
    /// convenience, never a reason to fail an open).
    pub fn add(&mut self, path: &Path) {
        let path = std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf());
        self.insert(path);
        if let Some(file) = &self.file {
            if let Some(dir) = file.parent() {
                let _ = std::fs::create_dir_all(dir);
            }
            if let Ok(text) = serde_json::to_string_pretty(&self.paths) {
                let _ = crate::io::write_file(file, text.as_bytes());
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn temp_dir(name: &str) -> PathBuf {
        let dir =
            std::env::temp_dir().join(format!("cutaway-recovery-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        dir
    }

    #[test]
    fn an_autosave_left_behind_is_offered_and_a_clean_exit_removes_it() {
        let dir = temp_dir("offer");
        let mut r = Recovery::new(dir.clone());
        assert!(r.pending().is_none());
        let path = r.begin_save().unwrap();
        std::fs::write(path, "{}").unwrap();
        // Our own pid owns it: a restart of this same process (the crash case) is offered it.
        assert_eq!(r.pending(), Some(dir.join("recovery-session.json")));
        r.discard();
        assert!(r.pending().is_none());
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn a_change_is_unsaved_until_the_user_saves_and_an_autosave_does_not_count() {
        let dir = temp_dir("unsaved");
        let mut r = Recovery::new(dir.clone());
        assert!(!r.has_unsaved());
        r.mark_dirty();
        assert!(r.has_unsaved());
        r.begin_save().unwrap();
        assert!(r.has_unsaved(), "an autosave is no save of the user's");
        r.mark_saved();
        assert!(!r.has_unsaved());
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn autosave_waits_for_a_change_and_the_interval() {
        let dir = temp_dir("tick");
        let mut r = Recovery::new(dir.clone());
        assert!(!r.due());
        r.mark_dirty();
        assert!(!r.due(), "interval not yet passed");
        r.last_save = Instant::now() - AUTOSAVE_EVERY;
        assert!(r.due());
        r.begin_save().unwrap();
        assert!(!r.due(), "saved: nothing changed since");
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn recent_files_are_unique_bounded_and_persisted() {
        let dir = temp_dir("recent");
        let mut list = RecentFiles::load(&dir);
        for i in 0..(RECENT_LIMIT + 3) {
            list.add(Path::new(&format!("/data/m{i}.obj")));
        }
        list.add(Path::new("/data/m5.obj"));
        assert_eq!(list.paths.len(), RECENT_LIMIT);
        assert_eq!(list.paths[0], PathBuf::from("/data/m5.obj"));
        assert_eq!(
            list.paths.iter().filter(|p| p.ends_with("m5.obj")).count(),
            1
        );
        let again = RecentFiles::load(&dir);
        assert_eq!(again.paths, list.paths);
        let _ = std::fs::remove_dir_all(&dir);
    }
}
