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
                    p.push(match e.checked_sub(1) {
                        Some(m) => self.powi(f, m),
                        None => {
                            let inv = self.powi(f, -1);
                            let fe = self.powi(f, e);
                            self.mul(fe, inv)
                        }
                    });
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

#[cfg(test)]
mod tests {
    use crate::text::golden;
    use crate::{Graph, Id, Var};

    const X: Var = Var(0);

    /// The derivative by x of what `f` builds from x and y, as text.
    fn d(f: impl Fn(&mut Graph, Id, Id) -> Id) -> String {
        let mut g = Graph::new();
        let (x, y) = (g.var(X), g.var(Var(1)));
        let e = f(&mut g, x, y);
        let de = g.diff(e, X);
        golden(&g, &[de])
    }

    #[test]
    fn rules() {
        assert_eq!(d(|g, x, _| g.sin(x)), "%a = cos(x)\nout[0] = %a\n");
        assert_eq!(
            d(|g, x, _| g.cos(x)),
            "%a = sin(x)\n%b = -1 * %a\nout[0] = %b\n"
        );
        assert_eq!(
            d(|g, x, _| g.tanh(x)),
            "%a = tanh(x)\n%b = %a^2\n%c = 1 + -1 * %b\nout[0] = %c\n"
        );
        assert_eq!(
            d(|g, x, _| g.sqrt(x)),
            "%a = sqrt(x)\n%b = 0.5 * %a^-1\nout[0] = %b\n"
        );
        assert_eq!(
            d(|g, x, _| g.abs(x)),
            "%a = abs(x)\n%b = x * %a^-1\nout[0] = %b\n"
        );
        assert_eq!(d(|g, x, _| g.powi(x, 3)), "%a = 3 * x^2\nout[0] = %a\n");
        assert_eq!(d(|g, x, _| g.powi(x, -1)), "%a = -1 * x^-2\nout[0] = %a\n");
        assert_eq!(d(|g, x, y| g.mul(x, y)), "out[0] = y\n");
        assert_eq!(d(|g, _, y| g.sin(y)), "out[0] = 0\n");
        assert_eq!(d(|g, _, _| g.constant(2.0)), "out[0] = 0\n");
        assert_eq!(
            d(|g, x, y| {
                let xy = g.mul(x, y);
                let s = g.sin(xy);
                let k = g.constant(3.0);
                g.sum(&[s, x, k])
            }),
            "%a = x * y\n%b = cos(%a)\n%c = y * %b\n%d = 1 + %c\nout[0] = %d\n"
        );
        // Chain rule through a square: d sin(x^2) = 2 x cos(x^2).
        assert_eq!(
            d(|g, x, _| {
                let x2 = g.powi(x, 2);
                g.sin(x2)
            }),
            "%a = x^2\n%b = cos(%a)\n%c = 2 * x * %b\nout[0] = %c\n"
        );
    }

    #[test]
    fn memoised_and_free_when_independent() {
        let mut g = Graph::new();
        let (x, y) = (g.var(X), g.var(Var(1)));
        let s = g.sin(x);
        let e = g.mul(s, y);
        let d1 = g.diff(e, X);
        let n = g.len();
        assert_eq!(g.diff(e, X), d1);
        assert_eq!(g.len(), n);
        let dz = g.diff(e, Var(7));
        assert!(g.is_zero(dz));
        // Second derivative: d2/dx2 (y sin x) = -y sin x.
        let d2 = g.diff(d1, X);
        let v = g.eval(&[d2], &|v| if v == X { 0.3 } else { 2.0 })[0];
        assert!((v + 2.0 * 0.3f64.sin()).abs() < 1e-15);
    }

    #[test]
    fn abs_kink_is_undefined() {
        let mut g = Graph::new();
        let x = g.var(X);
        let a = g.abs(x);
        let da = g.diff(a, X);
        assert_eq!(g.eval(&[da], &|_| -2.0), vec![-1.0]);
        assert_eq!(g.eval(&[da], &|_| 3.0), vec![1.0]);
        assert!(g.eval(&[da], &|_| 0.0)[0].is_nan());
    }
}
