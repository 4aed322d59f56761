//! Sums: flattened, like terms collected, constants folded (unless that
//! would make a NaN or an infinity), and `k r sin(x)^2 + k r cos(x)^2 = k r`.

use std::collections::BTreeMap;

use crate::graph::Graph;
use crate::node::{Id, Node, F64};

impl Graph {
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

    pub(super) fn make_sum(&mut self, constant: f64, acc: BTreeMap<Id, f64>) -> Id {
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
}

#[cfg(test)]
mod tests {
    use crate::build::xyz;
    use crate::text::golden as text;
    use crate::Graph;

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
}
