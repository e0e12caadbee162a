//! The Khronos glTF validator, run through node from its npm package, for the tests that check
//! what `cutaway export` writes (`.glb`, and the glTF inside a web page). Included with `#[path]`
//! by the test binaries that use it; not a test target of its own.

use std::path::{Path, PathBuf};
use std::process::Command;

/// The validator's npm package folder, named by `CUTAWAY_GLTF_VALIDATOR` (`.ci/run` installs the
/// package and sets it). Set but not a package folder is a failure, not a skip.
pub fn validator_package() -> Option<PathBuf> {
    let folder = PathBuf::from(std::env::var_os("CUTAWAY_GLTF_VALIDATOR")?);
    assert!(
        folder.join("package.json").is_file(),
        "CUTAWAY_GLTF_VALIDATOR={} is not the gltf-validator package folder",
        folder.display()
    );
    Some(folder)
}

/// Runs the Khronos validator on `file`; returns its report.
pub fn validate(package: &Path, file: &Path) -> serde_json::Value {
    let script = r#"
        const validator = require(process.argv[1]);
        const bytes = new Uint8Array(require('fs').readFileSync(process.argv[2]));
        validator.validateBytes(bytes, {maxIssues: 200})
            .then(report => console.log(JSON.stringify(report)))
            .catch(error => { console.error(String(error)); process.exit(1); });
    "#;
    let output = Command::new("node")
        .arg("-e")
        .arg(script)
        .arg(package)
        .arg(file)
        .output()
        .expect("node runs");
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    serde_json::from_slice(&output.stdout).unwrap()
}
