//! A small hash-consed symbolic expression DAG for deriving equations of
//! motion at compile time.
//!
//! - [`Graph`]: a flat arena of [`Node`]s where children come before parents
//!   (after egg's `RecExpr`), with a hash map so that structurally equal
//!   nodes are one [`Id`]: common subexpression elimination is free.
//! - [`Node`]: a constant, a variable, an n-ary [`Node::Sum`]
//!   (`c + sum k_i t_i`), an n-ary [`Node::Product`] (`k * prod f_i^e_i`,
//!   integer exponents, so division and powers are products), or a call
//!   (sin, cos, tanh, sqrt, abs).
//! - Builders simplify on construction (`build/`): constant folding that
//!   never makes a NaN or an infinity, flat sorted sums and products with
//!   like terms collected, negation as a coefficient, `sin^2 + cos^2 = 1`,
//!   sin/cos parity. Products are not distributed over sums.
//! - [`Graph::diff`]: exact differentiation; [`Graph::eval`]: numbers;
//!   [`Graph::to_text`]: a readable dump; [`Graph::count_ops`]: operation
//!   counts; [`Graph::expand`]: canonical trigonometric polynomials;
//!   [`emit()`]: a straight-line `let` chain as Rust tokens.
//!
//! ```
//! use dynamics_symbolic::{Graph, Var};
//! let mut g = Graph::new();
//! let q = g.var(Var(0));
//! let (s, c) = (g.sin(q), g.cos(q));
//! let s2 = g.powi(s, 2);
//! let c2 = g.powi(c, 2);
//! let one = g.add(s2, c2);
//! assert!(g.is_one(one));
//! ```

mod build;
mod count;
mod diff;
mod emit;
mod eval;
mod expand;
mod graph;
mod node;
mod text;

pub use count::OpCount;
pub use emit::{emit, emit_fused, emit_fused_stages, emit_with, float, Calls, Emitted};
pub use graph::Graph;
pub use node::{Id, Node, Var, F64};
