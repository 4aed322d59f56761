//! The arena and its hash-consing table.

use std::collections::HashMap;

use crate::node::{Id, Node, Var, F64};

/// A hash-consed expression DAG: structurally equal nodes are one [`Id`],
/// and children always come before parents, so arena order is a
/// topological order (the order of the emitted `let` chain).
///
/// ```
/// use dynamics_symbolic::{Graph, Var};
/// let mut g = Graph::new();
/// let x = g.var(Var(0));
/// let y = g.var(Var(1));
/// let a = g.add(x, y);
/// let b = g.add(y, x);
/// assert_eq!(a, b); // one node
/// let two_x = g.add(x, x);
/// assert_eq!(g.eval(&[two_x], &|_| 1.5), vec![3.0]);
/// ```
#[derive(Debug, Default, Clone)]
pub struct Graph {
    nodes: Vec<Node>,
    /// Bit set of the variables each node depends on.
    deps: Vec<Box<[u64]>>,
    table: HashMap<Node, Id>,
    pub(crate) diff_memo: HashMap<(Id, Var), Id>,
}

impl Graph {
    /// An empty graph.
    pub fn new() -> Self {
        Self::default()
    }

    /// Number of nodes.
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    /// True when no node was made.
    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// The node behind an id.
    pub fn node(&self, id: Id) -> &Node {
        &self.nodes[id.index()]
    }

    /// The node if it exists already (no insertion).
    pub(crate) fn lookup(&self, node: &Node) -> Option<Id> {
        self.table.get(node).copied()
    }

    /// Interns a node: the existing id when an equal node exists.
    pub(crate) fn intern(&mut self, node: Node) -> Id {
        if let Some(id) = self.table.get(&node) {
            return *id;
        }
        let deps = match &node {
            Node::Var(v) => {
                let mut d = vec![0u64; v.0 as usize / 64 + 1];
                d[v.0 as usize / 64] |= 1 << (v.0 % 64);
                d.into_boxed_slice()
            }
            other => {
                let mut d: Vec<u64> = Vec::new();
                other.for_each_child(|c| {
                    let cd = &self.deps[c.index()];
                    if cd.len() > d.len() {
                        d.resize(cd.len(), 0);
                    }
                    for (w, x) in d.iter_mut().zip(cd.iter()) {
                        *w |= x;
                    }
                });
                d.into_boxed_slice()
            }
        };
        let id = Id(self.nodes.len() as u32);
        self.nodes.push(node.clone());
        self.deps.push(deps);
        self.table.insert(node, id);
        id
    }

    /// A constant. The builders never fold to a NaN or an infinity, but a
    /// non-finite value given here is stored as it is (it then never folds
    /// with other constants).
    pub fn constant(&mut self, v: f64) -> Id {
        self.intern(Node::Const(F64::new(v)))
    }

    /// A free variable.
    pub fn var(&mut self, v: Var) -> Id {
        self.intern(Node::Var(v))
    }

    /// The value of a constant node.
    pub fn as_constant(&self, id: Id) -> Option<f64> {
        match self.node(id) {
            Node::Const(c) => Some(c.get()),
            _ => None,
        }
    }

    /// True for the constant 0.
    pub fn is_zero(&self, id: Id) -> bool {
        self.as_constant(id) == Some(0.0)
    }

    /// True for the constant 1.
    pub fn is_one(&self, id: Id) -> bool {
        self.as_constant(id) == Some(1.0)
    }

    /// Whether `id` depends on `v` (a bit test).
    pub fn depends_on(&self, id: Id, v: Var) -> bool {
        let d = &self.deps[id.index()];
        let w = v.0 as usize / 64;
        w < d.len() && d[w] & (1 << (v.0 % 64)) != 0
    }

    /// Ids reachable from `roots` (leaves included, each once), in arena
    /// (topological) order.
    pub fn reachable(&self, roots: &[Id]) -> Vec<Id> {
        let mut seen = vec![false; self.nodes.len()];
        let mut stack: Vec<Id> = roots.to_vec();
        while let Some(id) = stack.pop() {
            if std::mem::replace(&mut seen[id.index()], true) {
                continue;
            }
            self.node(id).for_each_child(|c| stack.push(c));
        }
        seen.iter()
            .enumerate()
            .filter(|(_, s)| **s)
            .map(|(i, _)| Id(i as u32))
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn equal_nodes_are_one_id_and_children_come_first() {
        let mut g = Graph::new();
        assert!(g.is_empty());
        let x = g.var(Var(0));
        let x2 = g.var(Var(0));
        assert_eq!(x, x2);
        let s = g.sin(x);
        assert_eq!(g.sin(x), s);
        assert!(s > x);
        assert_eq!(g.len(), 2);
        assert_eq!(g.node(s), &Node::Sin(x));
        let z = g.constant(-0.0);
        assert_eq!(z, g.constant(0.0));
        assert!(g.is_zero(z));
        assert!(!g.is_one(z));
    }

    #[test]
    fn dependencies_are_bit_tests_over_many_variables() {
        let mut g = Graph::new();
        let a = g.var(Var(3));
        let b = g.var(Var(130));
        let p = g.mul(a, b);
        let s = g.sin(p);
        for v in [Var(3), Var(130)] {
            assert!(g.depends_on(s, v));
        }
        for v in [Var(0), Var(64), Var(129), Var(131), Var(1000)] {
            assert!(!g.depends_on(s, v));
        }
        let k = g.constant(2.0);
        assert!(!g.depends_on(k, Var(0)));
    }

    #[test]
    fn reachable_is_sorted_and_skips_unused_nodes() {
        let mut g = Graph::new();
        let x = g.var(Var(0));
        let y = g.var(Var(1));
        let unused = g.cos(y);
        let s = g.sin(x);
        let e = g.mul(s, x);
        let r = g.reachable(&[e, s]);
        assert_eq!(r, vec![x, s, e]);
        assert!(!r.contains(&unused));
    }
}
