//! Cell classification: occupied / unexplained / free (eq. 3.7).

use super::error::MapError;
use super::raster::{Grid, Raster};
use super::ros::{MapYaml, Mode};

/// The class of one map cell, with the codes of eq. 3.7 (`C_M(x, y)`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, serde::Serialize, serde::Deserialize)]
#[repr(u8)]
pub enum Cell {
    /// Seen and empty (`C_M = 0`).
    Free = 0,
    /// Never observed, or too uncertain to call (`C_M = 1`, "unexplained").
    Unknown = 1,
    /// Seen and blocked: a wall or an object (`C_M = 2`).
    Occupied = 2,
}

impl Cell {
    /// The eq. 3.7 code: 0 free, 1 unknown, 2 occupied.
    pub fn code(self) -> u8 {
        self as u8
    }

    /// The cell for an eq. 3.7 code, `None` for codes above 2.
    pub fn from_code(code: u8) -> Option<Cell> {
        match code {
            0 => Some(Cell::Free),
            1 => Some(Cell::Unknown),
            2 => Some(Cell::Occupied),
            _ => None,
        }
    }
}

/// How gray levels become [`Cell`]s.
///
/// Pixels whose alpha is below one half are unknown under every rule: a transparent pixel
/// says nothing about the world.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(tag = "rule", rename_all = "snake_case")]
pub enum Classifier {
    /// Eq. 3.7 on the gray level `g` in [0, 1] (0 black, 1 white): occupied if
    /// `g <= occupied_max` (`h_o`), unknown if `occupied_max < g <= unknown_max` (`h_u`), free
    /// above. For plain images, where dark is occupied and white is free.
    Intensity {
        /// `h_o`: the brightest gray still counted as occupied.
        occupied_max: f64,
        /// `h_u`: the brightest gray still counted as unknown; anything brighter is free.
        unknown_max: f64,
    },
    /// Eq. 3.7 with the unknown class found from the data, for drawn and anti-aliased maps:
    /// free above `unknown_max`; among darker pixels, every 8-bit gray level that covers at
    /// least `plateau_share` of the map (within ±2 levels) is a background plateau and unknown
    /// (unexplored space is painted in one flat gray); all other grays are occupied, dark walls
    /// and the anti-aliased mid-gray edges of drawn walls alike.
    ///
    /// Why: benchmark floor plans draw walls with anti-aliasing, so half their wall pixels are
    /// mid-grays that fixed thresholds call unknown, losing the walls between rooms; but their
    /// unexplored space is always one flat gray (178, 180, 205, 230 in our data sets). Per pixel
    /// ([`Classifier::classify`]) no histogram is known and mid-grays count as unknown.
    Auto {
        /// Gray levels up to this are occupied whatever the histogram says.
        occupied_max: f64,
        /// Gray levels above this are free.
        unknown_max: f64,
        /// Share of all pixels a gray level needs to count as unknown background.
        plateau_share: f64,
    },
    /// ROS map_server's rule, as a `map.yaml` configures it: occupancy `p = (255 - v) / 255`
    /// (or `v / 255` when negated, or `v / 100` in raw mode); occupied if `p > occupied_thresh`,
    /// free if `p < free_thresh`, unknown otherwise (and above 100 in raw mode).
    MapServer {
        /// White means occupied.
        negate: bool,
        /// Probability above which a cell is occupied.
        occupied_thresh: f64,
        /// Probability below which a cell is free.
        free_thresh: f64,
        /// How pixel values become occupancy.
        mode: Mode,
    },
}

impl Default for Classifier {
    /// Gray levels up to 0.35 (89 of 255) are occupied and up to 0.92 (234 of 255) unknown.
    ///
    /// Why these numbers: benchmark maps mark unexplored space with light grays (205 in the
    /// ROS convention, 178 in some Bormann maps, 230 in the Radish Cartesium map), and free
    /// space with 254 or 255; scan edges are anti-aliased dark grays. ROS's own defaults would
    /// call 230 free.
    fn default() -> Self {
        Classifier::Intensity { occupied_max: 0.35, unknown_max: 0.92 }
    }
}

impl Classifier {
    /// The rule a `map.yaml` asks for.
    pub fn from_yaml(yaml: &MapYaml) -> Self {
        Classifier::MapServer {
            negate: yaml.negate,
            occupied_thresh: yaml.occupied_thresh,
            free_thresh: yaml.free_thresh,
            mode: yaml.mode,
        }
    }

    /// The adaptive rule with the default thresholds and a 2 % plateau share.
    pub fn auto() -> Self {
        Classifier::Auto { occupied_max: 0.35, unknown_max: 0.92, plateau_share: 0.02 }
    }

    /// The one rule by which ksmcmc reads a map's pixels, whatever file they came in: a PNG,
    /// a PGM, or either named by a `map.yaml`. It is [`Classifier::auto`] on the gray levels,
    /// so that the same pixels give the same cells, and so the same rooms, from every format.
    ///
    /// Why not the `map.yaml`'s own thresholds: map_server's default `free_thresh` (0.196)
    /// calls every gray from 206 up free, and drawn or edited maps carry their furniture (211
    /// in the benchmark floors) and the anti-aliased edges of their walls in exactly those
    /// grays; a map that `map_saver` wrote holds only 0, 205 and 254, which both rules read
    /// alike. Where the YAML says its pixels mean something else (`negate: 1`, or `mode: raw`,
    /// whose values are occupancy percentages) its own rule ([`Classifier::from_yaml`]) is kept.
    /// `ksmcmc floorplan --classify fixed` and `Map.reclassify('fixed')` ask for the YAML's
    /// rule (or, without a YAML, [`Classifier::default`]) instead.
    ///
    /// ```
    /// use ksmcmc::grid::{Classifier, MapYaml};
    /// let yaml = MapYaml::parse("image: m.pgm\nresolution: 0.1\norigin: [0, 0, 0]\n").unwrap();
    /// assert_eq!(Classifier::for_map(&yaml), Classifier::auto());
    /// let raw = MapYaml::parse("image: m.pgm\nresolution: 0.1\norigin: [0, 0, 0]\nmode: raw\n").unwrap();
    /// assert_eq!(Classifier::for_map(&raw), Classifier::from_yaml(&raw));
    /// ```
    pub fn for_map(yaml: &MapYaml) -> Self {
        if yaml.negate || yaml.mode == Mode::Raw {
            Classifier::from_yaml(yaml)
        } else {
            Classifier::auto()
        }
    }

    /// Checks that the thresholds are finite, ordered probabilities.
    pub fn validate(&self) -> Result<(), MapError> {
        if let Classifier::Auto { plateau_share, .. } = *self {
            if !(plateau_share.is_finite() && plateau_share > 0.0 && plateau_share <= 1.0) {
                return Err(MapError::BadThreshold {
                    name: "plateau_share",
                    message: format!("{plateau_share} is not a share in (0, 1]"),
                });
            }
        }
        let (lo_name, lo, hi_name, hi) = match *self {
            Classifier::Intensity { occupied_max, unknown_max }
            | Classifier::Auto { occupied_max, unknown_max, .. } => {
                ("occupied_max", occupied_max, "unknown_max", unknown_max)
            }
            Classifier::MapServer { occupied_thresh, free_thresh, .. } => {
                ("free_thresh", free_thresh, "occupied_thresh", occupied_thresh)
            }
        };
        for (name, v) in [(lo_name, lo), (hi_name, hi)] {
            if !v.is_finite() || !(0.0..=1.0).contains(&v) {
                return Err(MapError::BadThreshold { name, message: format!("{v} is not a number between 0 and 1") });
            }
        }
        if lo >= hi {
            return Err(MapError::BadThreshold {
                name: lo_name,
                message: format!("{lo_name} ({lo}) must be below {hi_name} ({hi})"),
            });
        }
        Ok(())
    }

    /// Classifies one pixel: `gray` and `alpha` are 16-bit (65535 = white / opaque).
    #[inline]
    pub fn classify(&self, gray: u16, alpha: u16) -> Cell {
        if alpha < 32768 {
            return Cell::Unknown;
        }
        match *self {
            Classifier::Intensity { occupied_max, unknown_max }
            | Classifier::Auto { occupied_max, unknown_max, .. } => {
                let g = gray as f64 / 65535.0;
                if g <= occupied_max {
                    Cell::Occupied
                } else if g <= unknown_max {
                    Cell::Unknown
                } else {
                    Cell::Free
                }
            }
            Classifier::MapServer { negate, occupied_thresh, free_thresh, mode } => {
                let mut v = gray as f64 / 257.0;
                if negate {
                    v = 255.0 - v;
                }
                let p = match mode {
                    Mode::Raw if v > 100.0 => return Cell::Unknown,
                    Mode::Raw => v / 100.0,
                    Mode::Trinary | Mode::Scale => (255.0 - v) / 255.0,
                };
                if p > occupied_thresh {
                    Cell::Occupied
                } else if p < free_thresh {
                    Cell::Free
                } else {
                    Cell::Unknown
                }
            }
        }
    }

    /// Classifies every pixel of a raster.
    pub fn classify_raster(&self, raster: &Raster) -> Grid<Cell> {
        if let Classifier::Auto { occupied_max, unknown_max, plateau_share } = *self {
            return classify_auto(raster, occupied_max, unknown_max, plateau_share);
        }
        let gray = raster.gray.cells();
        let cells: Vec<Cell> = match &raster.alpha {
            Some(alpha) => gray.iter().zip(alpha.cells()).map(|(&g, &a)| self.classify(g, a)).collect(),
            None => gray.iter().map(|&g| self.classify(g, u16::MAX)).collect(),
        };
        Grid::from_vec(raster.width(), raster.height(), cells).expect("same size as the raster")
    }
}

fn classify_auto(raster: &Raster, occupied_max: f64, unknown_max: f64, plateau_share: f64) -> Grid<Cell> {
    let opaque = |i: usize| raster.alpha.as_ref().is_none_or(|a| a.cells()[i] >= 32768);
    let level = |g: u16| (g as u32 * 255 + 32767) / 65535;
    let mut hist = [0u64; 256];
    for (i, &g) in raster.gray.cells().iter().enumerate() {
        if opaque(i) {
            hist[level(g) as usize] += 1;
        }
    }
    let n = raster.gray.len() as f64;
    let mut background = [false; 256];
    for (l, &count) in hist.iter().enumerate() {
        let g = l as f64 / 255.0;
        if g > occupied_max && g <= unknown_max && count as f64 >= plateau_share * n {
            for b in background.iter_mut().take((l + 3).min(256)).skip(l.saturating_sub(2)) {
                *b = true;
            }
        }
    }
    let cells = raster
        .gray
        .cells()
        .iter()
        .enumerate()
        .map(|(i, &g)| {
            if !opaque(i) {
                return Cell::Unknown;
            }
            let v = g as f64 / 65535.0;
            if v > unknown_max {
                Cell::Free
            } else if v > occupied_max && background[level(g) as usize] {
                Cell::Unknown
            } else {
                Cell::Occupied
            }
        })
        .collect();
    Grid::from_vec(raster.width(), raster.height(), cells).expect("same size as the raster")
}
