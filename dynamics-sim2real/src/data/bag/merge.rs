//! JointState messages into samples of the robot's joints, as they are
//! read: each message decoded at once into buffers reused from one message
//! to the next, its values kept in one flat array; joints matched by name
//! (once per distinct list of names); then the messages ordered by stamp
//! (the receive time where the stamp is zero), those of one stamp that
//! carry some joints each merged into one sample, velocities derived where
//! the messages carry none.

use std::collections::BTreeSet;

use nalgebra::SVector;

use super::cdr::Parts;
use super::{BagError, Place};
use crate::data::{differentiate, Measured};
use crate::Warning;

/// A list of names as messages carry it, and the robot's joint of each.
struct Layout {
    names: Vec<String>,
    /// For each name that is a joint of the robot: (its slot, the joint).
    carried: Vec<(usize, usize)>,
}

/// One message kept: where its values are in [`Collector::values`].
struct Message {
    stamp: i64,
    arrival: usize,
    place: Place,
    layout: usize,
    /// Its first value: per joint carried, position, velocity (NaN when
    /// the message has none), effort.
    at: usize,
}

/// Collects the messages of one topic.
pub(super) struct Collector<'j, const N: usize> {
    joints: &'j [&'j str; N],
    file: String,
    topic: String,
    parts: Parts,
    layouts: Vec<Layout>,
    last_layout: usize,
    messages: Vec<Message>,
    values: Vec<f64>,
    seen: [bool; N],
    extra: BTreeSet<String>,
    zero_stamps: usize,
    without_velocity: usize,
    received: usize,
}

impl<'j, const N: usize> Collector<'j, N> {
    /// A collector for the robot joints `joints`, of `topic` in `file`.
    pub(super) fn new(joints: &'j [&'j str; N], file: &str, topic: &str) -> Self {
        Collector {
            joints,
            file: file.to_string(),
            topic: topic.to_string(),
            parts: Parts::default(),
            layouts: Vec::new(),
            last_layout: 0,
            messages: Vec::new(),
            values: Vec::new(),
            seen: [false; N],
            extra: BTreeSet::new(),
            zero_stamps: 0,
            without_velocity: 0,
            received: 0,
        }
    }

    /// Messages taken (on the topic, whichever joints they carry).
    pub(super) fn received(&self) -> usize {
        self.received
    }

    /// The layout of the names just decoded from `bytes`.
    fn layout(&mut self, bytes: &[u8]) -> usize {
        let p = &self.parts;
        let same = |l: &Layout| {
            l.names.len() == p.names.len()
                && l.names
                    .iter()
                    .enumerate()
                    .all(|(i, n)| n.as_str() == p.name(bytes, i))
        };
        if self.layouts.get(self.last_layout).is_some_and(same) {
            return self.last_layout;
        }
        if let Some(i) = self.layouts.iter().position(same) {
            self.last_layout = i;
            return i;
        }
        let names: Vec<String> = (0..p.names.len())
            .map(|i| p.name(bytes, i).to_string())
            .collect();
        let mut carried = Vec::new();
        for (slot, name) in names.iter().enumerate() {
            match self.joints.iter().position(|j| j == name) {
                Some(j) => {
                    self.seen[j] = true;
                    carried.push((slot, j));
                }
                None => {
                    self.extra.insert(name.clone());
                }
            }
        }
        self.layouts.push(Layout { names, carried });
        self.last_layout = self.layouts.len() - 1;
        self.last_layout
    }

    /// Takes one serialized message, received at `received_ns`, at `place`.
    pub(super) fn push(
        &mut self,
        received_ns: i64,
        bytes: &[u8],
        place: Place,
    ) -> Result<(), BagError> {
        let bad = |message: String| BagError::Message {
            file: self.file.clone(),
            place: place.to_string(),
            message,
        };
        self.received += 1;
        self.parts.decode(bytes).map_err(bad)?;
        let p = &self.parts;
        let n = p.names.len();
        for (what, len) in [
            ("position", p.position.len()),
            ("velocity", p.velocity.len()),
            ("effort", p.effort.len()),
        ] {
            if len != n && !(len == 0 && what != "position") {
                return Err(bad(format!("{n} names but {len} values in `{what}`")));
            }
        }
        let stamp = if p.stamp_ns == 0 {
            self.zero_stamps += 1;
            received_ns
        } else {
            p.stamp_ns
        };
        let layout = self.layout(bytes);
        let p = &self.parts;
        let carried = &self.layouts[layout].carried;
        if carried.is_empty() {
            return Ok(());
        }
        if p.effort.is_empty() {
            return Err(BagError::NoEffort {
                file: self.file.clone(),
                place: place.to_string(),
            });
        }
        if p.velocity.is_empty() {
            self.without_velocity += 1;
        }
        let at = self.values.len();
        for &(slot, _) in carried {
            self.values.push(p.position[slot]);
            self.values
                .push(p.velocity.get(slot).copied().unwrap_or(f64::NAN));
            self.values.push(p.effort[slot]);
        }
        self.messages.push(Message {
            stamp,
            arrival: self.messages.len(),
            place,
            layout,
            at,
        });
        Ok(())
    }

    /// The samples, with warnings, and the first and last stamp (ns since
    /// the epoch).
    pub(super) fn finish(
        mut self,
        warnings: &mut Vec<Warning>,
    ) -> Result<(Measured<N>, i64, i64), BagError> {
        let (file, topic, joints) = (self.file.as_str(), self.topic.as_str(), self.joints);
        let note = |message: String| Warning::Imported { message };
        if self.zero_stamps > 0 {
            warnings.push(note(format!(
                "{file}: {} of {} messages on `{topic}` have a zero header.stamp: their receive time is used",
                self.zero_stamps,
                self.messages.len()
            )));
        }
        if self.seen.iter().any(|s| !s) {
            let missing: Vec<&str> = (0..N)
                .filter(|&i| !self.seen[i])
                .map(|i| joints[i])
                .collect();
            let mut names: BTreeSet<&str> = self.extra.iter().map(String::as_str).collect();
            names.extend((0..N).filter(|&i| self.seen[i]).map(|i| joints[i]));
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
        if !self.extra.is_empty() {
            warnings.push(note(format!(
                "{file}: joints on `{topic}` that the robot does not have, ignored: {}",
                self.extra.iter().cloned().collect::<Vec<_>>().join(", ")
            )));
        }
        let qd_measured = self.without_velocity == 0;
        if !qd_measured {
            warnings.push(note(format!(
                "{file}: {} messages on `{topic}` carry no velocities: velocities are differentiated from the positions",
                self.without_velocity
            )));
        }
        // By stamp, then as received.
        self.messages.sort_unstable_by_key(|m| (m.stamp, m.arrival));
        let msgs = &self.messages;
        let mut out = Measured::<N> {
            qd_measured,
            joints: joints.iter().map(|j| j.to_string()).collect(),
            ..Default::default()
        };
        out.t.reserve(msgs.len());
        out.q.reserve(msgs.len());
        out.tau.reserve(msgs.len());
        let first = msgs.first().map_or(0, |m| m.stamp);
        let last = msgs.last().map_or(0, |m| m.stamp);
        let quantities: [&'static str; 3] = ["position", "velocity", "effort"];
        let mut g = 0;
        while g < msgs.len() {
            let stamp = msgs[g].stamp;
            let mut end = g;
            while end < msgs.len() && msgs[end].stamp == stamp {
                end += 1;
            }
            // One sample from the messages of this stamp: q, qd, tau per joint.
            let mut cells = [[None::<f64>; 3]; N];
            for m in &msgs[g..end] {
                for (k, &(_, j)) in self.layouts[m.layout].carried.iter().enumerate() {
                    for (quantity, cell) in cells[j].iter_mut().enumerate() {
                        if quantity == 1 && !qd_measured {
                            continue;
                        }
                        let v = self.values[m.at + 3 * k + quantity];
                        if !v.is_finite() {
                            return Err(BagError::NotFinite {
                                file: file.to_string(),
                                place: m.place.to_string(),
                                quantity: quantities[quantity],
                                joint: joints[j].to_string(),
                                value: v,
                            });
                        }
                        match cell {
                            Some(old) if *old != v => {
                                return Err(BagError::Conflict {
                                    file: file.to_string(),
                                    stamp: stamp as f64 * 1e-9,
                                    joint: joints[j].to_string(),
                                })
                            }
                            _ => *cell = Some(v),
                        }
                    }
                }
            }
            let mut v = [SVector::<f64, N>::zeros(); 3];
            for (j, joint) in cells.iter().enumerate() {
                for quantity in 0..3 {
                    if quantity == 1 && !qd_measured {
                        continue;
                    }
                    v[quantity][j] = joint[quantity].ok_or_else(|| BagError::Unmerged {
                        file: file.to_string(),
                        stamp: stamp as f64 * 1e-9,
                        joint: joints[j].to_string(),
                        quantity: quantities[quantity],
                    })?;
                }
            }
            // Exact integer nanoseconds from the first stamp, then seconds.
            out.t.push((stamp - first) as f64 / 1e9);
            out.q.push(v[0]);
            if qd_measured {
                out.qd.push(v[1]);
            }
            out.tau.push(v[2]);
            g = end;
        }
        if !qd_measured && out.len() > 1 {
            out.qd = differentiate(&out.t, &out.q);
        }
        Ok((out, first, last))
    }
}
