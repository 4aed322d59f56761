//! The messages of one topic of an MCAP file, through the `mcap` crate's
//! record parser and chunk decompressor (zstd, lz4). The file's records are
//! walked here, from the magic bytes on (each an opcode and a 64-bit
//! length), so that a damaged or cut file is named with the byte offset of
//! the record that breaks; the messages before it are kept, with a warning.
//! A chunk is decompressed by the crate's sans-io reader with a bound on
//! the length of every record inside it (its `ChunkReader` has none: a
//! hostile length there asked for exabytes).

use std::collections::HashMap;

use mcap::read::parse_record;
use mcap::records::Record;
use mcap::sans_io::{LinearReadEvent, LinearReader, LinearReaderOptions};

use super::merge::Collector;
use super::{BagError, Place, JOINT_STATE};

const MAGIC: &[u8] = b"\x89MCAP0\r\n";

/// A chunk is decompressed only if it claims at most this many bytes
/// uncompressed, and at most [`MAX_RATIO`] times its compressed size plus
/// 64 KiB: a hostile header costs no more memory than that.
pub const MAX_CHUNK: u64 = 1 << 30;
/// See [`MAX_CHUNK`].
pub const MAX_RATIO: u64 = 1024;

/// Whether every length-prefixed field of a record this reader parses
/// (schema, channel, chunk header) lies inside its body: the crate's record
/// parser allocates a field's declared length before reading it, so a
/// hostile length must be refused first. Other records are not parsed.
fn lengths_fit(op: u8, body: &[u8]) -> bool {
    let u32_at = |at: usize| -> Option<usize> {
        let b: [u8; 4] = body.get(at..at.checked_add(4)?)?.try_into().ok()?;
        Some(u32::from_le_bytes(b) as usize)
    };
    // Skips `count` length-prefixed fields from `at`; the end, if inside.
    let fields = |mut at: usize, count: usize| -> Option<usize> {
        for _ in 0..count {
            let len = u32_at(at)?;
            at = at.checked_add(4)?.checked_add(len)?;
            if at > body.len() {
                return None;
            }
        }
        Some(at)
    };
    match op {
        // Schema: id u16, name, encoding, data.
        0x03 => fields(2, 3).is_some(),
        // Channel: id u16, schema id u16, topic, encoding, then a map of
        // string pairs whose byte length comes first.
        0x04 => (|| {
            let at = fields(4, 2)?;
            let map = u32_at(at)?;
            let end = at.checked_add(4)?.checked_add(map)?;
            let mut k = at + 4;
            while k < end {
                k = fields(k, 2)?;
            }
            (k == end && end <= body.len()).then_some(())
        })()
        .is_some(),
        // Chunk: three u64, a u32, then the compression string.
        0x06 => fields(28, 1).is_some(),
        _ => true,
    }
}

/// Whether `bytes` start like an MCAP file.
pub(super) fn is_mcap(bytes: &[u8]) -> bool {
    bytes.starts_with(MAGIC)
}

/// A channel: its topic, and its schema's name and encoding.
struct Channel {
    topic: String,
    schema_id: u16,
    encoding: String,
}

/// What the walk has seen.
struct Walk<'c, 'j, const N: usize> {
    schemas: HashMap<u16, (String, String)>,
    channels: HashMap<u16, Channel>,
    out: &'c mut Collector<'j, N>,
    /// Messages on the topic.
    taken: usize,
    /// Channels on the topic, checked once.
    wanted: HashMap<u16, bool>,
}

impl<const N: usize> Walk<'_, '_, N> {
    /// Handles one record (top-level or from a chunk) at `place`.
    fn record(
        &mut self,
        record: Record<'_>,
        place: Place,
        file: &str,
        topic: &str,
    ) -> Result<(), BagError> {
        match record {
            Record::Schema { header, .. } => {
                self.schemas
                    .insert(header.id, (header.name.clone(), header.encoding.clone()));
            }
            Record::Channel(c) => {
                self.channels.insert(
                    c.id,
                    Channel {
                        topic: c.topic.clone(),
                        schema_id: c.schema_id,
                        encoding: c.message_encoding.clone(),
                    },
                );
            }
            Record::Message { header, data } => {
                let wanted = match self.wanted.get(&header.channel_id) {
                    Some(&w) => w,
                    None => {
                        let Some(c) = self.channels.get(&header.channel_id) else {
                            return Err(BagError::Message {
                                file: file.to_string(),
                                place: place.to_string(),
                                message: format!("unknown channel {}", header.channel_id),
                            });
                        };
                        let w = c.topic == topic;
                        if w {
                            let (name, _) = self
                                .schemas
                                .get(&c.schema_id)
                                .cloned()
                                .unwrap_or_else(|| ("no schema".into(), String::new()));
                            if name != JOINT_STATE || c.encoding != "cdr" {
                                return Err(BagError::WrongType {
                                    file: file.to_string(),
                                    topic: topic.to_string(),
                                    found: name,
                                    encoding: c.encoding.clone(),
                                });
                            }
                        }
                        self.wanted.insert(header.channel_id, w);
                        w
                    }
                };
                if wanted {
                    self.taken += 1;
                    self.out.push(header.log_time as i64, &data, place)?;
                }
            }
            _ => {}
        }
        Ok(())
    }

    /// The topics seen, each with its type, for an error.
    fn topics(&self) -> String {
        let mut t: Vec<String> = self
            .channels
            .values()
            .map(|c| {
                let ty = self
                    .schemas
                    .get(&c.schema_id)
                    .map(|s| s.0.as_str())
                    .unwrap_or("?");
                format!("{} ({ty})", c.topic)
            })
            .collect();
        t.sort();
        t.dedup();
        if t.is_empty() {
            "no topics".into()
        } else {
            t.join(", ")
        }
    }
}

/// The messages on `topic` of the MCAP file `bytes`, into `out`; the
/// warnings (a file cut short).
pub(super) fn read<const N: usize>(
    bytes: &[u8],
    file: &str,
    topic: &str,
    out: &mut Collector<'_, N>,
) -> Result<Vec<String>, BagError> {
    if !is_mcap(bytes) {
        return Err(BagError::Mcap {
            file: file.to_string(),
            offset: 0,
            message: "no MCAP magic bytes".into(),
        });
    }
    let mut walk = Walk {
        schemas: HashMap::new(),
        channels: HashMap::new(),
        out,
        taken: 0,
        wanted: HashMap::new(),
    };
    let mut warnings = Vec::new();
    let mut at = MAGIC.len();
    let broken = |offset: usize, message: String| BagError::Mcap {
        file: file.to_string(),
        offset: offset as u64,
        message,
    };
    let mut ended = false;
    while at < bytes.len() {
        let rest = &bytes[at..];
        if rest == MAGIC {
            ended = true;
            break;
        }
        let step = (|| -> Result<usize, BagError> {
            if rest.len() < 9 {
                return Err(broken(
                    at,
                    format!(
                        "the file ends inside a record's opcode and length ({} bytes left)",
                        rest.len()
                    ),
                ));
            }
            let op = rest[0];
            let mut len8 = [0u8; 8];
            len8.copy_from_slice(&rest[1..9]);
            let len = u64::from_le_bytes(len8);
            let end = usize::try_from(len)
                .ok()
                .and_then(|l| l.checked_add(9))
                .filter(|&e| e <= rest.len())
                .ok_or_else(|| {
                    broken(
                        at,
                        format!(
                            "a record (opcode {op:#04x}) of {len} bytes, but the file ends {} bytes later (cut short?)",
                            rest.len() - 9
                        ),
                    )
                })?;
            let body = &rest[9..end];
            if !matches!(op, 0x03..=0x06) {
                return Ok(end);
            }
            if !lengths_fit(op, body) {
                return Err(broken(
                    at,
                    format!("a record (opcode {op:#04x}) whose fields run past its end"),
                ));
            }
            let record = parse_record(op, body).map_err(|e| broken(at, e.to_string()))?;
            if let Record::Chunk { header, .. } = record {
                let limit =
                    (header.compressed_size.saturating_mul(MAX_RATIO) + (64 << 10)).min(MAX_CHUNK);
                if header.uncompressed_size > limit {
                    return Err(broken(
                        at,
                        format!(
                            "a chunk of {} bytes claims {} bytes uncompressed (more than the {limit} read)",
                            header.compressed_size, header.uncompressed_size
                        ),
                    ));
                }
                // The chunk record alone through the sans-io reader, which
                // decompresses it and bounds every record inside by `limit`.
                let mut reader = LinearReader::new_with_options(
                    LinearReaderOptions::default()
                        .with_skip_start_magic(true)
                        .with_skip_end_magic(true)
                        .with_record_length_limit(limit as usize),
                );
                let mut src = &rest[..end];
                let mut index = 0;
                while let Some(event) = reader.next_event() {
                    match event.map_err(|e| broken(at, format!("in the chunk: {e}")))? {
                        LinearReadEvent::ReadRequest(need) => {
                            let n = need.min(src.len());
                            reader.insert(n).copy_from_slice(&src[..n]);
                            reader.notify_read(n);
                            src = &src[n..];
                        }
                        LinearReadEvent::Record { data, opcode } => {
                            if !matches!(opcode, 0x03..=0x05) {
                                index += 1;
                                continue;
                            }
                            if !lengths_fit(opcode, data) {
                                return Err(broken(
                                    at,
                                    format!("in the chunk: a record (opcode {opcode:#04x}) whose fields run past its end"),
                                ));
                            }
                            let inner = parse_record(opcode, data)
                                .map_err(|e| broken(at, format!("in the chunk: {e}")))?;
                            let place = Place::InChunk {
                                chunk: at as u64,
                                index,
                            };
                            walk.record(inner, place, file, topic)?;
                            index += 1;
                        }
                    }
                }
            } else {
                walk.record(record, Place::Record(at as u64), file, topic)?;
            }
            Ok(end)
        })();
        match step {
            Ok(n) => at += n,
            Err(e @ BagError::Mcap { .. }) => {
                if walk.taken == 0 {
                    return Err(e);
                }
                warnings.push(format!(
                    "{e}: the {} messages of `{topic}` before it are read, nothing after",
                    walk.taken
                ));
                ended = true;
                break;
            }
            Err(e) => return Err(e),
        }
    }
    if !ended {
        let e = broken(
            at,
            "the file ends without its closing magic bytes (cut short?)".into(),
        );
        if walk.taken == 0 {
            return Err(e);
        }
        warnings.push(e.to_string());
    }
    if !walk.channels.values().any(|c| c.topic == topic) {
        return Err(BagError::NoTopic {
            file: file.to_string(),
            topic: topic.to_string(),
            available: walk.topics(),
        });
    }
    Ok(warnings)
}
