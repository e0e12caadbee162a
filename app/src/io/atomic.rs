//! The one way Cutaway writes files: single files ([`write`], [`write_file`]) and sets of files
//! that belong together ([`OutputSet`]).
//!
//! # One file
//! The content goes to a temporary file next to the target (`.<name>.cutaway-tmp.<pid>-<n>`,
//! hidden, so directory loaders skip it), is flushed to disk, then renamed over the target. A
//! crash or an error midway leaves the old file or none, never a truncated one. The temporary file
//! is removed on error; one left by a killed process (its process id no longer runs) is removed by
//! the next write into the same folder.
//!
//! # A set of files
//! `cutaway subtract` writes `kept.obj`, `walls.obj`, `removed.obj`, `contour.obj` (and per-region
//! files under `regions/`) that describe one result; a mix of two runs would be wrong in a way no
//! single file shows. An [`OutputSet`] for folder `DIR` is written in three steps:
//!
//! 1. **Stage**: every file is written into a hidden staging folder `DIR/.cutaway-set.<pid>-<n>/`
//!    under its relative path, and flushed to disk.
//! 2. **Decide**: a marker file `.commit` listing the set's files (and the folders the set
//!    replaces wholly, see [`OutputSet::replace_folder`], and the files of an earlier set it
//!    replaces, see [`OutputSet::replace_file`]) is written into the staging folder. The set is
//!    committed from the moment this marker exists.
//! 3. **Move**: each file is renamed from the staging folder into `DIR` (an atomic rename each),
//!    files the set replaces but does not hold are removed, then the staging folder is removed.
//!
//! ## Recovery rule
//! A kill before step 2 leaves the old set and a staging folder without marker; a kill during
//! step 3 leaves a staging folder with a marker. Before anything else, [`OutputSet::begin`] runs
//! [`recover`] on `DIR`: a staging folder of a process that no longer runs is **rolled back**
//! (deleted) when it has no marker and **rolled forward** (its remaining files moved in, as
//! step 3) when it has one. So after any kill, the next write into `DIR` (or an explicit
//! [`recover`]) leaves exactly the old set or exactly the new one, and no temporary file. A
//! folder with no `.cutaway-set.*` entry holds one complete set.
//!
//! For tests of that rule, `CUTAWAY_TEST_KILL_AFTER_RENAMES=<n>` makes the process abort (as a
//! kill would) right after the n-th rename of step 3 (0: right after the marker is written).

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Component, Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

use anyhow::Context as _;

/// Marks a temporary file of [`write`]: `.<name>` + this + `.<pid>-<n>`.
const TEMP_MARK: &str = ".cutaway-tmp.";
/// Prefix of a staging folder of [`OutputSet`]: this + `<pid>-<n>`.
const STAGING_PREFIX: &str = ".cutaway-set.";
/// The marker that commits a staged set.
const COMMIT_MARKER: &str = ".commit";
/// The test hook of the module doc.
const KILL_HOOK: &str = "CUTAWAY_TEST_KILL_AFTER_RENAMES";

static COUNTER: AtomicU64 = AtomicU64::new(0);

fn unique_suffix() -> String {
    let n = COUNTER.fetch_add(1, Ordering::Relaxed);
    format!("{}-{n}", std::process::id())
}

/// Writes `path` atomically with `fill`. Errors do not name `path` (the caller adds it).
pub(crate) fn write(
    path: &Path,
    fill: impl FnOnce(&mut dyn Write) -> std::io::Result<()>,
) -> anyhow::Result<()> {
    let name = path
        .file_name()
        .ok_or_else(|| anyhow::anyhow!("not a file name"))?
        .to_string_lossy()
        .into_owned();
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    };
    remove_abandoned_temps(&dir);
    let temp = dir.join(format!(".{name}{TEMP_MARK}{}", unique_suffix()));
    let result = write_temp(&temp, fill)
        .and_then(|()| injected_failure(path))
        .and_then(|()| std::fs::rename(&temp, path));
    if result.is_err() {
        std::fs::remove_file(&temp).ok();
    }
    result.map_err(anyhow::Error::from)?;
    sync_dir(&dir);
    Ok(())
}

#[cfg(test)]
thread_local! {
    static FAIL_WRITES_TO: std::cell::RefCell<Option<PathBuf>> = const { std::cell::RefCell::new(None) };
}

/// Tests: makes [`write`] to `path` on this thread fail after its temporary file is written (as a
/// full disk would), until called with `None`.
#[cfg(test)]
pub(crate) fn fail_writes_to(path: Option<PathBuf>) {
    FAIL_WRITES_TO.with(|f| *f.borrow_mut() = path);
}

#[cfg(test)]
fn injected_failure(path: &Path) -> std::io::Result<()> {
    if FAIL_WRITES_TO.with(|f| f.borrow().as_deref() == Some(path)) {
        return Err(std::io::Error::other("injected write failure"));
    }
    Ok(())
}

#[cfg(not(test))]
fn injected_failure(_: &Path) -> std::io::Result<()> {
    Ok(())
}

/// Writes `bytes` to `path` atomically; the error names `path`.
pub fn write_file(path: &Path, bytes: &[u8]) -> anyhow::Result<()> {
    write(path, |w| w.write_all(bytes))
        .with_context(|| format!("{}: could not write", path.display()))
}

fn write_temp(
    temp: &Path,
    fill: impl FnOnce(&mut dyn Write) -> std::io::Result<()>,
) -> std::io::Result<()> {
    let file = File::create(temp)?;
    let mut writer = BufWriter::with_capacity(1 << 20, file);
    fill(&mut writer)?;
    let file = writer.into_inner().map_err(|e| e.into_error())?;
    file.sync_all()
}

/// Flushes a folder's entries (the renames into it) to disk; best effort.
fn sync_dir(dir: &Path) {
    if let Ok(d) = File::open(dir) {
        d.sync_all().ok();
    }
}

/// The process id in a name ending `<pid>-<n>`, if any.
fn owner_pid(name: &str) -> Option<u32> {
    let (pid, n) = name.rsplit_once('.')?.1.split_once('-')?;
    n.parse::<u64>().ok()?;
    pid.parse().ok()
}

/// True when `pid` is this process or a process that still runs.
fn is_alive(pid: u32) -> bool {
    pid == std::process::id() || Path::new("/proc").join(pid.to_string()).exists()
}

/// Removes temporary files of [`write`] in `dir` left by processes that no longer run.
fn remove_abandoned_temps(dir: &Path) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let name = entry.file_name();
        let name = name.to_string_lossy();
        if name.starts_with('.')
            && name.contains(TEMP_MARK)
            && owner_pid(&name).is_some_and(|pid| !is_alive(pid))
        {
            std::fs::remove_file(entry.path()).ok();
        }
    }
}

/// Checks that `relative` is a plain relative path (no `..`, no root, no hidden component), so
/// a set never writes outside its folder or over its own staging files.
fn check_relative(relative: &Path) -> anyhow::Result<()> {
    let plain = relative.components().count() > 0
        && relative.components().all(|c| match c {
            Component::Normal(name) => !name.to_string_lossy().starts_with('.'),
            _ => false,
        });
    if !plain {
        anyhow::bail!(
            "{}: not a plain relative path inside the output folder",
            relative.display()
        );
    }
    Ok(())
}

/// A set of files written into one folder so that it replaces the previous set as a whole (see
/// the module doc). Dropped without [`OutputSet::commit`], it leaves the folder as it was.
pub struct OutputSet {
    dir: PathBuf,
    staging: PathBuf,
    /// The files staged so far; behind a lock so that files are staged from several threads.
    files: std::sync::Mutex<Vec<PathBuf>>,
    replaced_folders: Vec<PathBuf>,
    /// Files of an earlier set that this set replaces: removed at commit unless the set holds them.
    replaced_files: Vec<PathBuf>,
    /// The commit marker exists: from here on the set is moved in, never rolled back.
    decided: bool,
}

impl OutputSet {
    /// Creates `dir` if needed, finishes or rolls back any interrupted set in it ([`recover`]),
    /// and opens a new staging folder.
    pub fn begin(dir: &Path) -> anyhow::Result<OutputSet> {
        std::fs::create_dir_all(dir)
            .with_context(|| format!("{}: cannot create the folder", dir.display()))?;
        recover(dir)?;
        let staging = dir.join(format!("{STAGING_PREFIX}{}", unique_suffix()));
        std::fs::create_dir(&staging)
            .with_context(|| format!("{}: cannot create a staging folder", staging.display()))?;
        Ok(OutputSet {
            dir: dir.to_path_buf(),
            staging,
            files: std::sync::Mutex::new(Vec::new()),
            replaced_folders: Vec::new(),
            replaced_files: Vec::new(),
            decided: false,
        })
    }

    /// Where `relative` will be once the set is committed (for messages).
    pub fn final_path(&self, relative: &Path) -> PathBuf {
        self.dir.join(relative)
    }

    /// Stages the file `relative` (to the set's folder) with the content `fill` writes. Errors
    /// name the final path. Files may be staged from several threads at once.
    pub fn write(
        &self,
        relative: &Path,
        fill: impl FnOnce(&mut dyn Write) -> std::io::Result<()>,
    ) -> anyhow::Result<()> {
        let final_path = self.final_path(relative);
        let context = || final_path.display().to_string();
        check_relative(relative).with_context(context)?;
        // The name is taken before the file is written, so two threads cannot both stage it.
        {
            let mut files = self.staged_files();
            if files.iter().any(|f| f == relative) {
                anyhow::bail!("{}: named twice in one output set", final_path.display());
            }
            files.push(relative.to_path_buf());
        }
        let forget = || self.staged_files().retain(|f| f != relative);
        let staged = self.staging.join(relative);
        let written = match staged.parent() {
            Some(parent) => std::fs::create_dir_all(parent),
            None => Ok(()),
        }
        .and_then(|()| write_temp(&staged, fill));
        if written.is_err() {
            forget();
        }
        written.with_context(context)
    }

    fn staged_files(&self) -> std::sync::MutexGuard<'_, Vec<PathBuf>> {
        self.files.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// Stages `bytes` as the file `relative`.
    pub fn write_bytes(&self, relative: &Path, bytes: &[u8]) -> anyhow::Result<()> {
        self.write(relative, |w| w.write_all(bytes))
    }

    /// The set replaces the folder `relative` wholly: at commit, files under it that the set does
    /// not hold (left from an earlier, larger set) are removed.
    pub fn replace_folder(&mut self, relative: &Path) -> anyhow::Result<()> {
        check_relative(relative)
            .with_context(|| self.final_path(relative).display().to_string())?;
        self.replaced_folders.push(relative.to_path_buf());
        Ok(())
    }

    /// The set replaces the file `relative` of an earlier set (one the set's writer recognises as
    /// its own, for a folder that also holds other files): at commit it is removed unless the set
    /// holds a file of that name.
    pub fn replace_file(&mut self, relative: &Path) -> anyhow::Result<()> {
        check_relative(relative)
            .with_context(|| self.final_path(relative).display().to_string())?;
        self.replaced_files.push(relative.to_path_buf());
        Ok(())
    }

    /// Commits the set: writes the marker, moves every file into place, removes what replaced
    /// folders no longer hold, removes the staging folder.
    pub fn commit(mut self) -> anyhow::Result<()> {
        let kill_after = std::env::var(KILL_HOOK)
            .ok()
            .and_then(|v| v.parse::<usize>().ok());
        self.commit_with(&mut |renamed| {
            if kill_after == Some(renamed) {
                std::process::abort();
            }
            Ok(())
        })
    }

    /// [`OutputSet::commit`] calling `after_rename(k)` after the k-th rename, and with 0 once the
    /// marker is written (tests stop there).
    fn commit_with(
        &mut self,
        after_rename: &mut dyn FnMut(usize) -> anyhow::Result<()>,
    ) -> anyhow::Result<()> {
        let mut marker = String::new();
        for f in self.staged_files().iter() {
            marker.push_str(&format!("file {}\n", f.display()));
        }
        for f in &self.replaced_folders {
            marker.push_str(&format!("folder {}\n", f.display()));
        }
        for f in &self.replaced_files {
            marker.push_str(&format!("replace {}\n", f.display()));
        }
        sync_dir(&self.staging);
        write(&self.staging.join(COMMIT_MARKER), |w| {
            w.write_all(marker.as_bytes())
        })
        .with_context(|| format!("{}: cannot commit the output set", self.dir.display()))?;
        self.decided = true;
        roll_forward(&self.dir, &self.staging, after_rename)
    }
}

impl Drop for OutputSet {
    fn drop(&mut self) {
        if !self.decided {
            std::fs::remove_dir_all(&self.staging).ok();
        }
    }
}

/// Finishes or rolls back every set in `dir` interrupted by a process that no longer runs (see
/// the module doc's recovery rule). Sets of running processes are left alone.
pub fn recover(dir: &Path) -> anyhow::Result<()> {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return Ok(());
    };
    let mut staged: Vec<PathBuf> = entries
        .flatten()
        .filter(|e| {
            let name = e.file_name();
            let name = name.to_string_lossy();
            name.starts_with(STAGING_PREFIX)
                && owner_pid(&name).is_some_and(|pid| pid != std::process::id() && !is_alive(pid))
        })
        .map(|e| e.path())
        .collect();
    staged.sort();
    for staging in staged {
        if staging.join(COMMIT_MARKER).is_file() {
            roll_forward(dir, &staging, &mut |_| Ok(())).with_context(|| {
                format!(
                    "{}: cannot finish an interrupted output set",
                    staging.display()
                )
            })?;
        } else {
            std::fs::remove_dir_all(&staging).with_context(|| {
                format!(
                    "{}: cannot remove an abandoned staging folder",
                    staging.display()
                )
            })?;
        }
    }
    remove_abandoned_temps(dir);
    Ok(())
}

/// Step 3 of the module doc: moves the staged files named by the marker into `dir` (those already
/// moved are skipped), removes files of replaced folders that the set does not hold, removes the
/// staging folder.
fn roll_forward(
    dir: &Path,
    staging: &Path,
    after_rename: &mut dyn FnMut(usize) -> anyhow::Result<()>,
) -> anyhow::Result<()> {
    let marker =
        super::bounded::read_text(&staging.join(COMMIT_MARKER), super::bounded::JSON_MAX_BYTES)?;
    let mut files = Vec::new();
    let mut folders = Vec::new();
    let mut replaced = Vec::new();
    for line in marker.lines() {
        match line.split_once(' ') {
            Some(("file", f)) => files.push(PathBuf::from(f)),
            Some(("folder", f)) => folders.push(PathBuf::from(f)),
            Some(("replace", f)) => replaced.push(PathBuf::from(f)),
            _ => anyhow::bail!("unreadable commit marker line {line:?}"),
        }
    }
    for f in files.iter().chain(&folders).chain(&replaced) {
        check_relative(f)?;
    }
    after_rename(0)?;
    for (k, relative) in files.iter().enumerate() {
        let from = staging.join(relative);
        if !from.exists() {
            continue; // moved before the interruption
        }
        let to = dir.join(relative);
        if let Some(parent) = to.parent() {
            std::fs::create_dir_all(parent)?;
        }
        std::fs::rename(&from, &to).with_context(|| to.display().to_string())?;
        after_rename(k + 1)?;
    }
    for folder in &folders {
        remove_unlisted(dir, folder, &files)?;
    }
    for relative in replaced.iter().filter(|f| !files.contains(f)) {
        match std::fs::remove_file(dir.join(relative)) {
            Err(e) if e.kind() != std::io::ErrorKind::NotFound => {
                return Err(e).with_context(|| dir.join(relative).display().to_string());
            }
            _ => {}
        }
    }
    sync_dir(dir);
    std::fs::remove_dir_all(staging)?;
    Ok(())
}

/// Removes the files under `dir/folder` that `keep` (relative to `dir`) does not list, and the
/// folders left empty.
fn remove_unlisted(dir: &Path, folder: &Path, keep: &[PathBuf]) -> anyhow::Result<()> {
    let root = dir.join(folder);
    let Ok(entries) = std::fs::read_dir(&root) else {
        return Ok(());
    };
    for entry in entries {
        let entry = entry?;
        let relative = folder.join(entry.file_name());
        if entry.file_type()?.is_dir() {
            remove_unlisted(dir, &relative, keep)?;
            std::fs::remove_dir(entry.path()).ok(); // only when left empty
        } else if !keep.contains(&relative) {
            std::fs::remove_file(entry.path())?;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn temp_dir(name: &str) -> PathBuf {
        let dir =
            std::env::temp_dir().join(format!("cutaway-atomic-{name}-{}", std::process::id()));
        std::fs::remove_dir_all(&dir).ok();
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    /// Every file under `dir` (relative, sorted) with its content.
    fn listing(dir: &Path) -> Vec<(String, String)> {
        fn walk(root: &Path, dir: &Path, out: &mut Vec<(String, String)>) {
            for entry in std::fs::read_dir(dir).unwrap().flatten() {
                let path = entry.path();
                if path.is_dir() {
                    walk(root, &path, out);
                } else {
                    let relative = path.strip_prefix(root).unwrap().display().to_string();
                    out.push((relative, std::fs::read_to_string(&path).unwrap()));
                }
            }
        }
        let mut out = Vec::new();
        walk(dir, dir, &mut out);
        out.sort();
        out
    }

    fn set_of(run: &str, regions: usize) -> Vec<(String, String)> {
        let mut files: Vec<(String, String)> = ["kept.obj", "walls.obj", "removed.obj"]
            .iter()
            .map(|f| (f.to_string(), format!("{run} {f}")))
            .collect();
        for r in 0..regions {
            files.push((format!("regions/{r}/kept.obj"), format!("{run} region {r}")));
        }
        files.sort();
        files
    }

    fn stage(dir: &Path, files: &[(String, String)]) -> OutputSet {
        let mut set = OutputSet::begin(dir).unwrap();
        set.replace_folder(Path::new("regions")).unwrap();
        for (f, content) in files {
            set.write_bytes(Path::new(f), content.as_bytes()).unwrap();
        }
        set
    }

    /// Pretends the staging folder belongs to a process that was killed (no such process id).
    fn orphan(dir: &Path) {
        for entry in std::fs::read_dir(dir).unwrap().flatten() {
            let name = entry.file_name().to_string_lossy().into_owned();
            if name.starts_with(STAGING_PREFIX) {
                let dead = dir.join(format!("{STAGING_PREFIX}{}-0", u32::MAX - 1));
                std::fs::rename(entry.path(), dead).unwrap();
            }
        }
    }

    #[test]
    fn failed_write_leaves_no_file_and_no_temp() {
        let dir = temp_dir("single");
        let target = dir.join("out.obj");
        let result = write(&target, |w| {
            w.write_all(b"partial")?;
            Err(std::io::Error::other("disk full"))
        });
        assert!(result.is_err());
        assert!(!target.exists());
        assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 0);
        write(&target, |w| w.write_all(b"whole")).unwrap();
        assert_eq!(std::fs::read(&target).unwrap(), b"whole");
        assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 1);
        // A temporary file of a killed process is removed by the next write.
        let abandoned = dir.join(format!(".out.obj{TEMP_MARK}{}-3", u32::MAX - 1));
        std::fs::write(&abandoned, b"half").unwrap();
        write_file(&target, b"again").unwrap();
        assert_eq!(listing(&dir), [("out.obj".into(), "again".into())]);
        std::fs::remove_dir_all(&dir).ok();
    }

    #[test]
    fn a_committed_set_replaces_the_old_one_wholly() {
        let dir = temp_dir("set");
        stage(&dir, &set_of("old", 3)).commit().unwrap();
        assert_eq!(listing(&dir), set_of("old", 3));
        // The new set has fewer regions: the old regions/2 must go.
        stage(&dir, &set_of("new", 2)).commit().unwrap();
        assert_eq!(listing(&dir), set_of("new", 2));
        // Dropped without commit: the old set stays, no staging folder.
        drop(stage(&dir, &set_of("dropped", 1)));
        assert_eq!(listing(&dir), set_of("new", 2));
        let set = OutputSet::begin(&dir).unwrap();
        assert!(set.write_bytes(Path::new("../escape"), b"x").is_err());
        assert!(set.write_bytes(Path::new(".hidden"), b"x").is_err());
        std::fs::remove_dir_all(&dir).ok();
    }

    #[test]
    fn replaced_files_of_an_earlier_set_go_and_other_files_stay() {
        let dir = temp_dir("replace-files");
        std::fs::write(dir.join("notes.txt"), "mine").unwrap();
        let set = OutputSet::begin(&dir).unwrap();
        set.write_bytes(Path::new("1_a.ply"), b"old a").unwrap();
        set.write_bytes(Path::new("2_b.ply"), b"old b").unwrap();
        set.commit().unwrap();
        let mut set = OutputSet::begin(&dir).unwrap();
        set.write_bytes(Path::new("1_a.ply"), b"new a").unwrap();
        set.replace_file(Path::new("1_a.ply")).unwrap();
        set.replace_file(Path::new("2_b.ply")).unwrap();
        set.replace_file(Path::new("3_gone.ply")).unwrap();
        assert!(set.replace_file(Path::new("../x.ply")).is_err());
        set.commit().unwrap();
        assert_eq!(
            listing(&dir),
            [
                ("1_a.ply".into(), "new a".into()),
                ("notes.txt".into(), "mine".into())
            ]
        );
        std::fs::remove_dir_all(&dir).ok();
    }

    /// A kill at every point of a commit: after recovery the folder holds exactly the old set or
    /// exactly the new one, and nothing else.
    #[test]
    fn a_kill_at_any_point_recovers_to_the_old_or_the_new_set() {
        let old = set_of("old", 3);
        let new = set_of("new", 1);
        // Killed while staging (no marker yet): rolled back.
        let dir = temp_dir("kill-staging");
        stage(&dir, &old).commit().unwrap();
        std::mem::forget(stage(&dir, &new));
        orphan(&dir);
        recover(&dir).unwrap();
        assert_eq!(listing(&dir), old);
        // Killed after k renames, for every k: rolled forward.
        for k in 0..=new.len() {
            let dir = temp_dir(&format!("kill-{k}"));
            stage(&dir, &old).commit().unwrap();
            let mut set = stage(&dir, &new);
            let result = set.commit_with(&mut |renamed| {
                if renamed == k {
                    anyhow::bail!("killed");
                }
                Ok(())
            });
            if k > 0 {
                assert!(result.is_err());
            }
            std::mem::forget(set);
            orphan(&dir);
            // The next set's begin recovers too; here the explicit call.
            recover(&dir).unwrap();
            assert_eq!(listing(&dir), new, "killed after {k} renames");
            std::fs::remove_dir_all(&dir).ok();
        }
    }
}
