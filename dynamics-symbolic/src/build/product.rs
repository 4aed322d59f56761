//! Products and powers: flattened, like factors collected into integer
//! exponents, constants folded exactly, and minus a sum distributed into
//! the sum (negation normal form).

use std::collections::BTreeMap;

use super::finite;
use crate::graph::Graph;
use crate::node::{Id, Node, F64};

/// Whether `k * (a + b)` becomes `k a + k b` for every constant k (else
/// only for k = -1: measured, keeping one multiply on a shared sum halved
/// the operations of a 7-DOF arm's inverse dynamics).
const DISTRIBUTE_CONSTANTS: bool = false;

impl Graph {
    /// Splits `id` into (coefficient, core with coefficient 1); the core is
    /// None for constants.
    pub(crate) fn split(&mut self, id: Id) -> (f64, Option<Id>) {
        let (coef, factors) = match self.node(id) {
            Node::Const(c) => return (c.get(), None),
            Node::Product { coef, factors } if coef.get() != 1.0 => (coef.get(), factors.to_vec()),
            _ => return (1.0, Some(id)),
        };
        let core = self.make_product(1.0, factors);
        (coef, Some(core))
    }

    /// n-ary product; empty is 1. A zero factor makes 0 (even next to a
    /// symbolic `1 / 0`).
    pub fn product(&mut self, factors: &[Id]) -> Id {
        let mut coef = 1.0;
        let mut acc: BTreeMap<Id, i32> = BTreeMap::new();
        let mut overflow = false;
        let mut bump = |acc: &mut BTreeMap<Id, i32>, id: Id, e: i32| {
            let slot = acc.entry(id).or_insert(0);
            match slot.checked_add(e) {
                Some(v) => *slot = v,
                None => overflow = true,
            }
        };
        for &f in factors {
            match self.node(f) {
                Node::Const(c) if c.get() == 0.0 => return self.constant(0.0),
                Node::Const(c) if c.get().is_finite() => coef *= c.get(),
                Node::Product {
                    coef: k,
                    factors: inner,
                } => {
                    coef *= k.get();
                    for (id, e) in inner.iter() {
                        bump(&mut acc, *id, *e);
                    }
                }
                _ => bump(&mut acc, f, 1),
            }
        }
        if overflow || !coef.is_finite() || coef == 0.0 {
            // An infinite coefficient, an underflow to 0 of non-zero
            // constants, or an exponent past i32: keep the factors as given.
            return self.unfolded_product(factors);
        }
        acc.retain(|_, e| *e != 0);
        self.make_product(coef, acc.into_iter().collect())
    }

    /// The product of `factors` as given (equal factors counted): the
    /// fallback when folding would not be exact.
    fn unfolded_product(&mut self, factors: &[Id]) -> Id {
        let mut acc: BTreeMap<Id, i32> = BTreeMap::new();
        for &f in factors {
            *acc.entry(f).or_insert(0) += 1;
        }
        if let [(f, 1)] = acc.iter().map(|(f, e)| (*f, *e)).collect::<Vec<_>>()[..] {
            return f;
        }
        self.intern(Node::Product {
            coef: F64::new(1.0),
            factors: acc.into_iter().collect(),
        })
    }

    /// Builds a product from collected (sorted, non-zero) factors and a
    /// finite coefficient.
    pub(super) fn make_product(&mut self, coef: f64, factors: Vec<(Id, i32)>) -> Id {
        if factors.is_empty() || coef == 0.0 {
            return self.constant(coef);
        }
        if factors.len() == 1 && factors[0].1 == 1 {
            let f = factors[0].0;
            if coef == 1.0 {
                return f;
            }
            // Minus a sum: distribute into the sum's coefficients (negation
            // normal form; exact). Other constants stay outside, one
            // multiply on a shared sum rather than one per term.
            if coef == -1.0 || DISTRIBUTE_CONSTANTS {
                if let Node::Sum { constant, terms } = self.node(f) {
                    let k = constant.get() * coef;
                    let acc: BTreeMap<Id, f64> =
                        terms.iter().map(|(t, c)| (*t, c.get() * coef)).collect();
                    if k.is_finite() && acc.values().all(|c| c.is_finite()) {
                        return self.make_sum(k, acc);
                    }
                }
            }
        }
        self.intern(Node::Product {
            coef: F64::new(coef),
            factors: factors.into(),
        })
    }

    /// `a^n` for an integer n (`a^0 = 1`, also for `a = 0`).
    pub fn powi(&mut self, a: Id, n: i32) -> Id {
        if n == 0 {
            return self.constant(1.0);
        }
        if n == 1 {
            return a;
        }
        let nested = Node::Product {
            coef: F64::new(1.0),
            factors: vec![(a, n)].into(),
        };
        match self.node(a) {
            Node::Const(c) => match finite(c.get().powi(n)) {
                Some(v) => self.constant(v),
                None => self.intern(nested),
            },
            Node::Product { coef, factors } => {
                let coef = coef.get();
                let k = coef.powi(n);
                let scaled: Option<Vec<(Id, i32)>> = factors
                    .iter()
                    .map(|&(id, e)| e.checked_mul(n).map(|m| (id, m)))
                    .collect();
                match scaled {
                    Some(f) if k.is_finite() && k != 0.0 => self.make_product(k, f),
                    Some(mut f) => {
                        // The coefficient's power is not representable:
                        // keep it as a constant factor.
                        let c = self.constant(coef);
                        f.push((c, n));
                        f.sort();
                        self.intern(Node::Product {
                            coef: F64::new(1.0),
                            factors: f.into(),
                        })
                    }
                    None => self.intern(nested),
                }
            }
            _ => self.make_product(1.0, vec![(a, n)]),
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::build::xyz;
    use crate::text::golden as text;
    use crate::Graph;

    #[test]
    fn negation_is_a_coefficient() {
        let mut g = Graph::new();
        let (x, y, _) = xyz(&mut g);
        let xy = g.mul(x, y);
        let n = g.neg(xy);
        assert_eq!(text(&g, &[n]), "%a = -1 * x * y\nout[0] = %a\n");
        let s = g.sub(x, y);
        let ns = g.neg(s);
        assert_eq!(text(&g, &[ns]), "%a = -1 * x + y\nout[0] = %a\n");
        // Another constant times a shared sum stays one product.
        let two = g.constant(2.0);
        let t = g.mul(two, s);
        assert_eq!(
            text(&g, &[t]),
            "%a = x + -1 * y\n%b = 2 * %a\nout[0] = %b\n"
        );
        let mt = g.neg(t);
        let zero = g.add(t, mt);
        assert!(g.is_zero(zero));
    }
}
