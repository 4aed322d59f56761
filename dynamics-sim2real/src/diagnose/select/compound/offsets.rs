//! Encoder offsets that only their own joint shows are not candidates: the
//! selection resumes without them.
//!
//! An encoder reading `q + d` turns every link beyond its joint by `d` in
//! the model: the efforts of the other joints change with it (the links
//! beyond weigh on the joints before it; the joints beyond see gravity
//! from another direction). At its own joint alone an offset's effort is
//! much what an effort offset, a spring or a link beyond placed wrong
//! makes (to gravity, an offset is the links beyond turned about the
//! joint's axis), so what tells an encoder offset from those is the other
//! joints. An encoder offset the selection chose is split into its own
//! joint's part and the other joints' ([`Pool::split_at_joint`]); the other
//! joints' part must be determined (a spread below a quarter of the
//! offset) and the common offset must help it, and its own joint's part
//! where the data determine it ([`whole_offset`]). Left out only in the
//! confirmation (`evaluate/confirm.rs`, rule 2) its place would stay
//! empty, so such an offset leaves the candidates here, as an effort scale
//! of part of the effort does (`scales.rs`), and the selection resumes
//! without it.

use super::left_out::{LeftOut, Why};
use crate::diagnose::candidates::Candidate;
use crate::diagnose::select::pool::{helps, Parts, Pool, Solution};

/// Whether an encoder offset fitted as `common` acts as one, given its
/// column's two parts (its own joint's rows, the other joints') fitted
/// apart, their spreads already counted as the noise through the smoothing
/// leaves the rows: the other joints' part determined (a spread below a
/// quarter of the common) and helped by the common offset (above half of
/// it by two standard deviations, as [`helps`] asks of a delay's part),
/// its own joint's part likewise where it is determined.
pub fn whole_offset(common: f64, parts: &Parts) -> bool {
    let sign = common.signum();
    let determined = |(_, std): (f64, f64)| std < 0.25 * common.abs();
    let helped = |(v, std): (f64, f64)| helps(sign * v, std, sign * common);
    determined(parts.rest) && helped(parts.rest) && (!determined(parts.part) || helped(parts.part))
}

/// The encoder offsets of `set` (fitted `sol`) that act at their own joint
/// alone, their columns split and the set refitted by `solve`, the split's
/// spreads times `inflate`.
pub fn partial_offsets(
    pool: &Pool,
    set: &[usize],
    sol: &Solution,
    inflate: f64,
    solve: impl Fn(&Pool, &[usize]) -> Solution + Copy,
) -> Vec<LeftOut> {
    (0..set.len())
        .filter_map(|i| partial_offset(pool, set, i, sol, inflate, solve))
        .collect()
}

/// [`partial_offsets`] of the term at position `at` of `set` alone: `None`
/// when it is no encoder offset, or one the other joints show.
pub fn partial_offset(
    pool: &Pool,
    set: &[usize],
    at: usize,
    sol: &Solution,
    inflate: f64,
    solve: impl Fn(&Pool, &[usize]) -> Solution + Copy,
) -> Option<LeftOut> {
    let t = *set.get(at)?;
    let Candidate::EncoderOffset(j) = pool.terms[t].fit.candidate else {
        return None;
    };
    // The offset as the split's own fit gives it whole (links held to
    // bodies or not, as the split is made).
    let common = *solve(pool, set).theta.get(at)?.first()?;
    if common == 0.0 || !common.is_finite() {
        return None;
    }
    let offsets = match pool.split_at_joint(set, at, j, solve) {
        Some(p) => Parts {
            part: (p.part.0, p.part.1 * inflate),
            rest: (p.rest.0, p.rest.1 * inflate),
        },
        // The other joints' part lies in the span of the rest of the set
        // (or is zero): nothing shows it.
        None => Parts {
            part: (common, 0.0),
            rest: (0.0, f64::INFINITY),
        },
    };
    (!whole_offset(common, &offsets)).then(|| LeftOut {
        term: t,
        theta: sol.theta[at].clone(),
        std: sol.std[at].clone(),
        why: Why::OwnJointOnly { common, offsets },
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diagnose::select::pool::{test_pool, test_term};
    use crate::rng::Rng;
    use nalgebra::{DMatrix, DVector};

    /// Two joints' rows interleaved; an encoder offset's column acts at
    /// both joints (`own` at joint 0, `other` at joint 1), an effort
    /// offset's at joint 0 alone. The residual is made by the given
    /// offsets of the two parts of the encoder's column.
    fn pool(own: f64, other: f64, rng: &mut Rng) -> Pool {
        let (n, joints) = (600, 2);
        let mut x = DMatrix::<f64>::zeros(n * joints, 2);
        let mut y = DVector::<f64>::zeros(n * joints);
        for i in 0..n {
            let a = (i as f64 * 0.021).sin() * 20.0 + 5.0;
            let b = (i as f64 * 0.013).cos() * 15.0;
            x[(i * joints, 0)] = a;
            x[(i * joints + 1, 0)] = b;
            x[(i * joints, 1)] = 1.0;
            y[i * joints] = own * a + rng.normal();
            y[i * joints + 1] = other * b + rng.normal();
        }
        let terms = vec![
            test_term(Candidate::EncoderOffset(0), vec![0], vec![false], None),
            test_term(Candidate::EffortOffset(0), vec![1], vec![false], None),
        ];
        test_pool(x, y, terms, joints)
    }

    #[test]
    fn an_encoder_offset_must_show_at_the_other_joints() {
        let mut rng = Rng::new(5);
        // A true offset moves both joints' efforts: kept.
        let p = pool(0.05, 0.05, &mut rng);
        let sol = p.solve(&[0]);
        assert!(partial_offset(&p, &[0], 0, &sol, 1.0, |q, s| q.solve(s)).is_none());
        // Its own joint alone: left out, the other joints asking for none.
        let p = pool(0.05, 0.0, &mut rng);
        let sol = p.solve(&[0]);
        let left = partial_offset(&p, &[0], 0, &sol, 1.0, |q, s| q.solve(s)).expect("left out");
        match left.why {
            Why::OwnJointOnly { common, offsets } => {
                assert!(common > 0.0, "{common}");
                assert!((offsets.part.0 - 0.05).abs() < 2e-3, "{offsets:?}");
                assert!(offsets.rest.0.abs() < 2e-3, "{offsets:?}");
            }
            other => panic!("{other:?}"),
        }
        // Any other kind of term is not judged here.
        assert!(partial_offset(&p, &[1], 0, &p.solve(&[1]), 1.0, |q, s| q.solve(s)).is_none());
    }

    #[test]
    fn the_other_joints_must_determine_the_offset() {
        let parts = |part: (f64, f64), rest: (f64, f64)| Parts { part, rest };
        // Both parts at the offset, well determined.
        assert!(whole_offset(0.05, &parts((0.049, 0.002), (0.051, 0.004))));
        // The other joints undetermined: nothing tells it from an effort
        // at its own joint.
        assert!(!whole_offset(0.64, &parts((0.66, 0.01), (0.3, 0.5))));
        // Determined, but asking for less than half of it.
        assert!(!whole_offset(0.64, &parts((0.7, 0.01), (0.2, 0.02))));
        // Its own joint undetermined (no gravity there): the others decide.
        assert!(whole_offset(-0.1, &parts((3.0, 5.0), (-0.1, 0.01))));
        // Its own joint determined and asking for the other sign.
        assert!(!whole_offset(-0.1, &parts((0.05, 0.01), (-0.1, 0.01))));
    }
}
