//! From the syntax tree to the [`Model`]: resolve names, check every item,
//! then check the tree (see `tree.rs`).

use std::collections::HashMap;
use std::path::Path;

use proc_macro2::Span;
use syn::{Expr, Ident};

use super::scalar::{resolve, resolve_array, Scalar, Scope};
use super::{
    inertia, transfer, tree, Inertial, Joint, JointForces, JointKind, Link, Model, Param, Point,
};
use crate::ctxt::Ctxt;
use crate::parse::ast::{Header, Input, Item, JointDecl, LinkDecl, Prop};

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

    // A URDF item stands for the links, joints and parameters it holds.
    let mut urdf: Option<(std::path::PathBuf, HashMap<String, crate::urdf::Limits>)> = None;
    let mut items = Vec::with_capacity(input.items.len());
    let mut urdf_links: Vec<LinkDecl> = Vec::new();
    for item in input.items {
        match item {
            Item::Urdf { kw, path } => {
                if urdf.is_some() {
                    cx.error_spanned_by(&kw, "`urdf` is given twice");
                    continue;
                }
                match crate::urdf::load(&path, base_dir, cx) {
                    Some(l) => {
                        items.extend(l.params.into_iter().map(Item::Param));
                        urdf_links = l.links;
                        items.extend(l.joints.into_iter().map(Item::Joint));
                        urdf = Some((l.path, l.limits));
                    }
                    // Nothing to check the rest against: stop here.
                    None => return None,
                }
            }
            other => items.push(other),
        }
    }
    if urdf.is_some() {
        items = override_urdf_links(items, urdf_links);
    }
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
                let scope = Scope {
                    consts: &consts,
                    params: &param_names,
                    coord: false,
                    allow_params: false,
                    joints: &[],
                };
                let value = resolve(&b.value, &scope, cx).and_then(|s| s.as_number());
                if unique_symbol(&b.name, &mut symbols, cx) {
                    consts.push((b.name.to_string(), value.unwrap_or(0.0)));
                }
            }
            Item::Param(b) => {
                let scope = Scope {
                    consts: &consts,
                    params: &param_names,
                    coord: false,
                    allow_params: false,
                    joints: &[],
                };
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
            let scope = Scope {
                consts: &consts,
                params: &param_names,
                coord: false,
                allow_params: false,
                joints: &[],
            };
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
    let (links, joints) = tree::order(built_links, built_joints, &joints, &links, cx)?;
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
    let coord_names: Vec<(String, usize)> = joints
        .iter()
        .filter_map(|j| j.coord.map(|c| (j.name.to_string(), c)))
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

/// One link: its properties resolved and checked.
fn link(decl: &LinkDecl, scope: &Scope, points: &mut HashMap<String, Span>, cx: &mut Ctxt) -> Link {
    let mut mass: Option<(Scalar, &Ident)> = None;
    let mut com = None;
    let mut inertia_v = None;
    let mut out_points = Vec::new();
    let mut seen: Vec<String> = Vec::new();
    let mut first_inertial: Option<&Ident> = None;
    let mut mass_given = false;
    for prop in &decl.props {
        match prop {
            Prop::Value { key, value } => {
                let k = key.to_string();
                if seen.contains(&k) {
                    cx.error_spanned_by(key, format!("`{k}` is given twice"));
                    continue;
                }
                seen.push(k.clone());
                match k.as_str() {
                    "mass" => {
                        mass_given = true;
                        if let Some(m) = resolve(value, scope, cx) {
                            if matches!(m.as_number(), Some(v) if v <= 0.0) {
                                cx.error_spanned_by(value, "mass must be positive");
                            }
                            mass = Some((m, key));
                        }
                    }
                    "com" => {
                        first_inertial.get_or_insert(key);
                        com = resolve_array::<3>(value, "`com`", scope, cx);
                    }
                    "inertia" => {
                        first_inertial.get_or_insert(key);
                        inertia_v = inertia_tensor(value, scope, cx);
                    }
                    _ => cx.error_spanned_by(
                        key,
                        format!("unknown link property `{k}`; expected mass, com, inertia, point or point_mass"),
                    ),
                }
            }
            Prop::Point { name, at, .. } => {
                if let Some(p) = point(name, at, None, scope, points, cx) {
                    out_points.push(p);
                }
            }
            Prop::PointMass { name, mass, at, .. } => {
                let m = resolve(mass, scope, cx);
                if matches!(m.as_ref().and_then(Scalar::as_number), Some(v) if v <= 0.0) {
                    cx.error_spanned_by(mass, "a point mass must be positive");
                }
                if let Some(p) = point(name, at, m, scope, points, cx) {
                    out_points.push(p);
                }
            }
        }
    }
    let zero = || Scalar::Num(0.0);
    let inertial = match (mass, first_inertial) {
        (None, Some(key)) if !mass_given => {
            cx.error_spanned_by(
                key,
                format!(
                    "link `{}` has a centre of mass or inertia but no `mass`",
                    decl.name
                ),
            );
            None
        }
        (None, _) => None,
        (Some((mass, _)), _) => Some(Inertial {
            mass,
            com: com.unwrap_or_else(|| [zero(), zero(), zero()]),
            inertia: inertia_v.unwrap_or_else(|| [zero(), zero(), zero(), zero(), zero(), zero()]),
        }),
    };
    Link {
        name: decl.name.clone(),
        parent: None,
        joint: None,
        inertial,
        points: out_points,
    }
}

fn point(
    name: &Ident,
    at: &Expr,
    mass: Option<Scalar>,
    scope: &Scope,
    points: &mut HashMap<String, Span>,
    cx: &mut Ctxt,
) -> Option<Point> {
    let key = name.to_string();
    if points.insert(key.clone(), name.span()).is_some() {
        cx.error_spanned_by(name, format!("duplicate point name `{key}`"));
        return None;
    }
    let at = resolve_array::<3>(at, "a point's position", scope, cx)?;
    Some(Point {
        name: name.clone(),
        at,
        mass,
    })
}

/// `[ixx, iyy, izz]` or `[ixx, iyy, izz, ixy, ixz, iyz]`, positive definite.
fn inertia_tensor(value: &Expr, scope: &Scope, cx: &mut Ctxt) -> Option<[Scalar; 6]> {
    let items = super::scalar::array_items(value, "`inertia`", cx)?;
    let zero = || Scalar::Num(0.0);
    let t: [Scalar; 6] = match items.len() {
        3 => {
            let [a, b, c] = resolve_array::<3>(value, "`inertia`", scope, cx)?;
            [a, b, c, zero(), zero(), zero()]
        }
        6 => resolve_array::<6>(value, "`inertia`", scope, cx)?,
        n => {
            cx.error_spanned_by(
                value,
                format!("`inertia` must be [ixx, iyy, izz] or [ixx, iyy, izz, ixy, ixz, iyz], found {n} entries"),
            );
            return None;
        }
    };
    let nums: Option<Vec<f64>> = t.iter().map(Scalar::as_number).collect();
    if let Some(n) = nums {
        let arr = [n[0], n[1], n[2], n[3], n[4], n[5]];
        if !inertia::positive_definite(arr) {
            cx.error_spanned_by(value, "inertia tensor is not positive definite");
            return None;
        }
    }
    Some(t)
}

/// One joint: kind, placement and forces.
fn joint(
    decl: &JointDecl,
    links: &HashMap<String, usize>,
    complete: bool,
    scope: &Scope,
    cx: &mut Ctxt,
) -> Option<Joint> {
    let kind = match decl.kind.to_string().as_str() {
        "revolute" | "continuous" => Some(JointKind::Revolute),
        "prismatic" => Some(JointKind::Prismatic),
        "fixed" => Some(JointKind::Fixed),
        other => {
            cx.error_spanned_by(
                &decl.kind,
                format!("unsupported joint kind `{other}`; expected revolute, prismatic or fixed"),
            );
            None
        }
    };
    let parent = links.get(&decl.parent.to_string()).copied();
    if parent.is_none() && complete {
        cx.error_spanned_by(&decl.parent, format!("unknown link `{}`", decl.parent));
    }
    let child = links.get(&decl.child.to_string()).copied();
    if child.is_none() && complete {
        cx.error_spanned_by(&decl.child, format!("unknown link `{}`", decl.child));
    }

    let mut values: HashMap<String, (&Ident, &Expr)> = HashMap::new();
    for prop in &decl.props {
        match prop {
            Prop::Value { key, value } => {
                let k = key.to_string();
                const KEYS: &[&str] = &[
                    "transfer",
                    "origin",
                    "rpy",
                    "axis",
                    "damping",
                    "coulomb",
                    "coulomb_smoothing",
                    "spring",
                    "rest",
                ];
                if !KEYS.contains(&k.as_str()) {
                    cx.error_spanned_by(
                        key,
                        format!(
                            "unknown joint property `{k}`; expected one of {}",
                            KEYS.join(", ")
                        ),
                    );
                } else if values.insert(k.clone(), (key, value)).is_some() {
                    cx.error_spanned_by(key, format!("`{k}` is given twice"));
                }
            }
            Prop::Point { kw, .. } | Prop::PointMass { kw, .. } => {
                cx.error_spanned_by(kw, "points belong to links, not joints");
            }
        }
    }
    let kind = kind?;
    let get = |k: &str| values.get(k).map(|(_, e)| *e);
    let chain_scope = Scope {
        coord: kind != JointKind::Fixed,
        ..*scope
    };
    let chain = match (
        values.get("transfer"),
        get("origin").or(get("rpy")).or(get("axis")),
    ) {
        (Some((key, _)), Some(_)) => {
            cx.error_spanned_by(
                *key,
                "give either `transfer` or `origin`/`rpy`/`axis`, not both",
            );
            None
        }
        (Some((_, t)), None) => {
            let chain = transfer::chain(t, &chain_scope, cx)?;
            let (rot, trans) = transfer::coord_use(&chain);
            match kind {
                JointKind::Revolute if !rot => {
                    cx.error_spanned_by(
                        *t,
                        "the joint coordinate `q` must drive a rotation of this revolute joint, e.g. `rot_z(q)`",
                    );
                    None
                }
                JointKind::Prismatic if !trans => {
                    cx.error_spanned_by(
                        *t,
                        "the joint coordinate `q` must drive a translation of this prismatic joint, e.g. `trans_x(q)`",
                    );
                    None
                }
                _ => Some(chain),
            }
        }
        (None, _) => transfer::urdf_style(
            kind,
            get("origin"),
            get("rpy"),
            values.get("axis").map(|(k, e)| (*k, *e)),
            &decl.name,
            scope,
            cx,
        ),
    };

    let mut forces = JointForces::default();
    let scalar = |k: &str, cx: &mut Ctxt| get(k).and_then(|e| resolve(e, scope, cx));
    if kind == JointKind::Fixed {
        for k in ["damping", "coulomb", "coulomb_smoothing", "spring", "rest"] {
            if let Some((key, _)) = values.get(k) {
                cx.error_spanned_by(*key, "a fixed joint carries no forces");
            }
        }
    } else {
        forces.damping = scalar("damping", cx);
        forces.coulomb = scalar("coulomb", cx);
        forces.coulomb_smoothing = scalar("coulomb_smoothing", cx);
        if matches!(forces.coulomb_smoothing.as_ref().and_then(Scalar::as_number), Some(v) if v <= 0.0)
        {
            if let Some(e) = get("coulomb_smoothing") {
                cx.error_spanned_by(e, "`coulomb_smoothing` must be positive");
            }
        }
        let stiffness = scalar("spring", cx);
        let rest = scalar("rest", cx);
        match (stiffness, rest) {
            (Some(c), r) => forces.spring = Some((c, r.unwrap_or(Scalar::Num(0.0)))),
            (None, Some(_)) => {
                if let Some((key, _)) = values.get("rest") {
                    cx.error_spanned_by(*key, "`rest` needs a `spring = stiffness;`");
                }
            }
            (None, None) => {}
        }
    }
    Some(Joint {
        name: decl.name.clone(),
        kind,
        parent: parent?,
        child: child?,
        chain: chain?,
        coord: None,
        forces,
    })
}
