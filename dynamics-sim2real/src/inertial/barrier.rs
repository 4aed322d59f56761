//! The smallest move along given combinations of a link's ten parameters
//! that makes it a physical body: a convex problem, solved by a barrier
//! method (Boyd and Vandenberghe, Convex Optimization, ch. 11).
//!
//! The pseudo-inertia `J(pi)` is linear in the parameters, so the moves
//! `z` along `free` (10 x f) that keep `J(pi + F z)` positive
//! semi-definite form a convex set, and the one nearest zero in a link's
//! units (`size.rs`) is the solution of a small semi-definite program:
//! minimise `|W F z|^2` subject to `J(pi + F z) >= -tol 1`. Phase one
//! finds a point inside (maximise `t` with `J - t 1 >= 0`, from `z = 0`
//! and `t` below the smallest eigenvalue, which is inside); phase two
//! follows the central path of `s |W F z|^2 - ln det(J + tol 1)` as `s`
//! grows. Each centring is a damped Newton method on at most eleven
//! variables with 4 x 4 matrices: the whole solve takes some hundred
//! small factorisations, and it either finds the nearest move or proves
//! there is none (the largest `t` is below `-tol`).

use nalgebra::{DMatrix, DVector, Matrix4, SVector};

use super::pseudo::pseudo_inertia;

/// Newton steps per centring.
const NEWTON: usize = 60;

/// Growth of the barrier's weight between centrings.
const GROWTH: f64 = 10.0;

/// Order of the constraints, the pseudo-inertia's four and the ball's one
/// (the duality gap of a centred point is `ORDER / s`).
const ORDER: f64 = 5.0;

/// One 4 x 4 affine matrix function of some of the variables,
/// `M(x) = m0 + sum a_c x_{var_c}`, kept positive definite.
pub(super) struct Block {
    pub(super) m0: Matrix4<f64>,
    /// (variable, its matrix).
    pub(super) a: Vec<(usize, Matrix4<f64>)>,
}

impl Block {
    fn matrix(&self, x: &DVector<f64>) -> Matrix4<f64> {
        let mut m = self.m0;
        for (c, a) in &self.a {
            m += a * x[*c];
        }
        m
    }
}

/// A ball `x^T b x < R^2` (`b` over all the variables).
pub(super) struct Ball {
    pub(super) b: DMatrix<f64>,
    pub(super) radius: f64,
}

impl Ball {
    /// `R^2 - x^T b x`: the ball's room left.
    fn room(&self, x: &DVector<f64>) -> f64 {
        self.radius * self.radius - (&self.b * x).dot(x)
    }
}

/// What one centring minimises: the quadratic `1/2 x^T q x + l^T x`
/// minus `ln det M(x)` of every block and `ln` of every ball's room.
pub(super) struct Problem {
    pub(super) blocks: Vec<Block>,
    pub(super) balls: Vec<Ball>,
    pub(super) q: DMatrix<f64>,
    pub(super) l: DVector<f64>,
}

impl Problem {
    /// The objective, `None` outside the domain (a block not positive
    /// definite, or outside a ball).
    fn value(&self, x: &DVector<f64>) -> Option<f64> {
        let mut v = 0.5 * (&self.q * x).dot(x) + self.l.dot(x);
        for block in &self.blocks {
            let ch = block.matrix(x).cholesky()?;
            v -= 2.0 * ch.l().diagonal().iter().map(|d| d.ln()).sum::<f64>();
        }
        for ball in &self.balls {
            let room = ball.room(x);
            if room.is_nan() || room <= 0.0 {
                return None;
            }
            v -= room.ln();
        }
        v.is_finite().then_some(v)
    }

    /// Damped Newton from `x` (inside the domain) until the Newton
    /// decrement is negligible or `done(x)`.
    pub(super) fn centre(
        &self,
        mut x: DVector<f64>,
        done: &dyn Fn(&DVector<f64>) -> bool,
    ) -> DVector<f64> {
        for _ in 0..NEWTON {
            if done(&x) {
                break;
            }
            let mut g = &self.q * &x + &self.l;
            let mut h = self.q.clone();
            let mut inside = true;
            for block in &self.blocks {
                let Some(inv) = block.matrix(&x).try_inverse() else {
                    inside = false;
                    break;
                };
                let b: Vec<(usize, Matrix4<f64>)> =
                    block.a.iter().map(|(c, a)| (*c, inv * a)).collect();
                for (i, (c, bc)) in b.iter().enumerate() {
                    g[*c] -= bc.trace();
                    for (d, bd) in &b[..=i] {
                        let v = (bc * bd).trace();
                        h[(*c, *d)] += v;
                        if c != d {
                            h[(*d, *c)] += v;
                        }
                    }
                }
            }
            if !inside {
                break;
            }
            for ball in &self.balls {
                let room = ball.room(&x);
                let bx = &ball.b * &x;
                g += &bx * (2.0 / room);
                h += &ball.b * (2.0 / room) + &bx * bx.transpose() * (4.0 / (room * room));
            }
            let Some(ch) = h.cholesky() else { break };
            let step = -ch.solve(&g);
            let decrement = -g.dot(&step);
            if decrement.is_nan() || decrement <= 1e-12 {
                break;
            }
            let Some(f0) = self.value(&x) else { break };
            let mut alpha = 1.0;
            let mut moved = false;
            while alpha > 1e-12 {
                let y = &x + &step * alpha;
                if let Some(f) = self.value(&y) {
                    if f <= f0 - 0.25 * alpha * decrement {
                        x = y;
                        moved = true;
                        break;
                    }
                }
                alpha *= 0.5;
            }
            if !moved {
                break;
            }
        }
        x
    }
}

/// The move along `free` (10 x f) nearest zero in the units `units`
/// (`|diag(1/units) F z|`), no longer than `radius` in them, after which
/// `J(pi + F z) >= -tol 1`, or `None` when there is none. (The radius
/// also keeps phase one bounded: the pseudo-inertia's determinant grows
/// without bound along some moves.) `tol` is in the pseudo-inertia's own units; the
/// method reaches the boundary to some `1e-9` of the pseudo-inertia's
/// norm, so a `tol` below that finds no move where the set of moves has
/// no inside (a point mass kept a point mass).
pub fn nearest_move(
    pi: &SVector<f64, 10>,
    free: &DMatrix<f64>,
    units: &SVector<f64, 10>,
    radius: f64,
    tol: f64,
) -> Option<SVector<f64, 10>> {
    let f = free.ncols();
    let j0 = pseudo_inertia(pi);
    let scale = j0.norm().max(tol).max(1e-300);
    let a: Vec<Matrix4<f64>> = (0..f)
        .map(|c| pseudo_inertia(&SVector::from_fn(|r, _| free[(r, c)])) / scale)
        .collect();
    let m0 = (j0 + Matrix4::identity() * tol) / scale;
    let rel = tol / scale;
    let smallest = m0.symmetric_eigenvalues().min();
    let to_move = |z: &[f64]| -> SVector<f64, 10> {
        let mut d = SVector::<f64, 10>::zeros();
        for (c, v) in z.iter().enumerate() {
            for r in 0..10 {
                d[r] += free[(r, c)] * v;
            }
        }
        d
    };
    let w = DMatrix::from_fn(10, f, |r, c| free[(r, c)] / units[r].max(1e-300));
    let wtw = w.tr_mul(&w);
    let mut z = DVector::<f64>::zeros(f);
    if smallest <= 0.5 * rel {
        // Phase one over (z, t): M = m0 - tol' 1 + sum z_c a_c - t 1, the
        // objective -s t.
        let mut a1 = a.clone();
        a1.push(-Matrix4::identity());
        let mut x = DVector::<f64>::zeros(f + 1);
        x[f] = smallest - rel - 1.0;
        let inside = |x: &DVector<f64>| x[f] > -0.5 * rel;
        let mut s = 1.0;
        loop {
            let mut l = DVector::<f64>::zeros(f + 1);
            l[f] = -s;
            let p = Problem {
                blocks: vec![Block {
                    m0: m0 - Matrix4::identity() * rel,
                    a: a1.iter().copied().enumerate().collect(),
                }],
                balls: vec![Ball {
                    b: DMatrix::from_fn(f + 1, f + 1, |r, c| {
                        if r < f && c < f {
                            wtw[(r, c)]
                        } else {
                            0.0
                        }
                    }),
                    radius,
                }],
                q: DMatrix::zeros(f + 1, f + 1),
                l,
            };
            x = p.centre(x, &inside);
            if inside(&x) {
                break;
            }
            // The largest t is at most the centred one plus the gap.
            if x[f] + ORDER / s < -0.5 * rel || s > 1e16 {
                return None;
            }
            s *= GROWTH;
        }
        z = x.rows(0, f).into_owned();
    }
    // Phase two: the nearest move, from inside.
    let mut s = 1.0;
    while ORDER / s > 1e-8 {
        let p = Problem {
            blocks: vec![Block {
                m0,
                a: a.iter().copied().enumerate().collect(),
            }],
            balls: vec![Ball {
                b: wtw.clone(),
                radius,
            }],
            q: &wtw * (2.0 * s),
            l: DVector::zeros(f),
        };
        z = p.centre(z, &|_| false);
        s *= GROWTH;
    }
    let d = to_move(z.as_slice());
    d.iter().all(|v| v.is_finite()).then_some(d)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::inertial::{margin, units};

    /// A point mass of 1 kg 0.3 m out on x: about the origin its inertia
    /// is diag(0, 0.09, 0.09).
    fn point_mass() -> SVector<f64, 10> {
        SVector::from([1.0, 0.3, 0.0, 0.0, 0.0, 0.0, 0.09, 0.0, 0.0, 0.09])
    }

    /// I_yy and I_zz free.
    fn inertia_free() -> DMatrix<f64> {
        let mut free = DMatrix::<f64>::zeros(10, 2);
        free[(6, 0)] = 1.0;
        free[(9, 1)] = 1.0;
        free
    }

    /// A fit that took 0.01 from I_yy and 0.02 from I_zz of a point mass
    /// (about its COM -0.01 and -0.02, with nothing about x: the triangle
    /// inequalities ask for I_yy' = I_zz' >= 0). By hand, the nearest
    /// move along them puts back exactly 0.01 and 0.02.
    #[test]
    fn the_nearest_move_is_the_hand_derived_one() {
        let nominal = point_mass();
        let mut pi = nominal;
        pi[6] -= 0.01;
        pi[9] -= 0.02;
        assert!(margin(&pi) < -1e-4);
        let d = nearest_move(&pi, &inertia_free(), &units(&nominal), 1.0, 1e-7).expect("a move");
        assert!(
            (d[6] - 0.01).abs() < 1e-5 && (d[9] - 0.02).abs() < 1e-5,
            "{d}"
        );
        assert!(margin(&(pi + d)) > -1e-7, "{}", margin(&(pi + d)));
    }

    /// A negative mass cannot be mended by inertia: no move.
    #[test]
    fn no_move_mends_a_negative_mass_through_the_inertia() {
        let mut pi = point_mass();
        pi[0] = -0.1;
        assert_eq!(
            nearest_move(&pi, &inertia_free(), &units(&point_mass()), 1.0, 1e-7),
            None
        );
    }

    /// A body already physical (inside) needs no move.
    #[test]
    fn a_body_inside_is_not_moved() {
        let mut pi = point_mass();
        pi[4] += 0.01;
        pi[6] += 0.01;
        pi[9] += 0.01;
        assert!(margin(&pi) > 0.0);
        let d = nearest_move(&pi, &inertia_free(), &units(&pi), 1.0, 1e-7).expect("inside");
        assert!(d.norm() < 1e-6, "{d}");
    }
}
