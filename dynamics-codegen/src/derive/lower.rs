//! Model scalars -> graph nodes.

use dynamics_symbolic::{Graph, Id};

use super::Vars;
use crate::model::scalar::{BinOp, Func, Scalar};

/// Lowers `s` into `g`; `coord` is the coordinate `q` stands for, if any.
pub fn lower(s: &Scalar, coord: Option<usize>, vars: Vars, g: &mut Graph) -> Id {
    match s {
        Scalar::Num(v) => g.constant(*v),
        Scalar::Param(k) => g.var(vars.param(*k)),
        Scalar::Coord => match coord {
            Some(i) => g.var(vars.q(i)),
            // The model stage only lets `q` appear in moving joints' chains.
            None => g.constant(0.0),
        },
        Scalar::Joint(i) => g.var(vars.q(*i)),
        Scalar::Time => g.var(vars.time()),
        Scalar::Neg(a) => {
            let a = lower(a, coord, vars, g);
            g.neg(a)
        }
        Scalar::Bin(op, a, b) => {
            let a = lower(a, coord, vars, g);
            let b = lower(b, coord, vars, g);
            match op {
                BinOp::Add => g.add(a, b),
                BinOp::Sub => g.sub(a, b),
                BinOp::Mul => g.mul(a, b),
                BinOp::Div => g.div(a, b),
            }
        }
        Scalar::Call(f, a) => {
            let a = lower(a, coord, vars, g);
            match f {
                Func::Sin => g.sin(a),
                Func::Cos => g.cos(a),
                Func::Sqrt => g.sqrt(a),
                Func::Tanh => g.tanh(a),
                Func::Abs => g.abs(a),
            }
        }
    }
}
