//! The simplifying builders. Every expression is built through them, so
//! every node is in canonical form:
//! - constants fold, unless the result would be NaN or infinite: then the
//!   operands are kept unfolded (`x / 0` is `x * 0^-1`, `sqrt(-1)` stays),
//!   never a panic and never a NaN constant;
//! - sums and products are flat, sorted, with like terms collected
//!   (`2x + 3x = 5x`, `x - x = 0`, `x x = x^2`), `x + 0`, `x * 1`, `x * 0`;
//! - minus a sum is distributed into the sum's coefficients, so a negation
//!   is only ever a coefficient (negation normal form); another constant
//!   times a shared sum stays one product `k * (a + b)`;
//! - `k r sin(x)^2 + k r cos(x)^2 = k r`;
//! - `sin(-x) = -sin(x)`, `cos(-x) = cos(x)`.
//!
//! Products are never distributed over sums (that would grow the DAG).

mod call;
mod product;
mod sum;

use crate::graph::Graph;
use crate::node::Id;
#[cfg(test)]
use crate::node::Var;

/// `Some(v)` if `v` is finite: the only values a constant folds to.
fn finite(v: f64) -> Option<f64> {
    v.is_finite().then_some(v)
}

impl Graph {
    /// `a + b`
    pub fn add(&mut self, a: Id, b: Id) -> Id {
        self.sum(&[a, b])
    }

    /// `a - b`
    pub fn sub(&mut self, a: Id, b: Id) -> Id {
        let nb = self.neg(b);
        self.sum(&[a, nb])
    }

    /// `-a`
    pub fn neg(&mut self, a: Id) -> Id {
        self.scale(a, -1.0)
    }

    /// `a * b`
    pub fn mul(&mut self, a: Id, b: Id) -> Id {
        self.product(&[a, b])
    }

    /// `a / b` (`x / 0` stays symbolic: no panic, no NaN constant).
    pub fn div(&mut self, a: Id, b: Id) -> Id {
        let inv = self.powi(b, -1);
        self.product(&[a, inv])
    }

    /// `k * a` for a number k.
    pub fn scale(&mut self, a: Id, k: f64) -> Id {
        let c = self.constant(k);
        self.product(&[c, a])
    }
}

/// Variables 0, 1, 2 of `g`, for tests.
#[cfg(test)]
fn xyz(g: &mut Graph) -> (Id, Id, Id) {
    (g.var(Var(0)), g.var(Var(1)), g.var(Var(2)))
}

#[cfg(test)]
mod tests {
    use crate::text::golden as text;
    use crate::{Graph, Node, Var};

    #[test]
    fn every_op_folds_on_constants() {
        let mut g = Graph::new();
        let (two, three, four) = (g.constant(2.0), g.constant(3.0), g.constant(4.0));
        let cases = [
            (g.add(two, three), 5.0),
            (g.sub(two, three), -1.0),
            (g.mul(two, three), 6.0),
            (g.div(three, two), 1.5),
            (g.neg(two), -2.0),
            (g.powi(two, 3), 8.0),
            (g.powi(two, -2), 0.25),
            (g.sum(&[two, three, four]), 9.0),
            (g.product(&[two, three, four]), 24.0),
            (g.sqrt(four), 2.0),
            (g.sin(two), 2f64.sin()),
            (g.cos(two), 2f64.cos()),
            (g.tanh(two), 2f64.tanh()),
            (g.sum(&[]), 0.0),
            (g.product(&[]), 1.0),
        ];
        for (id, v) in cases {
            assert_eq!(g.as_constant(id), Some(v), "{}", text(&g, &[id]));
        }
        let m = g.constant(-2.0);
        let a = g.abs(m);
        assert_eq!(g.as_constant(a), Some(2.0));
    }

    #[test]
    fn folding_never_makes_nan_or_infinity() {
        let mut g = Graph::new();
        let (zero, m1, big) = (g.constant(0.0), g.constant(-1.0), g.constant(1e300));
        let root = g.sqrt(m1);
        assert_eq!(text(&g, &[root]), "%a = sqrt(-1)\nout[0] = %a\n");
        let inv = g.powi(zero, -1);
        assert_eq!(text(&g, &[inv]), "%a = 0^-1\nout[0] = %a\n");
        let sq = g.mul(big, big);
        assert_eq!(text(&g, &[sq]), "%a = 1e300^2\nout[0] = %a\n");
        assert_eq!(g.eval(&[sq], &|_| 0.0), vec![f64::INFINITY]);
        let big2 = g.constant(1.7e308);
        let s = g.add(big2, big2);
        assert_eq!(g.as_constant(s), None);
        assert_eq!(g.eval(&[s], &|_| 0.0), vec![f64::INFINITY]);
        let inf = g.constant(f64::INFINITY);
        let ninf = g.constant(f64::NEG_INFINITY);
        let nan_sum = g.add(inf, ninf);
        assert_eq!(g.as_constant(nan_sum), None);
        assert!(g.eval(&[nan_sum], &|_| 0.0)[0].is_nan());
        let x = g.var(Var(0));
        let p = g.powi(big, 2);
        let q = g.mul(p, x);
        let r = g.powi(q, 2);
        assert_eq!(g.eval(&[r], &|_| 1.0), vec![f64::INFINITY]);
        for id in 0..g.len() {
            if let Node::Const(c) = g.node(crate::Id(id as u32)) {
                assert!(!c.get().is_nan());
            }
        }
    }

    #[test]
    fn identities() {
        let mut g = Graph::new();
        let (x, y, _) = super::xyz(&mut g);
        let (zero, one) = (g.constant(0.0), g.constant(1.0));
        assert_eq!(g.add(x, zero), x);
        assert_eq!(g.add(zero, x), x);
        assert_eq!(g.mul(x, one), x);
        assert_eq!(g.mul(one, x), x);
        assert_eq!(g.mul(x, zero), zero);
        assert_eq!(g.mul(zero, x), zero);
        assert_eq!(g.div(x, one), x);
        assert_eq!(g.div(zero, x), zero);
        let d = g.sub(x, x);
        assert_eq!(d, zero);
        let nx = g.neg(x);
        assert_eq!(g.neg(nx), x);
        let xy = g.mul(x, y);
        let q = g.div(xy, y);
        assert_eq!(q, x);
        let p0 = g.powi(x, 0);
        assert_eq!(p0, one);
        assert_eq!(g.powi(x, 1), x);
        let x_over_0 = g.div(x, zero);
        assert_eq!(text(&g, &[x_over_0]), "%a = x * 0^-1\nout[0] = %a\n");
    }

    #[test]
    fn order_does_not_matter() {
        let mut g = Graph::new();
        let (x, y, z) = super::xyz(&mut g);
        assert_eq!(g.add(x, y), g.add(y, x));
        assert_eq!(g.mul(x, y), g.mul(y, x));
        assert_eq!(g.sum(&[x, y, z]), g.sum(&[z, y, x]));
        let xy = g.add(x, y);
        let left = g.add(xy, z);
        let yz = g.add(y, z);
        let right = g.add(x, yz);
        assert_eq!(left, right);
        let s = g.sin(x);
        let a = g.product(&[s, y, z]);
        let b = g.product(&[z, s, y]);
        assert_eq!(a, b);
    }
}
