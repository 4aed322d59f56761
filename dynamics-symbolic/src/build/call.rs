//! Calls: sin, cos, tanh, sqrt and abs, folded on constants (unless the
//! result is not finite), with `sin(-x) = -sin(x)` and `cos(-x) = cos(x)`.

use super::finite;
use crate::graph::Graph;
use crate::node::{Id, Node};

impl Graph {
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
    use crate::build::xyz;
    use crate::text::golden as text;
    use crate::Graph;

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
