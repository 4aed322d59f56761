//! Decoded JointState messages into samples of the robot's joints: joints
//! matched by name, messages ordered by stamp (the receive time where the
//! stamp is zero), messages of one stamp that carry some joints each merged
//! into one sample, velocities derived where the messages carry none.

use std::collections::BTreeSet;

use nalgebra::SVector;

use super::cdr::{decode_joint_state, JointState};
use super::{BagError, Raw};
use crate::data::{differentiate, Measured};
use crate::Warning;

/// The samples of `messages` (on `topic` of `file`) for `joints`, with
/// warnings, and the first and last stamp (ns since the epoch).
pub(super) fn samples<const N: usize>(
    messages: &[Raw],
    joints: &[&str; N],
    file: &str,
    topic: &str,
    warnings: &mut Vec<Warning>,
) -> Result<(Measured<N>, i64, i64), BagError> {
    let note = |message: String| Warning::Imported { message };
    let mut decoded: Vec<(i64, usize, JointState)> = Vec::with_capacity(messages.len());
    let mut zero_stamps = 0usize;
    for (k, raw) in messages.iter().enumerate() {
        let m = decode_joint_state(&raw.data).map_err(|message| BagError::Message {
            file: file.to_string(),
            place: raw.place.to_string(),
            message,
        })?;
        let n = m.name.len();
        for (what, len) in [
            ("position", m.position.len()),
            ("velocity", m.velocity.len()),
            ("effort", m.effort.len()),
        ] {
            if len != n && !(len == 0 && what != "position") {
                return Err(BagError::Message {
                    file: file.to_string(),
                    place: raw.place.to_string(),
                    message: format!("{n} names but {len} values in `{what}`"),
                });
            }
        }
        let stamp = if m.stamp_ns == 0 {
            zero_stamps += 1;
            raw.received_ns
        } else {
            m.stamp_ns
        };
        decoded.push((stamp, k, m));
    }
    if zero_stamps > 0 {
        warnings.push(note(format!(
            "{file}: {zero_stamps} of {} messages on `{topic}` have a zero header.stamp: their receive time is used",
            decoded.len()
        )));
    }
    // Which message names which joint of the robot; the names it does not have.
    let mut extra = BTreeSet::new();
    let mut seen = [false; N];
    let mut without_velocity = 0usize;
    let index: Vec<Vec<Option<usize>>> = decoded
        .iter()
        .map(|(_, k, m)| {
            let mut carries = false;
            let idx = m
                .name
                .iter()
                .map(|name| {
                    let i = joints.iter().position(|j| j == name);
                    match i {
                        Some(i) => {
                            seen[i] = true;
                            carries = true;
                        }
                        None => {
                            extra.insert(name.clone());
                        }
                    }
                    i
                })
                .collect();
            if carries && m.velocity.is_empty() {
                without_velocity += 1;
            }
            let _ = k;
            idx
        })
        .collect();
    if seen.iter().any(|s| !s) {
        let missing: Vec<&str> = (0..N).filter(|&i| !seen[i]).map(|i| joints[i]).collect();
        let mut names: BTreeSet<&str> = extra.iter().map(String::as_str).collect();
        names.extend((0..N).filter(|&i| seen[i]).map(|i| joints[i]));
        return Err(BagError::MissingJoints {
            file: file.to_string(),
            topic: topic.to_string(),
            missing: missing.join(", "),
            names: if names.is_empty() {
                "no joints".into()
            } else {
                names.into_iter().collect::<Vec<_>>().join(", ")
            },
        });
    }
    if !extra.is_empty() {
        warnings.push(note(format!(
            "{file}: joints on `{topic}` that the robot does not have, ignored: {}",
            extra.into_iter().collect::<Vec<_>>().join(", ")
        )));
    }
    let qd_measured = without_velocity == 0;
    if !qd_measured {
        warnings.push(note(format!(
            "{file}: {without_velocity} messages on `{topic}` carry no velocities: velocities are differentiated from the positions"
        )));
    }
    // By stamp, then as recorded.
    let mut order: Vec<usize> = (0..decoded.len()).collect();
    order.sort_by_key(|&i| (decoded[i].0, decoded[i].1));
    let mut out = Measured::<N> {
        qd_measured,
        joints: joints.iter().map(|j| j.to_string()).collect(),
        ..Default::default()
    };
    let first = order.first().map(|&i| decoded[i].0).unwrap_or(0);
    let last = order.last().map(|&i| decoded[i].0).unwrap_or(0);
    let mut g = 0;
    while g < order.len() {
        let stamp = decoded[order[g]].0;
        let mut end = g;
        while end < order.len() && decoded[order[end]].0 == stamp {
            end += 1;
        }
        // One sample from the messages of this stamp.
        let mut q = [None; N];
        let mut qd = [None; N];
        let mut tau = [None; N];
        for &i in &order[g..end] {
            let (_, k, m) = &decoded[i];
            let place = || messages[*k].place.to_string();
            for (slot, joint) in index[i].iter().enumerate() {
                let Some(j) = *joint else { continue };
                let set = |cell: &mut Option<f64>,
                           values: &[f64],
                           quantity: &'static str|
                 -> Result<(), BagError> {
                    let Some(&v) = values.get(slot) else {
                        return Ok(());
                    };
                    if !v.is_finite() {
                        return Err(BagError::NotFinite {
                            file: file.to_string(),
                            place: place(),
                            quantity,
                            joint: joints[j].to_string(),
                            value: v,
                        });
                    }
                    match cell {
                        Some(old) if *old != v => Err(BagError::Conflict {
                            file: file.to_string(),
                            stamp: stamp as f64 * 1e-9,
                            joint: joints[j].to_string(),
                        }),
                        _ => {
                            *cell = Some(v);
                            Ok(())
                        }
                    }
                };
                set(&mut q[j], &m.position, "position")?;
                if qd_measured {
                    set(&mut qd[j], &m.velocity, "velocity")?;
                }
                if m.effort.is_empty() {
                    return Err(BagError::NoEffort {
                        file: file.to_string(),
                        place: place(),
                    });
                }
                set(&mut tau[j], &m.effort, "effort")?;
            }
        }
        let unmerged = |joint: usize, quantity| BagError::Unmerged {
            file: file.to_string(),
            stamp: stamp as f64 * 1e-9,
            joint: joints[joint].to_string(),
            quantity,
        };
        let mut vq = SVector::<f64, N>::zeros();
        let mut vqd = SVector::<f64, N>::zeros();
        let mut vtau = SVector::<f64, N>::zeros();
        for j in 0..N {
            vq[j] = q[j].ok_or_else(|| unmerged(j, "position"))?;
            vtau[j] = tau[j].ok_or_else(|| unmerged(j, "effort"))?;
            if qd_measured {
                vqd[j] = qd[j].ok_or_else(|| unmerged(j, "velocity"))?;
            }
        }
        // Exact integer nanoseconds from the first stamp, then seconds.
        out.t.push((stamp - first) as f64 / 1e9);
        out.q.push(vq);
        out.tau.push(vtau);
        if qd_measured {
            out.qd.push(vqd);
        }
        g = end;
    }
    if !qd_measured && out.len() > 1 {
        out.qd = differentiate(&out.t, &out.q);
    }
    Ok((out, first, last))
}
