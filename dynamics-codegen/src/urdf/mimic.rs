//! The `<mimic>` elements of a file, checked once all joints are read, so
//! that each error names the file, the joint and the line: the joint named
//! must exist, move, differ from the mimic itself, and the mimics must not
//! form a cycle. The coupling itself is the model stage's (`model/mimic.rs`).

use std::collections::{HashMap, HashSet};

use super::reader::Reader;

/// Records an error for every bad `<mimic>`; `mimics` holds (joint, joint
/// followed, line), `kinds` the kind of every joint read, `names` every
/// joint name in the file.
pub fn check_mimics(
    r: &mut Reader,
    mimics: &[(String, String, u32)],
    kinds: &HashMap<String, &'static str>,
    names: &HashSet<&str>,
) {
    let follows: HashMap<&str, &str> = mimics
        .iter()
        .map(|(j, of, _)| (j.as_str(), of.as_str()))
        .collect();
    for (joint, of, line) in mimics {
        let at = format!("joint `{joint}` (line {line}): <mimic joint=\"{of}\">");
        if joint == of {
            r.error(format!("{at} names the joint itself"));
        } else if !names.contains(of.as_str()) {
            r.error(format!("{at} names an unknown joint"));
        } else if kinds.get(of.as_str()) == Some(&"fixed") {
            r.error(format!(
                "{at} names a fixed joint: there is no motion to follow"
            ));
        } else if let Some(cycle) = cycle_from(joint, &follows) {
            // Reported once, at the cycle's first joint by name.
            if cycle.iter().min() == Some(&joint.as_str()) {
                let mut path: Vec<String> = cycle.iter().map(|j| format!("`{j}`")).collect();
                path.push(format!("`{joint}`"));
                r.error(format!(
                    "{at}: the mimic joints form a cycle ({}); one of them must be independent",
                    path.join(" -> ")
                ));
            }
        }
    }
}

/// The joints met from `start` along the mimics when that path returns to
/// `start`.
fn cycle_from<'a>(start: &'a str, follows: &HashMap<&'a str, &'a str>) -> Option<Vec<&'a str>> {
    let mut path = vec![start];
    let mut at = *follows.get(start)?;
    while at != start {
        if path.contains(&at) || path.len() > follows.len() {
            return None; // a cycle that `start` only leads into
        }
        path.push(at);
        at = follows.get(at)?;
    }
    Some(path)
}
