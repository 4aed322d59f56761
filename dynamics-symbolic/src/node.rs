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

/// A float kept by bit pattern so nodes can be hashed (`-0.0` is stored as `0.0`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct F64(u64);

impl F64 {
    /// Wraps a finite value.
    pub fn new(v: f64) -> Self {
        F64(if v == 0.0 { 0.0f64 } else { v }.to_bits())
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
    /// `constant + sum coef_i * term_i`; no term is a constant or a sum, and
    /// no term is a product with a coefficient other than 1.
    Sum {
        /// The constant part.
        constant: F64,
        /// (term, non-zero coefficient), sorted by term.
        terms: Box<[(Id, F64)]>,
    },
    /// `coef * prod factor_i ^ exp_i`; no factor is a constant or a product.
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
    /// The children of the node.
    pub fn children(&self) -> Vec<Id> {
        match self {
            Node::Const(_) | Node::Var(_) => Vec::new(),
            Node::Sum { terms, .. } => terms.iter().map(|t| t.0).collect(),
            Node::Product { factors, .. } => factors.iter().map(|f| f.0).collect(),
            Node::Sin(a) | Node::Cos(a) | Node::Tanh(a) | Node::Sqrt(a) | Node::Abs(a) => vec![*a],
        }
    }

    /// True for constants and variables.
    pub fn is_leaf(&self) -> bool {
        matches!(self, Node::Const(_) | Node::Var(_))
    }
}
