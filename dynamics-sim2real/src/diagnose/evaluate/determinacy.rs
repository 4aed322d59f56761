//! Values a user can act on: a parameter the data do not determine, or one
//! outside what its kind can physically be (an encoder offset beyond half
//! a turn, an effort scale held at its bound), cannot be acted on; the
//! report gives the reason instead of the number, and the explanation does
//! not name the effect (`confirm.rs`).

use crate::diagnose::candidates::EFFORT_SCALE_LIMIT;
use crate::diagnose::fit::Fit;
use crate::effects::EffectKind;
use dynamics_runtime::JointKind;

/// Below this, in any of the parameters' units (kg m^2, N m, s, rad, ...),
/// a value is the zero a sign constraint holds it at
/// plus rounding (a rotor inertia of 8e-16 kg m^2 came out of an hour's
/// log with nothing at that joint).
pub const HELD_AT_ZERO: f64 = 1e-12;

/// Whether `value` of parameter `name` is the zero a sign constraint
/// holds it at (a payload's centre of mass has no sign constraint).
pub(crate) fn held_at_zero(name: &str, value: f64) -> bool {
    !matches!(name, "com_x" | "com_y" | "com_z") && value.abs() <= HELD_AT_ZERO
}

/// The spread (m) below which a payload's centre-of-mass coordinate near
/// the tip frame's origin is still reported as a number.
pub const COM_SPREAD: f64 = 0.02;

/// Why the value `value` +- `std` of parameter `name` of an effect of
/// `kind` at a joint of `joint` (its kind and the range its position covers
/// on the data) cannot be acted on; `None` when it can.
pub fn why_not(
    kind: EffectKind,
    name: &str,
    value: f64,
    std: f64,
    joint: Option<(JointKind, f64)>,
) -> Option<String> {
    let moves = joint.map(|(k, range)| match k {
        JointKind::Revolute => format!("the joint moves {range:.3} rad"),
        JointKind::Prismatic => format!("the joint moves {range:.4} m"),
    });
    let on_data = |what: &str| match &moves {
        Some(m) => format!("{what} on these data: {m}"),
        None => format!("{what} on these data"),
    };
    // A link's ten parameters are judged together (`confirm.rs`: the
    // corrected body must be physical); alone, most are not determined.
    if kind == EffectKind::InertialParameters {
        return None;
    }
    if !value.is_finite() {
        return Some("the fit could not make it".into());
    }
    // A payload's centre of mass: a coordinate is a number when its spread
    // is below its own size or below [`COM_SPREAD`] (a centre at the
    // origin is a statement too).
    if matches!(name, "com_x" | "com_y" | "com_z") {
        return (!(std.is_finite() && std <= value.abs().max(COM_SPREAD)))
            .then(|| format!("not placed by these data (spread {std:.3} m)"));
    }
    // A value held at zero by its sign constraint (the fit's active bound:
    // nothing left of the value but rounding; its spread is the one it
    // would have if freed) is no effect.
    if held_at_zero(name, value) {
        return Some("zero, held at its bound: the data ask for none".into());
    }
    // Grid-searched values carry half a step as their spread by design.
    // A backlash's contact damping shapes only the instants of contact:
    // the fit's value is given (a baseline simulates the same motor side
    // with it), and the backlash is judged by its other parameters.
    // A finite spread above the value: the data hold it near zero without
    // telling it from zero (however far the joint moves); no finite
    // spread: they do not determine it at all.
    let grid = matches!(name, "vw" | "vs" | "alpha" | "contact_damping");
    if !grid && !std.is_finite() {
        return Some(on_data("not identifiable"));
    }
    if !grid && std > value.abs() {
        let spread = if std >= 1e-3 {
            format!("{std:.3}")
        } else {
            format!("{std:.2e}")
        };
        return Some(match &moves {
            Some(m) => format!("not told from zero on these data (spread {spread}; {m})"),
            None => format!("not told from zero on these data (spread {spread})"),
        });
    }
    beyond_its_kind(kind, name, value, joint)
}

/// Why the value `value` of parameter `name` of an effect of `kind` (at a
/// joint of `joint`, as for [`why_not`]) is outside what its kind can
/// physically be, however firmly the data hold it: an encoder offset
/// beyond half a turn, an effort scale at its bound.
fn beyond_its_kind(
    kind: EffectKind,
    name: &str,
    value: f64,
    joint: Option<(JointKind, f64)>,
) -> Option<String> {
    match kind {
        EffectKind::EncoderOffset => match joint.map(|j| j.0) {
            Some(JointKind::Prismatic) => None,
            _ if value.abs() > std::f64::consts::PI => {
                let moves = joint.map_or(String::new(), |(_, range)| {
                    format!(": the joint moves {range:.3} rad")
                });
                Some(format!(
                    "more than half a turn ({value:.1} rad): not identifiable on these data{moves}"
                ))
            }
            _ => None,
        },
        EffectKind::EffortScale
            if name == "scale" && (value - 1.0).abs() >= EFFORT_SCALE_LIMIT * (1.0 - 1e-9) =>
        {
            Some(format!(
                "held at its bound ({value:.2}): an effort off by more than {:.0} % is a wrong unit, channel or sign, not a scale",
                EFFORT_SCALE_LIMIT * 100.0
            ))
        }
        _ => None,
    }
}

/// The first parameter of fit `f` (at a joint of `joint`, as for
/// [`why_not`]) whose value is outside what its kind can physically be,
/// with the reason; a value the data merely do not determine is not one.
pub fn beyond_physical(f: &Fit, joint: Option<(JointKind, f64)>) -> Option<String> {
    let kind = f.candidate.kind();
    f.parameters()
        .into_iter()
        .filter(|(_, v, _)| v.is_finite())
        .find_map(|(name, v, _)| {
            beyond_its_kind(kind, name, v, joint).map(|w| format!("`{name}`: {w}"))
        })
}

/// Why fit `f` makes no effort at all: every parameter that sizes it (a
/// grid-searched shape and a payload's centre of mass aside) held at zero
/// by its sign constraint; `None` when one is not.
pub fn vanished(f: &Fit) -> Option<String> {
    let sizes: Vec<(&str, f64, f64)> = f
        .parameters()
        .into_iter()
        .filter(|(name, _, _)| {
            !matches!(*name, "vw" | "vs" | "alpha" | "contact_damping") && !name.starts_with("com_")
        })
        .collect();
    let names: Vec<String> = sizes
        .iter()
        .map(|(name, _, _)| format!("`{name}`"))
        .collect();
    (!sizes.is_empty() && sizes.iter().all(|&(name, v, _)| held_at_zero(name, v))).then(|| {
        format!(
            "{}: zero, held at its bound: the data ask for none",
            names.join(", ")
        )
    })
}

/// The first parameter of fit `f` (at a joint of `joint`, as for
/// [`why_not`]) that cannot be acted on, with the reason. A payload stands
/// on its mass: a centre of mass the data do not place is a note on its
/// coordinates in the report, not a reason to leave the payload out.
///
/// A Stribeck friction whose Coulomb level is held at zero under a
/// breakaway it carries is a friction that falls away with speed: the
/// breakaway is what it stands on, and the zero level is a note.
pub fn undetermined(f: &Fit, joint: Option<(JointKind, f64)>) -> Option<String> {
    let kind = f.candidate.kind();
    let params = f.parameters();
    let breakaway = params
        .iter()
        .any(|&(name, v, _)| name == "fs_minus_fc" && v.is_finite() && !held_at_zero(name, v));
    let carried = |name: &str, v: f64| {
        kind == EffectKind::StribeckFriction && name == "fc" && breakaway && held_at_zero(name, v)
    };
    params
        .into_iter()
        .filter(|(name, _, _)| !name.starts_with("com_"))
        .filter(|&(name, v, _)| !carried(name, v))
        .find_map(|(name, v, s)| why_not(kind, name, v, s, joint).map(|w| format!("`{name}`: {w}")))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diagnose::candidates::Candidate;

    fn fit(candidate: Candidate, theta: &[f64], std: &[f64]) -> Fit {
        Fit {
            candidate,
            theta: theta.to_vec(),
            std: std.to_vec(),
            motor: None,
            motor_std: None,
            sse: 0.0,
            k: theta.len(),
        }
    }

    /// A Stribeck friction with no Coulomb level under a breakaway the
    /// data determine is a friction; with neither it makes no effort, and
    /// neither does a resistance of zero.
    #[test]
    fn an_effect_vanishes_only_when_nothing_sizes_it() {
        let stribeck =
            |fc: f64, fs: f64| fit(Candidate::Stribeck(2, 0.3), &[fc, fs], &[0.05, 0.02]);
        let breakaway = stribeck(0.0, 0.33);
        assert!(undetermined(&breakaway, None).is_none());
        assert!(vanished(&breakaway).is_none());
        let none = stribeck(0.0, 0.0);
        assert!(undetermined(&none, None).is_some());
        assert!(vanished(&none).is_some());
        let resistance = fit(Candidate::Environment(3.0), &[0.0], &[0.26]);
        let why = vanished(&resistance).expect("no effort");
        assert!(why.contains("`mu`"), "{why}");
        assert!(vanished(&fit(Candidate::Environment(3.0), &[0.3], &[0.06])).is_none());
    }

    #[test]
    fn an_offset_beyond_a_turn_is_not_a_number_a_user_can_use() {
        let j = Some((JointKind::Revolute, 0.01));
        let why = why_not(EffectKind::EncoderOffset, "offset", -67.0, 2.0, j).unwrap();
        assert!(
            why.contains("half a turn") && why.contains("0.010 rad"),
            "{why}"
        );
        assert!(why_not(EffectKind::EncoderOffset, "offset", 0.02, 0.001, j).is_none());
    }

    /// A centre-of-mass coordinate is a number when its spread is below
    /// 2 cm or below its size; otherwise the note says it is not placed.
    #[test]
    fn a_payloads_centre_of_mass_is_a_number_only_where_the_data_place_it() {
        let k = EffectKind::PayloadMass;
        assert!(why_not(k, "com_z", 0.0, 0.01, None).is_none());
        assert!(why_not(k, "com_z", -0.07, 0.05, None).is_none());
        let why = why_not(k, "com_x", 0.01, 0.08, None).unwrap();
        assert!(why.starts_with("not placed"), "{why}");
    }

    #[test]
    fn a_spread_larger_than_the_value_means_the_data_do_not_determine_it() {
        let why = why_not(EffectKind::Armature, "inertia", 0.1, 0.3, None).unwrap();
        assert_eq!(why, "not told from zero on these data (spread 0.300)");
        let j = Some((JointKind::Revolute, 0.01));
        let why = why_not(EffectKind::Armature, "inertia", 0.1, f64::INFINITY, j).unwrap();
        assert_eq!(
            why,
            "not identifiable on these data: the joint moves 0.010 rad"
        );
        // A grid value's spread is half its step, by design.
        assert!(why_not(EffectKind::CoulombFriction, "vw", 0.01, 0.005, None).is_none());
    }

    #[test]
    fn a_value_held_at_zero_is_no_effect() {
        let why = why_not(EffectKind::Armature, "inertia", 8.4e-16, 0.0, None).unwrap();
        assert!(why.contains("held at its bound"), "{why}");
        assert!(held_at_zero("inertia", 8.4e-16) && !held_at_zero("inertia", 1e-9));
        assert!(!held_at_zero("com_z", 0.0));
        // Held with the spread it would have if freed.
        let why = why_not(EffectKind::Armature, "inertia", 0.0, 3e-4, None).unwrap();
        assert!(why.contains("held at its bound"), "{why}");
        // A small value the fit determines is still a value.
        assert!(why_not(EffectKind::Armature, "inertia", 1e-9, 1e-10, None).is_none());
    }

    #[test]
    fn an_effort_scale_at_its_bound_is_not_a_scale() {
        let held = why_not(EffectKind::EffortScale, "scale", 1.5, 0.0, None);
        assert!(held.unwrap().contains("held at its bound"));
        assert!(why_not(EffectKind::EffortScale, "scale", 1.1, 0.01, None).is_none());
    }

    /// What a kind cannot physically be is judged on the value alone; a
    /// value the data merely leave undetermined, or hold at zero, is not
    /// beyond its kind (the final fit's re-check in `confirm.rs`).
    #[test]
    fn beyond_its_kind_is_a_value_no_spread_can_mend() {
        let j = Some((JointKind::Revolute, 0.5));
        let bound = beyond_its_kind(EffectKind::EffortScale, "scale", 0.5, j).unwrap();
        assert!(bound.contains("held at its bound (0.50)"), "{bound}");
        let turn = beyond_its_kind(EffectKind::EncoderOffset, "offset", 4.0, j).unwrap();
        assert_eq!(
            turn,
            why_not(EffectKind::EncoderOffset, "offset", 4.0, 0.1, j).unwrap()
        );
        assert!(beyond_its_kind(EffectKind::EffortScale, "scale", 0.6, j).is_none());
        assert!(beyond_its_kind(EffectKind::JointSpring, "stiffness", 0.0, j).is_none());
        assert!(why_not(EffectKind::JointSpring, "stiffness", 0.0, 0.1, j).is_some());
        let prismatic = Some((JointKind::Prismatic, 0.5));
        assert!(beyond_its_kind(EffectKind::EncoderOffset, "offset", 4.0, prismatic).is_none());
    }
}
