//! A `<link>`: its `<inertial>` as `mass`, `com` and `inertia` properties.

use proc_macro2::Span;
use syn::Expr;

use super::reader::Reader;
use super::tokens::{array, num, value};
use crate::parse::ast::Prop;

/// mass, com, inertia (rotated into the link frame) of a link.
pub fn inertial(r: &mut Reader, link: roxmltree::Node, name: &str, span: Span) -> Vec<Prop> {
    let Some(inertial) = link.children().find(|c| c.has_tag_name("inertial")) else {
        return Vec::new();
    };
    let origin = inertial.children().find(|c| c.has_tag_name("origin"));
    let xyz = origin
        .and_then(|o| r.triple(o, "xyz", name))
        .unwrap_or([0.0; 3]);
    let rpy = origin
        .and_then(|o| r.triple(o, "rpy", name))
        .unwrap_or([0.0; 3]);
    let mass = inertial
        .children()
        .find(|c| c.has_tag_name("mass"))
        .and_then(|m| r.number(m, "value", name));
    let Some(mass) = mass else {
        r.error(format!(
            "link `{name}`: <inertial> without <mass value=\"...\"/>"
        ));
        return Vec::new();
    };
    if mass == 0.0 {
        // A massless frame (tool flanges and the like).
        return Vec::new();
    }
    if mass < 0.0 {
        r.error(format!(
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
            i[k] = r.number(t, a, name).unwrap_or(0.0);
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

/// `R I R^T` for the inertial frame's rpy.
fn rotate_inertia(i: [f64; 6], rpy: [f64; 3]) -> [f64; 6] {
    if rpy == [0.0; 3] {
        return i;
    }
    crate::rotation::rotate_tensor(i, &crate::rotation::rpy_matrix(rpy))
}
