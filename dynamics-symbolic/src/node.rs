//! Ids, variables and the nodes of the graph.

/// Index of a node in a [`crate::Graph`]; children always have smaller ids.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Id(pub(crate) u32);

impl Id {
    /// Position in the arena (also a topological rank).
    pub fn index(self) -> usize {
        self.0 as usize
    }
}

/// A free variable; the caller keeps its name.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Var(pub u32);

/// A float kept by bit pattern so nodes can be hashed (`-0.0` is stored as
/// `0.0`, and every NaN as the one `f64::NAN`). The builders never fold to a
/// NaN or an infinity; only [`crate::Graph::constant`] called with one
/// stores it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct F64(u64);

impl F64 {
    /// Wraps a value.
    pub fn new(v: f64) -> Self {
        let v = if v == 0.0 {
            0.0
        } else if v.is_nan() {
            f64::NAN
        } else {
            v
        };
        F64(v.to_bits())
    }
    /// The value.
    pub fn get(self) -> f64 {
        f64::from_bits(self.0)
    }
}

/// One node. Sums and products are n-ary and canonical: operands sorted by
/// id, like terms collected, constants pulled out as coefficients.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub enum Node {
    /// A number.
    Const(F64),
    /// A free variable.
    Var(Var),
    /// `constant + sum coef_i * term_i`, at least one term (or a constant
    /// and one term), with:
    /// - no term a constant or a product with a coefficient other than 1;
    /// - no term a sum, except a shared sum under a constant other than
    ///   +-1 (`k * (a + b)` is kept as one multiply, not distributed);
    /// - exception: when folding would create a NaN or an infinity, the
    ///   operands are kept unfolded as terms with coefficient 1.
    Sum {
        /// The constant part.
        constant: F64,
        /// (term, non-zero coefficient), sorted by term.
        terms: Box<[(Id, F64)]>,
    },
    /// `coef * prod factor_i ^ exp_i`, with a coefficient that is neither 0
    /// nor (for a single factor of exponent 1) 1; no factor is a product,
    /// and no factor is a constant unless folding it would create a NaN or
    /// an infinity (`1 / 0` stays `0^-1`).
    Product {
        /// The coefficient.
        coef: F64,
        /// (factor, non-zero exponent), sorted by factor.
        factors: Box<[(Id, i32)]>,
    },
    /// sin
    Sin(Id),
    /// cos
    Cos(Id),
    /// tanh
    Tanh(Id),
    /// square root
    Sqrt(Id),
    /// absolute value
    Abs(Id),
}

impl Node {
    /// The children of the node (allocates; see [`Node::for_each_child`]).
    pub fn children(&self) -> Vec<Id> {
        let mut out = Vec::new();
        self.for_each_child(|c| out.push(c));
        out
    }

    /// Calls `f` on every child, in order, without allocating.
    pub fn for_each_child(&self, mut f: impl FnMut(Id)) {
        match self {
            Node::Const(_) | Node::Var(_) => {}
            Node::Sum { terms, .. } => terms.iter().for_each(|t| f(t.0)),
            Node::Product { factors, .. } => factors.iter().for_each(|x| f(x.0)),
            Node::Sin(a) | Node::Cos(a) | Node::Tanh(a) | Node::Sqrt(a) | Node::Abs(a) => f(*a),
        }
    }

    /// True for constants and variables.
    pub fn is_leaf(&self) -> bool {
        matches!(self, Node::Const(_) | Node::Var(_))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn signed_zero_and_nan_have_one_bit_pattern() {
        assert_eq!(F64::new(-0.0), F64::new(0.0));
        assert!(F64::new(-0.0).get().is_sign_positive());
        assert_eq!(F64::new(f64::NAN), F64::new(-f64::NAN));
        assert_ne!(F64::new(1.0), F64::new(-1.0));
        assert_eq!(F64::new(2.5).get(), 2.5);
    }

    #[test]
    fn children_in_order() {
        let s = Node::Sum {
            constant: F64::new(1.0),
            terms: vec![(Id(3), F64::new(2.0)), (Id(5), F64::new(-1.0))].into(),
        };
        assert_eq!(s.children(), vec![Id(3), Id(5)]);
        assert_eq!(Node::Sin(Id(7)).children(), vec![Id(7)]);
        assert!(Node::Var(Var(0)).children().is_empty());
        assert!(Node::Const(F64::new(1.0)).is_leaf());
        assert!(!Node::Abs(Id(0)).is_leaf());
        assert_eq!(Id(9).index(), 9);
    }
}
