//! Operation counts of what would be emitted for a set of roots.

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
    /// Counts the operations of the sub-DAG reachable from `roots`.
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
        let mut trig_args: Vec<Id> = Vec::new();
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
                    if !trig_args.contains(a) {
                        trig_args.push(*a);
                        n.trig += 1;
                    }
                }
                Node::Tanh(_) | Node::Sqrt(_) | Node::Abs(_) => n.other += 1,
            }
        }
        n
    }
}
