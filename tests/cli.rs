//! End-to-end tests of the `cutaway` command line (the contract in `../shared/CONTRACT.md`).

use std::process::Command;

fn cutaway() -> Command {
    Command::new(env!("CARGO_BIN_EXE_cutaway"))
}

#[test]
fn missing_file_is_one_error_line() {
    let out = cutaway()
        .args(["info", "/nonexistent/knee.stl", "--json"])
        .output()
        .unwrap();
    assert!(!out.status.success());
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(stderr.starts_with("error: "), "{stderr}");
    assert!(stderr.contains("/nonexistent/knee.stl"), "{stderr}");
}
