//! Shared command-line plumbing: errors, option parsing helpers, file output.

use std::ffi::OsString;
use std::fmt::Display;
use std::path::{Path, PathBuf};

/// A command's failure, split by exit code.
#[derive(Debug)]
pub enum CliError {
    /// The command line is wrong (exit 2).
    Usage(String),
    /// The work failed (exit 1).
    Failed(String),
}

impl From<lexopt::Error> for CliError {
    fn from(e: lexopt::Error) -> Self {
        CliError::Usage(e.to_string())
    }
}

/// Turns a library error into a failure message.
pub fn failed(context: impl Display, e: impl Display) -> CliError {
    CliError::Failed(format!("{context}: {e}"))
}

/// Parses an option value, naming the option in the error.
pub fn value<T: std::str::FromStr>(name: &str, v: OsString) -> Result<T, CliError>
where
    T::Err: Display,
{
    let s = v.into_string().map_err(|v| CliError::Usage(format!("{name}: {v:?} is not UTF-8")))?;
    s.parse().map_err(|e| CliError::Usage(format!("{name}: {s:?}: {e}")))
}

/// Writes a file, creating its folder.
pub fn write(path: &Path, bytes: &[u8]) -> Result<(), CliError> {
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).map_err(|e| failed(dir.display(), e))?;
    }
    std::fs::write(path, bytes).map_err(|e| failed(path.display(), e))
}

/// Loads a map file with default limits.
pub fn load_map(path: &Path) -> Result<ksmcmc::grid::OccupancyMap, CliError> {
    ksmcmc::grid::OccupancyMap::load(path, &Default::default()).map_err(|e| failed(path.display(), e))
}

/// Requires an option that was not given.
pub fn required<T>(v: Option<T>, name: &str, command: &str) -> Result<T, CliError> {
    v.ok_or_else(|| CliError::Usage(format!("{command} needs {name}; run `ksmcmc {command} --help`")))
}

/// A path argument.
pub fn path(v: OsString) -> PathBuf {
    PathBuf::from(v)
}
