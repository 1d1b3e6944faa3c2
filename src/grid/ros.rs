//! The ROS map_server description file, `map.yaml`.
//!
//! gmapping, slam_toolbox and Cartographer users save a map as an image plus a YAML file such as
//!
//! ```yaml
//! image: office.pgm
//! resolution: 0.050000
//! origin: [-12.2, -8.4, 0.0]
//! negate: 0
//! occupied_thresh: 0.65
//! free_thresh: 0.196
//! mode: trinary   # optional: trinary (default), scale or raw
//! ```
//!
//! The format used in practice is flat `key: value` lines, so this module reads exactly that
//! (comments, quoted strings and `[a, b, c]` lists included) and says which line is wrong,
//! instead of pulling in a general YAML library for ten keys.

use super::error::MapError;

/// Longest `map.yaml` text read, bytes (64 KiB; map_server's files are a few hundred bytes).
pub const MAX_YAML_BYTES: usize = 64 << 10;

/// How map_server turns pixel values into occupancy (`mode:` in the YAML).
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Mode {
    /// Occupied above `occupied_thresh`, free below `free_thresh`, unknown between.
    Trinary,
    /// As trinary, but values between the thresholds are graded; for three classes they are
    /// unknown as in trinary.
    Scale,
    /// The pixel value is the occupancy in percent (0 free, 100 occupied); above 100 is unknown.
    Raw,
}

/// The contents of a `map.yaml`.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct MapYaml {
    /// The image file, relative to the YAML file's folder unless absolute.
    pub image: String,
    /// Metres per cell.
    pub resolution: f64,
    /// Pose of the lower-left pixel in the map frame: x, y (metres), yaw (radians).
    pub origin: [f64; 3],
    /// Whether white means occupied instead of free.
    pub negate: bool,
    /// Occupancy probability above which a cell is occupied.
    pub occupied_thresh: f64,
    /// Occupancy probability below which a cell is free.
    pub free_thresh: f64,
    /// How pixel values become occupancy.
    pub mode: Mode,
}

impl MapYaml {
    /// The description map_server gives a map with no YAML: 5 cm cells at the origin, default
    /// thresholds.
    pub fn for_image(image: &str) -> Self {
        MapYaml {
            image: image.to_string(),
            resolution: super::BENCHMARK_CELL_M,
            origin: [0.0, 0.0, 0.0],
            negate: false,
            occupied_thresh: 0.65,
            free_thresh: 0.196,
            mode: Mode::Trinary,
        }
    }

    /// Parses the text of a `map.yaml`.
    ///
    /// ```
    /// use ksmcmc::grid::MapYaml;
    /// let y = MapYaml::parse("image: m.pgm\nresolution: 0.05\norigin: [-1, -2.5, 0]\n").unwrap();
    /// assert_eq!(y.image, "m.pgm");
    /// assert_eq!(y.origin, [-1.0, -2.5, 0.0]);
    /// assert!(MapYaml::parse("image: m.pgm\n").unwrap_err().to_string().contains("resolution"));
    /// ```
    pub fn parse(text: &str) -> Result<Self, MapError> {
        if text.len() > MAX_YAML_BYTES {
            return Err(MapError::Yaml {
                line: 0,
                message: format!(
                    "the file is {} bytes, over the limit of {MAX_YAML_BYTES} (MAX_YAML_BYTES); a map.yaml is a \
                     few short `key: value` lines",
                    text.len()
                ),
            });
        }
        let mut image = None;
        let mut resolution = None;
        let mut origin = None;
        let mut negate = false;
        let mut occupied_thresh = 0.65;
        let mut free_thresh = 0.196;
        let mut mode = Mode::Trinary;
        for (i, raw) in text.lines().enumerate() {
            let line_no = i + 1;
            let err = |message: String| MapError::Yaml { line: line_no, message };
            let line = strip_comment(raw).trim();
            if line.is_empty() || line == "---" {
                continue;
            }
            let Some((key, value)) = line.split_once(':') else {
                return Err(err(format!("expected `key: value`, found {line:?}")));
            };
            let key = key.trim();
            let value = unquote(value.trim());
            match key {
                "image" => {
                    if value.is_empty() {
                        return Err(err("`image:` is empty; name the map's PGM or PNG file".into()));
                    }
                    image = Some(value.to_string())
                }
                "resolution" => resolution = Some(parse_resolution(value).map_err(err)?),
                "origin" => origin = Some(triple(value).map_err(|m| err(format!("origin: {m}")))?),
                "negate" => negate = parse_negate(value).map_err(err)?,
                "occupied_thresh" => {
                    occupied_thresh = probability(value).map_err(|m| err(format!("occupied_thresh: {m}")))?
                }
                "free_thresh" => free_thresh = probability(value).map_err(|m| err(format!("free_thresh: {m}")))?,
                "mode" => mode = parse_mode(value).map_err(err)?,
                // Other keys (e.g. Nav2's extra fields) are harmless; ignore them as map_server does.
                _ => {}
            }
        }
        let missing = |k: &str| MapError::Yaml { line: 0, message: format!("the required key `{k}:` is missing") };
        let yaml = MapYaml {
            image: image.ok_or_else(|| missing("image"))?,
            resolution: resolution.ok_or_else(|| missing("resolution"))?,
            origin: origin.ok_or_else(|| missing("origin"))?,
            negate,
            occupied_thresh,
            free_thresh,
            mode,
        };
        if yaml.free_thresh >= yaml.occupied_thresh {
            return Err(MapError::Yaml {
                line: 0,
                message: format!(
                    "free_thresh ({}) must be below occupied_thresh ({})",
                    yaml.free_thresh, yaml.occupied_thresh
                ),
            });
        }
        Ok(yaml)
    }

    /// Writes the YAML text map_server reads.
    pub fn to_text(&self) -> String {
        let mode = match self.mode {
            Mode::Trinary => "trinary",
            Mode::Scale => "scale",
            Mode::Raw => "raw",
        };
        format!(
            "image: {}\nmode: {mode}\nresolution: {}\norigin: [{}, {}, {}]\nnegate: {}\noccupied_thresh: {}\nfree_thresh: {}\n",
            self.image,
            self.resolution,
            self.origin[0],
            self.origin[1],
            self.origin[2],
            u8::from(self.negate),
            self.occupied_thresh,
            self.free_thresh
        )
    }
}

fn strip_comment(line: &str) -> &str {
    // A `#` inside quotes is not a comment.
    let mut quote = None;
    for (i, c) in line.char_indices() {
        match (quote, c) {
            (None, '"' | '\'') => quote = Some(c),
            (Some(q), c) if c == q => quote = None,
            (None, '#') => return &line[..i],
            _ => {}
        }
    }
    line
}

fn unquote(v: &str) -> &str {
    let b = v.as_bytes();
    if b.len() >= 2 && (b[0] == b'"' || b[0] == b'\'') && b[b.len() - 1] == b[0] {
        &v[1..v.len() - 1]
    } else {
        v
    }
}

/// The value of `resolution:`: a positive number of metres per cell.
fn parse_resolution(v: &str) -> Result<f64, String> {
    let r = number(v).map_err(|m| format!("resolution: {m}"))?;
    if !(r > 0.0 && r.is_finite()) {
        return Err(format!("resolution must be a positive number of metres per cell, not {r}"));
    }
    Ok(r)
}

/// The value of `negate:`: 0 or 1 (or false or true, as YAML writes them).
fn parse_negate(v: &str) -> Result<bool, String> {
    match v {
        "0" | "false" | "False" => Ok(false),
        "1" | "true" | "True" => Ok(true),
        _ => Err(format!("negate must be 0 or 1, not {v:?}")),
    }
}

/// The value of `mode:`: trinary, scale or raw.
fn parse_mode(v: &str) -> Result<Mode, String> {
    match v {
        "trinary" => Ok(Mode::Trinary),
        "scale" => Ok(Mode::Scale),
        "raw" => Ok(Mode::Raw),
        _ => Err(format!("mode must be trinary, scale or raw, not {v:?}")),
    }
}

fn number(v: &str) -> Result<f64, String> {
    let x: f64 = v.parse().map_err(|_| format!("{v:?} is not a number"))?;
    if x.is_finite() {
        Ok(x)
    } else {
        Err(format!("{v:?} is not a finite number"))
    }
}

fn probability(v: &str) -> Result<f64, String> {
    let p = number(v)?;
    if (0.0..=1.0).contains(&p) {
        Ok(p)
    } else {
        Err(format!("{p} is not a probability between 0 and 1"))
    }
}

fn triple(v: &str) -> Result<[f64; 3], String> {
    let inner = v
        .strip_prefix('[')
        .and_then(|s| s.strip_suffix(']'))
        .ok_or_else(|| format!("expected a list like [x, y, yaw], found {v:?}"))?;
    let parts: Vec<&str> = inner.split(',').map(str::trim).collect();
    if parts.len() != 3 {
        return Err(format!("expected three numbers [x, y, yaw], found {}", parts.len()));
    }
    Ok([number(parts[0])?, number(parts[1])?, number(parts[2])?])
}
