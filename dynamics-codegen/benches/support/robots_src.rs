//! The `robot!` inputs of the `robots` crate, read from its sources, for
//! the expansion bench and the `ir` example.

use std::path::{Path, PathBuf};

use proc_macro2::TokenStream;

/// The robots: source file and type name.
pub const ROBOTS: [(&str, &str); 5] = [
    ("arm3r.rs", "Arm3r"),
    ("rrp.rs", "Rrp"),
    ("mar.rs", "Mar"),
    ("urdf_robots.rs", "Ur5"),
    ("urdf_robots.rs", "Panda"),
];

/// The `robots` crate's folder (URDF paths are relative to it).
pub fn robots_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../robots")
}

/// The body of the `robot!` invocation declaring `robot <name>;` in `file`.
pub fn input(file: &str, name: &str) -> TokenStream {
    let path = robots_dir().join("src").join(file);
    let text = std::fs::read_to_string(&path).expect("a robots source file");
    let parsed = syn::parse_file(&text).expect("valid Rust");
    let header = format!("robot {name} ;");
    parsed
        .items
        .into_iter()
        .find_map(|item| match item {
            syn::Item::Macro(m) if m.mac.tokens.to_string().contains(&header) => Some(m.mac.tokens),
            _ => None,
        })
        .unwrap_or_else(|| panic!("no `robot {name};` in {}", path.display()))
}
