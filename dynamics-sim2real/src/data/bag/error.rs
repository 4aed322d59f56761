//! What can be wrong with a rosbag2 bag (or a Parquet file): every variant
//! names the file and the place in it (byte offset, message, topic, joint).

use thiserror::Error;

use crate::data::DataError;

/// What is wrong with a bag or a Parquet file.
///
/// ```
/// use dynamics_sim2real::data::bag::BagError;
/// let e = BagError::MissingJoints {
///     file: "run.mcap".into(),
///     topic: "/joint_states".into(),
///     missing: "elbow".into(),
///     names: "shoulder, wrist".into(),
/// };
/// assert_eq!(
///     e.to_string(),
///     "run.mcap: topic `/joint_states` has no joint `elbow` of this robot (its messages name: shoulder, wrist)"
/// );
/// ```
#[derive(Debug, Error)]
pub enum BagError {
    /// The file or directory could not be read.
    #[error("{file}: {source}")]
    Io {
        /// The file.
        file: String,
        /// The cause.
        source: std::io::Error,
    },
    /// Not a bag this reader knows (or a directory without one).
    #[error("{file}: {message}")]
    NotABag {
        /// The file or directory.
        file: String,
        /// What was found instead.
        message: String,
    },
    /// The program was built without the reader of this format.
    #[error("{file}: this build reads no {format} files (cargo feature `{feature}` of dynamics-sim2real)")]
    NotBuilt {
        /// The file.
        file: String,
        /// `MCAP`, `sqlite3 bag` or `Parquet`.
        format: &'static str,
        /// The cargo feature that adds it.
        feature: &'static str,
    },
    /// The MCAP container is damaged or cut short at a byte offset.
    #[error("{file}: at byte {offset}: {message}")]
    Mcap {
        /// The file.
        file: String,
        /// Where the broken record starts.
        offset: u64,
        /// What is wrong.
        message: String,
    },
    /// The sqlite3 database of a bag cannot be read.
    #[error("{file}: {message}")]
    Sqlite {
        /// The file.
        file: String,
        /// What SQLite or the layout check said.
        message: String,
    },
    /// The Parquet file cannot be read (or written).
    #[error("{file}: {message}")]
    Parquet {
        /// The file.
        file: String,
        /// What is wrong.
        message: String,
    },
    /// The topic asked for is not in the bag.
    #[error("{file}: no topic `{topic}` (the bag has: {available}); choose one with --topic")]
    NoTopic {
        /// The file.
        file: String,
        /// The topic asked for.
        topic: String,
        /// The topics there are, each with its type.
        available: String,
    },
    /// The topic carries messages of another type than JointState.
    #[error("{file}: topic `{topic}` carries `{found}` messages (encoded `{encoding}`), not sensor_msgs/msg/JointState in CDR")]
    WrongType {
        /// The file.
        file: String,
        /// The topic.
        topic: String,
        /// The type found.
        found: String,
        /// Its serialization (`cdr` is read).
        encoding: String,
    },
    /// A message cannot be decoded or is inconsistent.
    #[error("{file}: {place}: {message}")]
    Message {
        /// The file.
        file: String,
        /// Which message (`message 12 at byte 3456`, `row id 12`).
        place: String,
        /// What is wrong.
        message: String,
    },
    /// A joint of the robot is in no message.
    #[error("{file}: topic `{topic}` has no joint `{missing}` of this robot (its messages name: {names})")]
    MissingJoints {
        /// The file.
        file: String,
        /// The topic.
        topic: String,
        /// The robot's joints missing, comma-separated.
        missing: String,
        /// The names the messages carry.
        names: String,
    },
    /// The messages carry no efforts.
    #[error("{file}: {place}: no efforts (the `effort` array is empty); the diagnosis needs the joints' efforts")]
    NoEffort {
        /// The file.
        file: String,
        /// The first message without them.
        place: String,
    },
    /// Messages that carry only some joints and could not be merged into samples.
    #[error("{file}: at stamp {stamp} s, no {quantity} of joint `{joint}`: messages carrying only some joints are merged by their stamp, and no message of that stamp carries it")]
    Unmerged {
        /// The file.
        file: String,
        /// The stamp (s since the epoch).
        stamp: f64,
        /// The joint missing there.
        joint: String,
        /// `position`, `velocity` or `effort`.
        quantity: &'static str,
    },
    /// Two messages of one stamp disagree about a joint.
    #[error("{file}: at stamp {stamp} s, two messages give joint `{joint}` different values")]
    Conflict {
        /// The file.
        file: String,
        /// The stamp (s since the epoch).
        stamp: f64,
        /// The joint.
        joint: String,
    },
    /// A value is not a finite number.
    #[error("{file}: {place}: {quantity} of joint `{joint}` is {value}, not a finite number")]
    NotFinite {
        /// The file.
        file: String,
        /// Which message or row.
        place: String,
        /// `position`, `velocity`, `effort` or `t`.
        quantity: &'static str,
        /// The joint.
        joint: String,
        /// The value.
        value: f64,
    },
    /// Too few samples.
    #[error("{file}: {rows} samples on topic `{topic}`; at least {min} are needed")]
    TooFewSamples {
        /// The file.
        file: String,
        /// The topic (or `rows` for Parquet).
        topic: String,
        /// Samples read.
        rows: usize,
        /// The least number.
        min: usize,
    },
    /// Preparing the samples (or the Parquet's columns) failed as for a CSV.
    #[error(transparent)]
    Data(#[from] DataError),
}
