//! Compile-fail tests of `robot!`: every wrong input gives one clear error at
//! the token at fault. Grouped by the stage that rejects the input. The
//! expected messages depend on the compiler version (pinned in
//! rust-toolchain.toml); re-bless with `TRYBUILD=overwrite`.

#[test]
fn ui() {
    let t = trybuild::TestCases::new();
    t.compile_fail("tests/ui/parse/*.rs");
    t.compile_fail("tests/ui/model/*.rs");
}
