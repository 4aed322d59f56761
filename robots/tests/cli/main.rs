//! The `dynamics` program as a user runs it, one module a command:
//! `check` and `eval` (`eval.rs`), `scenario` (`scenario.rs`), `synth`
//! (`synth.rs`), `diagnose` (`diagnose.rs`) and its readable report
//! (`report.rs`); the default command here.

mod diagnose;
mod eval;
mod report;
mod scenario;
mod synth;

use std::process::Command;

/// The `dynamics` program of this crate, ready for arguments.
pub(crate) fn dynamics() -> Command {
    Command::new(env!("CARGO_BIN_EXE_dynamics"))
}

/// `name` in a temporary directory of this test run.
pub(crate) fn tmp(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("dynamics-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir.join(name)
}

#[test]
fn default_command_diagnoses_the_built_in_case() {
    let out = dynamics().output().expect("runs");
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{text}{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(text.contains("verdict: coulomb_friction j2"), "{text}");
    assert!(
        text.contains(
            "truth of the built-in case (read after the verdict): coulomb_friction at j2"
        ),
        "{text}"
    );
}
