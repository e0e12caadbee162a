//! The app's layers hold: every `crate::` path in the code of `app/src` (test code left out)
//! names a folder that the importing folder may use, by the table in `ARCHITECTURE.md`. The
//! table is read from that file, so the document and the check cannot drift apart, and a folder
//! the table does not name fails the test until someone decides where it sits.
//!
//! Test code is what `#[cfg(test)]` marks: items under it, and the files of modules declared
//! under it (`#[cfg(test)] mod tests;`). Comments and string literals are blanked before paths
//! are read, so a path in a doc comment or a message does not count.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// The folders of `app/src` and the folders each may use (its own is always allowed).
type Table = BTreeMap<String, BTreeSet<String>>;

fn workspace() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// The layer table of `ARCHITECTURE.md`: the markdown table whose header has the columns
/// `folder` and `may use`; a folder cell is `` `name/` ``, a may-use cell a comma-separated
/// list of folder names (backticks and a trailing `/` allowed) or `—` for none.
fn parse_table(markdown: &str) -> Result<Table, String> {
    let mut table = Table::new();
    let mut columns: Option<(usize, usize)> = None;
    for (number, line) in markdown.lines().enumerate() {
        let line = line.trim();
        if !line.starts_with('|') {
            if columns.is_some() && !table.is_empty() {
                break;
            }
            columns = None;
            continue;
        }
        let cells: Vec<&str> = line.trim_matches('|').split('|').map(str::trim).collect();
        if columns.is_none() {
            let find = |name: &str| cells.iter().position(|c| c.eq_ignore_ascii_case(name));
            if let (Some(folder), Some(uses)) = (find("folder"), find("may use")) {
                columns = Some((folder, uses));
            }
            continue;
        }
        let (folder_column, uses_column) = columns.unwrap();
        if cells
            .iter()
            .all(|c| c.chars().all(|ch| ch == '-' || ch == ':'))
        {
            continue;
        }
        let name = |cell: &str| {
            cell.trim()
                .trim_matches('`')
                .trim_end_matches('/')
                .to_string()
        };
        let (Some(folder), Some(uses)) = (cells.get(folder_column), cells.get(uses_column)) else {
            return Err(format!(
                "ARCHITECTURE.md line {}: a short table row",
                number + 1
            ));
        };
        let folder = name(folder);
        let uses: BTreeSet<String> = if uses.trim() == "—" || uses.trim() == "-" {
            BTreeSet::new()
        } else {
            uses.split(',')
                .map(name)
                .filter(|u| !u.is_empty())
                .collect()
        };
        if table.insert(folder.clone(), uses).is_some() {
            return Err(format!(
                "ARCHITECTURE.md line {}: `{folder}/` twice",
                number + 1
            ));
        }
    }
    if table.is_empty() {
        return Err("ARCHITECTURE.md has no table with `folder` and `may use` columns".into());
    }
    for (folder, uses) in &table {
        if let Some(unknown) = uses.iter().find(|u| !table.contains_key(*u)) {
            return Err(format!(
                "`{folder}/` may use `{unknown}`, which the table does not list"
            ));
        }
    }
    Ok(table)
}

/// The folders in a cycle of the table's "may use" relation, if any.
fn cycle(table: &Table) -> Option<Vec<String>> {
    fn visit(
        at: &str,
        table: &Table,
        path: &mut Vec<String>,
        done: &mut BTreeSet<String>,
    ) -> Option<Vec<String>> {
        if let Some(start) = path.iter().position(|p| p == at) {
            let mut found = path[start..].to_vec();
            found.push(at.to_string());
            return Some(found);
        }
        if done.contains(at) {
            return None;
        }
        path.push(at.to_string());
        for next in table.get(at).into_iter().flatten() {
            if let Some(found) = visit(next, table, path, done) {
                return Some(found);
            }
        }
        path.pop();
        done.insert(at.to_string());
        None
    }
    let mut done = BTreeSet::new();
    table
        .keys()
        .find_map(|folder| visit(folder, table, &mut Vec::new(), &mut done))
}

/// `code` with comments, string literals and character literals replaced by spaces (line breaks
/// kept, so positions still name lines). Lifetimes (`'a`) are left alone.
fn blank_comments_and_strings(code: &str) -> String {
    let chars: Vec<char> = code.chars().collect();
    let mut out = String::with_capacity(code.len());
    let mut i = 0;
    let blank = |out: &mut String, c: char| out.push(if c == '\n' { '\n' } else { ' ' });
    while i < chars.len() {
        let c = chars[i];
        let next = chars.get(i + 1).copied();
        if c == '/' && next == Some('/') {
            while i < chars.len() && chars[i] != '\n' {
                blank(&mut out, chars[i]);
                i += 1;
            }
        } else if c == '/' && next == Some('*') {
            let mut depth = 0;
            while i < chars.len() {
                if chars[i] == '/' && chars.get(i + 1) == Some(&'*') {
                    depth += 1;
                    out.push_str("  ");
                    i += 2;
                } else if chars[i] == '*' && chars.get(i + 1) == Some(&'/') {
                    depth -= 1;
                    out.push_str("  ");
                    i += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    blank(&mut out, chars[i]);
                    i += 1;
                }
            }
        } else if (c == 'r' || (c == 'b' && next == Some('r')))
            && !chars
                .get(i.wrapping_sub(1))
                .is_some_and(|p| p.is_alphanumeric() || *p == '_')
            && {
                let start = if c == 'b' { i + 2 } else { i + 1 };
                let hashes = chars[start.min(chars.len())..]
                    .iter()
                    .take_while(|h| **h == '#')
                    .count();
                chars.get(start + hashes) == Some(&'"')
            }
        {
            let start = if c == 'b' { i + 2 } else { i + 1 };
            let hashes = chars[start..].iter().take_while(|h| **h == '#').count();
            let close: Vec<char> = std::iter::once('"')
                .chain(std::iter::repeat_n('#', hashes))
                .collect();
            let mut j = start + hashes + 1;
            while j < chars.len() && !chars[j..].starts_with(&close) {
                j += 1;
            }
            let end = (j + close.len()).min(chars.len());
            for &ch in &chars[i..end] {
                blank(&mut out, ch);
            }
            i = end;
        } else if c == '"' {
            blank(&mut out, c);
            i += 1;
            while i < chars.len() && chars[i] != '"' {
                if chars[i] == '\\' {
                    blank(&mut out, chars[i]);
                    i += 1;
                }
                if i < chars.len() {
                    blank(&mut out, chars[i]);
                    i += 1;
                }
            }
            if i < chars.len() {
                blank(&mut out, chars[i]);
                i += 1;
            }
        } else if c == '\'' {
            // A character literal ('x', '\n', '\u{..}'), else a lifetime or label.
            let end = if next == Some('\\') {
                chars[i + 2..]
                    .iter()
                    .position(|&ch| ch == '\'')
                    .map(|p| i + 2 + p + 1)
            } else if chars.get(i + 2) == Some(&'\'') {
                Some(i + 3)
            } else {
                None
            };
            match end {
                Some(end) => {
                    for &ch in &chars[i..end] {
                        blank(&mut out, ch);
                    }
                    i = end;
                }
                None => {
                    out.push(c);
                    i += 1;
                }
            }
        } else {
            out.push(c);
            i += 1;
        }
    }
    out
}

/// The end (exclusive) of the item starting at `from`: the `;` that ends it at bracket depth 0,
/// or the `}` that closes its first `{`.
fn item_end(code: &[u8], from: usize) -> usize {
    let mut depth = 0i32;
    let mut i = from;
    while i < code.len() {
        match code[i] {
            b'{' | b'(' | b'[' => depth += 1,
            b'}' | b')' | b']' => {
                depth -= 1;
                if depth == 0 && code[i] == b'}' {
                    return i + 1;
                }
            }
            b';' if depth == 0 => return i + 1,
            _ => {}
        }
        i += 1;
    }
    code.len()
}

/// The names of the modules declared as `#[cfg(test)] mod name;` (files holding test code) and
/// `code` with every `#[cfg(test)]` item blanked. `code` is already free of comments and strings.
fn split_test_code(code: &str) -> (Vec<String>, String) {
    const MARK: &str = "#[cfg(test)]";
    let bytes = code.as_bytes();
    let mut kept = String::with_capacity(code.len());
    let mut test_modules = Vec::new();
    let mut at = 0;
    while let Some(found) = code[at..].find(MARK) {
        let start = at + found;
        kept.push_str(&code[at..start]);
        let end = item_end(bytes, start + MARK.len());
        let item = &code[start..end];
        // `#[cfg(test)] #[path = ...] pub(crate) mod name;`
        let words: Vec<&str> = item
            .split(|c: char| !(c.is_alphanumeric() || c == '_'))
            .filter(|w| !w.is_empty())
            .collect();
        if item.trim_end().ends_with(';')
            && let Some(m) = words.iter().position(|w| *w == "mod")
            && let Some(name) = words.get(m + 1)
        {
            test_modules.push(name.to_string());
        }
        kept.extend(item.chars().map(|c| if c == '\n' { '\n' } else { ' ' }));
        at = end;
    }
    kept.push_str(&code[at..]);
    (test_modules, kept)
}

/// Every path that follows `crate::` (use trees expanded: `crate::a::{b, c::d}` gives `a::b` and
/// `a::c::d`), with the line it starts on.
fn crate_paths(code: &str) -> Vec<(usize, Vec<String>)> {
    fn tree(code: &[char], mut i: usize, prefix: Vec<String>, out: &mut Vec<Vec<String>>) -> usize {
        let skip = |code: &[char], mut i: usize| {
            while i < code.len() && code[i].is_whitespace() {
                i += 1;
            }
            i
        };
        let mut path = prefix;
        loop {
            i = skip(code, i);
            if code.get(i) == Some(&'{') {
                i += 1;
                loop {
                    i = skip(code, i);
                    match code.get(i) {
                        Some('}') => return i + 1,
                        Some(',') => i += 1,
                        None => return i,
                        Some(_) => i = tree(code, i, path.clone(), out),
                    }
                }
            }
            let start = i;
            while i < code.len() && (code[i].is_alphanumeric() || code[i] == '_') {
                i += 1;
            }
            if i == start {
                out.push(path);
                return i;
            }
            path.push(code[start..i].iter().collect());
            let after = skip(code, i);
            if code.get(after) == Some(&':') && code.get(after + 1) == Some(&':') {
                i = after + 2;
            } else {
                out.push(path);
                return i;
            }
        }
    }
    let chars: Vec<char> = code.chars().collect();
    let mut found = Vec::new();
    let mut i = 0;
    while i + 7 <= chars.len() {
        let word_start = i == 0 || !(chars[i - 1].is_alphanumeric() || chars[i - 1] == '_');
        if word_start && chars[i..i + 7].iter().collect::<String>() == "crate::" {
            let line = chars[..i].iter().filter(|c| **c == '\n').count() + 1;
            let mut paths = Vec::new();
            i = tree(&chars, i + 7, Vec::new(), &mut paths);
            found.extend(paths.into_iter().map(|p| (line, p)));
        } else {
            i += 1;
        }
    }
    found
}

/// One source file of `app/src`: its path below `src/` and its text.
struct Source {
    path: PathBuf,
    text: String,
}

fn sources(src: &Path) -> Vec<Source> {
    fn walk(dir: &Path, src: &Path, out: &mut Vec<Source>) {
        let mut entries: Vec<PathBuf> = std::fs::read_dir(dir)
            .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
            .map(|e| e.expect("directory entry").path())
            .collect();
        entries.sort();
        for path in entries {
            if path.is_dir() {
                walk(&path, src, out);
            } else if path.extension().is_some_and(|e| e == "rs") {
                let text = std::fs::read_to_string(&path)
                    .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
                let path = path.strip_prefix(src).expect("below src").to_path_buf();
                out.push(Source { path, text });
            }
        }
    }
    let mut out = Vec::new();
    walk(src, src, &mut out);
    out
}

/// The folder (first path component) of a file below `src/`, `None` for the crate's root files.
fn folder_of(path: &Path) -> Option<String> {
    let mut parts = path.components();
    let first = parts.next()?.as_os_str().to_string_lossy().into_owned();
    parts.next().map(|_| first)
}

/// Imports that the table forbids, one line each (`file:line: folder uses other (crate::path)`),
/// and the folders the table does not name.
fn violations(files: &[Source], table: &Table) -> Vec<String> {
    // Files of modules declared under #[cfg(test)]: `a/b.rs` declaring `mod tests;` puts the
    // test code in `a/b/tests.rs` (or `a/b/tests/mod.rs`); `a/mod.rs` in `a/tests.rs`.
    let mut stripped = Vec::new();
    let mut test_dirs: BTreeSet<PathBuf> = BTreeSet::new();
    for file in files {
        let (test_modules, code) = split_test_code(&blank_comments_and_strings(&file.text));
        let parent = file.path.parent().unwrap_or(Path::new(""));
        let stem = file.path.file_stem().unwrap_or_default();
        let own_dir = if ["mod", "lib", "main"].iter().any(|s| stem == *s) {
            parent.to_path_buf()
        } else {
            parent.join(stem)
        };
        for name in test_modules {
            test_dirs.insert(own_dir.join(format!("{name}.rs")));
            test_dirs.insert(own_dir.join(&name));
        }
        stripped.push((file, code));
    }
    let is_test = |path: &Path| test_dirs.iter().any(|t| path == t || path.starts_with(t));
    let mut found = Vec::new();
    for (file, code) in stripped {
        if is_test(&file.path) {
            continue;
        }
        let Some(folder) = folder_of(&file.path) else {
            continue;
        };
        let Some(allowed) = table.get(&folder) else {
            found.push(format!(
                "{}: folder `{folder}/` is not in the layer table of ARCHITECTURE.md",
                file.path.display()
            ));
            continue;
        };
        let mut reported = BTreeSet::new();
        for (line, path) in crate_paths(&code) {
            let Some(used) = path.first() else { continue };
            if *used != folder
                && !allowed.contains(used)
                && table.contains_key(used)
                && reported.insert((line, used.clone()))
            {
                found.push(format!(
                    "{}:{line}: `{folder}/` uses `{used}/` (crate::{}), which the layer table \
                     does not allow",
                    file.path.display(),
                    path.join("::")
                ));
            }
        }
    }
    found
}

fn layer_table() -> Table {
    let path = workspace().join("ARCHITECTURE.md");
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    parse_table(&text).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn every_import_of_the_app_follows_the_layer_table() {
    let table = layer_table();
    let files = sources(&workspace().join("app/src"));
    assert!(files.len() > 100, "only {} files read", files.len());
    let found = violations(&files, &table);
    assert!(
        found.is_empty(),
        "{} imports against the layers (fix the import, or change the table in \
         ARCHITECTURE.md if the layer really is meant to use that folder):\n{}",
        found.len(),
        found.join("\n")
    );
}

#[test]
fn the_layer_table_is_acyclic_and_names_every_folder_of_the_app() {
    let table = layer_table();
    assert_eq!(cycle(&table), None, "the layer table has a cycle");
    let src = workspace().join("app/src");
    let mut folders = BTreeSet::new();
    let mut root_files = BTreeSet::new();
    for entry in std::fs::read_dir(&src).expect("app/src") {
        let entry = entry.expect("entry");
        let name = entry.file_name().to_string_lossy().into_owned();
        if entry.path().is_dir() {
            folders.insert(name);
        } else {
            root_files.insert(name);
        }
    }
    let listed: BTreeSet<String> = table.keys().cloned().collect();
    assert_eq!(
        folders, listed,
        "the folders of app/src and those of the layer table differ"
    );
    let expected: BTreeSet<String> = ["lib.rs", "main.rs", "test_support.rs"]
        .map(String::from)
        .into();
    assert_eq!(
        root_files, expected,
        "app/src's root holds folders and the crate's root files"
    );
}

/// The check itself: a planted upward import is found (in a `use` tree, a plain path and a
/// path split over lines), while test code, comments and strings are not read.
#[test]
fn a_planted_import_against_the_layers_is_found() {
    let table = parse_table(
        "| folder | may use |\n|---|---|\n| `io/` | — |\n| `scene/` | io |\n| `gui/` | scene, io |\n",
    )
    .expect("table");
    let file = |path: &str, text: &str| Source {
        path: PathBuf::from(path),
        text: text.to_string(),
    };
    let files = [
        file(
            "io/mod.rs",
            "//! Not `crate::gui` in a doc comment.\n\
             use crate::{io::x, scene::{self, Model}};\n\
             pub mod tested;\n\
             fn f() { let s = \"crate::gui::Window\"; crate::io::y(); }\n\
             fn g() -> crate::gui::panels::Panel { todo!() }\n\
             #[cfg(test)]\nmod tests { use crate::gui::App; }\n\
             #[cfg(test)]\nmod more_tests;\n",
        ),
        file("io/more_tests.rs", "use crate::gui::Everything;\n"),
        file(
            "scene/mod.rs",
            "use crate::io::Model;\nuse crate::scene::Scene;\n",
        ),
        file("gui/app.rs", "use crate::{io, scene::Scene};\n"),
        file("physics/mod.rs", "use crate::io::Model;\n"),
    ];
    let found = violations(&files, &table);
    assert_eq!(found.len(), 3, "{found:#?}");
    assert!(
        found[0].starts_with("io/mod.rs:2: `io/` uses `scene/`"),
        "{}",
        found[0]
    );
    assert!(
        found[1].starts_with("io/mod.rs:5: `io/` uses `gui/`"),
        "{}",
        found[1]
    );
    assert!(
        found[2].contains("`physics/` is not in the layer table"),
        "{}",
        found[2]
    );
    assert_eq!(cycle(&table), None);
    let cyclic =
        parse_table("| folder | may use |\n|---|---|\n| `a/` | b |\n| `b/` | a |\n").unwrap();
    assert!(cycle(&cyclic).is_some());
    assert!(parse_table("| folder | may use |\n|---|---|\n| `a/` | nowhere |\n").is_err());
}
