//! Exact symbolic differentiation, memoised per (node, variable). Results
//! are built with the simplifying builders, so derivatives of terms that do
//! not depend on the variable vanish without work (a bit test).

use crate::graph::Graph;
use crate::node::{Id, Node, Var};

impl Graph {
    /// d(id)/d(v).
    ///
    /// ```
    /// use dynamics_symbolic::{Graph, Var};
    /// let mut g = Graph::new();
    /// let x = g.var(Var(0));
    /// let s = g.sin(x);
    /// let e = g.mul(s, x);               // x sin x
    /// let d = g.diff(e, Var(0));          // sin x + x cos x
    /// let v = g.eval(&[d], &|_| 0.5)[0];
    /// assert!((v - (0.5f64.sin() + 0.5 * 0.5f64.cos())).abs() < 1e-15);
    /// ```
    ///
    /// `abs` differentiates to `x / |x|` (undefined at the kink x = 0).
    pub fn diff(&mut self, id: Id, v: Var) -> Id {
        if !self.depends_on(id, v) {
            return self.constant(0.0);
        }
        if let Some(d) = self.diff_memo.get(&(id, v)) {
            return *d;
        }
        let d = match self.node(id).clone() {
            Node::Const(_) => self.constant(0.0),
            Node::Var(w) => self.constant(if w == v { 1.0 } else { 0.0 }),
            Node::Sum { terms, .. } => {
                let mut parts = Vec::with_capacity(terms.len());
                for (t, c) in terms.iter() {
                    let dt = self.diff(*t, v);
                    parts.push(self.scale(dt, c.get()));
                }
                self.sum(&parts)
            }
            Node::Product { coef, factors } => {
                let mut parts = Vec::new();
                for (i, &(f, e)) in factors.iter().enumerate() {
                    let df = self.diff(f, v);
                    if self.is_zero(df) {
                        continue;
                    }
                    let mut p: Vec<Id> = Vec::with_capacity(factors.len() + 2);
                    p.push(self.constant(coef.get() * e as f64));
                    p.push(self.powi(f, e - 1));
                    p.push(df);
                    for (j, &(g, ge)) in factors.iter().enumerate() {
                        if j != i {
                            p.push(self.powi(g, ge));
                        }
                    }
                    parts.push(self.product(&p));
                }
                self.sum(&parts)
            }
            Node::Sin(a) => {
                let da = self.diff(a, v);
                let c = self.cos(a);
                self.mul(c, da)
            }
            Node::Cos(a) => {
                let da = self.diff(a, v);
                let s = self.sin(a);
                let p = self.mul(s, da);
                self.neg(p)
            }
            Node::Tanh(a) => {
                let da = self.diff(a, v);
                let t2 = self.powi(id, 2);
                let one = self.constant(1.0);
                let sech2 = self.sub(one, t2);
                self.mul(sech2, da)
            }
            Node::Sqrt(a) => {
                let da = self.diff(a, v);
                let inv = self.powi(id, -1);
                let p = self.mul(da, inv);
                self.scale(p, 0.5)
            }
            Node::Abs(a) => {
                let da = self.diff(a, v);
                let sign = self.div(a, id);
                self.mul(sign, da)
            }
        };
        self.diff_memo.insert((id, v), d);
        d
    }
}
