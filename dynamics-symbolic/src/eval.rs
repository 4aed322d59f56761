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
