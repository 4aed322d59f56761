//! The messages of one topic of a rosbag2 sqlite3 file (`.db3`), through
//! `rusqlite` (SQLite bundled, opened read-only): the `topics` table
//! (`id`, `name`, `type`, `serialization_format`) and the `messages` table
//! (`topic_id`, `timestamp` in ns, `data` the CDR bytes).

use std::path::Path;

use rusqlite::{Connection, OpenFlags};

use super::merge::Collector;
use super::{BagError, Place, JOINT_STATE};

const MAGIC: &[u8] = b"SQLite format 3\0";

/// Whether `bytes` start like an SQLite database.
pub(super) fn is_sqlite(bytes: &[u8]) -> bool {
    bytes.starts_with(MAGIC)
}

/// The messages on `topic` of the bag database at `path`, into `out`.
pub(super) fn read<const N: usize>(
    path: &Path,
    file: &str,
    topic: &str,
    out: &mut Collector<'_, N>,
) -> Result<Vec<String>, BagError> {
    let err = |e: rusqlite::Error| BagError::Sqlite {
        file: file.to_string(),
        message: e.to_string(),
    };
    let db = Connection::open_with_flags(
        path,
        OpenFlags::SQLITE_OPEN_READ_ONLY | OpenFlags::SQLITE_OPEN_NO_MUTEX,
    )
    .map_err(err)?;
    let mut topics = db
        .prepare("SELECT id, name, type, serialization_format FROM topics")
        .map_err(|e| BagError::Sqlite {
            file: file.to_string(),
            message: format!("not a rosbag2 database (no table `topics`: {e})"),
        })?;
    let rows = topics
        .query_map([], |r| {
            Ok((
                r.get::<_, i64>(0)?,
                r.get::<_, String>(1)?,
                r.get::<_, String>(2)?,
                r.get::<_, String>(3)?,
            ))
        })
        .map_err(err)?
        .collect::<Result<Vec<_>, _>>()
        .map_err(err)?;
    let Some((id, _, ty, format)) = rows.iter().find(|r| r.1 == topic) else {
        let mut available: Vec<String> =
            rows.iter().map(|r| format!("{} ({})", r.1, r.2)).collect();
        available.sort();
        return Err(BagError::NoTopic {
            file: file.to_string(),
            topic: topic.to_string(),
            available: if available.is_empty() {
                "no topics".into()
            } else {
                available.join(", ")
            },
        });
    };
    if ty != JOINT_STATE || format != "cdr" {
        return Err(BagError::WrongType {
            file: file.to_string(),
            topic: topic.to_string(),
            found: ty.clone(),
            encoding: format.clone(),
        });
    }
    let mut query = db
        .prepare(
            "SELECT id, timestamp, data FROM messages WHERE topic_id = ?1 ORDER BY timestamp, id",
        )
        .map_err(err)?;
    let mut rows = query.query([id]).map_err(err)?;
    while let Some(row) = rows.next().map_err(err)? {
        let place = Place::Row(row.get::<_, i64>(0).map_err(err)?);
        let received = row.get::<_, i64>(1).map_err(err)?;
        let data = row
            .get_ref(2)
            .and_then(|v| v.as_blob().map_err(Into::into))
            .map_err(err)?;
        out.push(received, data, place)?;
    }
    Ok(Vec::new())
}
