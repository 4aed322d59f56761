//! Shorter transfer chains, exactly: adjacent rotations about the same axis
//! become one rotation by the sum of the angles, adjacent translations one
//! translation by the sum. A URDF writes `rpy = "0 1.57079632679 0"` before
//! an `axis = "0 1 0"` joint (the UR5 does): kept apart, the constant
//! rotation by not-quite pi/2 (its cosine is 4.9e-12, not 0) fills every
//! later expression with near-zero terms; merged, it is `Ry(q + 1.5708)`
//! and costs one addition. Nothing is rounded: the chain's transform is the
//! same.

use super::scalar::{BinOp, Scalar};
use super::{Elem, Model};

/// Normalizes the chain of every joint.
pub fn chains(model: &mut Model) {
    for joint in &mut model.joints {
        joint.chain = chain(std::mem::take(&mut joint.chain));
    }
}

/// One chain, adjacent like elements merged.
pub fn chain(elems: Vec<Elem>) -> Vec<Elem> {
    let mut out: Vec<Elem> = Vec::with_capacity(elems.len());
    for e in elems {
        match (out.last_mut(), e) {
            (Some(Elem::Rot(u0, a0)), Elem::Rot(u1, a1)) if *u0 == u1 => {
                *a0 = sum(std::mem::replace(a0, Scalar::Num(0.0)), a1);
            }
            (Some(Elem::Trans(t0)), Elem::Trans(t1)) => {
                let [x, y, z] = t1;
                for (a, b) in t0.iter_mut().zip([x, y, z]) {
                    *a = sum(std::mem::replace(a, Scalar::Num(0.0)), b);
                }
            }
            (_, e) => out.push(e),
        }
    }
    // A rotation by exactly zero is the identity.
    out.retain(|e| !matches!(e, Elem::Rot(_, Scalar::Num(a)) if *a == 0.0));
    out
}

/// `a + b`, folded when both are numbers or one is zero.
fn sum(a: Scalar, b: Scalar) -> Scalar {
    match (a.as_number(), b.as_number()) {
        (Some(x), Some(y)) => Scalar::Num(x + y),
        (Some(0.0), None) => b,
        (None, Some(0.0)) => a,
        _ => Scalar::Bin(BinOp::Add, Box::new(a), Box::new(b)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const Y: [f64; 3] = [0.0, 1.0, 0.0];
    const Z: [f64; 3] = [0.0, 0.0, 1.0];

    #[test]
    // The UR5 file's literal, deliberately not pi/2.
    #[allow(clippy::approx_constant)]
    fn same_axis_rotations_become_one() {
        let c = 1.57079632679;
        let out = chain(vec![
            Elem::Trans([Scalar::Num(0.0), Scalar::Num(0.136), Scalar::Num(0.0)]),
            Elem::Rot(Y, Scalar::Num(c)),
            Elem::Rot(Y, Scalar::Coord),
        ]);
        assert_eq!(out.len(), 2);
        match &out[1] {
            Elem::Rot(u, a) => {
                assert_eq!(*u, Y);
                assert_eq!(
                    *a,
                    Scalar::Bin(
                        BinOp::Add,
                        Box::new(Scalar::Num(c)),
                        Box::new(Scalar::Coord)
                    )
                );
            }
            other => panic!("expected a rotation, got {other:?}"),
        }
    }

    #[test]
    fn different_axes_and_separated_rotations_stay() {
        let out = chain(vec![
            Elem::Rot(Y, Scalar::Num(0.3)),
            Elem::Rot(Z, Scalar::Coord),
            Elem::Trans([Scalar::Num(1.0), Scalar::Num(0.0), Scalar::Num(0.0)]),
            Elem::Rot(Z, Scalar::Num(0.2)),
        ]);
        assert_eq!(out.len(), 4);
    }

    #[test]
    fn translations_add_and_cancelling_rotations_vanish() {
        let out = chain(vec![
            Elem::Trans([Scalar::Num(1.0), Scalar::Num(0.0), Scalar::Num(2.0)]),
            Elem::Trans([Scalar::Num(0.5), Scalar::Coord, Scalar::Num(0.0)]),
            Elem::Rot(Z, Scalar::Num(0.25)),
            Elem::Rot(Z, Scalar::Num(-0.25)),
        ]);
        assert_eq!(out.len(), 1);
        match &out[0] {
            Elem::Trans(t) => {
                assert_eq!(t[0], Scalar::Num(1.5));
                assert_eq!(t[1], Scalar::Coord);
                assert_eq!(t[2], Scalar::Num(2.0));
            }
            other => panic!("expected a translation, got {other:?}"),
        }
    }
}
