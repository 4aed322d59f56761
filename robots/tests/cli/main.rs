//! The `dynamics` program as a user runs it, one module a command or
//! option: `check` and `eval` (`eval.rs`), `scenario` (`scenario.rs`),
//! `simulate` (`simulate.rs`), `synth` (`synth.rs`), `diagnose`
//! (`diagnose.rs`) and its readable report (`report.rs`), recorded data as
//! ROS 2 bags and Parquet (`bags.rs`), `new` (`new.rs`:
//! a scaffolded crate built and run), `--set` (`set.rs`) and `--baseline`
//! (`baseline.rs`); the default command here.

mod bags;
mod baseline;
mod diagnose;
mod eval;
mod excite;
mod new;
mod report;
mod scenario;
mod set;
mod simulate;
mod synth;

use std::path::{Path, PathBuf};
use std::process::Command;

/// The `dynamics` program of this crate, ready for arguments.
pub(crate) fn dynamics() -> Command {
    Command::new(env!("CARGO_BIN_EXE_dynamics"))
}

/// `name` in a temporary directory of this test run.
pub(crate) fn tmp(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("dynamics-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir.join(name)
}

/// A fresh, empty directory for `name` in this test run.
pub(crate) fn fresh_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("dynamics-any-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir
}

/// The workspace this crate is in.
pub(crate) fn workspace() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("workspace")
        .to_path_buf()
}

/// `dynamics diagnose --robot arm3r` of the files `train` and `holdout`,
/// ready for more arguments.
pub(crate) fn diagnose_arm3r(train: &Path, holdout: &Path) -> Command {
    let mut cmd = dynamics();
    cmd.args(["diagnose", "--robot", "arm3r", "--train"])
        .arg(train)
        .arg("--holdout")
        .arg(holdout);
    cmd
}

/// Runs `cmd`, asserts that it succeeded (its output in the message if
/// not) and returns what it printed.
pub(crate) fn succeeds(cmd: &mut Command) -> String {
    let out = cmd.output().expect("runs");
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(
        out.status.success(),
        "{cmd:?} failed:\n{text}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    text
}

/// Runs `cmd`, asserts that it failed and returns its error output.
pub(crate) fn fails(cmd: &mut Command) -> String {
    let out = cmd.output().expect("runs");
    assert!(!out.status.success(), "{cmd:?} should fail");
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// Runs `cmd` and asserts that it failed with `expect` in its error
/// output.
pub(crate) fn fails_with(cmd: &mut Command, expect: &str) {
    let err = fails(cmd);
    assert!(err.contains(expect), "{err}");
}

/// The JSON document in the file at `path`.
pub(crate) fn read_json(path: &Path) -> serde_json::Value {
    let text = std::fs::read_to_string(path).expect("a JSON file");
    serde_json::from_str(&text).expect("JSON")
}

#[test]
fn default_command_diagnoses_the_built_in_case() {
    let text = succeeds(&mut dynamics());
    assert!(text.contains("verdict: coulomb_friction j2"), "{text}");
    // The compound explanation, effect by effect, with the gap it leaves.
    assert!(
        text.contains("explanation (1 effect, in the order of their gains"),
        "{text}"
    );
    assert!(text.contains("   1 coulomb_friction         j2 "), "{text}");
    assert!(
        text.contains("  with it: held-out gap above noise -"),
        "{text}"
    );
    assert!(
        text.contains(
            "truth of the built-in case (read after the verdict): coulomb_friction at j2"
        ),
        "{text}"
    );
}
