//! Checks that span several items: every link but one hangs on exactly one
//! joint, the links form one tree without cycles; then depth-first order.

use std::collections::HashMap;

use super::{Joint, Link};
use crate::ctxt::Ctxt;
use crate::parse::ast::{JointDecl, LinkDecl};

/// Checks the tree and returns links and joints in depth-first order, with
/// parent indices and coordinates assigned. `None` when anything failed
/// (here or earlier).
pub fn order(
    links: Vec<Link>,
    joints: Vec<Joint>,
    joint_decls: &[JointDecl],
    link_decls: &[LinkDecl],
    cx: &mut Ctxt,
) -> Option<(Vec<Link>, Vec<Joint>)> {
    if link_decls.is_empty() {
        return None;
    }
    // Structure from the declarations alone, so that a joint that failed for
    // another reason does not show up as a missing edge here.
    let index: HashMap<String, usize> = link_decls
        .iter()
        .enumerate()
        .rev()
        .map(|(i, l)| (l.name.to_string(), i))
        .collect();
    let mut parent_of: Vec<Option<(usize, usize)>> = vec![None; link_decls.len()];
    // Links that are not roots for reasons already reported: a duplicate
    // declaration, or the child of a joint whose parent is unknown.
    let mut excused = vec![false; link_decls.len()];
    for (i, l) in link_decls.iter().enumerate() {
        excused[i] = index.get(&l.name.to_string()) != Some(&i);
    }
    for (j, decl) in joint_decls.iter().enumerate() {
        let (Some(&p), Some(&c)) = (
            index.get(&decl.parent.to_string()),
            index.get(&decl.child.to_string()),
        ) else {
            if let Some(&c) = index.get(&decl.child.to_string()) {
                excused[c] = true;
            }
            continue;
        };
        if p == c {
            cx.error_spanned_by(&decl.child, "a joint cannot connect a link to itself");
            continue;
        }
        match parent_of[c] {
            Some((_, other)) => cx.error_spanned_by(
                &decl.child,
                format!(
                    "link `{}` already hangs on joint `{}`; closed loops are not supported",
                    decl.child, joint_decls[other].name
                ),
            ),
            None => parent_of[c] = Some((p, j)),
        }
    }
    let roots: Vec<usize> = (0..link_decls.len())
        .filter(|&l| parent_of[l].is_none() && !excused[l])
        .collect();
    if roots.len() > 1 {
        for &r in &roots[1..] {
            cx.error_spanned_by(
                &link_decls[r].name,
                format!(
                    "two roots: link `{}` hangs on no joint, and neither does `{}`; attach it with a joint",
                    link_decls[r].name, link_decls[roots[0]].name
                ),
            );
        }
    }
    // Children lists in declaration order of the joints.
    let mut children: Vec<Vec<(usize, usize)>> = vec![Vec::new(); link_decls.len()];
    for (c, pj) in parent_of.iter().enumerate() {
        if let Some((p, j)) = pj {
            children[*p].push((*j, c));
        }
    }
    for ch in &mut children {
        ch.sort();
    }
    let mut seen = vec![false; link_decls.len()];
    let mut link_order = Vec::new();
    for &r in &roots {
        let mut stack = vec![r];
        while let Some(l) = stack.pop() {
            if seen[l] {
                continue;
            }
            seen[l] = true;
            link_order.push(l);
            for &(_, c) in children[l].iter().rev() {
                stack.push(c);
            }
        }
    }
    // A link not reachable from a root either hangs below a link excused
    // above, or sits on a cycle: follow its parents to tell which.
    for l in 0..link_decls.len() {
        if seen[l] {
            continue;
        }
        let mut at = l;
        let mut steps = 0;
        while let Some((p, j)) = parent_of[at] {
            at = p;
            steps += 1;
            if at == l {
                cx.error_spanned_by(
                    &joint_decls[j].name,
                    format!(
                        "joint `{}` closes a cycle: link `{}` is its own ancestor",
                        joint_decls[j].name, link_decls[l].name
                    ),
                );
                // Report each cycle once: mark its links as seen.
                let mut k = l;
                while let Some((p, _)) = parent_of[k] {
                    seen[k] = true;
                    if p == l {
                        break;
                    }
                    k = p;
                }
                break;
            }
            if steps > link_decls.len() {
                break; // below a cycle reported from another link
            }
        }
    }
    if !cx.is_ok() || joints.len() != joint_decls.len() || links.len() != link_decls.len() {
        return None;
    }

    let mut new_index = vec![0usize; link_decls.len()];
    for (new, &old) in link_order.iter().enumerate() {
        new_index[old] = new;
    }
    let mut links_opt: Vec<Option<Link>> = links.into_iter().map(Some).collect();
    let mut joints_opt: Vec<Option<Joint>> = joints.into_iter().map(Some).collect();
    let mut out_links = Vec::new();
    let mut out_joints = Vec::new();
    let mut coord = 0;
    for &old in &link_order {
        let mut link = links_opt[old].take()?;
        if let Some((p, j)) = parent_of[old] {
            let mut joint = joints_opt[j].take()?;
            joint.parent = new_index[p];
            joint.child = new_index[old];
            // A mimic joint has no coordinate of its own (see `mimic.rs`).
            if joint.kind != super::JointKind::Fixed && joint.mimic.is_none() {
                joint.coord = Some(coord);
                coord += 1;
            }
            link.parent = Some(new_index[p]);
            link.joint = Some(out_joints.len());
            out_joints.push(joint);
        }
        out_links.push(link);
    }
    Some((out_links, out_joints))
}
