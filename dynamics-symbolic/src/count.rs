//! Operation counts of what would be emitted for a set of roots.

use std::collections::HashSet;
use std::fmt;
use std::ops::Add;

use crate::graph::Graph;
use crate::node::{Id, Node};

/// Floating-point operations of the straight-line code for some roots, each
/// shared node counted once (as emitted).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct OpCount {
    /// Additions and subtractions.
    pub add: usize,
    /// Multiplications.
    pub mul: usize,
    /// Divisions.
    pub div: usize,
    /// sin/cos evaluations (a `sin_cos` pair counts once).
    pub trig: usize,
    /// Other calls (tanh, sqrt, abs, powi).
    pub other: usize,
}

impl OpCount {
    /// All operations.
    pub fn total(&self) -> usize {
        self.add + self.mul + self.div + self.trig + self.other
    }
}

impl Add for OpCount {
    type Output = OpCount;
    fn add(self, o: OpCount) -> OpCount {
        OpCount {
            add: self.add + o.add,
            mul: self.mul + o.mul,
            div: self.div + o.div,
            trig: self.trig + o.trig,
            other: self.other + o.other,
        }
    }
}

impl fmt::Display for OpCount {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} ops: {} add, {} mul, {} div, {} sin/cos, {} other",
            self.total(),
            self.add,
            self.mul,
            self.div,
            self.trig,
            self.other
        )
    }
}

impl Graph {
    /// Counts the operations of the sub-DAG reachable from `roots`, each
    /// shared node once, as [`crate::emit()`] writes them: a sum of n terms
    /// is n - 1 adds (one more for a constant) and a multiply per
    /// coefficient other than +-1; a product's factors, its coefficient and
    /// its powers 2 and 3 are multiplies, its negative powers one division,
    /// other powers `other`; negation is free.
    ///
    /// ```
    /// use dynamics_symbolic::{Graph, Var};
    /// let mut g = Graph::new();
    /// let x = g.var(Var(0));
    /// let s = g.sin(x);
    /// let c = g.cos(x);
    /// let e = g.mul(s, c);
    /// let n = g.count_ops(&[e]);
    /// assert_eq!((n.mul, n.trig), (1, 1));
    /// ```
    pub fn count_ops(&self, roots: &[Id]) -> OpCount {
        let mut n = OpCount::default();
        let reach = self.reachable(roots);
        let mut trig_args: HashSet<Id> = HashSet::new();
        for id in reach {
            match self.node(id) {
                Node::Const(_) | Node::Var(_) => {}
                Node::Sum { constant, terms } => {
                    n.add += terms.len() - 1 + usize::from(constant.get() != 0.0);
                    n.mul += terms.iter().filter(|(_, c)| c.get().abs() != 1.0).count();
                }
                Node::Product { coef, factors } => {
                    let num: Vec<&(Id, i32)> = factors.iter().filter(|f| f.1 > 0).collect();
                    let den: Vec<&(Id, i32)> = factors.iter().filter(|f| f.1 < 0).collect();
                    let pow_cost = |e: i32| {
                        if e.abs() <= 3 {
                            (e.abs() - 1) as usize
                        } else {
                            0
                        }
                    };
                    n.other += factors.iter().filter(|f| f.1.abs() > 3).count();
                    n.mul += num.iter().map(|f| pow_cost(f.1)).sum::<usize>()
                        + den.iter().map(|f| pow_cost(f.1)).sum::<usize>()
                        + num.len().saturating_sub(1)
                        + den.len().saturating_sub(1)
                        + usize::from(coef.get().abs() != 1.0 && !num.is_empty());
                    n.div += usize::from(!den.is_empty());
                }
                Node::Sin(a) | Node::Cos(a) => {
                    if trig_args.insert(*a) {
                        n.trig += 1;
                    }
                }
                Node::Tanh(_) | Node::Sqrt(_) | Node::Abs(_) => n.other += 1,
            }
        }
        n
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Var;

    #[test]
    fn sums_products_and_calls() {
        let mut g = Graph::new();
        let (x, y, z) = (g.var(Var(0)), g.var(Var(1)), g.var(Var(2)));
        // 3 + x + 2 y: two adds, one multiply.
        let two = g.constant(2.0);
        let three = g.constant(3.0);
        let y2 = g.mul(two, y);
        let s = g.sum(&[three, x, y2]);
        assert_eq!(
            g.count_ops(&[s]),
            OpCount {
                add: 2,
                mul: 1,
                ..OpCount::default()
            }
        );
        // -2 x^2 y / z^4 = -2 * x * x * y / z.powi(4): 3 mul, 1 div, 1 powi.
        let m2 = g.constant(-2.0);
        let x2 = g.powi(x, 2);
        let z4 = g.powi(z, -4);
        let p = g.product(&[m2, x2, y, z4]);
        assert_eq!(
            g.count_ops(&[p]),
            OpCount {
                mul: 3,
                div: 1,
                other: 1,
                ..OpCount::default()
            }
        );
        // sin and cos of one argument are one sin_cos; tanh, sqrt, abs.
        let (sx, cx, sy) = (g.sin(x), g.cos(x), g.sin(y));
        let (t, r, a) = (g.tanh(x), g.sqrt(y), g.abs(z));
        let e = g.product(&[sx, cx, sy, t, r, a]);
        assert_eq!(
            g.count_ops(&[e]),
            OpCount {
                mul: 5,
                trig: 2,
                other: 3,
                ..OpCount::default()
            }
        );
    }

    #[test]
    fn shared_nodes_count_once_and_counts_add() {
        let mut g = Graph::new();
        let (x, y) = (g.var(Var(0)), g.var(Var(1)));
        let xy = g.mul(x, y);
        let s = g.sin(xy);
        let e1 = g.add(s, x);
        let e2 = g.add(s, y);
        let one = g.count_ops(&[e1]);
        assert_eq!(
            one,
            OpCount {
                add: 1,
                mul: 1,
                trig: 1,
                ..OpCount::default()
            }
        );
        let both = g.count_ops(&[e1, e2, xy]);
        assert_eq!(
            both,
            OpCount {
                add: 2,
                mul: 1,
                trig: 1,
                ..OpCount::default()
            }
        );
        assert_eq!(both.total(), 4);
        assert_eq!((one + one).add, 2);
        assert_eq!(
            both.to_string(),
            "4 ops: 2 add, 1 mul, 0 div, 1 sin/cos, 0 other"
        );
        assert_eq!(g.count_ops(&[x]), OpCount::default());
    }
}
