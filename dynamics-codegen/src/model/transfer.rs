//! A joint's placement: its chain of elementary transfer matrices, written
//! either as `transfer = [...]` (dissertation, eqs. 2.1-2.5) or URDF-style as
//! `origin`, `rpy` and `axis`.

use syn::{Expr, Ident};

use super::scalar::{array_items, resolve, resolve_array, Scalar, Scope};
use super::{Elem, JointKind};
use crate::ctxt::Ctxt;

const ELEMS: &str = "expected an elementary transfer matrix: rot_x(a), rot_y(a), rot_z(a), \
                     trans_x(d), trans_y(d), trans_z(d), planar tu(d), tv(d), rot(a), \
                     or matrix([[..], ..]) (3x3 planar or 4x4 homogeneous)";

/// `transfer = [elem, elem, ...]`
pub fn chain(value: &Expr, scope: &Scope, cx: &mut Ctxt) -> Option<Vec<Elem>> {
    let items = array_items(value, "`transfer`", cx)?;
    let elems: Vec<Option<Elem>> = items.iter().map(|e| elem(e, scope, cx)).collect();
    elems.into_iter().collect()
}

fn elem(expr: &Expr, scope: &Scope, cx: &mut Ctxt) -> Option<Elem> {
    let Expr::Call(call) = expr else {
        cx.error_spanned_by(expr, ELEMS);
        return None;
    };
    let name = match &*call.func {
        Expr::Path(p) => p.path.get_ident().map(|i| i.to_string()),
        _ => None,
    };
    let Some(name) = name else {
        cx.error_spanned_by(&call.func, ELEMS);
        return None;
    };
    let args: Vec<&Expr> = call.args.iter().collect();
    if args.len() != 1 {
        cx.error_spanned_by(
            expr,
            format!("`{name}` takes exactly one argument, found {}", args.len()),
        );
        return None;
    }
    let zero = || Scalar::Num(0.0);
    let one = |cx: &mut Ctxt| resolve(args[0], scope, cx);
    Some(match name.as_str() {
        "rot_x" => Elem::Rot([1.0, 0.0, 0.0], one(cx)?),
        "rot_y" => Elem::Rot([0.0, 1.0, 0.0], one(cx)?),
        "rot_z" | "rot" => Elem::Rot([0.0, 0.0, 1.0], one(cx)?),
        "trans_x" | "tu" => Elem::Trans([one(cx)?, zero(), zero()]),
        "trans_y" | "tv" => Elem::Trans([zero(), one(cx)?, zero()]),
        "trans_z" => Elem::Trans([zero(), zero(), one(cx)?]),
        "matrix" => matrix(args[0], scope, cx)?,
        _ => {
            cx.error_spanned_by(&call.func, ELEMS);
            return None;
        }
    })
}

/// `matrix([[..],[..],[..]])` (planar) or 4x4 homogeneous.
fn matrix(expr: &Expr, scope: &Scope, cx: &mut Ctxt) -> Option<Elem> {
    let rows = array_items(expr, "a transfer matrix", cx)?;
    let n = rows.len();
    let mut entries: Vec<Vec<Scalar>> = Vec::new();
    let mut ok = true;
    for row in &rows {
        let Some(items) = array_items(row, "a matrix row", cx) else {
            ok = false;
            continue;
        };
        if items.len() != n || !(n == 3 || n == 4) {
            ok = false;
            continue;
        }
        let r: Option<Vec<Scalar>> = items.iter().map(|e| resolve(e, scope, cx)).collect();
        match r {
            Some(r) => entries.push(r),
            None => return None,
        }
    }
    if !ok || !(n == 3 || n == 4) {
        cx.error_spanned_by(
            expr,
            "a transfer matrix must be 3x3 (planar homogeneous) or 4x4 (spatial homogeneous)",
        );
        return None;
    }
    let last: Vec<Option<f64>> = entries[n - 1].iter().map(Scalar::as_number).collect();
    let mut expected = vec![Some(0.0); n];
    expected[n - 1] = Some(1.0);
    if last != expected {
        let msg = if n == 3 {
            "the last row of a planar homogeneous matrix must be [0, 0, 1]"
        } else {
            "the last row of a homogeneous matrix must be [0, 0, 0, 1]"
        };
        cx.error_spanned_by(rows[n - 1], msg);
        return None;
    }
    let e = |r: usize, c: usize| entries[r][c].clone();
    let z = || Scalar::Num(0.0);
    if n == 3 {
        Some(Elem::Matrix(
            Box::new([
                [e(0, 0), e(0, 1), z()],
                [e(1, 0), e(1, 1), z()],
                [z(), z(), Scalar::Num(1.0)],
            ]),
            [e(0, 2), e(1, 2), z()],
        ))
    } else {
        Some(Elem::Matrix(
            Box::new([
                [e(0, 0), e(0, 1), e(0, 2)],
                [e(1, 0), e(1, 1), e(1, 2)],
                [e(2, 0), e(2, 1), e(2, 2)],
            ]),
            [e(0, 3), e(1, 3), e(2, 3)],
        ))
    }
}

/// URDF-style placement: `Trans(origin) Rz(yaw) Ry(pitch) Rx(roll)`, then
/// the motion along or about `axis`.
pub fn urdf_style(
    kind: JointKind,
    origin: Option<&Expr>,
    rpy: Option<&Expr>,
    axis: Option<(&Ident, &Expr)>,
    joint: &Ident,
    scope: &Scope,
    cx: &mut Ctxt,
) -> Option<Vec<Elem>> {
    let fixed = Scope {
        coord: false,
        ..*scope
    };
    let mut chain = Vec::new();
    if let Some(o) = origin {
        let xyz = resolve_array::<3>(o, "`origin`", &fixed, cx)?;
        if xyz.iter().any(|s| s.as_number() != Some(0.0)) {
            chain.push(Elem::Trans(xyz));
        }
    }
    if let Some(r) = rpy {
        let [roll, pitch, yaw] = resolve_array::<3>(r, "`rpy`", &fixed, cx)?;
        for (axis, angle) in [
            ([0.0, 0.0, 1.0], yaw),
            ([0.0, 1.0, 0.0], pitch),
            ([1.0, 0.0, 0.0], roll),
        ] {
            if angle.as_number() != Some(0.0) {
                chain.push(Elem::Rot(axis, angle));
            }
        }
    }
    match (kind, axis) {
        (JointKind::Fixed, Some((key, _))) => {
            cx.error_spanned_by(key, "a fixed joint has no `axis`");
            return None;
        }
        (JointKind::Fixed, None) => {}
        (_, None) => {
            // URDF's default axis is x; here it must be written out.
            cx.error_spanned_by(
                joint,
                format!("joint `{joint}` needs `axis = [x, y, z];` (or a `transfer` chain)"),
            );
            return None;
        }
        (kind, Some((_, a))) => {
            let a = resolve_array::<3>(a, "`axis`", &fixed, cx)?;
            let Some(v) = numbers(&a) else {
                cx.error_spanned_by(axis.map(|x| x.1), "`axis` must be made of constants");
                return None;
            };
            let norm = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
            if norm < 1e-12 || !norm.is_finite() {
                cx.error_spanned_by(
                    axis.map(|x| x.1),
                    "`axis` has zero length; give the direction of the joint's motion",
                );
                return None;
            }
            let u = [v[0] / norm, v[1] / norm, v[2] / norm];
            chain.push(match kind {
                JointKind::Revolute => Elem::Rot(u, Scalar::Coord),
                _ => Elem::Trans(u.map(|c| {
                    Scalar::Bin(
                        super::scalar::BinOp::Mul,
                        Box::new(Scalar::Num(c)),
                        Box::new(Scalar::Coord),
                    )
                })),
            });
        }
    }
    Some(chain)
}

fn numbers(a: &[Scalar; 3]) -> Option<[f64; 3]> {
    Some([a[0].as_number()?, a[1].as_number()?, a[2].as_number()?])
}

/// Where the coordinate `q` drives the chain: (in a rotation, in a translation).
pub fn coord_use(chain: &[Elem]) -> (bool, bool) {
    let mut rot = false;
    let mut trans = false;
    for e in chain {
        match e {
            Elem::Rot(_, a) => rot |= a.has_coord(),
            Elem::Trans(t) => trans |= t.iter().any(Scalar::has_coord),
            Elem::Matrix(r, t) => {
                rot |= r.iter().flatten().any(Scalar::has_coord);
                trans |= t.iter().any(Scalar::has_coord);
            }
        }
    }
    (rot, trans)
}
