//! The compound explanation in the report's words: each effect with its
//! parameters from the joint fit, its share of the training gap (in the
//! order of the gains), its held-out contribution (how much the held-out gap
//! grows when it alone is left out of the set, the others refitted), and
//! the held-out gap left after each added effect.

use nalgebra::{DVector, SVector};

use super::ranked::ranked_entry;
use super::report::{self, EffectWindow, Explained, Parameter, Rival, ShrinkStep, Suggested};
use super::words::{add_direction_words, link_words, nominal_words};
use crate::diagnose::candidates::{delta, Candidate, Friction, LinkBasis, MOMENTS};
use crate::diagnose::evaluate::{
    fraction, Confidence, Holdout, Suggestion, Unconfirmed, PRACTICAL_SHARE,
};
use crate::diagnose::select::{joint_fit, Explanation, Parts, Pool, Solution};
use crate::inertial::{check, complete, describe};
use dynamics_runtime::Robot;

/// Where a candidate sits: its joint, or its point (the tip, or a link).
fn place_of<R: Robot<N>, const N: usize>(
    c: Candidate,
    tip: &str,
) -> (Option<String>, Option<String>) {
    match c {
        Candidate::Inertial(l) => (None, R::LINK_NAMES.get(l).map(|s| s.to_string())),
        _ => (
            c.joint().map(|j| R::JOINT_NAMES[j].to_string()),
            (c.kind().place() == crate::effects::PlaceKind::Point).then(|| tip.to_string()),
        ),
    }
}

/// The report's entries and the held-out steps.
#[allow(clippy::too_many_arguments)]
pub fn entries<R: Robot<N>, const N: usize>(
    pool: &Pool,
    e: &Explanation,
    hold: &Holdout<N>,
    tip: &str,
    aicc0: f64,
    nominal: &[SVector<f64, 10>],
    friction: &Friction<N>,
    confidence: &[Confidence],
) -> (Vec<Explained>, Vec<ShrinkStep>) {
    let n = pool.n();
    let sse0 = pool.yy();
    let gap0 = (sse0 - n as f64).max(1e-12);
    let all: Vec<usize> = (0..e.set.len()).collect();
    let h_full = hold.residual(&all, &e.sol.theta);
    let y = hold.observed();
    let (hgap0, plain0) = (hold.gap(y), hold.plain(y));
    let hsse = |r: &DVector<f64>| r.norm_squared();
    let hgap_sse = (hsse(y) - y.len() as f64).max(1e-12);
    // Prefixes: refitted on the training rows, checked on the held-out.
    let mut steps = vec![ShrinkStep {
        effects: 0,
        added: "nominal model".into(),
        torque_gap: hgap0.sqrt(),
        torque_fraction: 0.0,
        rms_fraction: 0.0,
    }];
    let mut prev_sse = sse0;
    let mut shares = Vec::new();
    for i in 0..e.set.len() {
        let which: Vec<usize> = (0..=i).collect();
        let sol: Solution = pool.solve(&e.set[..=i]);
        shares.push(((prev_sse - sol.sse) / gap0).clamp(0.0, 1.0));
        prev_sse = sol.sse;
        let r = hold.residual(&which, &sol.theta);
        let c = pool.terms[e.set[i]].fit.candidate;
        let (j, pt) = place_of::<R, N>(c, tip);
        let place = j.or(pt).unwrap_or_else(|| "all signals".into());
        let g = hold.gap(&r);
        steps.push(ShrinkStep {
            effects: i + 1,
            added: format!("{} at {place}", c.kind().name()),
            torque_gap: g.sqrt(),
            torque_fraction: fraction(hgap0.sqrt(), g.sqrt()),
            rms_fraction: fraction(plain0, hold.plain(&r)),
        });
    }
    if e.set.is_empty() {
        steps.clear();
    }
    let full = hsse(&h_full);
    let mut explained: Vec<Explained> = e
        .set
        .iter()
        .enumerate()
        .map(|(i, &t)| {
            // Held out without it, the others refitted on training.
            let rest: Vec<usize> = e.set.iter().copied().filter(|&u| u != t).collect();
            let which: Vec<usize> = (0..e.set.len()).filter(|&m| m != i).collect();
            let sol = pool.solve(&rest);
            let without = hsse(&hold.residual(&which, &sol.theta));
            let contribution = (without - full) / hgap_sse;
            let f = joint_fit(pool, t, &e.sol.theta[i], &e.sol.std[i]);
            let (joint, point) = place_of::<R, N>(f.candidate, tip);
            let (mut parameters, mut description) = match &pool.terms[t].link {
                Some(b) => link_parameters(
                    b,
                    &e.sol.theta[i],
                    &e.sol.std[i],
                    point.as_deref().unwrap_or("?"),
                    nominal.get(b.link),
                ),
                None => {
                    let parameters =
                        ranked_entry::<R, N>(&f, tip, aicc0, n, shares[i], 0.0).parameters;
                    let words = parameters.first().and_then(|p| {
                        nominal_words(f.candidate, p.value, joint.as_deref()?, friction)
                    });
                    (parameters, words)
                }
            };
            // No NaN in a report: a parameter the fit could not make says so.
            for p in parameters.iter_mut() {
                if !p.value.is_finite() {
                    p.value = 0.0;
                    p.std = f64::INFINITY;
                    description = Some(format!(
                        "{}: the fit of `{}` could not be made",
                        f.candidate.kind().name(),
                        p.name
                    ));
                } else if p.std.is_nan() {
                    p.std = f64::INFINITY;
                }
            }
            let rival = e.rivals[i].map(|u| {
                let c = pool.terms[u].fit.candidate;
                let (joint, point) = place_of::<R, N>(c, tip);
                Rival {
                    kind: c.kind(),
                    joint,
                    point,
                    inseparable: None,
                }
            });
            Explained {
                kind: f.candidate.kind(),
                joint,
                point,
                description,
                parameters,
                share: if shares[i].is_finite() {
                    shares[i]
                } else {
                    0.0
                },
                holdout_contribution: if contribution.is_finite() {
                    contribution
                } else {
                    0.0
                },
                window: None,
                channel: f.candidate.channel(),
                confidence: confidence_of(confidence.get(i)),
                ambiguous_with: rival,
            }
        })
        .collect();
    add_direction_words(&mut explained, &R::JOINT_NAMES, &friction.0);
    (explained, steps)
}

/// The report's confidence of an effect.
fn confidence_of(c: Option<&Confidence>) -> report::Confidence {
    let finite = |x: f64| if x.is_finite() { x } else { 0.0 };
    let (gain, chance, size, level) = c.map_or((0.0, 0.0, 0.0, 0.0), |c| {
        (c.gain_share, c.chance_share, c.size, c.level)
    });
    report::Confidence {
        status: "confirmed",
        held_out_gain: finite(gain),
        chance: finite(chance),
        effort_to_noise: finite(size),
        joint_gap_share: finite(c.map_or(0.0, |c| c.joint_share)),
        level: finite(level),
    }
}

/// A share as a percentage, small ones in scientific notation.
fn share(x: f64) -> String {
    if !x.is_finite() {
        "nothing".into()
    } else if x.abs() >= 1e-3 {
        format!("{:.2} %", 100.0 * x)
    } else {
        format!("{:.1e} %", 100.0 * x)
    }
}

/// The effects the selection chose that did not hold, with the reason.
pub fn suggested<R: Robot<N>, const N: usize>(
    pool: &Pool,
    suggestions: &[Suggestion],
    tip: &str,
) -> Vec<Suggested> {
    suggestions
        .iter()
        .map(|s| {
            let c = pool.terms[s.term].fit.candidate;
            let (joint, point) = place_of::<R, N>(c, tip);
            let reason = match &s.why {
                Unconfirmed::Undetermined(why) => why.clone(),
                Unconfirmed::NotPhysical if matches!(c, Candidate::Payload | Candidate::PayloadCom(_)) => {
                    "the payload the data ask for leaves the body that carries the tip no physical body (mass > 0, pseudo-inertia positive semi-definite: no mass taken from where the body has none)".into()
                }
                Unconfirmed::NotPhysical => {
                    "the correction the data ask for leaves no physical body (mass > 0, pseudo-inertia positive semi-definite)".into()
                }
                Unconfirmed::WithinCalibration(s) => format!(
                    "refines the baseline's calibration (its spread on this friction {s:.3e}): no change that the calibration would have seen"
                ),
                Unconfirmed::NotTheWholeEffort { common, lags } => not_the_whole(common, lags),
                Unconfirmed::PartOfTheEffort { common, scales } => part_of_the_effort(common, scales),
                Unconfirmed::OwnJointOnly { common, offsets } => own_joint_only(common, offsets),
                Unconfirmed::Simpler {
                    rival,
                    extra,
                    chance,
                } => {
                    let r = pool.terms[*rival].fit.candidate;
                    let at = match place_of::<R, N>(r, tip) {
                        (_, Some(point)) => format!(" at {point}"),
                        (Some(joint), None) => format!(" at {joint}"),
                        (None, None) => String::new(),
                    };
                    let gain = if *extra > 0.0 {
                        format!("removes {} more of the gap above noise there", share(*extra))
                    } else {
                        "removes nothing more of the gap above noise there".into()
                    };
                    format!(
                        "the held-out record holds a simpler effect in its place ({}{at}, {} fewer parameters); \
                         this one in that one's place {gain}, no more than chance gives the extra parameters ({})",
                        r.kind().name(),
                        pool.terms[s.term].k.saturating_sub(pool.terms[*rival].k),
                        share(*chance)
                    )
                }
                Unconfirmed::TooSmall(c) => format!(
                    "too small to act on: on the held-out record it removes {} of the gap above noise (more than chance, {}), \
                     but its effort is {:.1} % of the noise floor (RMS) and at most {} of one joint's gap; \
                     an effect named is as large as the noise floor or removes {} of a joint's gap",
                    share(c.gain_share),
                    share(c.chance_share),
                    100.0 * c.size,
                    share(c.joint_share),
                    share(PRACTICAL_SHARE)
                ),
                Unconfirmed::NotConfirmed(c) => format!(
                    "helps only where it was fitted: on the held-out record it removes {} of the gap above noise, no more than noise alone could ({})",
                    share(c.gain_share),
                    share(c.chance_share)
                ),
            };
            let parameters = if pool.terms[s.term].link.is_some() {
                vec![]
            } else {
                joint_fit(pool, s.term, &s.theta, &s.std)
                    .parameters()
                    .into_iter()
                    .map(|(name, value, std)| Parameter {
                        name: name.into(),
                        value,
                        std,
                        note: None,
                    })
                    .collect()
            };
            Suggested {
                kind: c.kind(),
                joint,
                point,
                parameters,
                channel: c.channel(),
                status: "suggested",
                reason,
            }
        })
        .collect()
}

/// Why a delay the model's own effort does not show is not named, in
/// words: the common delay and the two parts' lags.
fn not_the_whole(common: &f64, lags: &Parts) -> String {
    let ms = |(v, s): (f64, f64)| format!("{:+.2} +- {:.2} ms", 1e3 * v, 1e3 * s);
    format!(
        "not the whole effort late: its column split, the effort the model predicts lags {} and the rest {}; \
         the common {:.2} ms is not shown to help the model's part (its lag is not above half of it by two standard deviations), \
         as a lag of what the model misses alone does (a friction that lags its velocity reversals), not a late stream",
        ms(lags.part),
        ms(lags.rest),
        1e3 * *common
    )
}

/// Why an effort scale that acts on a part of the effort is not one.
fn part_of_the_effort(common: &f64, scales: &Parts) -> String {
    let pc = |(v, s): (f64, f64)| format!("{:+.1} +- {:.1} %", 100.0 * v, 100.0 * s);
    format!(
        "not a scale of the whole effort: its column split, the effort beside gravity (inertia, Coriolis, the drive) \
         is scaled {} and the gravity effort {}; the common {:+.1} % is not shown to act on each part the data determine \
         (above half of it by two standard deviations), as a sensor's scale would: what scales one part alone is \
         a model error of that part (a mass the model places wrong scales the gravity effort)",
        pc(scales.part),
        pc(scales.rest),
        100.0 * *common
    )
}

/// Why an encoder offset that only its own joint shows is not named.
fn own_joint_only(common: &f64, offsets: &Parts) -> String {
    let rad = |(v, s): (f64, f64)| {
        if s.is_finite() {
            format!("{v:+.4} +- {s:.4} rad")
        } else {
            "nothing the rest of the explanation does not already make".into()
        }
    };
    format!(
        "not shown to be the encoder: its own joint's effort asks for {} and the other joints' efforts for {}, \
         where an encoder off by {:+.4} rad would move both (the links beyond it turned); what its own joint \
         alone shows, an effort offset, a spring or the links beyond placed wrong in the model make as well",
        rad(offsets.part),
        rad(offsets.rest),
        *common
    )
}

/// A link correction's parameters and its words: the change along the
/// combinations the data determine (standard deviations through them),
/// moved along the others until the link with its nominal parameters
/// `nominal` is a physical body (`inertial::complete`; when no such move
/// exists the determined part is scaled back, and the words say so).
fn link_parameters(
    b: &LinkBasis,
    theta: &[f64],
    std: &[f64],
    link: &str,
    nominal: Option<&SVector<f64, 10>>,
) -> (Vec<Parameter>, Option<String>) {
    let fitted = delta(b, theta);
    let made = nominal.and_then(|nom| complete(nom, &fitted, &b.free_combinations()));
    let d = made.as_ref().map_or(fitted, |c| c.delta);
    let names = crate::inertial::PARAMETER_NAMES_DELTA;
    let params = (0..10)
        .map(|c| {
            let var: f64 = (0..b.v.ncols())
                .map(|r| (b.v[(c, r)] * std.get(r).copied().unwrap_or(0.0)).powi(2))
                .sum();
            Parameter {
                name: names[c].into(),
                value: d[c],
                std: var.sqrt(),
                note: None,
            }
        })
        .collect();
    let text = match (nominal, &made) {
        (Some(nom), Some(c)) => {
            let mut t = describe(link, nom, &d);
            if b.tip && d[0] < 0.0 {
                t = format!(
                    "about {:.2} kg of the tip body {link} that the model carries is not on the \
                     robot (e.g. the hand or tool of the model is absent): {t}",
                    -d[0]
                );
            }
            if b.moments {
                t += "; its mass and centre of mass alone (the rotational inertia about the link \
                      frame's origin is the model's)";
            }
            if c.moved && !c.projected {
                t += &format!(
                    "; the data determine {} of the {} combinations, the others are set to keep the link physical",
                    b.v.ncols(),
                    if b.moments { MOMENTS } else { 10 }
                );
            }
            if c.projected {
                t += &format!(
                    "; the fit is not a physical body ({}): the nearest one is given (its pseudo-inertia's negative eigenvalues set to zero)",
                    check(&(nom + fitted), 1e-9)
                        .err()
                        .map_or(String::new(), |e| e.to_string())
                );
            } else if c.scale < 1.0 {
                t += &format!(
                    "; scaled to {:.2} of the fit, which is not a physical body ({})",
                    c.scale,
                    check(&(nom + fitted), 1e-9)
                        .err()
                        .map_or(String::new(), |e| e.to_string())
                );
            }
            t
        }
        (Some(nom), None) => format!(
            "{}; the nominal link is not a physical body ({})",
            link_words(link, &d),
            check(nom, 1e-9)
                .err()
                .map_or(String::new(), |e| e.to_string())
        ),
        (None, _) => link_words(link, &d),
    };
    (params, Some(text))
}

/// The training windows on the report's entries of the explanation.
pub fn annotate(effects: &mut [Explained], pool: &Pool, e: &Explanation) {
    for (entry, &t) in effects.iter_mut().zip(&e.set) {
        if let Some(w) = pool.terms[t].window {
            entry.window = Some(EffectWindow {
                start: w.start,
                end: w.end,
            });
        }
    }
}
