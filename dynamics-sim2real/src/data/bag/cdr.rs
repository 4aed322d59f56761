//! A `sensor_msgs/msg/JointState` decoded from its CDR serialization as
//! ROS 2 writes it: a 4-byte encapsulation header (`00 01` little-endian,
//! `00 00` big-endian; the XCDR2 plain forms `00 07` / `00 06` alike for
//! this message of no optional members), then the fields in order, each
//! primitive aligned to its size counted from the end of the header:
//!
//! ```text
//! header.stamp.sec int32, header.stamp.nanosec uint32, header.frame_id string,
//! name string[], position float64[], velocity float64[], effort float64[]
//! ```
//!
//! A string is a uint32 length (its terminating NUL included) and its bytes;
//! a sequence a uint32 count and its elements. Every count is checked against
//! the bytes left before anything is allocated, so that a hostile count
//! costs no memory.

/// One decoded message.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct JointState {
    /// `header.stamp` in nanoseconds since the epoch.
    pub stamp_ns: i64,
    /// The joints' names.
    pub name: Vec<String>,
    /// Positions (empty or one per name).
    pub position: Vec<f64>,
    /// Velocities (empty or one per name).
    pub velocity: Vec<f64>,
    /// Efforts (empty or one per name).
    pub effort: Vec<f64>,
}

/// A reader over the bytes after the encapsulation header.
struct Cursor<'a> {
    bytes: &'a [u8],
    at: usize,
    little: bool,
}

impl<'a> Cursor<'a> {
    fn align(&mut self, n: usize) -> Result<(), String> {
        let pad = (n - self.at % n) % n;
        self.take(pad).map(|_| ())
    }

    fn take(&mut self, n: usize) -> Result<&'a [u8], String> {
        let end = self
            .at
            .checked_add(n)
            .filter(|&e| e <= self.bytes.len())
            .ok_or_else(|| {
                format!(
                    "cut short: {n} bytes needed at byte {} of {}",
                    self.at + 4,
                    self.bytes.len() + 4
                )
            })?;
        let out = &self.bytes[self.at..end];
        self.at = end;
        Ok(out)
    }

    fn u32(&mut self) -> Result<u32, String> {
        self.align(4)?;
        let b: [u8; 4] = self.take(4)?.try_into().map_err(|_| "cut short")?;
        Ok(if self.little {
            u32::from_le_bytes(b)
        } else {
            u32::from_be_bytes(b)
        })
    }

    fn f64(&mut self) -> Result<f64, String> {
        let b: [u8; 8] = self.take(8)?.try_into().map_err(|_| "cut short")?;
        Ok(if self.little {
            f64::from_le_bytes(b)
        } else {
            f64::from_be_bytes(b)
        })
    }

    /// A count of elements of `size` bytes each, refused if they cannot fit
    /// in the bytes left.
    fn count(&mut self, size: usize, what: &str) -> Result<usize, String> {
        self.align(4)?;
        let at = self.at + 4;
        let n = self.u32()? as usize;
        let left = self.bytes.len() - self.at;
        if n.saturating_mul(size) > left {
            return Err(format!(
                "{what}: {n} elements at byte {at}, only {left} bytes follow"
            ));
        }
        Ok(n)
    }

    /// A string's bytes (without its terminating NUL), checked to be UTF-8.
    fn string(&mut self, what: &str) -> Result<&'a str, String> {
        let n = self.count(1, what)?;
        let bytes = self.take(n)?;
        let text = bytes.strip_suffix(&[0]).unwrap_or(bytes);
        std::str::from_utf8(text).map_err(|_| format!("{what}: not UTF-8 text"))
    }

    /// A sequence of doubles, appended to `out`.
    fn doubles(&mut self, what: &str, out: &mut Vec<f64>) -> Result<(), String> {
        let n = self.count(8, what)?;
        if n > 0 {
            self.align(8)?;
        }
        // Alignment may have eaten into the bytes counted above.
        if n.saturating_mul(8) > self.bytes.len() - self.at {
            return Err(format!("{what}: {n} values do not fit in the message"));
        }
        out.reserve(n);
        for _ in 0..n {
            out.push(self.f64()?);
        }
        Ok(())
    }
}

/// A message decoded into buffers reused from one message to the next:
/// the names as byte ranges of the message ([`Parts::name`]).
#[derive(Debug, Default)]
pub(crate) struct Parts {
    pub(crate) stamp_ns: i64,
    pub(crate) names: Vec<(usize, usize)>,
    pub(crate) position: Vec<f64>,
    pub(crate) velocity: Vec<f64>,
    pub(crate) effort: Vec<f64>,
}

impl Parts {
    /// Name `i` of the message `bytes` these parts were decoded from.
    pub(crate) fn name<'b>(&self, bytes: &'b [u8], i: usize) -> &'b str {
        let (a, b) = self.names[i];
        std::str::from_utf8(&bytes[a..b]).unwrap_or("")
    }

    /// Decodes `bytes` into these buffers (cleared first).
    pub(crate) fn decode(&mut self, bytes: &[u8]) -> Result<(), String> {
        self.names.clear();
        self.position.clear();
        self.velocity.clear();
        self.effort.clear();
        let (head, body) = bytes
            .split_first_chunk::<4>()
            .ok_or("shorter than the 4-byte CDR encapsulation header")?;
        let little = match (head[0], head[1]) {
            (0, 1) | (0, 7) | (0, 3) => true,
            (0, 0) | (0, 6) | (0, 2) => false,
            (a, b) => {
                return Err(format!(
                    "encapsulation {a:02x} {b:02x} is not a CDR one (00 00 or 00 01)"
                ))
            }
        };
        let mut c = Cursor {
            bytes: body,
            at: 0,
            little,
        };
        let sec = c.u32()? as i32;
        let nanosec = c.u32()?;
        let _frame = c.string("header.frame_id")?;
        let n = c.count(4, "name")?;
        self.names.reserve(n);
        for _ in 0..n {
            let name = c.string("a name")?;
            let start = name.as_ptr() as usize - bytes.as_ptr() as usize;
            self.names.push((start, start + name.len()));
        }
        c.doubles("position", &mut self.position)?;
        c.doubles("velocity", &mut self.velocity)?;
        c.doubles("effort", &mut self.effort)?;
        self.stamp_ns = sec as i64 * 1_000_000_000 + nanosec as i64;
        Ok(())
    }
}

/// Decodes one CDR-serialized `JointState`; the error says what is wrong
/// and at which byte (the caller names the file and the message).
///
/// ```
/// use dynamics_sim2real::data::bag::cdr::decode_joint_state;
/// // Little-endian: stamp 3 s + 5 ns, frame "", names ["a"], position [1.5],
/// // no velocities, effort [2.0].
/// let mut b = vec![0, 1, 0, 0];
/// b.extend(3i32.to_le_bytes());
/// b.extend(5u32.to_le_bytes());
/// b.extend(1u32.to_le_bytes()); b.push(0); b.extend([0; 3]); // "" then padding
/// b.extend(1u32.to_le_bytes());
/// b.extend(2u32.to_le_bytes()); b.extend(b"a\0"); b.extend([0; 2]);
/// b.extend(1u32.to_le_bytes()); b.extend(1.5f64.to_le_bytes()); // at body offset 32: aligned
/// b.extend(0u32.to_le_bytes());
/// b.extend(1u32.to_le_bytes()); b.extend(2.0f64.to_le_bytes()); // at 48: aligned
/// let m = decode_joint_state(&b).unwrap();
/// assert_eq!(m.stamp_ns, 3_000_000_005);
/// assert_eq!((m.name, m.position, m.velocity, m.effort), (vec!["a".to_string()], vec![1.5], vec![], vec![2.0]));
/// assert!(decode_joint_state(&b[..30]).is_err());
/// ```
pub fn decode_joint_state(bytes: &[u8]) -> Result<JointState, String> {
    let mut parts = Parts::default();
    parts.decode(bytes)?;
    Ok(JointState {
        stamp_ns: parts.stamp_ns,
        name: (0..parts.names.len())
            .map(|i| parts.name(bytes, i).to_string())
            .collect(),
        position: parts.position,
        velocity: parts.velocity,
        effort: parts.effort,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A message serialized by hand, per the CDR rules, in either byte order.
    fn message(little: bool) -> Vec<u8> {
        let u32b = |v: u32| {
            if little {
                v.to_le_bytes()
            } else {
                v.to_be_bytes()
            }
        };
        let f64b = |v: f64| {
            if little {
                v.to_le_bytes()
            } else {
                v.to_be_bytes()
            }
        };
        let mut b = vec![0, u8::from(little), 0, 0];
        b.extend(u32b(7)); // sec
        b.extend(u32b(999_999_999));
        b.extend(u32b(5));
        b.extend(b"base\0"); // 5 bytes: at 17
        b.extend([0; 3]); // to 20
        b.extend(u32b(2));
        b.extend(u32b(3));
        b.extend(b"j1\0");
        b.push(0); // 32
        b.extend(u32b(3));
        b.extend(b"j2\0"); // 39
        b.push(0); // 40
        for values in [&[1.0, -2.0][..], &[][..], &[0.5, 4.0]] {
            b.extend(u32b(values.len() as u32));
            if !values.is_empty() && (b.len() - 4) % 8 != 0 {
                b.extend([0; 4]);
            }
            for &v in values {
                b.extend(f64b(v));
            }
        }
        b
    }

    #[test]
    fn both_byte_orders_decode_the_same() {
        for little in [true, false] {
            let m = decode_joint_state(&message(little)).unwrap();
            assert_eq!(m.stamp_ns, 7_999_999_999);
            assert_eq!(m.name, ["j1", "j2"]);
            assert_eq!(m.position, [1.0, -2.0]);
            assert!(m.velocity.is_empty());
            assert_eq!(m.effort, [0.5, 4.0]);
        }
    }

    #[test]
    fn hostile_counts_and_cuts_are_refused_without_allocating() {
        let mut b = message(true);
        // The name count says 2^32 - 1 strings.
        b[24..28].copy_from_slice(&u32::MAX.to_le_bytes());
        let e = decode_joint_state(&b).unwrap_err();
        assert!(e.starts_with("name: 4294967295 elements at byte 24"), "{e}");
        let whole = message(true);
        for cut in 0..whole.len() {
            assert!(decode_joint_state(&whole[..cut]).is_err(), "cut at {cut}");
        }
        assert!(decode_joint_state(&[1, 0, 0, 0, 0]).is_err());
    }
}
