//! The readable text form of a DAG, for golden tests and debugging.
//!
//! One line per used non-leaf node in topological order, `%N = ...` with N
//! the node's arena index (the `tN` of the emitted code), then one line
//! `out[k] = ...` per root. Leaves are written inline: variables by the
//! caller's names, numbers by Rust's shortest round-trip `{}` form (`5`,
//! `-0.5`), or by `{:e}` (`1e300`) where `{}` takes over 24 characters.
//! Sums are `c + k * a + b` (the constant first unless 0, then the terms by
//! id, each `coefficient * term` unless the coefficient is 1); products are
//! `k * a * b^2 * c^-1` (the coefficient first unless 1, then the factors
//! by id, `^e` unless e = 1); calls are `sin(a)`, `cos(a)`, `tanh(a)`,
//! `sqrt(a)`, `abs(a)`. For `0.2 cos q - 0.5 sin q cos^2 q`:
//!
//! ```text
//! %1 = sin(q0)
//! %2 = cos(q0)
//! %8 = %1 * %2^2
//! %9 = 0.2 * %2 + -0.5 * %8
//! out[0] = %9
//! ```

use std::fmt::Write as _;

use crate::graph::Graph;
use crate::node::{Id, Node, Var};

impl Graph {
    /// The sub-DAG reachable from `roots` as text.
    ///
    /// ```
    /// use dynamics_symbolic::{Graph, Var};
    /// let mut g = Graph::new();
    /// let x = g.var(Var(0));
    /// let s = g.sin(x);
    /// let e = g.add(s, s);
    /// let text = g.to_text(&[e], &|v| format!("x{}", v.0));
    /// assert_eq!(text, "%1 = sin(x0)\n%3 = 2 * %1\nout[0] = %3\n"); // %2 is the constant 2
    /// ```
    pub fn to_text(&self, roots: &[Id], names: &dyn Fn(Var) -> String) -> String {
        let operand = |id: Id| -> String {
            match self.node(id) {
                Node::Const(c) => number(c.get()),
                Node::Var(v) => names(*v),
                _ => format!("%{}", id.index()),
            }
        };
        let mut out = String::new();
        for id in self.reachable(roots) {
            let rhs = match self.node(id) {
                Node::Const(_) | Node::Var(_) => continue,
                Node::Sum { constant, terms } => {
                    let mut parts: Vec<String> = Vec::new();
                    if constant.get() != 0.0 {
                        parts.push(number(constant.get()));
                    }
                    for (t, c) in terms.iter() {
                        parts.push(if c.get() == 1.0 {
                            operand(*t)
                        } else {
                            format!("{} * {}", number(c.get()), operand(*t))
                        });
                    }
                    parts.join(" + ")
                }
                Node::Product { coef, factors } => {
                    let mut parts: Vec<String> = Vec::new();
                    if coef.get() != 1.0 {
                        parts.push(number(coef.get()));
                    }
                    for (f, e) in factors.iter() {
                        parts.push(if *e == 1 {
                            operand(*f)
                        } else {
                            format!("{}^{}", operand(*f), e)
                        });
                    }
                    parts.join(" * ")
                }
                Node::Sin(a) => format!("sin({})", operand(*a)),
                Node::Cos(a) => format!("cos({})", operand(*a)),
                Node::Tanh(a) => format!("tanh({})", operand(*a)),
                Node::Sqrt(a) => format!("sqrt({})", operand(*a)),
                Node::Abs(a) => format!("abs({})", operand(*a)),
            };
            let _ = writeln!(out, "%{} = {}", id.index(), rhs);
        }
        for (k, r) in roots.iter().enumerate() {
            let _ = writeln!(out, "out[{k}] = {}", operand(*r));
        }
        out
    }
}

/// A number as text: `{}` unless that is long, then `{:e}`.
fn number(v: f64) -> String {
    let s = format!("{v}");
    if s.len() > 24 {
        format!("{v:e}")
    } else {
        s
    }
}

/// `to_text` with node numbers renamed `%a, %b, ...` in order of first
/// appearance, so test goldens pin structure, not arena positions.
#[cfg(test)]
pub(crate) fn golden(g: &Graph, roots: &[Id]) -> String {
    let raw = g.to_text(roots, &|v| ["x", "y", "z"][v.0 as usize].to_string());
    let mut seen: Vec<String> = Vec::new();
    let mut out = String::new();
    let mut chars = raw.chars().peekable();
    while let Some(c) = chars.next() {
        out.push(c);
        if c != '%' {
            continue;
        }
        let mut num = String::new();
        while let Some(d) = chars.next_if(|d| d.is_ascii_digit()) {
            num.push(d);
        }
        let k = match seen.iter().position(|s| *s == num) {
            Some(k) => k,
            None => {
                seen.push(num);
                seen.len() - 1
            }
        };
        out.push(char::from(b'a' + (k % 26) as u8));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn format_of_every_node_kind() {
        let mut g = Graph::new();
        let x = g.var(Var(0));
        let y = g.var(Var(1));
        let s = g.sin(x);
        let c = g.cos(y);
        let t = g.tanh(s);
        let one = g.constant(1.0);
        let x2 = g.powi(x, 2);
        let r0 = g.add(one, x2);
        let r = g.sqrt(r0);
        let a = g.abs(c);
        let k = g.constant(-0.5);
        let p0 = g.product(&[k, t, r]);
        let p = g.div(p0, a);
        let big = g.constant(1e300);
        let e = g.sum(&[p, big, s, s]);
        assert_eq!(
            g.to_text(&[e, x, k], &|v| format!("q{}", v.0)),
            "%2 = sin(q0)\n\
             %3 = cos(q1)\n\
             %4 = tanh(%2)\n\
             %6 = q0^2\n\
             %7 = 1 + %6\n\
             %8 = sqrt(%7)\n\
             %9 = abs(%3)\n\
             %15 = %4 * %8 * %9^-1\n\
             %16 = 1e300 + 2 * %2 + -0.5 * %15\n\
             out[0] = %16\n\
             out[1] = q0\n\
             out[2] = -0.5\n"
        );
    }

    #[test]
    fn golden_renames_in_order_of_appearance() {
        let mut g = Graph::new();
        let x = g.var(Var(0));
        let _unused = g.var(Var(1));
        let c = g.cos(x);
        let s = g.sin(x);
        let e = g.mul(s, c);
        assert_eq!(
            golden(&g, &[e]),
            "%a = cos(x)\n%b = sin(x)\n%c = %a * %b\nout[0] = %c\n"
        );
    }
}
