//! Joint effects in the report's words: a friction correction against the
//! nominal model's own friction ("the nominal model's viscous coefficient
//! 0.800 corrected by -0.800 to 0.000"), a Coulomb level that depends on
//! the direction of motion (a Coulomb friction and an effort offset at the
//! same joint: forward and backward levels), a spring's rest position, an
//! encoder offset and the mass placement that gravity cannot tell from it.

use dynamics_runtime::JointKind;
use nalgebra::SVector;

use super::report::Explained;
use crate::diagnose::candidates::Candidate;
use crate::diagnose::candidates::Friction;
use crate::effects::EffectKind;

/// In words, a friction correction `value` of parameter `name` at joint
/// `j` (named `joint`) where the nominal model has friction of its own.
pub fn nominal_words<const N: usize>(
    c: Candidate,
    value: f64,
    joint: &str,
    friction: &Friction<N>,
) -> Option<String> {
    let (what, nominal) = match c {
        Candidate::Coulomb(j, _) | Candidate::Stribeck(j, _) => {
            ("Coulomb level", friction.0.get(j))
        }
        Candidate::Viscous(j) => ("viscous coefficient", friction.1.get(j)),
        _ => return None,
    };
    let n = *nominal.filter(|n| **n > 0.0)?;
    let total = (n + value).max(0.0);
    let gone = if total <= 1e-9 * n {
        " (all of it taken away: the data show none)"
    } else {
        ""
    };
    Some(format!(
        "{joint}: the nominal model's {what} {n:.3} corrected by {value:+.3} to {total:.3}{gone}"
    ))
}

/// The Coulomb level at `joint` with an effort offset beside it, in words:
/// while the joint moves, a level `L` (nominal plus correction) and an
/// offset `o` of the measured effort are a level `L + o` moving forward and
/// `L - o` moving backward. Only samples at standstill tell the two
/// readings apart, so the words give both.
pub fn direction_words(joint: &str, level: f64, offset: f64) -> String {
    let (forward, backward) = (level + offset, level - offset);
    let reading = if forward < 0.0 || backward < 0.0 {
        "the offset is larger than the friction: more likely the sensor's own"
    } else {
        "or an offset of the effort sensor: only standstill tells them apart"
    };
    format!(
        "{joint}: with the effort offset {offset:+.3} at this joint, the Coulomb level depends \
         on the direction: {forward:.3} moving forward, {backward:.3} moving backward ({reading})"
    )
}

/// Adds to each Coulomb (or Stribeck) friction of `entries` that has an
/// effort offset at the same joint its direction-dependent levels
/// ([`direction_words`]); `names` are the joints' names, `coulomb` the
/// nominal model's Coulomb levels.
pub fn add_direction_words<const N: usize>(
    entries: &mut [Explained],
    names: &[&str; N],
    coulomb: &SVector<f64, N>,
) {
    let offset = |joint: &str| {
        entries.iter().find_map(|e| {
            (e.kind == EffectKind::EffortOffset && e.joint.as_deref() == Some(joint))
                .then(|| e.parameters.first().map(|p| p.value))
                .flatten()
        })
    };
    let words: Vec<Option<String>> = entries
        .iter()
        .map(|e| {
            let friction = matches!(
                e.kind,
                EffectKind::CoulombFriction | EffectKind::StribeckFriction
            );
            let joint = e.joint.as_deref().filter(|_| friction)?;
            let j = names.iter().position(|n| *n == joint)?;
            let fc = e.parameters.iter().find(|p| p.name == "fc")?.value;
            let o = offset(joint).filter(|o| o.is_finite() && *o != 0.0)?;
            let level = fc + coulomb[j].max(0.0);
            level.is_finite().then(|| direction_words(joint, level, o))
        })
        .collect();
    for (e, w) in entries.iter_mut().zip(words) {
        if let Some(w) = w {
            e.description = Some(match e.description.take() {
                Some(d) => format!("{d}; {w}"),
                None => w,
            });
        }
    }
}

/// Says where each joint spring of `entries` is at rest
/// (`q = -preload / stiffness`), where it has a stiffness, and when that
/// lies outside the range the joint moved in the training data (`range`,
/// per joint of `names`): there the data show an effort that grows with
/// the position over the range, not where it would vanish.
pub fn add_spring_words<const N: usize>(
    entries: &mut [Explained],
    names: &[&str; N],
    range: &[(f64, f64)],
) {
    for e in entries
        .iter_mut()
        .filter(|e| e.kind == EffectKind::JointSpring)
    {
        let get = |n: &str| e.parameters.iter().find(|p| p.name == n).map(|p| p.value);
        let (Some(k), Some(p), Some(joint)) =
            (get("stiffness"), get("preload"), e.joint.as_deref())
        else {
            continue;
        };
        let rest = -p / k;
        if !(k > 0.0 && rest.is_finite()) {
            continue;
        }
        let mut words = format!(
            "{joint}: a spring of stiffness {k:.4} at rest at q = {rest:.3} (its effort {p:+.3} at q = 0)"
        );
        let moved = names
            .iter()
            .position(|n| *n == joint)
            .and_then(|j| range.get(j));
        if let Some(&(lo, hi)) = moved.filter(|(lo, hi)| rest < *lo || rest > *hi) {
            words.push_str(&format!(
                "; it rests outside the range the joint moved ({lo:.3} to {hi:.3}): what the data show is an effort rising {k:.4} per unit of position over that range, from {:+.3} to {:+.3}, which a cable or a hose pulling, or gravity on masses the model places wrong, could make as well",
                k * lo + p,
                k * hi + p
            ));
        }
        e.description = Some(words);
    }
}

/// Says what each encoder offset of `entries` (joints `names` of kinds
/// `kinds`) means and what else looks the same: the encoder reading
/// `q + offset` places every link beyond the joint turned (moved) by
/// `-offset` about (along) its axis from where the model puts it, so to
/// gravity an offset is the same as those links' centres of mass placed
/// wrong by that much; only the inertial efforts of faster motion tell the
/// two apart. Where no joint moves beyond it (`leaf`), what lies beyond
/// is one rigid body, and the offset is exactly that body's mass
/// properties turned (moved) in the model: no motion tells them apart.
pub fn add_encoder_words<const N: usize>(
    entries: &mut [Explained],
    names: &[&str; N],
    kinds: &[JointKind; N],
    leaf: &[bool; N],
) {
    for e in entries
        .iter_mut()
        .filter(|e| e.kind == EffectKind::EncoderOffset)
    {
        let offset = e
            .parameters
            .iter()
            .find(|p| p.name == "offset")
            .map(|p| p.value);
        let (Some(offset), Some(joint)) = (offset.filter(|x| x.is_finite()), e.joint.as_deref())
        else {
            continue;
        };
        let Some(j) = names.iter().position(|n| *n == joint) else {
            continue;
        };
        let words = match (kinds[j], leaf[j]) {
            (JointKind::Revolute, true) => format!(
                "{joint}: the encoder reads {offset:+.4} rad ({:+.1} deg) off the joint's angle; no joint moves beyond it, so this is exactly the body it carries turned by {:+.4} rad about its axis in the model (its centre of mass and inertia placed wrong), which no motion tells apart: a measured joint angle or the body's mass properties decide",
                offset.to_degrees(),
                -offset
            ),
            (JointKind::Prismatic, true) => format!(
                "{joint}: the encoder reads {offset:+.4} m off the joint's position; no joint moves beyond it, so this is exactly the body it carries moved by {:+.4} m along its axis in the model (its centre of mass placed wrong), which no motion tells apart: a measured joint position or the body's mass properties decide",
                -offset
            ),
            (JointKind::Revolute, false) => format!(
                "{joint}: the encoder reads {offset:+.4} rad ({:+.1} deg) off the joint's angle; to gravity this is the same as every link beyond the joint turned by {:+.4} rad about its axis (centres of mass placed wrong in the model), which only the inertial efforts of faster motion tell apart",
                offset.to_degrees(),
                -offset
            ),
            (JointKind::Prismatic, false) => format!(
                "{joint}: the encoder reads {offset:+.4} m off the joint's position; to gravity this is the same as every link beyond the joint moved by {:+.4} m along its axis (centres of mass placed wrong in the model), which only the inertial efforts of faster motion tell apart",
                -offset
            ),
        };
        e.description = Some(match e.description.take() {
            Some(before) => format!("{before}; {words}"),
            None => words,
        });
    }
}

/// A payload relative to the model in words: mass `mass` (kg) at the
/// tip named `tip`; a negative mass is mass the model carries there that
/// the robot does not (a hand or tool in the model that is absent).
pub fn payload_words(tip: &str, mass: f64) -> String {
    if mass < 0.0 {
        format!(
            "about {:.2} kg at {tip} that the model carries is not on the robot \
             (e.g. the hand or tool of the model is absent)",
            -mass
        )
    } else {
        format!("about {mass:.2} kg at {tip} that the model does not carry (a payload or tool)")
    }
}

/// Adds to each payload of `entries` whose mass is a number its words
/// ([`payload_words`]) at its point, and where its centre of mass is
/// reported, where that lies in the tip's frame (or that the data do not
/// place it).
pub fn add_payload_words(entries: &mut [Explained]) {
    for e in entries
        .iter_mut()
        .filter(|e| e.kind == EffectKind::PayloadMass && e.description.is_none())
    {
        let value = |name: &str| e.parameters.iter().find(|p| p.name == name);
        let mass = value("mass").filter(|p| p.note.is_none()).map(|p| p.value);
        let (Some(m), Some(tip)) = (mass.filter(|m| m.is_finite()), e.point.as_deref()) else {
            continue;
        };
        let mut words = payload_words(tip, m);
        let com: Vec<Option<f64>> = ["com_x", "com_y", "com_z"]
            .iter()
            .filter_map(|n| value(n))
            .map(|p| p.note.is_none().then_some(p.value))
            .collect();
        if let [Some(x), Some(y), Some(z)] = com[..] {
            words +=
                &format!("; its centre of mass at ({x:.3}, {y:.3}, {z:.3}) m in {tip}'s frame");
        } else if !com.is_empty() {
            words += "; the data do not place its centre of mass";
        }
        e.description = Some(words);
    }
}

/// Link corrections on adjacent links (`links`: `Robot::LINK_NAMES`,
/// depth-first from the root, so that on a serial chain a link's next is
/// its child) whose masses change with opposite
/// signs: one change, said once. Where the joint between two links moves
/// little, the data see the two bodies nearly as one, and mass taken from
/// one and added to the other is how a least-squares fit places mass it
/// cannot place; the words give the mass moved (the smaller of the two
/// changes), which way along the chain, and the net change of the pair,
/// on the distal link's entry; the proximal one's words point to it.
pub fn add_placement_words(entries: &mut [Explained], links: &[&str]) {
    let mass = |e: &Explained| {
        e.parameters
            .iter()
            .find(|p| p.name == "d_m" && p.note.is_none())
            .map(|p| p.value)
            .filter(|m| m.is_finite() && *m != 0.0)
    };
    let at = |e: &Explained| {
        (e.kind == EffectKind::InertialParameters)
            .then_some(e.point.as_deref())
            .flatten()
            .and_then(|name| links.iter().position(|l| *l == name))
    };
    let placed: Vec<(usize, usize, f64)> = entries
        .iter()
        .enumerate()
        .filter_map(|(i, e)| Some((i, at(e)?, mass(e)?)))
        .collect();
    for &(i, l, m) in &placed {
        let Some(&(j, _, md)) = placed
            .iter()
            .find(|&&(_, k, md)| k == l + 1 && md * m < 0.0)
        else {
            continue;
        };
        let (near, far) = (links[l], links[l + 1]);
        let moved = m.abs().min(md.abs());
        let way = if md > 0.0 {
            format!("that the model has at {near} is at {far} or further out, toward the tool")
        } else {
            format!("that the model has at {far} or further out is at {near}")
        };
        let words = format!(
            "one change of {near} and {far}, which these data cannot divide between the two \
             links: about {moved:.2} kg {way}; net {:+.2} kg over both ({near} {m:+.2} kg, \
             {far} {md:+.2} kg)",
            m + md
        );
        let with = |d: &Option<String>, w: &str| match d {
            Some(d) => format!("{w}. {d}"),
            None => w.to_string(),
        };
        entries[j].description = Some(with(&entries[j].description, &words));
        let pointer = format!("part of one change with {far}: see there");
        entries[i].description = Some(with(&entries[i].description, &pointer));
    }
}

/// A link correction in words: mass, first moments and inertia about the
/// link frame's origin, as changed.
pub fn link_words(link: &str, d: &SVector<f64, 10>) -> String {
    let names = [
        "mass", "m c_x", "m c_y", "m c_z", "I_xx", "I_xy", "I_yy", "I_xz", "I_yz", "I_zz",
    ];
    let units = [
        "kg", "kg m", "kg m", "kg m", "kg m^2", "kg m^2", "kg m^2", "kg m^2", "kg m^2", "kg m^2",
    ];
    let scale = d.amax().max(1e-300);
    let parts: Vec<String> = (0..10)
        .filter(|&i| d[i].abs() >= 0.05 * scale)
        .map(|i| format!("{} {:+.3e} {}", names[i], d[i], units[i]))
        .collect();
    format!("link {link}: {}", parts.join(", "))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diagnose::explain::report::{test_entry as entry, Parameter};

    /// A negative payload reads as mass the robot lacks, a positive one as
    /// mass it carries; the figure is the mass to two decimals.
    #[test]
    fn a_negative_payload_reads_as_the_models_mass_that_is_absent() {
        let absent = payload_words("panda_hand_tcp", -0.734);
        assert!(
            absent.starts_with(
                "about 0.73 kg at panda_hand_tcp that the model carries is not on the robot"
            ),
            "{absent}"
        );
        let carried = payload_words("tool0", 1.25);
        assert!(
            carried.starts_with("about 1.25 kg at tool0 that the model does not carry"),
            "{carried}"
        );
    }

    /// +3.0 kg at the wrist and -2.6 kg at the forearm before it: one
    /// statement, 2.6 kg moved out to the wrist, net +0.4 kg (by hand);
    /// a link correction on a link that is not adjacent gets no words.
    #[test]
    fn opposite_masses_on_adjacent_links_are_one_statement() {
        let link = |name: &str, m: f64| Explained {
            kind: EffectKind::InertialParameters,
            joint: None,
            point: Some(name.to_string()),
            ..entry(EffectKind::InertialParameters, "-", "d_m", m)
        };
        let mut entries = vec![link("wrist", 3.0), link("forearm", -2.6), link("base", 1.0)];
        add_placement_words(&mut entries, &["base", "upper", "forearm", "wrist"]);
        let words = entries[0].description.as_deref().unwrap_or("");
        assert!(
            words.starts_with("one change of forearm and wrist"),
            "{words}"
        );
        assert!(
            words.contains("about 2.60 kg that the model has at forearm is at wrist"),
            "{words}"
        );
        assert!(words.contains("net +0.40 kg"), "{words}");
        let pointer = entries[1].description.as_deref().unwrap_or("");
        assert!(
            pointer.starts_with("part of one change with wrist"),
            "{pointer}"
        );
        assert!(entries[2].description.is_none());
    }

    /// A Coulomb correction of +0.2 on a nominal level of 0.1 with an
    /// effort offset of +0.05: 0.35 forward, 0.25 backward (by hand); a
    /// Coulomb friction at another joint gets no words.
    #[test]
    fn coulomb_and_offset_at_a_joint_read_as_direction_dependent_levels() {
        let mut entries = vec![
            entry(EffectKind::CoulombFriction, "j1", "fc", 0.2),
            entry(EffectKind::EffortOffset, "j1", "offset", 0.05),
            entry(EffectKind::CoulombFriction, "j2", "fc", 0.3),
        ];
        let coulomb = SVector::<f64, 2>::new(0.1, 0.0);
        add_direction_words(&mut entries, &["j1", "j2"], &coulomb);
        let words = entries[0].description.as_deref().unwrap_or("");
        assert!(words.contains("0.350 moving forward"), "{words}");
        assert!(words.contains("0.250 moving backward"), "{words}");
        assert!(words.contains("standstill"), "{words}");
        assert!(entries[1].description.is_none());
        assert!(entries[2].description.is_none());
    }

    /// A spring of 0.5 with a preload of -0.1 rests at q = 0.2 (by hand);
    /// one without stiffness gets no words.
    #[test]
    fn a_spring_is_said_with_its_rest_position() {
        let mut entries = vec![
            entry(EffectKind::JointSpring, "j1", "stiffness", 0.5),
            entry(EffectKind::JointSpring, "j2", "stiffness", 0.0),
        ];
        for e in &mut entries {
            e.parameters.push(Parameter {
                name: "preload".into(),
                value: -0.1,
                std: 0.01,
                note: None,
            });
        }
        add_spring_words(&mut entries, &["j1", "j2"], &[(-0.5, 0.5), (-0.5, 0.5)]);
        let words = entries[0].description.as_deref().unwrap_or("");
        assert_eq!(
            words,
            "j1: a spring of stiffness 0.5000 at rest at q = 0.200 (its effort -0.100 at q = 0)"
        );
        assert!(entries[1].description.is_none());
    }

    /// The same spring on a joint that moved over 0.5-1.0 rad rests
    /// outside it: its effort over the range is +0.150 to +0.400 (by hand).
    #[test]
    fn a_spring_at_rest_outside_the_range_moved_says_so() {
        let mut entries = vec![entry(EffectKind::JointSpring, "j1", "stiffness", 0.5)];
        entries[0].parameters.push(Parameter {
            name: "preload".into(),
            value: -0.1,
            std: 0.01,
            note: None,
        });
        add_spring_words(&mut entries, &["j1"], &[(0.5, 1.0)]);
        let words = entries[0].description.as_deref().unwrap_or("");
        assert!(
            words.contains("it rests outside the range the joint moved (0.500 to 1.000)"),
            "{words}"
        );
        assert!(words.contains("from +0.150 to +0.400"), "{words}");
    }

    /// An offset larger than the level reads as the sensor's.
    #[test]
    fn an_offset_larger_than_the_level_reads_as_the_sensors() {
        let w = direction_words("j", 0.1, -0.3);
        assert!(w.contains("-0.200 moving forward"), "{w}");
        assert!(w.contains("more likely the sensor's own"), "{w}");
    }

    /// An offset of -0.2 rad reads as the links beyond turned by +0.2
    /// (-11.5 deg by hand); a prismatic joint's in metres; words already
    /// there (a window's) are kept in front.
    #[test]
    fn an_encoder_offset_is_said_with_the_mass_placement_gravity_confuses_it_with() {
        let mut entries = vec![
            entry(EffectKind::EncoderOffset, "j1", "offset", -0.2),
            entry(EffectKind::EncoderOffset, "j2", "offset", 0.01),
        ];
        entries[1].description = Some("from t = 1.000 s".into());
        add_encoder_words(
            &mut entries,
            &["j1", "j2"],
            &[JointKind::Revolute, JointKind::Prismatic],
            &[false, false],
        );
        let w0 = entries[0].description.as_deref().unwrap_or("");
        assert!(
            w0.starts_with("j1: the encoder reads -0.2000 rad (-11.5 deg)"),
            "{w0}"
        );
        assert!(w0.contains("turned by +0.2000 rad about its axis"), "{w0}");
        let w1 = entries[1].description.as_deref().unwrap_or("");
        assert!(
            w1.starts_with("from t = 1.000 s; j2: the encoder reads +0.0100 m"),
            "{w1}"
        );
        assert!(w1.contains("moved by -0.0100 m along its axis"), "{w1}");
    }

    /// At a joint beyond which nothing moves, the offset is said to be
    /// the carried body turned, which no motion tells apart.
    #[test]
    fn an_encoder_offset_at_the_last_joint_is_the_body_turned() {
        let mut entries = vec![
            entry(EffectKind::EncoderOffset, "j1", "offset", -0.2),
            entry(EffectKind::EncoderOffset, "j2", "offset", -1.02),
        ];
        add_encoder_words(
            &mut entries,
            &["j1", "j2"],
            &[JointKind::Revolute, JointKind::Revolute],
            &[false, true],
        );
        let w0 = entries[0].description.as_deref().unwrap_or("");
        assert!(w0.contains("faster motion tell apart"), "{w0}");
        let w1 = entries[1].description.as_deref().unwrap_or("");
        assert!(
            w1.contains("exactly the body it carries turned by +1.0200 rad")
                && w1.contains("no motion tells apart"),
            "{w1}"
        );
    }
}
