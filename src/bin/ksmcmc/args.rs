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

/// Loads a map and classifies it as `--classify` asks: `auto`, the one rule for every format
/// (background grays from the histogram, [`ksmcmc::grid::Classifier::for_map`]), so that a
/// PNG, a PGM and a map.yaml of the same pixels give the same cells; or `fixed` (a map.yaml's
/// own thresholds, eq. 3.7's defaults for a plain image).
pub fn load_classified(path: &Path, classify: &str) -> Result<ksmcmc::grid::OccupancyMap, CliError> {
    match classify {
        "auto" => ksmcmc::grid::OccupancyMap::open(path, &Default::default()).map_err(|e| failed(path.display(), e)),
        "fixed" => load_map(path),
        other => Err(CliError::Usage(format!("--classify must be auto or fixed, not {other:?}"))),
    }
}

/// `map` at `resolution` metres per cell when one is given. Without one, a plain image (no
/// map.yaml says its cell size) is read at the default 0.05 m, and a note on standard error
/// says so and how to change it: every length of the floor plan is in metres, so the cell
/// size decides which walls, doors and rooms are seen.
pub fn at_resolution(
    map: ksmcmc::grid::OccupancyMap,
    path: &Path,
    resolution: Option<f64>,
) -> ksmcmc::grid::OccupancyMap {
    let is_yaml = matches!(path.extension().and_then(|e| e.to_str()), Some("yaml" | "yml"));
    match resolution {
        Some(r) => {
            let yaml = ksmcmc::grid::MapYaml { resolution: r, ..map.yaml().clone() };
            map.with_yaml(yaml)
        }
        None => {
            if !is_yaml {
                eprintln!(
                    "note: {} has no map.yaml; reading it at {} m a cell (give --resolution M, or its map.yaml)",
                    path.display(),
                    map.yaml().resolution
                );
            }
            map
        }
    }
}

/// Reads a world.json and checks that it belongs to `map`.
pub fn load_world(path: &Path, map: &ksmcmc::grid::OccupancyMap) -> Result<ksmcmc::floorplan::World, CliError> {
    let bytes = std::fs::read(path).map_err(|e| failed(path.display(), e))?;
    let text = std::str::from_utf8(&bytes).map_err(|e| {
        failed(path.display(), format!("not UTF-8 text (bad byte at offset {}); save it as UTF-8", e.valid_up_to()))
    })?;
    let world = ksmcmc::floorplan::World::from_json(text).map_err(|e| failed(path.display(), e))?;
    world.fits(map.width(), map.height()).map_err(|e| failed(path.display(), e))?;
    Ok(world)
}
