//! Several links' corrections made physical in the metric of the data.
//!
//! A fit determines each link's correction along some combinations of its
//! ten parameters (`v`, 10 x r) and leaves others free (`free`, 10 x f).
//! When the fitted values leave a link no physical body and no move along
//! the free combinations mends it, the correction the data allow is the
//! one that costs the fit least: minimise `1/2 (x - x0)^T S (x - x0)` (`S`
//! the fit's curvature in the determined coordinates `x` of every link
//! taken together, the other effects of the fit profiled out) subject to
//! every link's pseudo-inertia `J(nominal + V x + F z)` being positive
//! semi-definite for some move `z` along its free combinations no longer
//! than one of the link's units (Wensing, Kim and Slotine, RA-L 2018: the
//! constraint is a linear matrix inequality, so the problem is convex).
//! The barrier method of `barrier.rs`: from the nominal model (inside),
//! along the central path of `s q(x, z) - sum ln det J - sum ln(room)`.

use nalgebra::{DMatrix, DVector, Matrix4, SVector};

use super::barrier::{Ball, Block, Problem};
use super::pseudo::pseudo_inertia;
use super::size::units;

/// One link of the problem.
#[derive(Debug, Clone)]
pub struct Link {
    /// Its nominal parameters (a physical body).
    pub nominal: SVector<f64, 10>,
    /// The combinations the data determine, 10 x r (orthonormal columns):
    /// `x`'s coordinates for this link, in order.
    pub determined: DMatrix<f64>,
    /// The combinations they leave free, 10 x f.
    pub free: DMatrix<f64>,
}

/// Relative tolerance on each pseudo-inertia's smallest eigenvalue: the
/// corrected links are bodies to this fraction of their nominal
/// pseudo-inertia's norm (well inside the completion's own slack,
/// `consistent.rs`, so the report's completion finds them physical).
const TOL: f64 = 1e-10;

/// Growth of the barrier's weight between centrings.
const GROWTH: f64 = 10.0;

/// Weight of a move along the free combinations, in the links' units,
/// relative to the fit's cost at the nominal model: small enough that the
/// fit decides, large enough that the move is the least one.
const MOVE_WEIGHT: f64 = 1e-6;

/// The determined coordinates `x` (every link's, concatenated in order)
/// nearest `x0` in the metric `s` (positive semi-definite, as long as `x`)
/// for which every link is a physical body after a move along its free
/// combinations of at most one of its units; `None` when a nominal link is
/// not physical or the sizes do not agree.
///
/// ```
/// use dynamics_sim2real::inertial::{nearest_in_metric, MetricLink};
/// use nalgebra::{DMatrix, DVector, SVector};
/// // A uniform rod of 2 kg whose parameters are determined only all
/// // together (one coordinate: the rod scaled); the fit asks to take away
/// // one and a half rods. No body has less than nothing: the nearest one
/// // takes the whole rod away.
/// let rod = SVector::<f64, 10>::from([2.0, 0.6, 0.0, 0.0, 1e-4, 0.0, 0.2067, 0.0, 0.0, 0.2067]);
/// let size = rod.norm();
/// let determined = DMatrix::from_column_slice(10, 1, (rod / size).as_slice());
/// let link = MetricLink { nominal: rod, determined, free: DMatrix::zeros(10, 0) };
/// let x = nearest_in_metric(&[link], &DMatrix::identity(1, 1), &DVector::from_element(1, -1.5 * size))
///     .expect("a physical nominal link");
/// assert!((x[0] / size + 1.0).abs() < 1e-6, "{x}");
/// ```
pub fn nearest_in_metric(
    links: &[Link],
    s: &DMatrix<f64>,
    x0: &DVector<f64>,
) -> Option<DVector<f64>> {
    let nx: usize = links.iter().map(|l| l.determined.ncols()).sum();
    let nz: usize = links.iter().map(|l| l.free.ncols()).sum();
    if s.nrows() != nx || s.ncols() != nx || x0.len() != nx {
        return None;
    }
    let n = nx + nz;
    let cost0 = 0.5 * (s * x0).dot(x0);
    if !cost0.is_finite() {
        return None;
    }
    let mut blocks = Vec::with_capacity(links.len());
    let mut balls = Vec::with_capacity(links.len());
    // q: the fit's metric over x, the moves' weight over z.
    let mut q = DMatrix::<f64>::zeros(n, n);
    q.view_mut((0, 0), (nx, nx)).copy_from(s);
    let (mut at_x, mut at_z) = (0, nx);
    for link in links {
        let j0 = pseudo_inertia(&link.nominal);
        let scale = j0.norm().max(1e-300);
        let m0 = (j0 + Matrix4::identity() * (TOL * scale)) / scale;
        // The nominal link must be a body: the barrier starts from it.
        m0.cholesky()?;
        let column = |m: &DMatrix<f64>, c: usize| {
            pseudo_inertia(&SVector::from_fn(|r, _| m[(r, c)])) / scale
        };
        let mut a = Vec::new();
        for c in 0..link.determined.ncols() {
            a.push((at_x + c, column(&link.determined, c)));
        }
        let f = link.free.ncols();
        for c in 0..f {
            a.push((at_z + c, column(&link.free, c)));
        }
        blocks.push(Block { m0, a });
        if f > 0 {
            let u = units(&link.nominal);
            let w = DMatrix::from_fn(10, f, |r, c| link.free[(r, c)] / u[r].max(1e-300));
            let wtw = w.tr_mul(&w);
            let mut b = DMatrix::<f64>::zeros(n, n);
            b.view_mut((at_z, at_z), (f, f)).copy_from(&wtw);
            q.view_mut((at_z, at_z), (f, f))
                .copy_from(&(&wtw * (MOVE_WEIGHT * cost0.max(1e-300))));
            balls.push(Ball { b, radius: 1.0 });
        }
        at_x += link.determined.ncols();
        at_z += f;
    }
    let mut lin = DVector::<f64>::zeros(n);
    lin.rows_mut(0, nx).copy_from(&(-(s * x0)));
    // Duality gap of a centred point: (4 per block + 1 per ball) / weight.
    let order = (4 * blocks.len() + balls.len()) as f64;
    let enough = 1e-9 * cost0.max(1e-300);
    let mut weight = order / cost0.max(1e-300);
    let mut x = DVector::<f64>::zeros(n);
    let mut problem = Problem {
        blocks,
        balls,
        q: DMatrix::zeros(n, n),
        l: DVector::zeros(n),
    };
    loop {
        problem.q = &q * weight;
        problem.l = &lin * weight;
        x = problem.centre(x, &|_| false);
        if order / weight < enough || weight > 1e30 {
            break;
        }
        weight *= GROWTH;
    }
    let out = x.rows(0, nx).into_owned();
    out.iter().all(|v| v.is_finite()).then_some(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::inertial::margin;
    use crate::inertial::tests::rod;

    fn unit(i: usize) -> DMatrix<f64> {
        let mut v = DMatrix::<f64>::zeros(10, 1);
        v[(i, 0)] = 1.0;
        v
    }

    /// A fit inside the physical set is its own answer.
    #[test]
    fn a_physical_fit_is_kept() {
        let link = Link {
            nominal: rod(),
            determined: unit(0),
            free: DMatrix::zeros(10, 0),
        };
        let x = nearest_in_metric(
            &[link],
            &DMatrix::identity(1, 1),
            &DVector::from_element(1, 0.5),
        )
        .expect("solved");
        assert!((x[0] - 0.5).abs() < 1e-6, "{x}");
    }

    /// Two coordinates of one link, the metric coupling them: the mass may
    /// not fall below what the first moment needs (m >= h^2 / (m c^2)
    /// region, here checked by the pseudo-inertia), and the answer is the
    /// metric's nearest point on that boundary, which the hand check
    /// below confirms: no physical point on a fine grid is nearer.
    #[test]
    fn the_nearest_physical_point_in_the_metric() {
        let nominal = rod();
        let mut determined = DMatrix::<f64>::zeros(10, 2);
        determined[(0, 0)] = 1.0;
        determined[(1, 1)] = 1.0;
        let link = Link {
            nominal,
            determined,
            free: DMatrix::zeros(10, 0),
        };
        let s = DMatrix::from_row_slice(2, 2, &[4.0, 1.0, 1.0, 2.0]);
        let x0 = DVector::from_row_slice(&[-2.5, 0.1]);
        let x = nearest_in_metric(&[link], &s, &x0).expect("solved");
        let at = |a: f64, b: f64| {
            let mut pi = nominal;
            pi[0] += a;
            pi[1] += b;
            pi
        };
        assert!(margin(&at(x[0], x[1])) > -1e-8);
        let cost = |a: f64, b: f64| {
            let d = DVector::from_row_slice(&[a, b]) - &x0;
            0.5 * (&s * &d).dot(&d)
        };
        let best = cost(x[0], x[1]);
        for i in 0..=200 {
            for k in 0..=200 {
                let (a, b) = (-2.0 + 0.01 * i as f64, -0.6 + 0.006 * k as f64);
                if margin(&at(a, b)) >= 0.0 {
                    assert!(cost(a, b) >= best - 1e-6, "({a}, {b}) beats {x}");
                }
            }
        }
    }

    /// Lowering I_yy of a thin rod along x by more than its I_xx breaks the
    /// triangle inequality (the rod's z extent, `1/2 tr I - I_zz`, would
    /// go negative): with I_yy alone determined, the nearest body keeps
    /// 1e-4 of the 0.005 asked; with I_zz free, lowering I_zz as much
    /// mends it (by hand: `1/2 tr I - I_zz` changes by `-d/2 + e/2`), and
    /// the whole change is kept.
    #[test]
    fn free_combinations_take_what_they_can() {
        let link = Link {
            nominal: rod(),
            determined: unit(6),
            free: unit(9),
        };
        let ask = DVector::from_element(1, -0.005);
        let with = nearest_in_metric(std::slice::from_ref(&link), &DMatrix::identity(1, 1), &ask)
            .expect("solved");
        let alone = Link {
            free: DMatrix::zeros(10, 0),
            ..link
        };
        let without = nearest_in_metric(&[alone], &DMatrix::identity(1, 1), &ask).expect("solved");
        assert!((with[0] + 0.005).abs() < 1e-6, "{with}");
        assert!((without[0] + 1e-4).abs() < 1e-6, "{without}");
    }
}
