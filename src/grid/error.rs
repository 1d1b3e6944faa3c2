//! Errors from reading and writing occupancy maps.
//!
//! Every message says what was wrong and, where it can, what to do about it: a map loader is
//! the first thing a new user touches, and "invalid data" teaches nothing.

use std::fmt;

/// Why a map could not be read or written.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum MapError {
    /// The bytes are not a PGM, a PNG or a ROS `map.yaml`.
    UnknownFormat {
        /// A short, printable rendering of the first bytes.
        start: String,
    },
    /// A PGM header is malformed.
    BadPgmHeader {
        /// What was wrong.
        message: String,
    },
    /// The file ends before the pixel data the header promises.
    Truncated {
        /// `"PGM"` or `"PNG"`.
        format: &'static str,
        /// Samples (or bytes) the header promises.
        expected: usize,
        /// Samples (or bytes) present.
        found: usize,
    },
    /// A sample is larger than the PGM's declared maximum value.
    SampleOutOfRange {
        /// Index of the sample, row-major from the top-left.
        index: usize,
        /// Its value.
        value: u32,
        /// The declared maximum.
        maxval: u32,
    },
    /// Width or height is zero.
    Empty {
        /// Declared width.
        width: u64,
        /// Declared height.
        height: u64,
    },
    /// The map has more cells than the configured limit.
    TooLarge {
        /// Declared width.
        width: u64,
        /// Declared height.
        height: u64,
        /// The cell limit in force.
        limit: usize,
    },
    /// The PNG decoder rejected the data.
    Png {
        /// The decoder's description.
        message: String,
    },
    /// A `map.yaml` could not be understood.
    Yaml {
        /// 1-based line number, 0 where the problem is not on one line.
        line: usize,
        /// What was wrong.
        message: String,
    },
    /// Text that must be UTF-8 is not.
    NotUtf8 {
        /// What was being read.
        what: String,
        /// Offset of the first bad byte.
        offset: usize,
    },
    /// A `map.yaml` names an image that does not exist.
    MissingImage {
        /// The image path as resolved.
        path: String,
        /// The YAML file that named it.
        yaml: String,
    },
    /// A file could not be read or written.
    Io {
        /// The path involved.
        path: String,
        /// The operating system's message.
        message: String,
    },
    /// A classification threshold is not a usable number.
    BadThreshold {
        /// Which threshold.
        name: &'static str,
        /// Why it was refused.
        message: String,
    },
    /// Cells handed over from memory (an array of pixels or of occupancy values, as the Python
    /// package passes numpy arrays) are not a map.
    BadCells {
        /// Why they were refused.
        message: String,
    },
}

impl fmt::Display for MapError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            MapError::UnknownFormat { start } => write!(
                f,
                "not an occupancy map: the data starts with {start}; expected a PGM (P2 or P5), \
                 a PNG, or a ROS map.yaml together with its image"
            ),
            MapError::BadPgmHeader { message } => write!(f, "malformed PGM header: {message}"),
            MapError::Truncated { format, expected, found } => write!(
                f,
                "truncated {format}: the header promises {expected} samples but the file holds \
                 only {found}; the file was probably cut off while copying"
            ),
            MapError::SampleOutOfRange { index, value, maxval } => {
                write!(f, "PGM sample {index} is {value}, above the header's maximum value {maxval}")
            }
            MapError::Empty { width, height } => {
                write!(f, "the map is {width}x{height}: a map needs at least one row and one column")
            }
            MapError::TooLarge { width, height, limit } => write!(
                f,
                "the map is {width}x{height} = {} cells, over the limit of {limit} cells; crop or \
                 downsample it, or raise the limit (Limits::max_cells) if this machine has the memory",
                (*width as u128) * (*height as u128)
            ),
            MapError::Png { message } => write!(f, "cannot decode PNG: {message}"),
            MapError::Yaml { line, message } if *line > 0 => {
                write!(f, "map.yaml line {line}: {message}")
            }
            MapError::Yaml { message, .. } => write!(f, "map.yaml: {message}"),
            MapError::NotUtf8 { what, offset } => {
                write!(f, "{what} is not UTF-8 text (bad byte at offset {offset}); save it as UTF-8")
            }
            MapError::MissingImage { path, yaml } => write!(
                f,
                "{yaml} names the image {path}, which does not exist; put the image beside the \
                 YAML file or fix its `image:` line"
            ),
            MapError::Io { path, message } => write!(f, "{path}: {message}"),
            MapError::BadThreshold { name, message } => {
                write!(f, "classification threshold `{name}`: {message}")
            }
            MapError::BadCells { message } => f.write_str(message),
        }
    }
}

impl std::error::Error for MapError {}

/// Renders the first bytes of unknown data so that a person can recognise what it is.
pub(crate) fn describe_start(bytes: &[u8]) -> String {
    if bytes.is_empty() {
        return "nothing (the data is empty)".to_string();
    }
    let head = &bytes[..bytes.len().min(8)];
    let printable = head.iter().all(|b| b.is_ascii_graphic() || *b == b' ');
    if printable {
        format!("{:?}", String::from_utf8_lossy(head))
    } else {
        let hex: Vec<String> = head.iter().map(|b| format!("{b:02x}")).collect();
        format!("bytes {}", hex.join(" "))
    }
}
