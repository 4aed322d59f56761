//! The simplifying builders. Every expression is built through them, so
//! every node is in canonical form:
//! - constants fold (unless the result would be NaN or infinite);
//! - sums and products are flat, sorted, with like terms collected
//!   (`2x + 3x = 5x`, `x - x = 0`, `x x = x^2`), `x + 0`, `x * 1`, `x * 0`;
//! - a constant times a sum is distributed into the sum's coefficients, so a
//!   negation is only ever a coefficient (negation normal form);
//! - `k r sin(x)^2 + k r cos(x)^2 = k r`;
//! - `sin(-x) = -sin(x)`, `cos(-x) = cos(x)`.
//!
//! Products are never distributed over sums (that would grow the DAG).

use std::collections::BTreeMap;

use crate::graph::Graph;
use crate::node::{Id, Node, F64};

/// Whether `k * (a + b)` becomes `k a + k b` for every constant k (else
/// only for k = -1).
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
        match self.node(id).clone() {
            Node::Const(c) => (c.get(), None),
            Node::Product { coef, factors } if coef.get() != 1.0 => {
                let core = self.make_product(1.0, factors.to_vec());
                (coef.get(), Some(core))
            }
            _ => (1.0, Some(id)),
        }
    }

    /// n-ary sum; empty is 0.
    pub fn sum(&mut self, terms: &[Id]) -> Id {
        let mut constant = 0.0;
        let mut acc: BTreeMap<Id, f64> = BTreeMap::new();
        for &t in terms {
            match self.node(t).clone() {
                Node::Const(c) => constant += c.get(),
                Node::Sum { constant: k, terms } => {
                    constant += k.get();
                    for (id, c) in terms.iter() {
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
        acc.retain(|_, c| *c != 0.0);
        self.pythagoras(&mut acc, &mut constant);
        self.make_sum(constant, acc)
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

    /// n-ary product; empty is 1.
    pub fn product(&mut self, factors: &[Id]) -> Id {
        let mut coef = 1.0;
        let mut acc: BTreeMap<Id, i32> = BTreeMap::new();
        for &f in factors {
            match self.node(f).clone() {
                Node::Const(c) if c.get().is_finite() => coef *= c.get(),
                Node::Product { coef: k, factors } => {
                    coef *= k.get();
                    for (id, e) in factors.iter() {
                        *acc.entry(*id).or_insert(0) += e;
                    }
                }
                _ => *acc.entry(f).or_insert(0) += 1,
            }
        }
        if coef == 0.0 {
            return self.constant(0.0);
        }
        acc.retain(|_, e| *e != 0);
        self.make_product(coef, acc.into_iter().collect())
    }

    /// Builds a product from collected (sorted, non-zero) factors.
    fn make_product(&mut self, coef: f64, factors: Vec<(Id, i32)>) -> Id {
        if factors.is_empty() {
            return self.constant(coef);
        }
        if factors.len() == 1 && factors[0].1 == 1 {
            let f = factors[0].0;
            if coef == 1.0 {
                return f;
            }
            // Minus a sum: distribute into the sum's coefficients (negation
            // normal form). Other constants stay outside, one multiply on
            // a shared sum rather than one per term.
            if coef != -1.0 && !DISTRIBUTE_CONSTANTS {
                return self.intern(Node::Product {
                    coef: F64::new(coef),
                    factors: factors.into(),
                });
            }
            if let Node::Sum { constant, terms } = self.node(f).clone() {
                let acc: BTreeMap<Id, f64> =
                    terms.iter().map(|(t, c)| (*t, c.get() * coef)).collect();
                return self.make_sum(constant.get() * coef, acc);
            }
        }
        self.intern(Node::Product {
            coef: F64::new(coef),
            factors: factors.into(),
        })
    }

    /// `a^n` for an integer n.
    pub fn powi(&mut self, a: Id, n: i32) -> Id {
        if n == 0 {
            return self.constant(1.0);
        }
        if n == 1 {
            return a;
        }
        match self.node(a).clone() {
            Node::Const(c) => match finite(c.get().powi(n)) {
                Some(v) => self.constant(v),
                None => self.intern(Node::Product {
                    coef: F64::new(1.0),
                    factors: vec![(a, n)].into(),
                }),
            },
            Node::Product { coef, factors } => {
                let k = coef.get().powi(n);
                let f: Vec<(Id, i32)> = factors.iter().map(|(id, e)| (*id, e * n)).collect();
                if k.is_finite() {
                    self.make_product(k, f)
                } else {
                    let c = self.intern(Node::Const(coef));
                    let mut f = f;
                    f.push((c, n));
                    f.sort();
                    self.make_product(1.0, f)
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
