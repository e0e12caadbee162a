//! The JavaScript modules a page carries: the pinned copy of three.js in `assets/three/` (see
//! its `PINNED` and `check.sh`) and the viewer's own modules in `viewer/`.
//!
//! A page opened from disk cannot fetch files, and a module built from memory (a `blob:` URL)
//! has no folder its relative imports could resolve against. So every import a module makes is
//! rewritten here, in the page's copy only, to a token `cutaway-module:<name>` naming another
//! module of [`MODULES`]; the page's loader turns each module into a `blob:` URL in the order of
//! [`MODULES`] (dependencies first) and replaces the tokens with the URLs of the modules already
//! made. The files in `assets/three/` stay byte for byte the npm package's.

/// The three.js version of the copy in `assets/three/` (kept equal to `PINNED` by a test).
pub const THREE_VERSION: &str = "0.187.0";

/// The three.js licence, shipped in every page with the code it covers.
pub const THREE_LICENSE: &str = include_str!("../../../../assets/three/LICENSE");

/// `assets/three/PINNED`: version, tarball hash and the files of the copy.
pub const PINNED: &str = include_str!("../../../../assets/three/PINNED");

/// One JavaScript module of the page.
#[derive(Debug)]
pub struct Module {
    /// The name other modules import it by (after rewriting) and the page's loader knows it by.
    pub name: &'static str,
    /// Where the source comes from: a path of `assets/three/` (the npm package's path) or of the
    /// viewer's folder.
    pub path: &'static str,
    pub source: &'static str,
    /// Each import specifier as the source writes it, and the module it stands for.
    pub imports: &'static [(&'static str, &'static str)],
}

macro_rules! three {
    ($name:literal, $path:literal, $imports:expr) => {
        Module {
            name: $name,
            path: $path,
            source: include_str!(concat!("../../../../assets/three/", $path)),
            imports: $imports,
        }
    };
}

macro_rules! viewer {
    ($name:literal, $imports:expr) => {
        Module {
            name: $name,
            path: concat!("viewer/", $name),
            source: include_str!(concat!("viewer/", $name)),
            imports: $imports,
        }
    };
}

/// What the viewer's modules import by the names three.js's documentation uses.
const THREE: (&str, &str) = ("three", "three.module.js");

/// Every module, dependencies before the modules that import them; the last one is the
/// viewer's entry point.
pub const MODULES: &[Module] = &[
    three!("three.core.js", "build/three.core.js", &[]),
    three!(
        "three.module.js",
        "build/three.module.js",
        &[("./three.core.js", "three.core.js")]
    ),
    three!(
        "BufferGeometryUtils.js",
        "examples/jsm/utils/BufferGeometryUtils.js",
        &[THREE]
    ),
    three!(
        "SkeletonUtils.js",
        "examples/jsm/utils/SkeletonUtils.js",
        &[THREE]
    ),
    three!(
        "GLTFLoader.js",
        "examples/jsm/loaders/GLTFLoader.js",
        &[
            THREE,
            ("../utils/BufferGeometryUtils.js", "BufferGeometryUtils.js"),
            ("../utils/SkeletonUtils.js", "SkeletonUtils.js"),
        ]
    ),
    three!(
        "OrbitControls.js",
        "examples/jsm/controls/OrbitControls.js",
        &[THREE]
    ),
    three!(
        "LineSegmentsGeometry.js",
        "examples/jsm/lines/LineSegmentsGeometry.js",
        &[THREE]
    ),
    three!(
        "LineMaterial.js",
        "examples/jsm/lines/LineMaterial.js",
        &[THREE]
    ),
    three!(
        "LineSegments2.js",
        "examples/jsm/lines/LineSegments2.js",
        &[
            THREE,
            ("./LineSegmentsGeometry.js", "LineSegmentsGeometry.js"),
            ("./LineMaterial.js", "LineMaterial.js"),
        ]
    ),
    viewer!(
        "shading.js",
        &[
            THREE,
            ("./LineSegments2.js", "LineSegments2.js"),
            ("./LineMaterial.js", "LineMaterial.js"),
            ("./LineSegmentsGeometry.js", "LineSegmentsGeometry.js")
        ]
    ),
    viewer!("overlays.js", &[THREE]),
    viewer!("panels.js", &[]),
    viewer!(
        "main.js",
        &[
            THREE,
            ("./GLTFLoader.js", "GLTFLoader.js"),
            ("./OrbitControls.js", "OrbitControls.js"),
            ("./shading.js", "shading.js"),
            ("./overlays.js", "overlays.js"),
            ("./panels.js", "panels.js"),
        ]
    ),
];

/// The prefix of a rewritten import specifier.
pub const TOKEN: &str = "cutaway-module:";

/// `module`'s source with every import of [`Module::imports`] rewritten to its token. Fails
/// (naming the module) when an import the table lists is not in the source, or names a module
/// that does not come before it: the copy in `assets/three/` then is not the one this table was
/// written for.
pub fn rewritten(module: &Module) -> anyhow::Result<String> {
    let position = |name: &str| MODULES.iter().position(|m| m.name == name);
    let own = position(module.name).unwrap_or(MODULES.len());
    let mut text = module.source.to_string();
    for &(specifier, target) in module.imports {
        if position(target).is_none_or(|p| p >= own) {
            anyhow::bail!(
                "{}: imports {target}, which is not loaded before it",
                module.path
            );
        }
        let mut found = 0;
        for quote in ['\'', '"'] {
            let written = format!("from {quote}{specifier}{quote}");
            found += text.matches(&written).count();
            text = text.replace(&written, &format!("from '{TOKEN}{target}'"));
        }
        if found == 0 {
            anyhow::bail!("{}: has no import from '{specifier}'", module.path);
        }
    }
    Ok(text)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The import and export statements left in a module after rewriting that still name a
    /// file or a bare package (the page has neither): the lines that start a statement
    /// (`import …`, `export … from`) or end a multi-line one (`} from …`).
    fn unrewritten_imports(text: &str) -> Vec<String> {
        text.lines()
            .map(str::trim_start)
            .filter(|line| {
                ["import ", "export ", "} from "]
                    .iter()
                    .any(|s| line.starts_with(s))
            })
            .filter_map(|line| {
                let at = line.find("from '").or_else(|| line.find("from \""))?;
                let specifier = &line[at + 6..];
                (!specifier.starts_with(TOKEN)).then(|| line.to_string())
            })
            .collect()
    }

    #[test]
    fn every_import_of_every_module_is_rewritten_to_a_module_loaded_before_it() {
        for module in MODULES {
            let text = rewritten(module).unwrap_or_else(|e| panic!("{e:#}"));
            let left = unrewritten_imports(&text);
            assert!(left.is_empty(), "{}: {left:?}", module.path);
        }
        assert_eq!(MODULES.last().unwrap().name, "main.js");
    }

    #[test]
    fn a_missing_import_or_a_late_dependency_is_refused() {
        let missing = Module {
            name: "main.js",
            path: "test.js",
            source: "import * as THREE from 'three';\n",
            imports: &[("./absent.js", "shading.js")],
        };
        assert!(rewritten(&missing).is_err());
        let late = Module {
            name: "three.core.js",
            path: "test.js",
            source: "import * as THREE from 'three';\n",
            imports: &[THREE],
        };
        let err = rewritten(&late).unwrap_err().to_string();
        assert!(err.contains("not loaded before"), "{err}");
        // A double-quoted import is rewritten as well.
        let double = Module {
            name: "main.js",
            path: "test.js",
            source: "import * as THREE from \"three\";\n",
            imports: &[THREE],
        };
        assert_eq!(
            rewritten(&double).unwrap(),
            "import * as THREE from 'cutaway-module:three.module.js';\n"
        );
    }

    /// `PINNED` lists exactly the files this table includes (and the licence), at the version
    /// the page names; `check.sh` compares those files with the npm tarball.
    #[test]
    fn the_module_table_and_pinned_list_the_same_files() {
        let field = |name: &str| {
            PINNED
                .lines()
                .find_map(|l| l.strip_prefix(&format!("{name} ")))
                .unwrap_or_else(|| panic!("PINNED has no {name}"))
        };
        assert_eq!(field("package"), "three");
        assert_eq!(field("version"), THREE_VERSION);
        assert!(field("integrity").starts_with("sha512-"));
        let mut listed: Vec<&str> = PINNED
            .lines()
            .skip_while(|l| *l != "files")
            .skip(1)
            .filter(|l| !l.is_empty())
            .collect();
        listed.sort_unstable();
        let mut included: Vec<&str> = MODULES
            .iter()
            .filter(|m| !m.path.starts_with("viewer/"))
            .map(|m| m.path)
            .chain(["LICENSE"])
            .collect();
        included.sort_unstable();
        assert_eq!(listed, included);
        assert!(THREE_LICENSE.starts_with("The MIT License"));
        let core = MODULES[0].source;
        assert!(
            core.contains(&format!("REVISION = '{}'", &THREE_VERSION[2..5])),
            "the core is r{}",
            &THREE_VERSION[2..5]
        );
    }
}
