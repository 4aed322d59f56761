//! Reading a URDF file into `robot!` items.

use std::collections::{HashMap, HashSet};
use std::path::{Path, PathBuf};

use proc_macro2::{Literal, Span, TokenStream};
use quote::quote_spanned;
use syn::{Expr, Ident, LitStr};

use crate::ctxt::Ctxt;
use crate::parse::ast::{Binding, JointDecl, LinkDecl, Prop};

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

/// What a URDF file contributes.
pub struct Loaded {
    /// Absolute path of the file (for `include_str!`).
    pub path: PathBuf,
    /// Links.
    pub links: Vec<LinkDecl>,
    /// Joints.
    pub joints: Vec<JointDecl>,
    /// Run-time parameters made for damping and friction.
    pub params: Vec<Binding>,
    /// Limits by joint name.
    pub limits: HashMap<String, Limits>,
}

/// Reads `lit`'s file, relative to `base_dir` (the using crate's
/// `CARGO_MANIFEST_DIR` when called by the macro); every problem goes to
/// `cx`, naming file and element.
pub fn load(lit: &LitStr, base_dir: &Path, cx: &mut Ctxt) -> Option<Loaded> {
    let rel = lit.value();
    let path = base_dir.join(&rel);
    let text = match std::fs::read_to_string(&path) {
        Ok(t) => t,
        Err(e) => {
            cx.error_spanned_by(
                lit,
                format!(
                    "cannot read URDF `{rel}` (relative to the crate's CARGO_MANIFEST_DIR): {e}"
                ),
            );
            return None;
        }
    };
    let doc = match roxmltree::Document::parse(&text) {
        Ok(d) => d,
        Err(e) => {
            cx.error_spanned_by(lit, format!("{rel}: malformed XML: {e}"));
            return None;
        }
    };
    let root = doc.root_element();
    if root.tag_name().name() != "robot" {
        cx.error_spanned_by(
            lit,
            format!(
                "{rel}: the root element is <{}>, not <robot>",
                root.tag_name().name()
            ),
        );
        return None;
    }
    let mut r = Reader {
        rel: &rel,
        lit,
        cx,
        ok: true,
    };
    let span = lit.span();
    let mut links = Vec::new();
    let mut link_names = HashSet::new();
    for node in root.children().filter(|n| n.has_tag_name("link")) {
        let Some(name) = r.attr(node, "name", "link") else {
            continue;
        };
        if !link_names.insert(name.to_string()) {
            r.error(format!("<link name=\"{name}\"> is declared twice"));
            continue;
        }
        let props = r.inertial(node, name, span);
        links.push(LinkDecl {
            name: ident(name, span),
            props,
        });
    }
    let mut joints = Vec::new();
    let mut params = Vec::new();
    let mut limits = HashMap::new();
    let mut children: HashMap<String, String> = HashMap::new();
    let mut parent_of: HashMap<String, String> = HashMap::new();
    for node in root.children().filter(|n| n.has_tag_name("joint")) {
        let Some(name) = r.attr(node, "name", "joint") else {
            continue;
        };
        let Some(kind) = r.attr(node, "type", &format!("joint `{name}`")) else {
            continue;
        };
        let kind = match kind {
            "revolute" | "continuous" => "revolute",
            "prismatic" => "prismatic",
            "fixed" => "fixed",
            other => {
                r.error(format!(
                    "joint `{name}`: type \"{other}\" is not supported (revolute, continuous, prismatic, fixed)"
                ));
                continue;
            }
        };
        if node.children().any(|c| c.has_tag_name("mimic")) {
            r.error(format!("joint `{name}`: <mimic> joints are not supported"));
            continue;
        }
        let link_of = |tag: &str, r: &mut Reader| -> Option<String> {
            let el = node.children().find(|c| c.has_tag_name(tag));
            match el.and_then(|e| e.attribute("link")) {
                Some(l) if link_names.contains(l) => Some(l.to_string()),
                Some(l) => {
                    r.error(format!(
                        "joint `{name}`: <{tag} link=\"{l}\"> names an unknown link"
                    ));
                    None
                }
                None => {
                    r.error(format!("joint `{name}`: missing <{tag} link=\"...\"/>"));
                    None
                }
            }
        };
        let (Some(parent), Some(child)) = (link_of("parent", &mut r), link_of("child", &mut r))
        else {
            continue;
        };
        if let Some(other) = children.insert(child.clone(), name.to_string()) {
            r.error(format!(
                "joint `{name}`: link `{child}` is already the child of joint `{other}` (closed loops are not supported)"
            ));
            continue;
        }
        parent_of.insert(child.clone(), parent.clone());
        let mut props = Vec::new();
        let origin = node.children().find(|c| c.has_tag_name("origin"));
        let xyz = origin
            .map(|o| r.triple(o, "xyz", name))
            .unwrap_or(Some([0.0; 3]));
        let rpy = origin
            .map(|o| r.triple(o, "rpy", name))
            .unwrap_or(Some([0.0; 3]));
        let (Some(xyz), Some(rpy)) = (xyz, rpy) else {
            continue;
        };
        props.push(value("origin", array(xyz, span), span));
        props.push(value("rpy", array(rpy, span), span));
        if kind != "fixed" {
            let axis = match node.children().find(|c| c.has_tag_name("axis")) {
                Some(a) => match r.triple(a, "xyz", name) {
                    Some(v) => v,
                    None => continue,
                },
                None => [1.0, 0.0, 0.0],
            };
            if axis.iter().map(|x| x * x).sum::<f64>().sqrt() < 1e-12 {
                r.error(format!(
                    "joint `{name}`: <axis xyz=\"0 0 0\"> has zero length"
                ));
                continue;
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
                        params.push(Binding {
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
            if kind == "revolute" && node.attribute("type") == Some("revolute") {
                if let Some(Some(v)) = get(&mut r, "lower") {
                    l.lower = v;
                }
                if let Some(Some(v)) = get(&mut r, "upper") {
                    l.upper = v;
                }
            } else if kind == "prismatic" {
                if let Some(Some(v)) = get(&mut r, "lower") {
                    l.lower = v;
                }
                if let Some(Some(v)) = get(&mut r, "upper") {
                    l.upper = v;
                }
            }
            if let Some(Some(v)) = get(&mut r, "effort") {
                l.effort = v;
            }
            if let Some(Some(v)) = get(&mut r, "velocity") {
                l.velocity = v;
            }
            limits.insert(name.to_string(), l);
        }
        joints.push(JointDecl {
            name: ident(name, span),
            kind: Ident::new(kind, span),
            parent: ident(&parent, span),
            child: ident(&child, span),
            props,
        });
    }
    // Exactly one root, and no cycle: checked here to name the file.
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
    if !r.ok {
        return None;
    }
    Some(Loaded {
        path,
        links,
        joints,
        params,
        limits,
    })
}

struct Reader<'a> {
    rel: &'a str,
    lit: &'a LitStr,
    cx: &'a mut Ctxt,
    ok: bool,
}

impl Reader<'_> {
    fn error(&mut self, msg: String) {
        self.ok = false;
        self.cx
            .error_spanned_by(self.lit, format!("{}: {msg}", self.rel));
    }

    fn attr<'n>(
        &mut self,
        node: roxmltree::Node<'n, '_>,
        attr: &str,
        what: &str,
    ) -> Option<&'n str> {
        let v = node.attribute(attr);
        if v.is_none() {
            let pos = node.document().text_pos_at(node.range().start);
            self.error(format!(
                "{what} at line {}: missing attribute `{attr}`",
                pos.row
            ));
        }
        v
    }

    fn number(&mut self, node: roxmltree::Node, attr: &str, owner: &str) -> Option<f64> {
        let text = node.attribute(attr)?;
        match text.trim().parse::<f64>() {
            Ok(v) if v.is_finite() => Some(v),
            _ => {
                self.error(format!(
                    "`{owner}`: <{} {attr}=\"{text}\"> is not a finite number",
                    node.tag_name().name()
                ));
                None
            }
        }
    }

    fn triple(&mut self, node: roxmltree::Node, attr: &str, owner: &str) -> Option<[f64; 3]> {
        let Some(text) = node.attribute(attr) else {
            return Some([0.0; 3]);
        };
        let parts: Vec<Option<f64>> = text
            .split_whitespace()
            .map(|p| p.parse::<f64>().ok().filter(|v| v.is_finite()))
            .collect();
        match parts.as_slice() {
            [Some(a), Some(b), Some(c)] => Some([*a, *b, *c]),
            _ => {
                self.error(format!(
                    "`{owner}`: <{} {attr}=\"{text}\"> must be three finite numbers",
                    node.tag_name().name()
                ));
                None
            }
        }
    }

    /// mass, com, inertia (rotated into the link frame) of a link.
    fn inertial(&mut self, link: roxmltree::Node, name: &str, span: Span) -> Vec<Prop> {
        let Some(inertial) = link.children().find(|c| c.has_tag_name("inertial")) else {
            return Vec::new();
        };
        let origin = inertial.children().find(|c| c.has_tag_name("origin"));
        let xyz = origin
            .and_then(|o| self.triple(o, "xyz", name))
            .unwrap_or([0.0; 3]);
        let rpy = origin
            .and_then(|o| self.triple(o, "rpy", name))
            .unwrap_or([0.0; 3]);
        let mass = inertial
            .children()
            .find(|c| c.has_tag_name("mass"))
            .and_then(|m| self.number(m, "value", name));
        let Some(mass) = mass else {
            self.error(format!(
                "link `{name}`: <inertial> without <mass value=\"...\"/>"
            ));
            return Vec::new();
        };
        if mass == 0.0 {
            // A massless frame (tool flanges and the like).
            return Vec::new();
        }
        if mass < 0.0 {
            self.error(format!(
                "link `{name}`: <mass value=\"{mass}\"> is negative"
            ));
            return Vec::new();
        }
        let mut i = [0.0; 6];
        if let Some(t) = inertial.children().find(|c| c.has_tag_name("inertia")) {
            for (k, a) in ["ixx", "iyy", "izz", "ixy", "ixz", "iyz"]
                .iter()
                .enumerate()
            {
                i[k] = self.number(t, a, name).unwrap_or(0.0);
            }
        }
        let i = rotate_inertia(i, rpy);
        let mut props = vec![
            value("mass", num(mass, span), span),
            value("com", array(xyz, span), span),
        ];
        if i.iter().any(|x| *x != 0.0) {
            let lits: Vec<Expr> = i.iter().map(|v| num(*v, span)).collect();
            props.push(value(
                "inertia",
                syn::parse_quote_spanned!(span=> [#(#lits),*]),
                span,
            ));
        }
        props
    }
}

/// `R I R^T` for the inertial frame's rpy.
fn rotate_inertia(i: [f64; 6], rpy: [f64; 3]) -> [f64; 6] {
    if rpy == [0.0; 3] {
        return i;
    }
    crate::model::merge::rotate_tensor(i, &crate::model::merge::rpy_matrix(rpy))
}

/// A name as an identifier (characters that cannot be in one become `_`).
fn ident(name: &str, span: Span) -> Ident {
    let mut s: String = name
        .chars()
        .map(|c| {
            if c.is_alphanumeric() || c == '_' {
                c
            } else {
                '_'
            }
        })
        .collect();
    if s.is_empty() || s.starts_with(|c: char| c.is_ascii_digit()) {
        s.insert(0, '_');
    }
    if syn::parse_str::<Ident>(&s).is_err() {
        s.push('_');
    }
    Ident::new(&s, span)
}

fn num(v: f64, span: Span) -> Expr {
    let mut lit = Literal::f64_unsuffixed(v.abs());
    lit.set_span(span);
    let tokens: TokenStream = if v < 0.0 {
        quote_spanned!(span=> -#lit)
    } else {
        quote_spanned!(span=> #lit)
    };
    syn::parse2(tokens).expect("a number is an expression")
}

fn array(v: [f64; 3], span: Span) -> Expr {
    let [a, b, c] = v.map(|x| num(x, span));
    syn::parse_quote_spanned!(span=> [#a, #b, #c])
}

fn value(key: &str, value: Expr, span: Span) -> Prop {
    Prop::Value {
        key: Ident::new(key, span),
        value,
    }
}
