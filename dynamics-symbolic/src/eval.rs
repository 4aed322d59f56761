//! Numerical evaluation (for tests and checks at expansion time).

use crate::graph::Graph;
use crate::node::{Id, Node, Var};

impl Graph {
    /// Values of `roots` with the variables given by `vars`.
    ///
    /// ```
    /// use dynamics_symbolic::{Graph, Var};
    /// let mut g = Graph::new();
    /// let x = g.var(Var(0));
    /// let y = g.var(Var(1));
    /// let e = g.div(x, y);
    /// assert_eq!(g.eval(&[e], &|v| if v == Var(0) { 3.0 } else { 2.0 }), vec![1.5]);
    /// ```
    pub fn eval(&self, roots: &[Id], vars: &dyn Fn(Var) -> f64) -> Vec<f64> {
        let order = self.reachable(roots);
        let mut val = vec![0.0; self.len()];
        for id in order {
            val[id.index()] = match self.node(id) {
                Node::Const(c) => c.get(),
                Node::Var(v) => vars(*v),
                Node::Sum { constant, terms } => terms
                    .iter()
                    .fold(constant.get(), |s, (t, c)| s + c.get() * val[t.index()]),
                Node::Product { coef, factors } => factors
                    .iter()
                    .fold(coef.get(), |p, (f, e)| p * val[f.index()].powi(*e)),
                Node::Sin(a) => val[a.index()].sin(),
                Node::Cos(a) => val[a.index()].cos(),
                Node::Tanh(a) => val[a.index()].tanh(),
                Node::Sqrt(a) => val[a.index()].sqrt(),
                Node::Abs(a) => val[a.index()].abs(),
            };
        }
        roots.iter().map(|r| val[r.index()]).collect()
    }
}

#[cfg(test)]
mod tests {
    use crate::{Graph, Var};

    #[test]
    fn every_node_kind() {
        let mut g = Graph::new();
        let (x, y) = (g.var(Var(0)), g.var(Var(1)));
        let (xv, yv) = (0.7f64, -1.3f64);
        let vars = |v: Var| if v == Var(0) { xv } else { yv };
        let s = g.sin(x);
        let c = g.cos(y);
        let t = g.tanh(y);
        let r = g.sqrt(x);
        let a = g.abs(y);
        let k = g.constant(-2.5);
        let p = g.product(&[k, s, c]);
        let q = g.div(t, a);
        let w = g.powi(r, 5);
        let e = g.sum(&[p, q, w, k]);
        let got = g.eval(&[e, x, k, s], &vars);
        let want = -2.5 * xv.sin() * yv.cos() + yv.tanh() / yv.abs() + xv.sqrt().powi(5) - 2.5;
        assert!((got[0] - want).abs() < 1e-14, "{} vs {want}", got[0]);
        assert_eq!(got[1..], [xv, -2.5, xv.sin()]);
    }

    #[test]
    fn no_roots_no_values() {
        let g = Graph::new();
        assert!(g.eval(&[], &|_| 0.0).is_empty());
    }
}
