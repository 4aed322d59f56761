//! A crate's module tree read from its files: each module's file, child
//! modules, items, imports, and every path it writes (in `use` trees and in
//! code), following `mod` declarations from the crate root as the compiler
//! does (`x.rs` or `x/mod.rs`, `#[path]`, inline `mod x { ... }`).

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

use super::lex::{lex, Tok, Token};

/// A module's path inside its crate (empty: the crate root).
pub type ModPath = Vec<String>;

/// A path as written in a module, and where.
#[derive(Clone, Debug)]
pub struct Written {
    /// Its segments (`crate`, `self`, `super` kept; a leading `::` as `"::"`).
    pub segments: Vec<String>,
    /// The line.
    pub line: usize,
}

/// What a `use` brings into a module.
#[derive(Clone, Debug)]
pub struct Import {
    /// The name it is known by in the module; `None` for a glob.
    pub name: Option<String>,
    /// The path imported (for a glob: the module whose names come in).
    pub path: Vec<String>,
}

/// One module.
#[derive(Clone, Debug, Default)]
pub struct Module {
    /// The file it is written in (an inline module: the file holding it).
    pub file: PathBuf,
    /// Whether it is written inline (`mod x { ... }`).
    pub inline: bool,
    /// Whether it is compiled for tests only (`#[cfg(test)]`, or inside
    /// such a module).
    pub test: bool,
    /// Its child modules.
    pub children: BTreeSet<String>,
    /// The names of the items it defines.
    pub items: BTreeSet<String>,
    /// What its `use` declarations bring in.
    pub imports: Vec<Import>,
    /// Every path it writes that has at least two segments or is a `use`.
    pub paths: Vec<Written>,
}

/// A crate's modules by path.
pub type Tree = BTreeMap<ModPath, Module>;

/// Reads the crate whose root file is `root` (`src/lib.rs`, `src/main.rs`,
/// `src/bin/x.rs`).
pub fn read_crate(root: &Path) -> Result<Tree, String> {
    let mut tree = Tree::new();
    let dir = root.parent().map(Path::to_path_buf).unwrap_or_default();
    read_file(root, Vec::new(), false, &dir, &mut tree)?;
    Ok(tree)
}

fn read_file(
    file: &Path,
    path: ModPath,
    test: bool,
    child_dir: &Path,
    tree: &mut Tree,
) -> Result<(), String> {
    let text = std::fs::read_to_string(file).map_err(|e| format!("{}: {e}", file.display()))?;
    let tokens = lex(&text);
    tree.insert(
        path.clone(),
        Module {
            file: file.to_path_buf(),
            test,
            ..Module::default()
        },
    );
    read_body(&tokens, &path, file, child_dir, tree)
}

/// The index after the bracket that closes the one opened at `t[i]`.
fn after_group(t: &[Token], i: usize) -> usize {
    let mut depth = 0usize;
    let mut k = i;
    while k < t.len() {
        match t[k].tok {
            Tok::Open(_) => depth += 1,
            Tok::Close(_) => {
                depth = depth.saturating_sub(1);
                if depth == 0 {
                    return k + 1;
                }
            }
            _ => {}
        }
        k += 1;
    }
    t.len()
}

fn ident(t: &[Token], i: usize) -> Option<&str> {
    match t.get(i).map(|t| &t.tok) {
        Some(Tok::Ident(s)) => Some(s),
        _ => None,
    }
}

const ITEM_KEYWORDS: [&str; 9] = [
    "fn", "struct", "enum", "trait", "type", "const", "static", "union", "mod",
];

/// Reads the items of one module's body `t`.
fn read_body(
    t: &[Token],
    path: &ModPath,
    file: &Path,
    child_dir: &Path,
    tree: &mut Tree,
) -> Result<(), String> {
    let mut depth = 0usize;
    let mut attr_path: Option<String> = None;
    let mut attr_test = false;
    let test = tree.get(path).is_some_and(|m| m.test);
    let mut i = 0;
    while i < t.len() {
        match &t[i].tok {
            Tok::Punct('#') if depth == 0 => {
                // An attribute: `#[...]` or `#![...]`; only `path = ".."` matters.
                let open = if t.get(i + 1).map(|t| &t.tok) == Some(&Tok::Punct('!')) {
                    i + 2
                } else {
                    i + 1
                };
                if t.get(open).map(|t| &t.tok) == Some(&Tok::Open('[')) {
                    let end = after_group(t, open);
                    let words: Vec<&Tok> = t[open + 1..end - 1].iter().map(|t| &t.tok).collect();
                    let cfg_test = [
                        &Tok::Ident("cfg".into()),
                        &Tok::Open('('),
                        &Tok::Ident("test".into()),
                        &Tok::Close(')'),
                    ];
                    attr_test |= words == cfg_test;
                    if ident(t, open + 1) == Some("path") {
                        if let Some(Tok::Str(s)) = t.get(open + 3).map(|t| &t.tok) {
                            attr_path = Some(s.clone());
                        }
                    }
                    i = end;
                    continue;
                }
                i += 1;
            }
            Tok::Ident(kw) if depth == 0 && kw == "mod" => {
                let Some(name) = ident(t, i + 1).map(str::to_string) else {
                    i += 1;
                    continue;
                };
                let mut child = path.clone();
                child.push(name.clone());
                if let Some(m) = tree.get_mut(path) {
                    m.children.insert(name.clone());
                    m.items.insert(name.clone());
                }
                match t.get(i + 2).map(|t| &t.tok) {
                    Some(Tok::Open('{')) => {
                        let end = after_group(t, i + 2);
                        tree.insert(
                            child.clone(),
                            Module {
                                file: file.to_path_buf(),
                                inline: true,
                                test: test || attr_test,
                                ..Module::default()
                            },
                        );
                        let body = &t[i + 3..end.saturating_sub(1).max(i + 3)];
                        read_body(body, &child, file, &child_dir.join(&name), tree)?;
                        i = end;
                    }
                    _ => {
                        let (child_file, grand_dir) = match attr_path.take() {
                            Some(p) => {
                                // A file named by `#[path]` holds its children
                                // beside it, as a `mod.rs` does.
                                let f = file.parent().unwrap_or(Path::new("")).join(p);
                                let d = f.parent().unwrap_or(Path::new("")).to_path_buf();
                                (f, d)
                            }
                            None => {
                                let flat = child_dir.join(format!("{name}.rs"));
                                if flat.is_file() {
                                    (flat, child_dir.join(&name))
                                } else {
                                    (child_dir.join(&name).join("mod.rs"), child_dir.join(&name))
                                }
                            }
                        };
                        read_file(&child_file, child, test || attr_test, &grand_dir, tree)?;
                        i += 2;
                    }
                }
                attr_path = None;
                attr_test = false;
            }
            Tok::Ident(kw) if kw == "use" => {
                let line = t[i].line;
                let mut k = i + 1;
                let mut found = Vec::new();
                use_tree(t, &mut k, Vec::new(), &mut found);
                if let Some(m) = tree.get_mut(path) {
                    for (segments, alias, glob) in found {
                        let mut segments = segments;
                        if segments.last().map(String::as_str) == Some("self") {
                            segments.pop();
                        }
                        if depth == 0 {
                            let name = if glob {
                                None
                            } else {
                                alias.or_else(|| segments.last().cloned())
                            };
                            m.imports.push(Import {
                                name,
                                path: segments.clone(),
                            });
                        }
                        m.paths.push(Written { segments, line });
                    }
                }
                i = k;
            }
            Tok::Ident(kw) if depth == 0 && ITEM_KEYWORDS.contains(&kw.as_str()) => {
                if let (Some(name), Some(m)) = (ident(t, i + 1), tree.get_mut(path)) {
                    m.items.insert(name.to_string());
                }
                i += 1;
            }
            Tok::Ident(kw) if depth == 0 && kw == "macro_rules" => {
                if let (Some(name), Some(m)) = (ident(t, i + 2), tree.get_mut(path)) {
                    m.items.insert(name.to_string());
                }
                i += 1;
            }
            Tok::Ident(first) => {
                let continues = i > 0 && t[i - 1].tok == Tok::PathSep;
                if continues || t.get(i + 1).map(|t| &t.tok) != Some(&Tok::PathSep) {
                    i += 1;
                    continue;
                }
                let line = t[i].line;
                let mut segments = vec![first.clone()];
                let mut k = i + 1;
                while t.get(k).map(|t| &t.tok) == Some(&Tok::PathSep) {
                    match ident(t, k + 1) {
                        Some(s) => segments.push(s.to_string()),
                        None => break,
                    }
                    k += 2;
                }
                if let Some(m) = tree.get_mut(path) {
                    m.paths.push(Written { segments, line });
                }
                i = k;
            }
            Tok::Open(_) => {
                depth += 1;
                i += 1;
            }
            Tok::Close(_) => {
                depth = depth.saturating_sub(1);
                if depth == 0 {
                    attr_test = false;
                }
                i += 1;
            }
            Tok::Punct(';') if depth == 0 => {
                attr_test = false;
                i += 1;
            }
            _ => i += 1,
        }
    }
    Ok(())
}

/// Reads the `use` tree at `t[*i]` into `(path, alias, glob)` triples.
fn use_tree(
    t: &[Token],
    i: &mut usize,
    prefix: Vec<String>,
    out: &mut Vec<(Vec<String>, Option<String>, bool)>,
) {
    let mut segments = prefix;
    if t.get(*i).map(|t| &t.tok) == Some(&Tok::PathSep) {
        if segments.is_empty() {
            segments.push("::".to_string());
        }
        *i += 1;
    }
    loop {
        match t.get(*i).map(|t| &t.tok) {
            Some(Tok::Ident(s)) if s != "as" => {
                segments.push(s.clone());
                *i += 1;
            }
            Some(Tok::Punct('*')) => {
                *i += 1;
                out.push((segments, None, true));
                return;
            }
            Some(Tok::Open('{')) => {
                *i += 1;
                loop {
                    match t.get(*i).map(|t| &t.tok) {
                        None => return,
                        Some(Tok::Close('}')) => {
                            *i += 1;
                            return;
                        }
                        Some(Tok::Punct(',')) => *i += 1,
                        _ => {
                            let before = *i;
                            use_tree(t, i, segments.clone(), out);
                            if *i == before {
                                *i += 1;
                            }
                        }
                    }
                }
            }
            _ => break,
        }
        if t.get(*i).map(|t| &t.tok) == Some(&Tok::PathSep) {
            *i += 1;
        } else {
            break;
        }
    }
    let mut alias = None;
    if ident(t, *i) == Some("as") {
        alias = ident(t, *i + 1).map(str::to_string);
        *i += 2;
    }
    if !segments.is_empty() {
        out.push((segments, alias, false));
    }
}
