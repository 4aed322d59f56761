//! No import circle between modules anywhere in the workspace.
//!
//! Every member crate's module tree is read from its `src/` as text
//! (`modules.rs`; comments and strings skipped, `lex.rs`), every path a
//! module writes to another module of its crate becomes an edge between the
//! two siblings under their lowest common parent, and every circle among
//! siblings is reported as a chain of files with the line that makes each
//! step (`cycles.rs`). A circle means two modules that cannot be read, tested
//! or moved one without the other; imports should go one way.

mod cycles;
mod lex;
mod modules;

use std::path::{Path, PathBuf};

use cycles::{cycles, Cycle};

/// The workspace's member directories, from the `members` list of its
/// `Cargo.toml`.
fn members(root: &Path) -> Vec<PathBuf> {
    let manifest = std::fs::read_to_string(root.join("Cargo.toml")).unwrap_or_default();
    let Some(list) = manifest
        .lines()
        .find(|l| l.trim_start().starts_with("members"))
    else {
        return Vec::new();
    };
    list.split('"')
        .skip(1)
        .step_by(2)
        .map(|m| root.join(m))
        .collect()
}

/// A crate directory's crate roots: `src/lib.rs`, `src/main.rs`,
/// `src/bin/x.rs`, `src/bin/x/main.rs`.
fn crate_roots(dir: &Path) -> Vec<PathBuf> {
    let src = dir.join("src");
    let mut roots: Vec<PathBuf> = ["lib.rs", "main.rs"]
        .iter()
        .map(|f| src.join(f))
        .filter(|p| p.is_file())
        .collect();
    if let Ok(bins) = std::fs::read_dir(src.join("bin")) {
        let mut bins: Vec<PathBuf> = bins.filter_map(|e| e.ok().map(|e| e.path())).collect();
        bins.sort();
        for b in bins {
            if b.extension().is_some_and(|e| e == "rs") {
                roots.push(b);
            } else if b.join("main.rs").is_file() {
                roots.push(b.join("main.rs"));
            }
        }
    }
    roots
}

/// The circles of every crate under the crate directories `dirs`, files
/// named relative to `base`.
fn all_cycles(dirs: &[PathBuf], base: &Path) -> Result<Vec<Cycle>, String> {
    let mut found = Vec::new();
    for dir in dirs {
        for root in crate_roots(dir) {
            let tree = modules::read_crate(&root)?;
            let name = root
                .strip_prefix(base)
                .unwrap_or(&root)
                .display()
                .to_string();
            found.extend(cycles(&name, &tree, base));
        }
    }
    Ok(found)
}

#[test]
fn no_import_circle_between_modules_in_the_workspace() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("the tests crate lies in the workspace")
        .to_path_buf();
    let dirs = members(&root);
    assert!(dirs.len() >= 5, "members of {}: {dirs:?}", root.display());
    let found = all_cycles(&dirs, &root).expect("every module file is readable");
    let text: String = found.iter().map(Cycle::to_string).collect();
    assert!(
        found.is_empty(),
        "{} import circle(s) between modules (make the imports go one way):\n{text}",
        found.len()
    );
}

/// A crate in a fresh directory under the system's temporary directory,
/// removed when dropped.
struct Fixture(PathBuf);

impl Fixture {
    fn new(name: &str, files: &[(&str, &str)]) -> Fixture {
        let dir = std::env::temp_dir().join(format!(
            "dynamics-module-graph-{name}-{}",
            std::process::id()
        ));
        let _ = std::fs::remove_dir_all(&dir);
        for (path, text) in files {
            let p = dir.join(path);
            std::fs::create_dir_all(p.parent().expect("a file has a directory"))
                .expect("temporary directory writable");
            std::fs::write(&p, text).expect("temporary file writable");
        }
        Fixture(dir)
    }

    fn cycles(&self) -> Vec<String> {
        let found = all_cycles(std::slice::from_ref(&self.0), &self.0).expect("fixture readable");
        let mut chains: Vec<String> = found
            .iter()
            .map(|c| format!("{}: {}", c.parent, c.modules.join(" -> ")))
            .collect();
        chains.sort();
        chains
    }
}

impl Drop for Fixture {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// The files both fixtures share: a root with `a` (a folder with `p`, `q`),
/// `b` and `c`.
const TREE: [(&str, &str); 3] = [
    (
        "src/lib.rs",
        "//! Root.\nmod a;\npub mod b;\n#[path = \"c_file.rs\"]\nmod c;\n",
    ),
    (
        "src/a/mod.rs",
        "mod p;\npub(crate) mod q;\npub use self::p::Thing;\npub struct Own;\n",
    ),
    ("src/a/p.rs", "pub struct Thing;\npub fn f() {}\n"),
];

#[test]
fn a_tree_without_circles_reports_none() {
    let fixture = Fixture::new(
        "acyclic",
        &[
            TREE[0],
            TREE[1],
            TREE[2],
            // Down the tree, back to the parent's items, and a test module's
            // paths (b's tests use c, which uses b): not circles.
            (
                "src/a/q.rs",
                "use super::Own;\npub fn g() { super::p::f(); let _ = crate::b::B; }\n",
            ),
            (
                "src/b.rs",
                "// crate::a::q::g() in a comment\n/* and crate::c::h() */\n\
                 pub struct B;\npub fn h() -> &'static str { \"crate::a::Own\" }\n\
                 #[cfg(test)]\nmod tests {\n    use super::*;\n    #[test]\n    fn t() { let _ = B; crate::c::f(); }\n}\n",
            ),
            ("src/c_file.rs", "use crate::{a::Thing, b::{self, B}};\n"),
        ],
    );
    assert_eq!(fixture.cycles(), Vec::<String>::new());
}

#[test]
fn every_circle_is_found_at_the_level_of_the_siblings() {
    let fixture = Fixture::new(
        "cyclic",
        &[
            TREE[0],
            TREE[1],
            TREE[2],
            // q -> p (a path in code) and p -> q (through a `use` group):
            // a circle among the children of `a`.
            ("src/a/q.rs", "pub fn g() { super::p::f(); }\n"),
            (
                "src/b.rs",
                "pub struct B;\npub fn h() { let _ = crate::a::Thing; }\n",
            ),
            // b -> a (through `a`'s re-export of `p::Thing`), a::p -> b and
            // a::p -> c (deep edges count at the root as a -> b, a -> c),
            // c -> b: circles a -> b -> a and a -> c -> b -> a at the root.
            ("src/c_file.rs", "use crate::b::B;\n"),
        ],
    );
    std::fs::write(
        fixture.0.join("src/a/p.rs"),
        "use super::{q::g, Own};\npub struct Thing;\npub fn f() { g(); let _ = crate::b::B; }\n\
         fn k() { crate::c::main(); }\n",
    )
    .expect("temporary file writable");
    assert_eq!(
        fixture.cycles(),
        ["crate: a -> b", "crate: a -> c -> b", "crate::a: p -> q",]
    );
}
