//! The batch functions (`dynamics_runtime::batch`) against the scalar
//! methods on every robot of the workspace, at every lane level this CPU
//! runs: the same values to the last bit where the build has FMA (the
//! lanes run the scalar code's operations in the scalar code's order),
//! else within 1e-14 of each output's scale; a tail of states that does
//! not fill the lanes; errors naming the state.

use dynamics_runtime::batch::{self, Batch, BatchError, Level};
use dynamics_runtime::linearize::forward_dynamics_derivatives;
use dynamics_runtime::{DynamicsError, Robot};
use nalgebra::{SMatrix, SVector};

/// 203 states (not a multiple of 4 or 8) in the reference box.
fn states<const N: usize>(seed: u64) -> [Vec<SVector<f64, N>>; 3] {
    let mut x = seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1;
    let mut next = move |lo: f64, hi: f64| {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        lo + (hi - lo) * ((x >> 11) as f64 / (1u64 << 53) as f64)
    };
    let mut out: [Vec<SVector<f64, N>>; 3] = Default::default();
    for _ in 0..203 {
        out[0].push(SVector::from_fn(|_, _| next(-3.1, 3.1)));
        out[1].push(SVector::from_fn(|_, _| next(-2.0, 2.0)));
        out[2].push(SVector::from_fn(|_, _| next(-2.0, 2.0)));
    }
    out
}

/// The lane levels this CPU runs.
fn levels() -> Vec<Level> {
    [Level::Scalar, Level::Avx2, Level::Avx512]
        .into_iter()
        .filter(|l| *l <= Level::detect())
        .collect()
}

/// `batch == scalar` bit for bit with FMA, else to 1e-14 of the scale.
fn same<const R: usize, const C: usize>(
    what: &str,
    batch: &SMatrix<f64, R, C>,
    scalar: &SMatrix<f64, R, C>,
) {
    if cfg!(target_feature = "fma") {
        assert_eq!(batch, scalar, "{what}");
    } else {
        let scale = scalar.abs().max().max(1.0);
        assert!(
            (batch - scalar).abs().max() <= 1e-14 * scale,
            "{what}: {batch} vs {scalar}"
        );
    }
}

fn check<R: Robot<N>, const N: usize>(name: &str, r: &R) {
    for seed in 1..=3 {
        let [q, v, a] = states::<N>(seed);
        let n = q.len();
        for level in levels() {
            let at = |k: usize, what: &str| format!("{name} {level:?} state {k}: {what}");
            let mut tau = vec![SVector::zeros(); n];
            batch::inverse_dynamics(r, level, &q, &v, &a, &mut tau).expect("lengths");
            let mut m = vec![SMatrix::zeros(); n];
            batch::mass_matrix(r, level, &q, &mut m).expect("lengths");
            let mut terms = vec![r.motion_terms(&q[0], &v[0]); n];
            batch::motion_terms(r, level, &q, &v, &mut terms).expect("lengths");
            let mut kd = vec![r.perturbation_jacobians(&q[0], &v[0], &a[0]); n];
            batch::perturbation_jacobians(r, level, &q, &v, &a, &mut kd).expect("lengths");
            let first = forward_dynamics_derivatives(r, &q[0], &v[0], &a[0]).expect("solvable");
            let mut fd = vec![first; n];
            batch::forward_dynamics_derivatives(r, level, &q, &v, &a, &mut fd)
                .expect("every state solvable");
            let mut qdd = vec![SVector::zeros(); n];
            batch::forward_dynamics(r, level, &q, &v, &a, &mut qdd).expect("solvable");
            for k in 0..n {
                same(
                    &at(k, "tau"),
                    &tau[k],
                    &r.inverse_dynamics(&q[k], &v[k], &a[k]),
                );
                same(&at(k, "A"), &m[k], &r.mass_matrix(&q[k]));
                let t = r.motion_terms(&q[k], &v[k]);
                same(&at(k, "terms.a"), &terms[k].a, &t.a);
                same(&at(k, "terms.qqt"), &terms[k].qqt, &t.qqt);
                same(&at(k, "terms.q0"), &terms[k].q0, &t.q0);
                let pj = r.perturbation_jacobians(&q[k], &v[k], &a[k]);
                same(&at(k, "K"), &kd[k].k, &pj.k);
                same(&at(k, "D"), &kd[k].d, &pj.d);
                let d = forward_dynamics_derivatives(r, &q[k], &v[k], &a[k]).expect("solvable");
                same(&at(k, "qdd"), &fd[k].qdd, &d.qdd);
                same(&at(k, "ddq_dq"), &fd[k].ddq_dq, &d.ddq_dq);
                same(&at(k, "ddq_dv"), &fd[k].ddq_dv, &d.ddq_dv);
                // Forward dynamics alone: A and the bias of `motion_terms`
                // (whose Coriolis terms may be derived otherwise than those of
                // the fused pass), L D L^T; the scalar method: Cholesky. Equal
                // to rounding, amplified by A's conditioning.
                let chol = r.forward_dynamics(&q[k], &v[k], &a[k]).expect("solvable");
                let scale = 1.0 + chol.abs().max();
                assert!(
                    (qdd[k] - chol).abs().max() <= 1e-9 * scale,
                    "{}",
                    at(k, "Cholesky")
                );
                assert!(
                    (qdd[k] - d.qdd).abs().max() <= 1e-9 * scale,
                    "{}",
                    at(k, "fused")
                );
            }
        }
    }
}

#[test]
fn batches_give_the_scalar_results_on_every_robot() {
    check("arm3r", &robots::Arm3r::default());
    check("arm3r urdf", &robots::Arm3rUrdf::default());
    check("rrp", &robots::Rrp::default());
    check("rrp urdf", &robots::RrpUrdf::default());
    check("mar", &robots::Mar::default());
    check("mar urdf", &robots::MarUrdf::default());
    check("ur5", &robots::Ur5::default());
    check("panda", &robots::Panda::default());
    check("panda arm", &robots::PandaArm::default());
    check("panda payload", &robots::PandaPayload::default());
    check("piston", &robots::Piston::default());
    check("elastic grip", &robots::ElasticGrip::default());
}

#[test]
fn a_state_that_fails_is_named_and_the_states_before_it_written() {
    let r = robots::Ur5::default();
    let [mut q, v, a] = states::<6>(7);
    q[13][4] = f64::NAN;
    for level in levels() {
        let first = forward_dynamics_derivatives(&r, &q[0], &v[0], &a[0]).expect("solvable");
        let mut fd = vec![first; q.len()];
        let e = batch::forward_dynamics_derivatives(&r, level, &q, &v, &a, &mut fd);
        assert_eq!(
            e,
            Err(BatchError::State {
                state: 13,
                error: DynamicsError::NonFinite {
                    quantity: "q",
                    index: 4
                }
            }),
            "{level:?}"
        );
        let d12 = forward_dynamics_derivatives(&r, &q[12], &v[12], &a[12]).expect("solvable");
        assert_eq!(fd[12].qdd, d12.qdd, "{level:?}");
        let mut qdd = vec![SVector::zeros(); q.len()];
        let e = batch::forward_dynamics(&r, level, &q, &v, &a, &mut qdd);
        assert!(
            matches!(e, Err(BatchError::State { state: 13, .. })),
            "{level:?}: {e:?}"
        );
    }
    let mut tau = vec![SVector::zeros(); 5];
    let e = r.inverse_dynamics_many(&q[..5], &v[..4], &a[..5], &mut tau);
    assert_eq!(
        e.map_err(|e| e.to_string()),
        Err("qd has 4 states, 5 expected (one per state of q)".to_string())
    );
    // No states: nothing to do, no error.
    assert_eq!(r.inverse_dynamics_many(&[], &[], &[], &mut []), Ok(()));
}
