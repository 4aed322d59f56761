//! The prior toward the nominal model: what keeps the compound
//! explanation's parameters physically plausible where the data leave
//! them free.
//!
//! A real robot's model error is not all in its candidates, and a joint
//! fit with every link's inertial parameters and every joint's effort
//! scale bends to it along the directions the data barely determine: a
//! common effort scale on every joint is exactly a common scaling of every
//! link's inertial parameters (both scale the rigid-body effort), and one
//! link's mass regroups into its neighbours'. Unpenalised, a KUKA log
//! gave an effort scale of -16 (a sign-flipped torque constant) and a
//! Panda log +41 kg on a 3 kg link. The fit is therefore penalised, as a
//! Gaussian prior centred on the nominal (CAD) values, by
//! `weight * sum ((parameter change) / sigma)^2` with
//! - a link's ten inertial parameters ([`INERTIAL_SIGMA`]: a relative
//!   spread of its mass, its first moments at its size, its inertia at its
//!   size squared; `link_sigmas`);
//! - an effort scale's `s - 1` ([`EFFORT_SCALE_SIGMA`]), which is besides
//!   held within [`EFFORT_SCALE_LIMIT`] (`Pool::solve`).
//!
//! The weight is a strength times the nominal residual's mean square per
//! row in the pool's current weights: the prior is worth as many rows of
//! the gap as the strength says, so it bites only along directions the
//! data do not determine, whatever the units and the weighting. The
//! strength is chosen per diagnosis among [`STRENGTHS`] by
//! cross-validation on the training data (`strength.rs`).

use nalgebra::{DMatrix, SVector};

use crate::inertial::units;

use crate::diagnose::candidates::Candidate;
use crate::diagnose::select::pool::Term;

/// The prior's spread of an effort scale's `s - 1`.
pub const EFFORT_SCALE_SIGMA: f64 = 0.2;

/// The prior's relative spread of a link's inertial parameters: of its
/// mass (CAD masses miss cables, screws and motors by some ten per cent),
/// of its first moments at the link's size, of its inertia at its size
/// squared.
pub const INERTIAL_SIGMA: f64 = 0.3;

/// How many rows of the nominal gap one prior spread may be worth, the
/// strongest first: the diagnosis starts at the first and moves to a
/// weaker one only where blocks of the training data, each predicted by
/// the fit on the others, say so (`strength.rs`). One row is the prior of
/// a CAD model trusted to some ten per cent; a hundredth of a row lets
/// data that determine a parameter move it freely while still holding the
/// directions they do not determine.
pub const STRENGTHS: [f64; 5] = [1.0, 0.3, 0.1, 0.03, 0.01];

/// The prior's spreads of a link's ten parameters (Pinocchio's order)
/// around its nominal ones: [`INERTIAL_SIGMA`] of its units
/// (`inertial::units`).
pub fn link_sigmas(nominal: &SVector<f64, 10>) -> SVector<f64, 10> {
    units(nominal) * INERTIAL_SIGMA
}

/// The strength (rows of the nominal gap per spread) of the effort
/// scales' prior, whatever the links' strength: a common effort scale on
/// every joint and a common scaling of every link's parameters change the
/// rigid-body effort alike, and only this prior says which of the two the
/// data are to be read as (a torque constant trusted to its spread, the
/// rest of the change in the links).
pub const SCALE_STRENGTH: f64 = 1.0;

/// The prior's matrices over the pool's free columns, in parameter units:
/// `theta^T P theta`, each part at its own strength (0 x 0: none).
#[derive(Debug, Clone)]
pub struct Prior {
    /// The link corrections' part, at the pool's strength.
    pub links: DMatrix<f64>,
    /// The effort scales' part, at [`SCALE_STRENGTH`].
    pub scales: DMatrix<f64>,
}

impl Prior {
    /// No prior.
    #[cfg(test)]
    pub fn none() -> Prior {
        Prior {
            links: DMatrix::zeros(0, 0),
            scales: DMatrix::zeros(0, 0),
        }
    }

    /// The prior over the pool's `columns` free columns for `terms` (a
    /// link correction's combinations through its basis; `nominal[link]`
    /// its nominal parameters, none: no prior on it).
    pub fn new(terms: &[Term], columns: usize, nominal: &[SVector<f64, 10>]) -> Prior {
        let mut links = DMatrix::<f64>::zeros(columns, columns);
        let mut scales = DMatrix::<f64>::zeros(columns, columns);
        for term in terms {
            match (term.fit.candidate, &term.link) {
                (Candidate::EffortScale(_), _) => {
                    for &c in &term.cols {
                        scales[(c, c)] += 1.0 / (EFFORT_SCALE_SIGMA * EFFORT_SCALE_SIGMA);
                    }
                }
                (Candidate::Inertial(l), Some(b)) => {
                    let Some(nom) = nominal.get(l) else { continue };
                    let s = link_sigmas(nom);
                    // theta^T V^T S^-2 V theta.
                    let mut v = b.v.clone();
                    for r in 0..10 {
                        for c in 0..v.ncols() {
                            v[(r, c)] /= s[r];
                        }
                    }
                    let q = v.tr_mul(&v);
                    for (a, &ca) in term.cols.iter().enumerate() {
                        for (bb, &cb) in term.cols.iter().enumerate() {
                            links[(ca, cb)] += q[(a, bb)];
                        }
                    }
                }
                _ => {}
            }
        }
        Prior { links, scales }
    }

    /// Whether the links' part holds any of `cols`: the only part the
    /// strength changes.
    pub fn holds_links(&self, cols: &[usize]) -> bool {
        cols.iter()
            .any(|&c| c < self.links.nrows() && self.links[(c, c)] != 0.0)
    }

    /// Adds the prior to `gram` (`X^T X` of `n` rows against a residual of
    /// sum of squares `yy`), the links' part at `strength`.
    pub fn add_to(&self, gram: &mut DMatrix<f64>, yy: f64, n: usize, strength: f64) {
        if self.links.shape() == gram.shape() {
            *gram += &self.links * weight(yy, n, strength);
        }
        if self.scales.shape() == gram.shape() {
            *gram += &self.scales * weight(yy, n, SCALE_STRENGTH);
        }
    }
}

/// The prior's weight for a pool whose (weighted, whitened) nominal
/// residual has sum of squares `yy` over `n` rows, at `strength` rows of
/// the gap per spread.
pub fn weight(yy: f64, n: usize, strength: f64) -> f64 {
    let w = strength * yy / n.max(1) as f64;
    if w.is_finite() {
        w
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diagnose::candidates::EFFORT_SCALE_LIMIT;
    use crate::diagnose::select::pool::{test_term, Pool};
    use crate::inertial::{LIGHTEST, SMALLEST};
    use nalgebra::DVector;

    fn pool(cols: &[Vec<f64>], y: Vec<f64>, terms: Vec<Term>, prior: Prior) -> Pool {
        let n = y.len();
        let x = DMatrix::from_fn(n, cols.len(), |r, c| cols[c][r]);
        let yv = DVector::from_vec(y);
        let yy = yv.norm_squared();
        let x = crate::diagnose::select::pool::Cols::from_matrix(&x, 1);
        Pool {
            gram: crate::diagnose::select::pool::penalised(&x, &prior, yy, STRENGTHS[0]),
            xty: x.tr_mul(yv.as_slice(), 0, n),
            yy,
            x,
            y: yv,
            terms,
            weights: vec![1.0],
            prior,
            strength: STRENGTHS[0],
            blocks: Default::default(),
        }
    }

    /// An effort scale the data push to 3 (s - 1 = 2) is held at its
    /// limit, and the other term is fitted to what that leaves, as a
    /// direct least-squares fit of the rest does.
    #[test]
    fn an_effort_scale_is_held_at_its_limit() {
        let n = 400;
        let c0: Vec<f64> = (0..n).map(|i| (i as f64 * 0.05).sin()).collect();
        let c1: Vec<f64> = (0..n).map(|i| (i as f64 * 0.017).cos()).collect();
        let y: Vec<f64> = (0..n).map(|i| 2.0 * c0[i] + 0.7 * c1[i]).collect();
        let mut scale = test_term(Candidate::EffortScale(0), vec![0], vec![false], None);
        scale.limit = vec![EFFORT_SCALE_LIMIT];
        let offset = test_term(Candidate::Viscous(0), vec![1], vec![true], None);
        let p = pool(
            &[c0.clone(), c1.clone()],
            y.clone(),
            vec![scale, offset],
            Prior::none(),
        );
        let sol = p.solve(&[0, 1]);
        assert_eq!(sol.theta[0][0], EFFORT_SCALE_LIMIT);
        // The rest: y - 0.5 c0 on c1 alone.
        let rest: Vec<f64> = (0..n).map(|i| y[i] - EFFORT_SCALE_LIMIT * c0[i]).collect();
        let (a, b) = (
            c1.iter().zip(&rest).map(|(x, r)| x * r).sum::<f64>(),
            c1.iter().map(|x| x * x).sum::<f64>(),
        );
        assert!((sol.theta[1][0] - a / b).abs() < 1e-9, "{:?}", sol.theta);
        let sse: f64 = (0..n).map(|i| (rest[i] - a / b * c1[i]).powi(2)).sum();
        assert!((sol.sse / sse - 1.0).abs() < 1e-9);
        // Within its limit, the scale is fitted freely.
        let inside: Vec<f64> = (0..n).map(|i| 0.3 * c0[i] + 0.7 * c1[i]).collect();
        let mut scale = test_term(Candidate::EffortScale(0), vec![0], vec![false], None);
        scale.limit = vec![EFFORT_SCALE_LIMIT];
        let offset = test_term(Candidate::Viscous(0), vec![1], vec![true], None);
        let q = pool(&[c0, c1], inside, vec![scale, offset], Prior::none());
        let free = q.solve(&[0, 1]);
        assert!((free.theta[0][0] - 0.3).abs() < 1e-9 && (free.theta[1][0] - 0.7).abs() < 1e-9);
    }

    /// Two terms with the same column (an effort scale and what stands for
    /// a link correction that scales the same effort): unpenalised the
    /// split is arbitrary; with the prior on the scale alone, the other
    /// term takes the whole change and the scale stays at its nominal 1.
    #[test]
    fn the_prior_settles_what_the_data_cannot_split() {
        let n = 300;
        let c: Vec<f64> = (0..n).map(|i| (i as f64 * 0.03).sin()).collect();
        let y: Vec<f64> = c.iter().map(|x| 0.4 * x).collect();
        let terms = || {
            vec![
                test_term(Candidate::EffortScale(0), vec![0], vec![false], None),
                test_term(Candidate::EffortOffset(0), vec![1], vec![false], None),
            ]
        };
        let probe = pool(&[c.clone(), c.clone()], y.clone(), terms(), Prior::none());
        let mut prior = Prior::none();
        prior.links = DMatrix::zeros(2, 2);
        prior.scales = DMatrix::zeros(2, 2);
        prior.scales[(0, 0)] = 1.0 / (EFFORT_SCALE_SIGMA * EFFORT_SCALE_SIGMA);
        let p = pool(&[c.clone(), c], y, terms(), prior);
        let sol = p.solve(&[0, 1]);
        assert!(sol.theta[0][0].abs() < 1e-3, "{:?}", sol.theta);
        assert!((sol.theta[1][0] - 0.4).abs() < 1e-3, "{:?}", sol.theta);
        // Without the prior the later copy is left out as dependent.
        assert_eq!(probe.solve(&[1, 0]).k, 1);
    }

    /// A link's spreads: its mass's relative spread, its first moments at
    /// its size (the larger of its centre of mass's distance and its
    /// radius of gyration), its inertia at that size squared.
    #[test]
    fn a_rods_spreads_follow_its_mass_and_size() {
        // 2 kg, centre of mass at 0.3 m on x, 0.4 m long.
        let (m, c, l) = (2.0, 0.3, 0.4);
        let iyy = m * l * l / 12.0 + m * c * c;
        let rod = SVector::<f64, 10>::from([m, m * c, 0.0, 0.0, 1e-4, 0.0, iyy, 0.0, 0.0, iyy]);
        let s = link_sigmas(&rod);
        let r = ((1e-4 + 2.0 * iyy) / (2.0 * m)).sqrt();
        let size = r.max(c);
        assert!((s[0] - INERTIAL_SIGMA * m).abs() < 1e-12);
        assert!((s[1] - INERTIAL_SIGMA * m * size).abs() < 1e-12);
        assert!((s[9] - INERTIAL_SIGMA * m * size * size).abs() < 1e-12);
        // A massless link is given the lightest mass and smallest size.
        let none = link_sigmas(&SVector::zeros());
        assert!((none[0] - INERTIAL_SIGMA * LIGHTEST).abs() < 1e-12);
        assert!((none[4] - INERTIAL_SIGMA * LIGHTEST * SMALLEST * SMALLEST).abs() < 1e-15);
    }
}
