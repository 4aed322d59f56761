//! A `<joint>`: its kind, parent and child links, origin, axis, limits and
//! `<dynamics>` (damping and friction as run-time parameters), `<mimic>`.

use std::collections::{HashMap, HashSet};

use proc_macro2::Span;
use syn::Ident;

use super::reader::Reader;
use super::tokens::{array, ident, num, value};
use crate::parse::ast::{Binding, JointDecl, Prop};

/// Joint limits from `<limit>` (infinite where absent).
#[derive(Clone, Copy, Debug)]
pub struct Limits {
    /// Lower position limit.
    pub lower: f64,
    /// Upper position limit.
    pub upper: f64,
    /// Effort limit.
    pub effort: f64,
    /// Velocity limit.
    pub velocity: f64,
}

/// What the joints of a file add up to, beside the joint items.
#[derive(Default)]
pub struct Joints {
    /// Run-time parameters made for damping and friction.
    pub params: Vec<Binding>,
    /// Limits by joint name.
    pub limits: HashMap<String, Limits>,
    /// Child link -> the joint that has it as child.
    pub children: HashMap<String, String>,
    /// Child link -> parent link.
    pub parent_of: HashMap<String, String>,
    /// Joint name -> kind (`revolute`, `prismatic`, `fixed`).
    pub kinds: HashMap<String, &'static str>,
    /// The mimic joints: (joint, the joint it follows, line of `<mimic>`).
    pub mimics: Vec<(String, String, u32)>,
}

/// `<mimic joint=".." multiplier=".." offset=".."/>` (defaults 1 and 0) as
/// the properties `mimic`, `multiplier`, `offset`; the joint named is
/// checked once all joints are read (`mimic.rs`).
fn mimic(
    r: &mut Reader,
    joint: roxmltree::Node,
    m: roxmltree::Node,
    kind: &str,
    out: &mut Joints,
    span: Span,
) -> Option<Vec<Prop>> {
    let name = joint.attribute("name").unwrap_or("?");
    let line = Reader::line(m);
    if kind == "fixed" {
        r.error(format!(
            "joint `{name}` (line {line}): a fixed joint cannot <mimic> another joint"
        ));
        return None;
    }
    let of = r.attr(m, "joint", &format!("<mimic> of joint `{name}`"))?;
    let multiplier = match m.attribute("multiplier") {
        Some(_) => r.number(m, "multiplier", name)?,
        None => 1.0,
    };
    let offset = match m.attribute("offset") {
        Some(_) => r.number(m, "offset", name)?,
        None => 0.0,
    };
    out.mimics.push((name.to_string(), of.to_string(), line));
    let of = ident(of, span);
    Some(vec![
        value("mimic", syn::parse_quote_spanned!(span=> #of), span),
        value("multiplier", num(multiplier, span), span),
        value("offset", num(offset, span), span),
    ])
}

/// One `<joint>` element as a joint item; `None` (with the error recorded)
/// when it cannot be read.
pub fn joint(
    r: &mut Reader,
    node: roxmltree::Node,
    link_names: &HashSet<String>,
    out: &mut Joints,
    span: Span,
) -> Option<JointDecl> {
    let name = r.attr(node, "name", "joint")?;
    let kind = r.attr(node, "type", &format!("joint `{name}`"))?;
    let line = Reader::line(node);
    let link_of = |tag: &str, r: &mut Reader| -> Option<String> {
        let el = node.children().find(|c| c.has_tag_name(tag));
        match el.and_then(|e| e.attribute("link")) {
            Some(l) if link_names.contains(l) => Some(l.to_string()),
            Some(l) => {
                r.error(format!(
                    "joint `{name}` (line {line}): <{tag} link=\"{l}\"> names an unknown link"
                ));
                None
            }
            None => {
                r.error(format!(
                    "joint `{name}` (line {line}): missing <{tag} link=\"...\"/>"
                ));
                None
            }
        }
    };
    let (Some(parent), Some(child)) = (link_of("parent", r), link_of("child", r)) else {
        return None;
    };
    if let Some(other) = out.children.insert(child.clone(), name.to_string()) {
        r.error(format!(
            "joint `{name}` (line {line}): link `{child}` is already the child of joint `{other}` (closed loops are not supported)"
        ));
        return None;
    }
    out.parent_of.insert(child.clone(), parent.clone());
    // Refused after its links are known, so that the tree check does not
    // add a follow-on error (two roots) to this one.
    let kind = match kind {
        "revolute" | "continuous" => "revolute",
        "prismatic" => "prismatic",
        "fixed" => "fixed",
        other => {
            let why = match other {
                "floating" | "planar" => ": the models here have a fixed base and one coordinate per joint; \
                                          declare the base link as the root (a mobile base's motion is not modelled)",
                _ => "",
            };
            r.error(format!(
                "joint `{name}` (line {line}): type \"{other}\" is not supported (revolute, continuous, prismatic, fixed){why}"
            ));
            return None;
        }
    };
    out.kinds.insert(name.to_string(), kind);
    let mut props = Vec::new();
    let origin = node.children().find(|c| c.has_tag_name("origin"));
    let xyz = origin
        .map(|o| r.triple(o, "xyz", name))
        .unwrap_or(Some([0.0; 3]));
    let rpy = origin
        .map(|o| r.triple(o, "rpy", name))
        .unwrap_or(Some([0.0; 3]));
    let (Some(xyz), Some(rpy)) = (xyz, rpy) else {
        return None;
    };
    props.push(value("origin", array(xyz, span), span));
    props.push(value("rpy", array(rpy, span), span));
    if let Some(m) = node.children().find(|c| c.has_tag_name("mimic")) {
        props.extend(mimic(r, node, m, kind, out, span)?);
    }
    if kind != "fixed" {
        let axis = match node.children().find(|c| c.has_tag_name("axis")) {
            Some(a) => r.triple(a, "xyz", name)?,
            None => [1.0, 0.0, 0.0],
        };
        if axis.iter().map(|x| x * x).sum::<f64>().sqrt() < 1e-12 {
            r.error(format!(
                "joint `{name}` (line {line}): <axis xyz=\"0 0 0\"> has zero length"
            ));
            return None;
        }
        props.push(value("axis", array(axis, span), span));
        if let Some(d) = node.children().find(|c| c.has_tag_name("dynamics")) {
            for (attr, key, prefix) in [
                ("damping", "damping", "damping_"),
                ("friction", "coulomb", "friction_"),
            ] {
                let Some(v) = r.number(d, attr, name) else {
                    continue;
                };
                if v != 0.0 {
                    let pname = ident(&format!("{prefix}{name}"), span);
                    out.params.push(Binding {
                        attrs: Vec::new(),
                        name: pname.clone(),
                        value: num(v, span),
                    });
                    props.push(Prop::Value {
                        key: Ident::new(key, span),
                        value: syn::parse_quote_spanned!(span=> #pname),
                    });
                }
            }
        }
        let lim = node.children().find(|c| c.has_tag_name("limit"));
        let get = |r: &mut Reader, a: &str| {
            lim.and_then(|l| l.attribute(a))
                .map(|_| r.number(lim.expect("present"), a, name))
        };
        let mut l = Limits {
            lower: f64::NEG_INFINITY,
            upper: f64::INFINITY,
            effort: f64::INFINITY,
            velocity: f64::INFINITY,
        };
        // A continuous joint has no position limits, whatever the file says.
        let bounded = kind == "prismatic" || node.attribute("type") == Some("revolute");
        if bounded {
            if let Some(Some(v)) = get(r, "lower") {
                l.lower = v;
            }
            if let Some(Some(v)) = get(r, "upper") {
                l.upper = v;
            }
        }
        if let Some(Some(v)) = get(r, "effort") {
            l.effort = v;
        }
        if let Some(Some(v)) = get(r, "velocity") {
            l.velocity = v;
        }
        out.limits.insert(name.to_string(), l);
    }
    Some(JointDecl {
        name: ident(name, span),
        kind: Ident::new(kind, span),
        parent: ident(&parent, span),
        child: ident(&child, span),
        props,
    })
}
