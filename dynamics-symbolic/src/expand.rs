//! Expansion into a canonical trigonometric polynomial: products are
//! distributed over sums, and every `sin(x)^k` with k >= 2 is rewritten as
//! `sin(x)^(k-2) (1 - cos(x)^2)`, so that every polynomial identity in
//! sin/cos of the same arguments (sin^2 + cos^2 = 1 in any arrangement)
//! cancels. Used where it pays: the caller gives a term budget and keeps
//! the unexpanded form when the expansion would be larger.

use std::collections::BTreeMap;

use crate::graph::Graph;
use crate::node::{Id, Node};

/// Coefficients below this fraction of the largest one are rounding noise.
const ROUNDING: f64 = 1e-13;

/// A monomial: sorted (atom, exponent) pairs.
type Mono = Vec<(Id, i32)>;
/// A polynomial: monomial -> coefficient.
type Poly = BTreeMap<Mono, f64>;

impl Graph {
    /// `id` expanded, or `None` when the expansion has more than `limit`
    /// terms at any stage.
    ///
    /// ```
    /// use dynamics_symbolic::{Graph, Var};
    /// let mut g = Graph::new();
    /// let x = g.var(Var(0));
    /// let (s, c) = (g.sin(x), g.cos(x));
    /// let one = g.constant(1.0);
    /// let a = g.add(one, c);               // (1 + cos x)
    /// let b = g.sub(one, c);               // (1 - cos x)
    /// let p = g.mul(a, b);                 // = sin^2 x
    /// let s2 = g.powi(s, 2);
    /// let e = g.sub(p, s2);
    /// let z = g.expand(e, 100).unwrap();
    /// assert!(g.is_zero(z));
    /// ```
    pub fn expand(&mut self, id: Id, limit: usize) -> Option<Id> {
        let mut memo: BTreeMap<Id, Poly> = BTreeMap::new();
        let poly = self.poly(id, limit, &mut memo)?;
        Some(self.build_poly(&poly))
    }

    fn poly(&mut self, id: Id, limit: usize, memo: &mut BTreeMap<Id, Poly>) -> Option<Poly> {
        if let Some(p) = memo.get(&id) {
            return Some(p.clone());
        }
        let p = match self.node(id).clone() {
            Node::Const(c) => {
                let mut p = Poly::new();
                if c.get() != 0.0 {
                    p.insert(Vec::new(), c.get());
                }
                p
            }
            Node::Sum { constant, terms } => {
                let mut p = Poly::new();
                if constant.get() != 0.0 {
                    p.insert(Vec::new(), constant.get());
                }
                for (t, c) in terms.iter() {
                    let tp = self.poly(*t, limit, memo)?;
                    for (m, k) in tp {
                        *p.entry(m).or_insert(0.0) += k * c.get();
                    }
                    if p.len() > limit {
                        return None;
                    }
                }
                p.retain(|_, c| *c != 0.0);
                p
            }
            Node::Product { coef, factors } => {
                let mut p = Poly::new();
                p.insert(Vec::new(), coef.get());
                for (f, e) in factors.iter() {
                    let fp = if *e > 0 {
                        let base = self.poly(*f, limit, memo)?;
                        let mut acc = base.clone();
                        for _ in 1..*e {
                            acc = self.poly_mul(&acc, &base, limit)?;
                        }
                        acc
                    } else {
                        // Negative powers stay atoms.
                        let mut q = Poly::new();
                        q.insert(vec![(*f, *e)], 1.0);
                        q
                    };
                    p = self.poly_mul(&p, &fp, limit)?;
                }
                p
            }
            _ => {
                let mut p = Poly::new();
                p.insert(vec![(id, 1)], 1.0);
                p
            }
        };
        memo.insert(id, p.clone());
        Some(p)
    }

    fn poly_mul(&mut self, a: &Poly, b: &Poly, limit: usize) -> Option<Poly> {
        let mut out = Poly::new();
        for (ma, ca) in a {
            for (mb, cb) in b {
                let mut m: BTreeMap<Id, i32> = ma.iter().copied().collect();
                for (atom, e) in mb {
                    *m.entry(*atom).or_insert(0) += e;
                }
                m.retain(|_, e| *e != 0);
                for (mono, k) in self.reduce_sin_squares(m.into_iter().collect()) {
                    *out.entry(mono).or_insert(0.0) += ca * cb * k;
                }
                if out.len() > limit {
                    return None;
                }
            }
        }
        out.retain(|_, c| *c != 0.0);
        Some(out)
    }

    /// Rewrites `sin(x)^k`, k >= 2, as `sin(x)^(k-2) (1 - cos(x)^2)`.
    fn reduce_sin_squares(&mut self, mono: Mono) -> Vec<(Mono, f64)> {
        let pos = mono
            .iter()
            .position(|(a, e)| *e >= 2 && matches!(self.node(*a), Node::Sin(_)));
        let Some(i) = pos else {
            return vec![(mono, 1.0)];
        };
        let (atom, e) = mono[i];
        let Node::Sin(x) = *self.node(atom) else {
            return vec![(mono, 1.0)];
        };
        let cos = self.cos(x);
        let mut base: BTreeMap<Id, i32> = mono.iter().copied().collect();
        *base.entry(atom).or_insert(0) -= 2;
        base.retain(|_, e| *e != 0);
        let mut with_cos = base.clone();
        *with_cos.entry(cos).or_insert(0) += 2;
        with_cos.retain(|_, e| *e != 0);
        let _ = e;
        let mut out = self.reduce_sin_squares(base.into_iter().collect());
        for (m, k) in self.reduce_sin_squares(with_cos.into_iter().collect()) {
            out.push((m, -k));
        }
        out
    }

    fn build_poly(&mut self, p: &Poly) -> Id {
        // Coefficients that cancelled up to rounding (e.g. 3e-18 next to
        // 0.2) are dropped: they are float noise of the distribution, not
        // terms of the expression.
        let largest = p.values().fold(0.0f64, |m, c| m.max(c.abs()));
        let mut terms = Vec::with_capacity(p.len());
        for (mono, c) in p {
            if c.abs() <= ROUNDING * largest {
                continue;
            }
            let mut factors: Vec<Id> = Vec::with_capacity(mono.len() + 1);
            factors.push(self.constant(*c));
            for (atom, e) in mono {
                factors.push(self.powi(*atom, *e));
            }
            terms.push(self.product(&factors));
        }
        self.sum(&terms)
    }
}

#[cfg(test)]
mod tests {
    use crate::text::golden;
    use crate::{Graph, Var};

    #[test]
    fn sin_squares_become_cos_squares_and_cancel() {
        let mut g = Graph::new();
        let (x, y) = (g.var(Var(0)), g.var(Var(1)));
        let (s, c) = (g.sin(x), g.cos(x));
        // (y + s)^2 + (c - y)(c + y) ... = s^2 + 2 y s + c^2 = 1 + 2 y s
        let ys = g.add(y, s);
        let a = g.powi(ys, 2);
        let cmy = g.sub(c, y);
        let cpy = g.add(c, y);
        let b = g.mul(cmy, cpy);
        let e = g.add(a, b);
        let z = g.expand(e, 100).expect("small");
        assert_eq!(
            golden(&g, &[z]),
            "%a = sin(x)\n%b = y * %a\n%c = 1 + 2 * %b\nout[0] = %c\n"
        );
        let at = |v: Var| if v == Var(0) { 0.4 } else { -1.1 };
        let (before, after) = (g.eval(&[e], &at)[0], g.eval(&[z], &at)[0]);
        assert!((before - after).abs() < 1e-14);
    }

    #[test]
    fn too_many_terms_is_none() {
        let mut g = Graph::new();
        let (x, y) = (g.var(Var(0)), g.var(Var(1)));
        let s = g.add(x, y);
        let p = g.powi(s, 6); // 7 terms
        assert!(g.expand(p, 6).is_none());
        assert!(g.expand(p, 7).is_some());
    }
}
