//! The joints of a file must make a tree: one root link, no cycle. Checked
//! here rather than in the model stage so that the error names the file.

use std::collections::{HashMap, HashSet};

use super::reader::Reader;

/// Records an error for a cycle or for several roots.
pub fn check_tree(
    r: &mut Reader,
    link_names: &HashSet<String>,
    children: &HashMap<String, String>,
    parent_of: &HashMap<String, String>,
) {
    let mut names: Vec<&String> = parent_of.keys().collect();
    names.sort();
    for start in names {
        let mut at = start;
        for _ in 0..=parent_of.len() {
            match parent_of.get(at) {
                Some(p) if p == start => {
                    r.error(format!(
                        "the joints form a cycle through link `{start}` (joint `{}` has it as child)",
                        children.get(start).map(String::as_str).unwrap_or("?")
                    ));
                    break;
                }
                Some(p) => at = p,
                None => break,
            }
        }
        if !r.ok {
            break;
        }
    }
    let roots: Vec<&String> = link_names
        .iter()
        .filter(|l| !children.contains_key(*l))
        .collect();
    if roots.is_empty() && !link_names.is_empty() {
        r.error("the joints form a cycle: every link is some joint's child".to_string());
    } else if roots.len() > 1 {
        let mut names: Vec<&str> = roots.iter().map(|s| s.as_str()).collect();
        names.sort();
        r.error(format!("several root links ({}): every link but one must be some joint's child (a cycle elsewhere also shows as this)", names.join(", ")));
    }
}
