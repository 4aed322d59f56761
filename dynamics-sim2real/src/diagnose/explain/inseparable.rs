//! Ambiguous pairs that no motion separates: the verdict's rival and an
//! explanation's `ambiguous_with` whose columns share a direction with
//! the named effect's once the robot's base parameters are regrouped
//! ([`crate::excite::inseparable`]; the first joint's rotor inertia and
//! its link's inertia about the joint's fixed axis are one base
//! parameter). For those the report says so instead of pointing at a
//! separating motion (and `dynamics excite --separate` leaves them out).

use super::report::{Explained, Verdict};
use crate::effects::EffectKind;
use crate::excite::{inseparable, Limits, Rival};
use dynamics_runtime::Robot;
use nalgebra::SVector;

/// Marks the verdict's rival and the entries' rivals that no motion
/// separates from the named effect on `robot`; `range` is each joint's
/// range of motion in the data (the base columns are found around it).
pub fn mark_inseparable<R: Robot<N>, const N: usize>(
    robot: &R,
    range: &[(f64, f64)],
    verdict: &mut Verdict,
    effects: &mut [Explained],
) {
    let center = SVector::<f64, N>::from_fn(|j, _| range.get(j).map_or(0.0, |r| 0.5 * (r.0 + r.1)));
    let half = SVector::<f64, N>::from_fn(|j, _| {
        range.get(j).map_or(0.5, |r| (0.5 * (r.1 - r.0)).max(0.5))
    });
    let limits = Limits::around(center, half);
    let why = |a: (EffectKind, Option<&str>), b: (EffectKind, Option<&str>)| -> Option<String> {
        let rival = |(k, p): (EffectKind, Option<&str>)| {
            Rival::named(k.name(), p, &R::JOINT_NAMES, R::LINK_NAMES).ok()
        };
        let (ra, rb) = (rival(a)?, rival(b)?);
        inseparable(robot, &limits, ra, rb)
            .ok()?
            .then(|| words::<R, N>(ra, rb))
    };
    if let (Some(kind), Some(r)) = (verdict.effect(), verdict.rival.as_ref()) {
        let place = verdict.joint.clone().or(verdict.point.clone());
        let other = r.joint.clone().or(r.point.clone());
        if let Some(w) = why((kind, place.as_deref()), (r.kind, other.as_deref())) {
            verdict.separating_motion = None;
            verdict.inseparable = Some(w);
        }
    }
    for e in effects.iter_mut() {
        let place = e.joint.clone().or(e.point.clone());
        if let Some(r) = e.ambiguous_with.as_mut() {
            let other = r.joint.clone().or(r.point.clone());
            r.inseparable = why((e.kind, place.as_deref()), (r.kind, other.as_deref()));
        }
    }
}

/// Why no motion separates `a` and `b`, in words.
fn words<R: Robot<N>, const N: usize>(a: Rival, b: Rival) -> String {
    match (a, b) {
        (Rival::Armature(j), Rival::Link(l)) | (Rival::Link(l), Rival::Armature(j)) => {
            let joint = R::JOINT_NAMES[j];
            format!(
                "no motion separates them: the rotor inertia of {joint} and {}'s inertia about {joint}'s axis act on the efforts as one base parameter (every motion shows their sum); a measured rotor inertia (the drive's datasheet) splits it",
                R::LINK_NAMES[l]
            )
        }
        _ => "no motion separates them: once the robot's base parameters are regrouped, a change of one acts on the efforts as a change of the other (the same base parameter); only a measurement of one of them splits it".into(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diagnose::explain::report::{Rival as Other, Status, VerdictKind};

    dynamics_macros::robot! {
        pub robot TwoLink;
        gravity = [0.0, 0.0, -9.81];
        link base;
        link l1 { mass = 1.0; com = [0.5, 0.0, 0.0]; inertia = [1e-3, 0.08, 0.08]; }
        link l2 { mass = 1.0; com = [0.5, 0.0, 0.0]; inertia = [1e-3, 0.08, 0.08]; }
        joint j1 = revolute(base -> l1) { transfer = [rot_z(q)]; }
        joint j2 = revolute(l1 -> l2) { transfer = [trans_x(1.0), rot_z(q)]; }
    }

    fn entry(kind: EffectKind, joint: &str, rival: (EffectKind, &str, bool)) -> Explained {
        let mut e = crate::diagnose::explain::report::test_entry(kind, joint, "x", 1.0);
        let (rk, place, is_link) = rival;
        e.ambiguous_with = Some(Other {
            kind: rk,
            joint: (!is_link).then(|| place.to_string()),
            point: is_link.then(|| place.to_string()),
            inseparable: None,
        });
        e
    }

    #[test]
    fn the_first_rotor_against_its_link_points_at_no_motion() {
        // A 2R arm in the horizontal plane. j1 turns about the fixed
        // vertical axis: its rotor and l1's inertia about it are one base
        // parameter. j2's rotor against l2 (whose inertia acts on j1's
        // effort too), and Coulomb friction against an offset, are
        // separable.
        let arm = TwoLink::default();
        let mut verdict = Verdict {
            kind: VerdictKind::Effect(EffectKind::Armature),
            joint: Some("j1".into()),
            point: None,
            channel: None,
            status: Status::Ambiguous,
            rival: None,
            separating_motion: Some("a richer excitation".into()),
            inseparable: None,
        };
        let mut effects = vec![
            entry(
                EffectKind::Armature,
                "j1",
                (EffectKind::InertialParameters, "l1", true),
            ),
            entry(
                EffectKind::Armature,
                "j2",
                (EffectKind::InertialParameters, "l2", true),
            ),
            entry(
                EffectKind::CoulombFriction,
                "j2",
                (EffectKind::EffortOffset, "j2", false),
            ),
        ];
        mark_inseparable(
            &arm,
            &[(-1.0, 1.0), (-1.0, 1.0)],
            &mut verdict,
            &mut effects,
        );
        let said = |e: &Explained| e.ambiguous_with.as_ref().unwrap().inseparable.clone();
        let first = said(&effects[0]).expect("j1's rotor and l1 are one parameter");
        assert!(first.starts_with("no motion separates them: the rotor inertia of j1 and l1's"));
        assert_eq!(said(&effects[1]), None);
        assert_eq!(said(&effects[2]), None);
        // A verdict without a rival keeps its words.
        assert_eq!(verdict.inseparable, None);
        assert!(verdict.separating_motion.is_some());
    }
}
