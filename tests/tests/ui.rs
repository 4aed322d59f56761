//! Compile-fail tests of `robot!`: every wrong input gives one clear error at
//! the token at fault. Grouped by the stage that rejects the input. The
//! expected messages depend on the compiler version (pinned in
//! rust-toolchain.toml); re-bless with `TRYBUILD=overwrite`.

use std::path::Path;

/// The URDF files of `tests/ui/urdf/` are read by the macro relative to the
/// crate trybuild generates (`<target>/tests/trybuild/dynamics-tests/`):
/// copy them there, under `urdf-fixtures/`.
fn install_urdf_fixtures() {
    let target = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .parent()
        .expect("CARGO_TARGET_TMPDIR is <target>/tmp");
    let dest = target.join("tests/trybuild/dynamics-tests/urdf-fixtures");
    std::fs::create_dir_all(&dest).expect("create the fixture folder");
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/ui/urdf");
    for entry in std::fs::read_dir(&src).expect("tests/ui/urdf exists") {
        let path = entry.expect("readable folder").path();
        if path.extension().is_some_and(|e| e == "urdf") {
            let name = path.file_name().expect("a file name");
            std::fs::copy(&path, dest.join(name)).expect("copy a fixture");
        }
    }
}

#[test]
fn ui() {
    install_urdf_fixtures();
    let t = trybuild::TestCases::new();
    t.compile_fail("tests/ui/parse/*.rs");
    t.compile_fail("tests/ui/model/*.rs");
    t.compile_fail("tests/ui/urdf/*.rs");
}
