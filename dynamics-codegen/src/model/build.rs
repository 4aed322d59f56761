//! From the syntax tree to the [`Model`]: resolve names, check every item,
//! then check the tree (see `tree.rs`).

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use proc_macro2::Span;
use syn::{Expr, Ident};

use super::joint::joint;
use super::link::link;
use super::scalar::{resolve, resolve_array, Scalar, Scope};
use super::{tree, Model, Param};
use crate::ctxt::Ctxt;
use crate::parse::ast::{Header, Input, Item, JointDecl, LinkDecl, Prop};
use crate::urdf::Limits;

/// Builds and validates the model; `None` when any error was recorded.
///
/// `complete` is false when the parse stage lost items: checks that need
/// every item (a missing header or gravity, unknown links, the tree) are then
/// skipped, so that one syntax error does not cascade into follow-on ones.
/// `urdf = "..."` paths are relative to `base_dir`.
pub fn build(input: Input, complete: bool, base_dir: &Path, cx: &mut Ctxt) -> Option<Model> {
    let mut header: Option<Header> = None;
    let mut gravity: Option<(Ident, Expr)> = None;
    let mut consts: Vec<(String, f64)> = Vec::new();
    let mut params: Vec<Param> = Vec::new();
    let mut param_names: Vec<String> = Vec::new();
    let mut links: Vec<LinkDecl> = Vec::new();
    let mut joints: Vec<JointDecl> = Vec::new();
    let mut constraint_decls = Vec::new();
    let mut symbols: HashMap<String, Span> = HashMap::new();

    let (items, urdf) = expand_urdf(input.items, base_dir, cx)?;
    for item in items {
        match item {
            Item::Urdf { .. } => {}
            Item::Header(h) => {
                if header.is_some() {
                    cx.error_spanned_by(
                        &h.name,
                        "a second `robot` header; there must be exactly one",
                    );
                } else {
                    header = Some(h);
                }
            }
            Item::Gravity { kw, value } => {
                if gravity.is_some() {
                    cx.error_spanned_by(&kw, "`gravity` is given twice");
                } else {
                    gravity = Some((kw, value));
                }
            }
            Item::Const(b) => {
                let scope = constants_only(&consts, &param_names);
                let value = resolve(&b.value, &scope, cx).and_then(|s| s.as_number());
                if unique_symbol(&b.name, &mut symbols, cx) {
                    consts.push((b.name.to_string(), value.unwrap_or(0.0)));
                }
            }
            Item::Param(b) => {
                let scope = constants_only(&consts, &param_names);
                let default = resolve(&b.value, &scope, cx).and_then(|s| s.as_number());
                if unique_symbol(&b.name, &mut symbols, cx) {
                    param_names.push(b.name.to_string());
                    params.push(Param {
                        attrs: b.attrs,
                        name: b.name,
                        default: default.unwrap_or(0.0),
                    });
                }
            }
            Item::Constraint(b) => constraint_decls.push(b),
            Item::Link(l) => links.push(l),
            Item::Joint(j) => joints.push(j),
        }
    }

    let Some(header) = header else {
        if complete {
            cx.error_at(
                Span::call_site(),
                "missing the robot's name: start with `pub robot Name;`",
            );
        }
        return None;
    };
    let gravity = match &gravity {
        None if !complete => None,
        None => {
            cx.error_spanned_by(
                &header.name,
                "missing `gravity = [gx, gy, gz];` (m/s^2, world frame)",
            );
            None
        }
        Some((_, value)) => {
            let scope = constants_only(&consts, &param_names);
            resolve_array::<3>(value, "`gravity`", &scope, cx)
                .and_then(|g| Some([g[0].as_number()?, g[1].as_number()?, g[2].as_number()?]))
        }
    };
    if joints.is_empty() && complete {
        cx.error_spanned_by(
            &header.name,
            "empty robot: declare links and at least one revolute or prismatic joint",
        );
    }

    let scope = Scope {
        consts: &consts,
        params: &param_names,
        coord: false,
        allow_params: true,
        joints: &[],
    };
    let mut link_index: HashMap<String, usize> = HashMap::new();
    let mut point_names: HashMap<String, Span> = HashMap::new();
    let mut built_links = Vec::new();
    for decl in &links {
        let key = decl.name.to_string();
        if link_index.contains_key(&key) {
            cx.error_spanned_by(&decl.name, format!("duplicate link name `{key}`"));
            continue;
        }
        link_index.insert(key, built_links.len());
        built_links.push(link(decl, &scope, &mut point_names, cx));
    }

    let mut joint_names: HashMap<String, Span> = HashMap::new();
    let mut built_joints = Vec::new();
    for decl in &joints {
        let key = decl.name.to_string();
        if joint_names.insert(key.clone(), decl.name.span()).is_some() {
            cx.error_spanned_by(&decl.name, format!("duplicate joint name `{key}`"));
            continue;
        }
        if let Some(j) = joint(decl, &link_index, complete, &scope, cx) {
            built_joints.push(j);
        }
    }

    if !complete {
        return None;
    }
    let (links, mut joints) = tree::order(built_links, built_joints, &joints, &links, cx)?;
    if !cx.is_ok() {
        return None;
    }
    super::mimic::resolve(&mut joints, cx);
    if !cx.is_ok() {
        return None;
    }
    if !joints.iter().any(|j| j.coord.is_some()) {
        cx.error_spanned_by(
            &header.name,
            "the robot has no revolute or prismatic joint: nothing moves",
        );
        return None;
    }
    // Constraints name joints: resolve them against the coordinates.
    let coord_names: Vec<(String, Scalar)> = joints
        .iter()
        .filter_map(|j| Some((j.name.to_string(), super::mimic::coupling(j.position()?))))
        .collect();
    let mut constraints = Vec::new();
    let mut constraint_names: Vec<String> = Vec::new();
    for b in &constraint_decls {
        let key = b.name.to_string();
        if constraint_names.contains(&key) {
            cx.error_spanned_by(&b.name, format!("duplicate constraint name `{key}`"));
            continue;
        }
        constraint_names.push(key);
        let scope = Scope {
            consts: &consts,
            params: &param_names,
            coord: false,
            allow_params: true,
            joints: &coord_names,
        };
        if let Some(f) = resolve(&b.value, &scope, cx) {
            constraints.push(super::Constraint {
                name: b.name.clone(),
                f,
            });
        }
    }
    if !cx.is_ok() {
        return None;
    }
    let (urdf, limits) = match urdf {
        Some((p, l)) => (Some(p), l),
        None => (None, HashMap::new()),
    };
    let mut model = Model {
        urdf,
        limits,
        constraints,
        attrs: header.attrs,
        vis: header.vis,
        name: header.name,
        gravity: gravity?,
        params,
        links,
        joints,
    };
    super::merge::weld_fixed(&mut model);
    super::normalize::chains(&mut model);
    Some(model)
}

/// A `link` item naming a link the URDF already has overrides that link's
/// properties one by one (e.g. `link panda_link7 { mass = payload; }` keeps
/// a payload mass symbolic); its other properties stay as the file says.
fn override_urdf_links(items: Vec<Item>, mut urdf_links: Vec<LinkDecl>) -> Vec<Item> {
    let mut out: Vec<Item> = Vec::with_capacity(items.len() + urdf_links.len());
    for item in items {
        match item {
            Item::Link(o) if urdf_links.iter().any(|l| l.name == o.name) => {
                let Some(target) = urdf_links.iter_mut().find(|l| l.name == o.name) else {
                    continue;
                };
                for prop in o.props {
                    if let Prop::Value { key: k, .. } = &prop {
                        let k = k.to_string();
                        target
                            .props
                            .retain(|p| !matches!(p, Prop::Value { key, .. } if *key == k));
                    }
                    target.props.push(prop);
                }
            }
            other => out.push(other),
        }
    }
    out.extend(urdf_links.into_iter().map(Item::Link));
    out
}

/// The items with a `urdf = "..."` item replaced by the parameters, links and
/// joints the file holds (`link` items of the input override the file's
/// links property by property). `None` when the file cannot be read: there
/// is nothing to check the rest against.
#[allow(clippy::type_complexity)]
fn expand_urdf(
    input: Vec<Item>,
    base_dir: &Path,
    cx: &mut Ctxt,
) -> Option<(Vec<Item>, Option<(PathBuf, HashMap<String, Limits>)>)> {
    let mut urdf: Option<(PathBuf, HashMap<String, Limits>)> = None;
    let mut items = Vec::with_capacity(input.len());
    let mut urdf_links: Vec<LinkDecl> = Vec::new();
    for item in input {
        match item {
            Item::Urdf { kw, path } => {
                if urdf.is_some() {
                    cx.error_spanned_by(&kw, "`urdf` is given twice");
                    continue;
                }
                let l = crate::urdf::load(&path, base_dir, cx)?;
                items.extend(l.params.into_iter().map(Item::Param));
                urdf_links = l.links;
                items.extend(l.joints.into_iter().map(Item::Joint));
                urdf = Some((l.path, l.limits));
            }
            other => items.push(other),
        }
    }
    if urdf.is_some() {
        items = override_urdf_links(items, urdf_links);
    }
    Some((items, urdf))
}

/// The scope of `const`, `param` and `gravity` values: constants only.
fn constants_only<'a>(consts: &'a [(String, f64)], params: &'a [String]) -> Scope<'a> {
    Scope {
        consts,
        params,
        coord: false,
        allow_params: false,
        joints: &[],
    }
}

fn unique_symbol(name: &Ident, seen: &mut HashMap<String, Span>, cx: &mut Ctxt) -> bool {
    let key = name.to_string();
    if matches!(key.as_str(), "q" | "pi" | "PI") {
        cx.error_spanned_by(name, format!("`{key}` is reserved"));
        return false;
    }
    if seen.insert(key.clone(), name.span()).is_some() {
        cx.error_spanned_by(name, format!("`{key}` is declared twice"));
        return false;
    }
    true
}
