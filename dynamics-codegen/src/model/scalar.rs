//! Scalar expressions of the model: user expressions with every name
//! resolved (constants folded to numbers, parameters and the joint
//! coordinate kept as symbols).

use proc_macro2::Span;
use syn::{Expr, Lit};

use crate::ctxt::Ctxt;

/// A resolved scalar expression.
#[derive(Debug, Clone, PartialEq)]
pub enum Scalar {
    /// A number (literals and `const` items are folded to this).
    Num(f64),
    /// Run-time parameter number k (declaration order).
    Param(usize),
    /// The coordinate `q` of the joint whose transfer chain this is in.
    Coord,
    /// Coordinate number i, named by its joint (in constraint expressions).
    Joint(usize),
    /// Time `t` (in constraint expressions).
    Time,
    /// `-x`
    Neg(Box<Scalar>),
    /// `a op b`
    Bin(BinOp, Box<Scalar>, Box<Scalar>),
    /// `f(x)`
    Call(Func, Box<Scalar>),
}

/// Binary operators.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum BinOp {
    /// `+`
    Add,
    /// `-`
    Sub,
    /// `*`
    Mul,
    /// `/`
    Div,
}

/// Functions usable in expressions.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Func {
    /// `sin(x)`
    Sin,
    /// `cos(x)`
    Cos,
    /// `sqrt(x)`
    Sqrt,
    /// `tanh(x)`
    Tanh,
    /// `abs(x)`
    Abs,
}

impl Scalar {
    /// The value when the expression holds no symbol.
    pub fn as_number(&self) -> Option<f64> {
        Some(match self {
            Scalar::Num(v) => *v,
            Scalar::Param(_) | Scalar::Coord | Scalar::Joint(_) | Scalar::Time => return None,
            Scalar::Neg(a) => -a.as_number()?,
            Scalar::Bin(op, a, b) => {
                let (a, b) = (a.as_number()?, b.as_number()?);
                match op {
                    BinOp::Add => a + b,
                    BinOp::Sub => a - b,
                    BinOp::Mul => a * b,
                    BinOp::Div => a / b,
                }
            }
            Scalar::Call(f, a) => {
                let a = a.as_number()?;
                match f {
                    Func::Sin => a.sin(),
                    Func::Cos => a.cos(),
                    Func::Sqrt => a.sqrt(),
                    Func::Tanh => a.tanh(),
                    Func::Abs => a.abs(),
                }
            }
        })
    }

    /// True when a coordinate appears: the joint's own `q`, or a
    /// coordinate named by its joint (a mimic joint's chain).
    pub fn moves(&self) -> bool {
        match self {
            Scalar::Coord | Scalar::Joint(_) => true,
            Scalar::Num(_) | Scalar::Param(_) | Scalar::Time => false,
            Scalar::Neg(a) | Scalar::Call(_, a) => a.moves(),
            Scalar::Bin(_, a, b) => a.moves() || b.moves(),
        }
    }

    /// True when the joint coordinate `q` appears.
    pub fn has_coord(&self) -> bool {
        match self {
            Scalar::Coord => true,
            Scalar::Num(_) | Scalar::Param(_) | Scalar::Joint(_) | Scalar::Time => false,
            Scalar::Neg(a) | Scalar::Call(_, a) => a.has_coord(),
            Scalar::Bin(_, a, b) => a.has_coord() || b.has_coord(),
        }
    }
}

/// What names mean where an expression is resolved.
pub struct Scope<'a> {
    /// `const` items: name and folded value.
    pub consts: &'a [(String, f64)],
    /// `param` items, in order.
    pub params: &'a [String],
    /// Whether `q` (the joint's own coordinate) may appear.
    pub coord: bool,
    /// Whether run-time parameters may appear.
    pub allow_params: bool,
    /// Joint names that stand for their coordinates, and whether `t` is
    /// time (in constraint expressions).
    /// A mimic joint's name stands for `multiplier * q + offset`.
    pub joints: &'a [(String, Scalar)],
}

/// Resolves `expr`; every problem is recorded in `cx` (None then).
pub fn resolve(expr: &Expr, scope: &Scope, cx: &mut Ctxt) -> Option<Scalar> {
    match expr {
        Expr::Lit(l) => match &l.lit {
            Lit::Float(f) => number(f.base10_parse::<f64>(), f.span(), cx),
            Lit::Int(i) => number(i.base10_parse::<f64>(), i.span(), cx),
            other => {
                cx.error_spanned_by(other, "expected a number");
                None
            }
        },
        Expr::Paren(p) => resolve(&p.expr, scope, cx),
        Expr::Group(g) => resolve(&g.expr, scope, cx),
        Expr::Unary(u) => match u.op {
            syn::UnOp::Neg(_) => Some(Scalar::Neg(Box::new(resolve(&u.expr, scope, cx)?))),
            _ => {
                cx.error_spanned_by(u, "only unary `-` is supported in expressions");
                None
            }
        },
        Expr::Binary(b) => {
            let op = match b.op {
                syn::BinOp::Add(_) => BinOp::Add,
                syn::BinOp::Sub(_) => BinOp::Sub,
                syn::BinOp::Mul(_) => BinOp::Mul,
                syn::BinOp::Div(_) => BinOp::Div,
                _ => {
                    cx.error_spanned_by(b.op, "unsupported operator; use + - * / and functions");
                    return None;
                }
            };
            let l = resolve(&b.left, scope, cx);
            let r = resolve(&b.right, scope, cx);
            Some(Scalar::Bin(op, Box::new(l?), Box::new(r?)))
        }
        Expr::Path(p) => {
            let Some(ident) = p.path.get_ident() else {
                cx.error_spanned_by(p, "expected a constant, parameter or `q`");
                return None;
            };
            let name = ident.to_string();
            if name == "q" {
                if scope.coord {
                    return Some(Scalar::Coord);
                }
                cx.error_spanned_by(
                    ident,
                    "`q` (the joint coordinate) is only allowed in a joint's transfer chain",
                );
                return None;
            }
            if let Some((_, s)) = scope.joints.iter().find(|(n, _)| *n == name) {
                return Some(s.clone());
            }
            if name == "t" && !scope.joints.is_empty() {
                return Some(Scalar::Time);
            }
            if name == "PI" || name == "pi" {
                return Some(Scalar::Num(std::f64::consts::PI));
            }
            if let Some((_, v)) = scope.consts.iter().rev().find(|(n, _)| *n == name) {
                return Some(Scalar::Num(*v));
            }
            if let Some(k) = scope.params.iter().position(|n| *n == name) {
                if scope.allow_params {
                    return Some(Scalar::Param(k));
                }
                cx.error_spanned_by(
                    ident,
                    format!("`{name}` is a run-time parameter; a constant is needed here"),
                );
                return None;
            }
            let msg = if scope.joints.is_empty() {
                format!("unknown symbol `{name}`: declare it with `const {name} = ...;` or `param {name} = ...;`")
            } else {
                let joints: Vec<&str> = scope.joints.iter().map(|(n, _)| n.as_str()).collect();
                format!(
                    "unknown symbol `{name}`: not a joint ({}), `t`, a constant or a parameter",
                    joints.join(", ")
                )
            };
            cx.error_spanned_by(ident, msg);
            None
        }
        Expr::Call(c) => {
            let fname = match &*c.func {
                Expr::Path(p) => p.path.get_ident().map(|i| i.to_string()),
                _ => None,
            };
            let func = match fname.as_deref() {
                Some("sin") => Func::Sin,
                Some("cos") => Func::Cos,
                Some("sqrt") => Func::Sqrt,
                Some("tanh") => Func::Tanh,
                Some("abs") => Func::Abs,
                _ => {
                    cx.error_spanned_by(
                        &c.func,
                        "unknown function; expressions may call sin, cos, sqrt, tanh, abs",
                    );
                    return None;
                }
            };
            if c.args.len() != 1 {
                cx.error_spanned_by(&c.args, "expected exactly one argument");
                return None;
            }
            let arg = resolve(&c.args[0], scope, cx)?;
            Some(Scalar::Call(func, Box::new(arg)))
        }
        other => {
            cx.error_spanned_by(
                other,
                "expected a scalar expression (numbers, names, + - * /, sin, cos, sqrt, tanh, abs)",
            );
            None
        }
    }
}

fn number(v: syn::Result<f64>, span: Span, cx: &mut Ctxt) -> Option<Scalar> {
    match v {
        Ok(v) if v.is_finite() => Some(Scalar::Num(v)),
        _ => {
            cx.error_at(span, "number out of range");
            None
        }
    }
}

/// Resolves a fixed-length `[a, b, c]` array expression.
pub fn resolve_array<const K: usize>(
    expr: &Expr,
    what: &str,
    scope: &Scope,
    cx: &mut Ctxt,
) -> Option<[Scalar; K]> {
    let items = array_items(expr, what, cx)?;
    if items.len() != K {
        cx.error_spanned_by(
            expr,
            format!("{what} must have {K} entries, found {}", items.len()),
        );
        return None;
    }
    let resolved: Vec<Option<Scalar>> = items.iter().map(|e| resolve(e, scope, cx)).collect();
    let resolved: Option<Vec<Scalar>> = resolved.into_iter().collect();
    resolved?.try_into().ok()
}

/// The entries of an `[...]` expression, or an error naming `what`.
pub fn array_items<'e>(expr: &'e Expr, what: &str, cx: &mut Ctxt) -> Option<Vec<&'e Expr>> {
    match expr {
        Expr::Array(a) => Some(a.elems.iter().collect()),
        Expr::Group(g) => array_items(&g.expr, what, cx),
        Expr::Paren(p) => array_items(&p.expr, what, cx),
        other => {
            cx.error_spanned_by(other, format!("{what} must be an array `[..]`"));
            None
        }
    }
}
