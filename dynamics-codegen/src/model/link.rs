//! One `link` item: mass, centre of mass, inertia tensor and named points,
//! each resolved and checked (positive mass, positive-definite inertia,
//! unique point names).

use std::collections::HashMap;

use proc_macro2::Span;
use syn::{Expr, Ident};

use super::scalar::{resolve, resolve_array, Scalar, Scope};
use super::{inertia, Inertial, Link, Point};
use crate::ctxt::Ctxt;
use crate::parse::ast::{LinkDecl, Prop};

/// One link: its properties resolved and checked.
pub fn link(
    decl: &LinkDecl,
    scope: &Scope,
    points: &mut HashMap<String, Span>,
    cx: &mut Ctxt,
) -> Link {
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
