//! One `joint` item: its kind, the links it joins, its placement (a
//! transfer chain or URDF-style origin/rpy/axis) and the forces it carries
//! (damping, Coulomb friction, spring).

use std::collections::HashMap;

use syn::{Expr, Ident};

use super::scalar::{resolve, Scalar, Scope};
use super::{transfer, Joint, JointForces, JointKind, Mimic};
use crate::ctxt::Ctxt;
use crate::parse::ast::{JointDecl, Prop};

/// One joint: kind, placement and forces.
pub fn joint(
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
                    "mimic",
                    "multiplier",
                    "offset",
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
    let mimic = mimic(kind, &values, scope, cx);
    Some(Joint {
        name: decl.name.clone(),
        kind,
        parent: parent?,
        child: child?,
        chain: chain?,
        coord: None,
        forces,
        mimic: mimic?,
        follows: None,
    })
}

/// `mimic = other; multiplier = m; offset = o;` (constants, defaults 1 and
/// 0): `Some(None)` for an independent joint, `None` after an error.
fn mimic(
    kind: JointKind,
    values: &HashMap<String, (&Ident, &Expr)>,
    scope: &Scope,
    cx: &mut Ctxt,
) -> Option<Option<Mimic>> {
    let constants = Scope {
        coord: false,
        allow_params: false,
        ..*scope
    };
    let number = |k: &str, default: f64, cx: &mut Ctxt| -> Option<f64> {
        let Some((_, e)) = values.get(k) else {
            return Some(default);
        };
        let v = resolve(e, &constants, cx)?;
        match v.as_number() {
            Some(x) if x.is_finite() => Some(x),
            _ => {
                cx.error_spanned_by(*e, format!("`{k}` must be a finite constant"));
                None
            }
        }
    };
    let Some((key, of)) = values.get("mimic") else {
        for k in ["multiplier", "offset"] {
            if let Some((key, _)) = values.get(k) {
                cx.error_spanned_by(*key, format!("`{k}` needs `mimic = <joint>;`"));
            }
        }
        return Some(None);
    };
    if kind == JointKind::Fixed {
        cx.error_spanned_by(*key, "a fixed joint cannot mimic another joint");
        return None;
    }
    let of = match of {
        Expr::Path(p) if p.path.get_ident().is_some() => p.path.get_ident()?.clone(),
        other => {
            cx.error_spanned_by(
                other,
                "`mimic` names the joint this one follows, e.g. `mimic = finger_left;`",
            );
            return None;
        }
    };
    let multiplier = number("multiplier", 1.0, cx);
    let offset = number("offset", 0.0, cx);
    Some(Some(Mimic {
        of,
        multiplier: multiplier?,
        offset: offset?,
    }))
}
