//! The readable text form of a DAG, for golden tests and debugging.
//!
//! One line per used non-leaf node in topological order, then one line per
//! root; leaves are written inline (variables by name, numbers with `{}`):
//!
//! ```text
//! %3 = sin(q0)
//! %5 = 0.2 + 2 * %3 + -1 * %4
//! %6 = 3 * %3^2 * %5^-1
//! out[0] = %6
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
                Node::Const(c) => format!("{}", c.get()),
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
                        parts.push(format!("{}", constant.get()));
                    }
                    for (t, c) in terms.iter() {
                        parts.push(if c.get() == 1.0 {
                            operand(*t)
                        } else {
                            format!("{} * {}", c.get(), operand(*t))
                        });
                    }
                    parts.join(" + ")
                }
                Node::Product { coef, factors } => {
                    let mut parts: Vec<String> = Vec::new();
                    if coef.get() != 1.0 {
                        parts.push(format!("{}", coef.get()));
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
