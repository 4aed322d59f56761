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

use std::collections::BTreeMap;

use crate::graph::Graph;
use crate::node::{Id, Node, F64};

/// Whether `k * (a + b)` becomes `k a + k b` for every constant k (else
/// only for k = -1: measured, keeping one multiply on a shared sum halved
/// the operations of a 7-DOF arm's inverse dynamics).
const DISTRIBUTE_CONSTANTS: bool = false;

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

    /// n-ary sum; empty is 0.
    pub fn sum(&mut self, terms: &[Id]) -> Id {
        let mut constant = 0.0;
        let mut acc: BTreeMap<Id, f64> = BTreeMap::new();
        for &t in terms {
            match self.node(t) {
                Node::Const(c) => constant += c.get(),
                Node::Sum {
                    constant: k,
                    terms: inner,
                } => {
                    constant += k.get();
                    for (id, c) in inner.iter() {
                        *acc.entry(*id).or_insert(0.0) += c.get();
                    }
                }
                _ => {
                    let (c, core) = self.split(t);
                    if let Some(core) = core {
                        *acc.entry(core).or_insert(0.0) += c;
                    }
                }
            }
        }
        if !constant.is_finite() || acc.values().any(|c| !c.is_finite()) {
            return self.unfolded_sum(terms);
        }
        acc.retain(|_, c| *c != 0.0);
        self.pythagoras(&mut acc, &mut constant);
        self.make_sum(constant, acc)
    }

    /// The sum of `terms` as given, each with coefficient 1 (equal terms
    /// counted): the fallback when folding would make a NaN or an infinity.
    fn unfolded_sum(&mut self, terms: &[Id]) -> Id {
        let mut acc: BTreeMap<Id, f64> = BTreeMap::new();
        for &t in terms {
            *acc.entry(t).or_insert(0.0) += 1.0;
        }
        if let [(t, 1.0)] = acc.iter().map(|(t, c)| (*t, *c)).collect::<Vec<_>>()[..] {
            return t;
        }
        let terms: Box<[(Id, F64)]> = acc.into_iter().map(|(t, c)| (t, F64::new(c))).collect();
        self.intern(Node::Sum {
            constant: F64::new(0.0),
            terms,
        })
    }

    /// `k r sin(x)^2 + k r cos(x)^2 -> k r` over the collected terms.
    fn pythagoras(&mut self, acc: &mut BTreeMap<Id, f64>, constant: &mut f64) {
        loop {
            let mut found = None;
            'outer: for (&t, &c) in acc.iter() {
                let Node::Product { coef, factors } = self.node(t) else {
                    // A lone sin(x)^2 is a product too; plain sin(x) is not squared.
                    continue;
                };
                debug_assert_eq!(coef.get(), 1.0);
                for (k, &(f, e)) in factors.iter().enumerate() {
                    let Node::Sin(x) = *self.node(f) else {
                        continue;
                    };
                    if e != 2 {
                        continue;
                    }
                    let Some(cos) = self.lookup(&Node::Cos(x)) else {
                        continue;
                    };
                    let mut partner: Vec<(Id, i32)> = factors.to_vec();
                    partner[k] = (cos, 2);
                    partner.sort();
                    let pnode = Node::Product {
                        coef: F64::new(1.0),
                        factors: partner.into(),
                    };
                    if let Some(p) = self.lookup(&pnode) {
                        if acc.get(&p) == Some(&c) {
                            let mut rest: Vec<(Id, i32)> = factors.to_vec();
                            rest.remove(k);
                            found = Some((t, p, c, rest));
                            break 'outer;
                        }
                    }
                }
            }
            let Some((t, p, c, rest)) = found else { return };
            acc.remove(&t);
            acc.remove(&p);
            let r = self.make_product(1.0, rest);
            match self.node(r).clone() {
                Node::Const(k) => *constant += c * k.get(),
                _ => *acc.entry(r).or_insert(0.0) += c,
            }
            acc.retain(|_, c| *c != 0.0);
        }
    }

    fn make_sum(&mut self, constant: f64, acc: BTreeMap<Id, f64>) -> Id {
        if acc.is_empty() {
            return self.constant(constant);
        }
        if acc.len() == 1 && constant == 0.0 {
            let (&t, &c) = acc.iter().next().expect("one term");
            if c == 1.0 {
                return t;
            }
            let k = self.constant(c);
            return self.product(&[k, t]);
        }
        let terms: Box<[(Id, F64)]> = acc.into_iter().map(|(t, c)| (t, F64::new(c))).collect();
        self.intern(Node::Sum {
            constant: F64::new(constant),
            terms,
        })
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
    fn make_product(&mut self, coef: f64, factors: Vec<(Id, i32)>) -> Id {
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

    fn unary(&mut self, a: Id, fold: fn(f64) -> f64, node: fn(Id) -> Node) -> Id {
        if let Some(v) = self.as_constant(a).map(fold).and_then(finite) {
            return self.constant(v);
        }
        self.intern(node(a))
    }

    /// `sin(a)`; `sin(-x) = -sin(x)`.
    pub fn sin(&mut self, a: Id) -> Id {
        match self.split(a) {
            (c, Some(core)) if c < 0.0 => {
                let pos = self.scale(core, -c);
                let s = self.unary(pos, f64::sin, Node::Sin);
                self.neg(s)
            }
            _ => self.unary(a, f64::sin, Node::Sin),
        }
    }

    /// `cos(a)`; `cos(-x) = cos(x)`.
    pub fn cos(&mut self, a: Id) -> Id {
        match self.split(a) {
            (c, Some(core)) if c < 0.0 => {
                let pos = self.scale(core, -c);
                self.unary(pos, f64::cos, Node::Cos)
            }
            _ => self.unary(a, f64::cos, Node::Cos),
        }
    }

    /// `tanh(a)`
    pub fn tanh(&mut self, a: Id) -> Id {
        self.unary(a, f64::tanh, Node::Tanh)
    }

    /// `sqrt(a)` (a negative constant stays symbolic).
    pub fn sqrt(&mut self, a: Id) -> Id {
        self.unary(a, f64::sqrt, Node::Sqrt)
    }

    /// `|a|`
    pub fn abs(&mut self, a: Id) -> Id {
        self.unary(a, f64::abs, Node::Abs)
    }
}

#[cfg(test)]
mod tests {
    use crate::text::golden as text;
    use crate::{Graph, Id, Node, Var};

    fn xyz(g: &mut Graph) -> (Id, Id, Id) {
        (g.var(Var(0)), g.var(Var(1)), g.var(Var(2)))
    }

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
        let (x, y, _) = xyz(&mut g);
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
    fn like_terms_and_powers_collect() {
        let mut g = Graph::new();
        let (x, y, _) = xyz(&mut g);
        let (two, three) = (g.constant(2.0), g.constant(3.0));
        let a = g.mul(two, x);
        let b = g.mul(x, three);
        let s = g.sum(&[a, y, b]);
        assert_eq!(text(&g, &[s]), "%a = 5 * x + y\nout[0] = %a\n");
        let xx = g.mul(x, x);
        let p = g.product(&[xx, y, x, two]);
        assert_eq!(
            text(&g, &[xx, p]),
            "%a = x^2\n%b = 2 * x^3 * y\nout[0] = %a\nout[1] = %b\n"
        );
        let p2 = g.powi(p, 2);
        assert_eq!(text(&g, &[p2]), "%a = 4 * x^6 * y^2\nout[0] = %a\n");
    }

    #[test]
    fn order_does_not_matter() {
        let mut g = Graph::new();
        let (x, y, z) = xyz(&mut g);
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

    #[test]
    fn pythagoras_with_common_factors() {
        let mut g = Graph::new();
        let (x, y, z) = xyz(&mut g);
        let (s, c) = (g.sin(x), g.cos(x));
        let (s2, c2) = (g.powi(s, 2), g.powi(c, 2));
        let k = g.constant(0.5);
        let a = g.product(&[k, y, z, s2]);
        let b = g.product(&[c2, z, y, k]);
        let e = g.sum(&[a, y, b]);
        assert_eq!(
            text(&g, &[e]),
            "%a = y * z\n%b = y + 0.5 * %a\nout[0] = %b\n"
        );
        let plain = g.add(s2, c2);
        assert!(g.is_one(plain));
        // Different remaining factors or coefficients do not combine.
        let three = g.constant(3.0);
        let b3 = g.product(&[three, y, z, c2]);
        let e3 = g.add(a, b3);
        assert_eq!(
            text(&g, &[e3]),
            "%a = sin(x)\n%b = cos(x)\n%c = y * z * %a^2\n%d = y * z * %b^2\n\
             %e = 0.5 * %c + 3 * %d\nout[0] = %e\n"
        );
        let a2 = g.mul(y, s2);
        let b2 = g.mul(z, c2);
        let e2 = g.add(a2, b2);
        assert_eq!(
            text(&g, &[e2]),
            "%a = sin(x)\n%b = cos(x)\n%c = y * %a^2\n%d = z * %b^2\n%e = %c + %d\nout[0] = %e\n"
        );
    }

    #[test]
    fn trig_parity() {
        let mut g = Graph::new();
        let (x, y, _) = xyz(&mut g);
        let xy = g.mul(x, y);
        let m = g.neg(xy);
        let s = g.sin(m);
        let c = g.cos(m);
        assert_eq!(
            text(&g, &[s, c]),
            "%a = x * y\n%b = sin(%a)\n%c = -1 * %b\n%d = cos(%a)\nout[0] = %c\nout[1] = %d\n"
        );
        let k = g.constant(-3.0);
        let kx = g.mul(k, x);
        let s = g.sin(kx);
        assert_eq!(
            text(&g, &[s]),
            "%a = 3 * x\n%b = sin(%a)\n%c = -1 * %b\nout[0] = %c\n"
        );
    }
}
