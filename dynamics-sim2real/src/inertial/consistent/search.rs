//! The compass search behind [`complete`](super::complete): a move along
//! the combinations the data do not determine that raises the
//! pseudo-inertia's negative eigenvalues to zero, within a budget of
//! evaluations.

use nalgebra::{DMatrix, SVector};

use super::{margin, negativity};

/// The best move `z` along `free` (10 x f) from `pi`: the smallest
/// negativity found, stopping once it is >= `goal` (`-tol`) or `budget`
/// evaluations are spent (counted down); returns the move and the
/// smallest eigenvalue there.
pub(super) fn search(
    pi: &SVector<f64, 10>,
    free: &DMatrix<f64>,
    goal: f64,
    budget: &mut usize,
) -> (SVector<f64, 10>, f64) {
    let f = free.ncols();
    let scale = pi.amax().max(1e-12);
    let mut z = vec![0.0; f];
    let at = |z: &[f64]| -> SVector<f64, 10> {
        let mut p = *pi;
        for (c, v) in z.iter().enumerate() {
            for r in 0..10 {
                p[r] += free[(r, c)] * v;
            }
        }
        p
    };
    let mut best = negativity(pi);
    let mut step = scale;
    while best < goal && step > 1e-10 * scale && f > 0 && *budget > 0 {
        let mut improved = false;
        for c in 0..f {
            for sign in [1.0, -1.0] {
                let mut t = z.clone();
                t[c] += sign * step;
                *budget = budget.saturating_sub(1);
                let m = negativity(&at(&t));
                if m > best {
                    best = m;
                    z = t;
                    improved = true;
                    break;
                }
            }
            if best >= goal {
                break;
            }
        }
        if !improved {
            step *= 0.5;
        }
    }
    let done = at(&z);
    (done - pi, margin(&done))
}
