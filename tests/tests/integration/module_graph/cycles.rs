//! The edges between sibling modules and the circles among them.
//!
//! A path written in module `m` is resolved as the compiler would to the
//! deepest module of the crate it reaches: `crate::`, `self::`, `super::`,
//! a child module's name, or a name `m` imports; through a module's own
//! imports and glob imports (a parent re-exporting `Item` from its child `y`
//! makes `super::Item`, written in a sibling `x`, an edge `x -> y`). An edge
//! `a::x::.. -> a::y::..` is an edge `x -> y` among the children of `a`, their
//! lowest common parent. A path to one's own ancestor or descendant is no
//! edge: a child's `super::Item` depends on the parent that declares it,
//! which is not a circle. Test modules (`#[cfg(test)]`) have no edges: nothing
//! depends on them, so a unit test that builds its input with a neighbour
//! (`mimic`'s tests calling `build`) closes no circle in the code it tests.

use std::collections::{BTreeMap, BTreeSet};
use std::fmt;

use super::modules::{ModPath, Tree};

/// Where an edge was seen first.
#[derive(Clone, Debug)]
pub struct Evidence {
    /// The file and line of the path.
    pub place: String,
    /// The path as written.
    pub written: String,
}

/// Edges among the children of one module: `(from, to) -> evidence`.
type Level = BTreeMap<(String, String), Evidence>;

/// A circle among sibling modules.
#[derive(Clone, Debug)]
pub struct Cycle {
    /// The crate (its directory in the workspace).
    pub krate: String,
    /// The common parent (`crate`, or `crate::a::b`).
    pub parent: String,
    /// The siblings in order; the last one leads back to the first.
    pub modules: Vec<String>,
    /// Each sibling's file.
    pub files: Vec<String>,
    /// The reference that makes each step.
    pub evidence: Vec<Evidence>,
}

impl fmt::Display for Cycle {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mut chain = self.modules.clone();
        chain.push(self.modules[0].clone());
        writeln!(
            f,
            "{}: in {}: {}",
            self.krate,
            self.parent,
            chain.join(" -> ")
        )?;
        for (k, e) in self.evidence.iter().enumerate() {
            let next = &self.files[(k + 1) % self.files.len()];
            writeln!(
                f,
                "    {} -> {}   ({}: `{}`)",
                self.files[k], next, e.place, e.written
            )?;
        }
        Ok(())
    }
}

/// The module a path written in `m` reaches, `None` when it leaves the crate.
fn resolve(tree: &Tree, m: &ModPath, segments: &[String], hops: usize) -> Option<ModPath> {
    if hops > 8 || segments.is_empty() {
        return None;
    }
    let mut k = 0;
    let mut cur: ModPath = match segments[0].as_str() {
        "::" => return None,
        "crate" => {
            k = 1;
            Vec::new()
        }
        "self" => {
            k = 1;
            m.clone()
        }
        "super" => {
            let mut c = m.clone();
            while segments.get(k).map(String::as_str) == Some("super") {
                c.pop()?;
                k += 1;
            }
            c
        }
        first => {
            let module = tree.get(m)?;
            if module.children.contains(first) {
                k = 1;
                let mut c = m.clone();
                c.push(first.to_string());
                c
            } else {
                let import = module
                    .imports
                    .iter()
                    .find(|i| i.name.as_deref() == Some(first))?;
                k = 1;
                resolve(tree, m, &import.path, hops + 1)?
            }
        }
    };
    // Walk the rest: modules down, then the first name that is not a module.
    while let Some(seg) = segments.get(k) {
        let Some(module) = tree.get(&cur) else { break };
        if module.children.contains(seg) {
            cur.push(seg.clone());
            k += 1;
            continue;
        }
        if module.items.contains(seg) {
            break;
        }
        if let Some(import) = module
            .imports
            .iter()
            .find(|i| i.name.as_deref() == Some(seg.as_str()))
        {
            if let Some(target) = resolve(tree, &cur, &import.path, hops + 1) {
                cur = target;
            }
            break;
        }
        // A glob import that brings the name in.
        let via_glob = module
            .imports
            .iter()
            .filter(|i| i.name.is_none())
            .find_map(|i| {
                let source = resolve(tree, &cur, &i.path, hops + 1)?;
                let s = tree.get(&source)?;
                let brings = s.items.contains(seg)
                    || s.imports
                        .iter()
                        .any(|j| j.name.as_deref() == Some(seg.as_str()));
                brings.then_some(source)
            });
        if let Some(source) = via_glob {
            let mut rest = vec!["self".to_string()];
            rest.extend(segments[k..].iter().cloned());
            return resolve(tree, &source, &rest, hops + 1).or(Some(source));
        }
        break;
    }
    Some(cur)
}

fn display_path(p: &[String]) -> String {
    std::iter::once("crate".to_string())
        .chain(p.iter().cloned())
        .collect::<Vec<_>>()
        .join("::")
}

/// The circles among sibling modules of the crate `krate` (a name for the
/// report), file names shown relative to `base`.
pub fn cycles(krate: &str, tree: &Tree, base: &std::path::Path) -> Vec<Cycle> {
    let file_of = |p: &ModPath| -> String {
        let Some(m) = tree.get(p) else {
            return display_path(p);
        };
        let f = m
            .file
            .strip_prefix(base)
            .unwrap_or(&m.file)
            .display()
            .to_string();
        if m.inline {
            format!("{f} (mod {})", p.last().map(String::as_str).unwrap_or(""))
        } else {
            f
        }
    };
    let mut levels: BTreeMap<ModPath, Level> = BTreeMap::new();
    for (m, module) in tree.iter().filter(|(_, module)| !module.test) {
        for w in &module.paths {
            let Some(target) = resolve(tree, m, &w.segments, 0) else {
                continue;
            };
            let common = m.iter().zip(&target).take_while(|(a, b)| a == b).count();
            if common == m.len() || common == target.len() {
                continue; // an ancestor, a descendant or itself
            }
            let level = levels.entry(m[..common].to_vec()).or_default();
            level
                .entry((m[common].clone(), target[common].clone()))
                .or_insert_with(|| Evidence {
                    place: format!("{}:{}", file_of(m), w.line),
                    written: w.segments.join("::"),
                });
        }
    }
    let mut found = Vec::new();
    for (parent, edges) in &levels {
        for cycle in elementary_cycles(edges) {
            let files = cycle
                .iter()
                .map(|c| {
                    let mut p = parent.clone();
                    p.push(c.clone());
                    file_of(&p)
                })
                .collect();
            let evidence = (0..cycle.len())
                .map(|k| edges[&(cycle[k].clone(), cycle[(k + 1) % cycle.len()].clone())].clone())
                .collect();
            found.push(Cycle {
                krate: krate.to_string(),
                parent: display_path(parent),
                modules: cycle,
                files,
                evidence,
            });
        }
    }
    found
}

/// Every elementary circle of the graph `edges` (each once, starting at its
/// smallest node), at most 100 per graph.
fn elementary_cycles(edges: &Level) -> Vec<Vec<String>> {
    let mut next: BTreeMap<&str, BTreeSet<&str>> = BTreeMap::new();
    for (a, b) in edges.keys() {
        next.entry(a.as_str()).or_default().insert(b.as_str());
    }
    let nodes: Vec<&str> = next.keys().copied().collect();
    let mut out = Vec::new();
    for &start in &nodes {
        // Paths from `start` through nodes greater than it back to `start`.
        let mut stack: Vec<(Vec<&str>, BTreeSet<&str>)> =
            vec![(vec![start], BTreeSet::from([start]))];
        while let Some((path, seen)) = stack.pop() {
            let last = path[path.len() - 1];
            for &n in next.get(last).into_iter().flatten() {
                if n == start {
                    out.push(path.iter().map(|s| s.to_string()).collect());
                    if out.len() >= 100 {
                        return out;
                    }
                } else if n > start && !seen.contains(n) {
                    let mut p = path.clone();
                    p.push(n);
                    let mut s = seen.clone();
                    s.insert(n);
                    stack.push((p, s));
                }
            }
        }
    }
    out
}
