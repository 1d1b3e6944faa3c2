//! The generator's parameters, their validation, and their conversion from metres to cells.

use super::SynthError;
use crate::grid::DEFAULT_MAX_CELLS;
use serde::{Deserialize, Serialize};

/// Parameters of the synthetic generator.
///
/// Sizes of the layout (corridor, room, hall, door widths) are in metres and are converted to
/// cells with [`SynthConfig::resolution`]; the canvas, margin and wall thickness are in cells.
/// Ranges are `[low, high]`, both inclusive. Every field has a default, so a JSON config only
/// needs the fields it changes; unknown fields are refused so that typos are caught.
///
/// ```
/// use ksmcmc::floorplan::synth::SynthConfig;
/// let c = SynthConfig::from_json(r#"{ "width": 600, "rotation_deg": 20 }"#).unwrap();
/// assert_eq!((c.width, c.height), (600, 300));
/// assert!(SynthConfig::from_json(r#"{ "widht": 600 }"#).is_err());
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SynthConfig {
    /// Width of the world-frame canvas, cells (default 400). The map has this width when
    /// `rotation_deg` is 0; a rotated map grows to hold the whole rotated canvas.
    pub width: u32,
    /// Height of the world-frame canvas, cells (default 300).
    pub height: u32,
    /// Metres per cell (default 0.05), written to `map.yaml`; converts the metric sizes below.
    pub resolution: f64,
    /// Unknown border between the canvas edge and the building's outer wall, cells (default 10).
    pub margin: u32,
    /// Thickness of every wall, cells (default 3).
    pub wall_thickness: u32,
    /// Number of corridors, 1 or 2; `null` (the default) chooses by the building's depth: two
    /// when one corridor would leave rooms deeper than `room_depth`'s upper bound.
    pub corridors: Option<u32>,
    /// Number of halls, 0 to 2 (default 0): large units at the ends of the building that the
    /// corridors open into.
    pub halls: u32,
    /// Number of small units of type "other" (storage, stairs, shafts) among the rooms, 0 to
    /// 200 (default 1).
    pub others: u32,
    /// Accepted number of rooms, `[low, high]` (default `[1, 1000]`); the generator draws a count
    /// the building can hold inside this range, or fails saying which counts it could hold.
    pub rooms: [u32; 2],
    /// Clear width of corridors, metres (default `[1.5, 2.5]`).
    pub corridor_width: [f64; 2],
    /// Width of rooms along the corridor, metres (default `[3.0, 6.0]`); a room is widened past
    /// the upper bound only when the leftover space cannot hold another one.
    pub room_width: [f64; 2],
    /// Depth of rooms away from the corridor, metres (default `[3.0, 7.0]`): the lower bound is
    /// enforced, the upper bound steers the automatic corridor count.
    pub room_depth: [f64; 2],
    /// Width of halls, metres (default `[8.0, 15.0]`).
    pub hall_width: [f64; 2],
    /// Width of "other" units, metres (default `[1.5, 2.5]`).
    pub other_width: [f64; 2],
    /// Clear width of doors, metres (default `[0.8, 1.2]`); a door never takes more than its
    /// wall minus two cells at either end.
    pub door_width: [f64; 2],
    /// Probability, per pair of neighbouring units not needed for connectivity, of a door
    /// between them (default 0.2).
    pub extra_doors: f64,
    /// Rotation of the building against the image axes, degrees, -360 to 360 (default 0).
    pub rotation_deg: f64,
    /// A second wing (issue 13): 0 (the default) draws one building; an angle of 10 to 80
    /// degrees either way draws a second building of this configuration to the right of the
    /// first, turned by this much more, joined to it by a short passage. The truth's units of
    /// the second wing carry their own `angle`.
    pub wing_deg: f64,
    /// Probability that a free map cell reads occupied (scan speckle), 0 to 1 (default 0.002).
    pub speckle_occupied: f64,
    /// Probability that a free map cell reads unknown (scan dropout), 0 to 1 (default 0.004).
    pub speckle_unknown: f64,
    /// Probability that a free map cell next to an occupied one reads occupied, which makes wall
    /// faces and furniture outlines ragged as in real scans, 0 to 1 (default 0.05).
    pub wall_roughness: f64,
    /// Probability, per 5 cm along each side of each unit (a cell at 5 cm, scaled at other
    /// resolutions), that a gap (0.1 to 0.4 m of the wall read as unknown, across its whole
    /// thickness) starts there, 0 to 1 (default 0.004).
    pub wall_gaps: f64,
    /// Fraction of the free area of explored rooms and halls covered by furniture blobs, 0 to
    /// 0.5 (default 0.03).
    pub clutter: f64,
    /// Fraction of the rooms, halls and "other" units the robot never entered, 0 to 1 (default
    /// 0): their free space reads unknown, their walls only where seen from outside.
    pub unexplored: f64,
    /// Probability, per door of an unexplored unit into an explored one, that the robot looked
    /// in through it, leaving a fan of free cells (default 0.5).
    pub peek: f64,
    /// Glass panes per metre of the walls of explored units, 0 to 1 (default 0). A pane is 1 to
    /// 3 m of wall the laser sees through: half its wall columns read free, as rays crossed
    /// them, and where the pane is in the building's outer wall the rays fan out into the
    /// outside for 1 to 4 m, now and then ending on an occupied cell (a tree, a car). Panes
    /// between an explored and an unexplored unit stay opaque. The truth keeps the wall.
    pub glass: f64,
    /// Probability, per opening between two hubs (a corridor and a hall, or two corridors),
    /// that it is an open arch as wide as their shared wall allows rather than a door, 0 to 1
    /// (default 0).
    pub open_hubs: f64,
}

impl Default for SynthConfig {
    fn default() -> Self {
        SynthConfig {
            width: 400,
            height: 300,
            resolution: 0.05,
            margin: 10,
            wall_thickness: 3,
            corridors: None,
            halls: 0,
            others: 1,
            rooms: [1, 1000],
            corridor_width: [1.5, 2.5],
            room_width: [3.0, 6.0],
            room_depth: [3.0, 7.0],
            hall_width: [8.0, 15.0],
            other_width: [1.5, 2.5],
            door_width: [0.8, 1.2],
            extra_doors: 0.2,
            rotation_deg: 0.0,
            wing_deg: 0.0,
            speckle_occupied: 0.002,
            speckle_unknown: 0.004,
            wall_roughness: 0.05,
            wall_gaps: 0.004,
            clutter: 0.03,
            unexplored: 0.0,
            peek: 0.5,
            glass: 0.0,
            open_hubs: 0.0,
        }
    }
}

/// Cells kept clear between a door and the ends of its wall.
pub(super) const DOOR_CLEARANCE: i32 = 2;

/// Width and height of the bounding box of a `canvas` (width, height) turned by `angle`
/// radians: the map's size for one building, each wing's share of it for two.
pub(super) fn turned_extent(canvas: (u32, u32), angle: f64) -> (f64, f64) {
    let (s, c) = (libm::fabs(libm::sin(angle)), libm::fabs(libm::cos(angle)));
    let (w, h) = (canvas.0 as f64, canvas.1 as f64);
    (w * c + h * s, w * s + h * c)
}

/// The largest canvas side, cells.
const MAX_SIDE: u32 = 1 << 16;

/// A `[low, high]` range in cells.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct Span {
    pub lo: i32,
    pub hi: i32,
}

/// The configuration in cells, after validation.
#[derive(Debug, Clone)]
pub(super) struct Cells {
    pub canvas: (i32, i32),
    pub map_size: (u32, u32),
    pub angle: f64,
    pub resolution: f64,
    pub margin: i32,
    pub wall: i32,
    pub corridors: Option<u32>,
    pub halls: u32,
    pub others: u32,
    pub rooms: [u32; 2],
    pub corridor: Span,
    pub room: Span,
    pub depth: Span,
    pub hall: Span,
    pub other: Span,
    pub door: Span,
    pub open_hubs: f64,
}

impl SynthConfig {
    /// Parses a JSON config (missing fields take their defaults; blank text is the defaults)
    /// and validates it: what `ksmcmc synth --config` and the wasm `synth` read.
    pub fn from_json(text: &str) -> Result<SynthConfig, SynthError> {
        let max = crate::floorplan::chain::MAX_CONFIG_JSON_BYTES;
        if text.len() > max {
            return Err(SynthError::new(format!(
                "synth config: the text is {} bytes, over the limit of {max} bytes (MAX_CONFIG_JSON_BYTES)",
                text.len()
            )));
        }
        let c = SynthConfig::parse_json(text)?;
        c.validate()?;
        Ok(c)
    }

    /// Parses a JSON config like [`SynthConfig::from_json`] but leaves validation to the
    /// caller, who may change fields first (as the command line's options do).
    ///
    /// ```
    /// use ksmcmc::floorplan::synth::SynthConfig;
    /// let c = SynthConfig::parse_json(r#"{ "width": 0 }"#).unwrap();
    /// assert!(c.validate().is_err());
    /// let e = SynthConfig::parse_json("[1]").unwrap_err().to_string();
    /// assert_eq!(e, r#"synth config: expected a JSON object such as {"width": 200}"#);
    /// ```
    pub fn parse_json(text: &str) -> Result<SynthConfig, SynthError> {
        crate::json::settings(text, r#"{"width": 200}"#).map_err(|m| SynthError::new(format!("synth config: {m}")))
    }

    /// The config as pretty JSON.
    pub fn to_json(&self) -> String {
        serde_json::to_string_pretty(self).expect("a config always serialises")
    }

    /// Checks every field; the error names the field and the accepted range.
    pub fn validate(&self) -> Result<(), SynthError> {
        self.cells().map(|_| ())
    }

    /// The rotation in radians.
    pub fn angle(&self) -> f64 {
        self.rotation_deg * (core::f64::consts::PI / 180.0)
    }

    /// The second wing's angle against the image axes in radians (`rotation_deg + wing_deg`),
    /// when there is one.
    pub fn wing_angle(&self) -> Option<f64> {
        (self.wing_deg != 0.0).then(|| (self.rotation_deg + self.wing_deg) * (core::f64::consts::PI / 180.0))
    }

    /// Width and height of the map: the canvas, grown to hold it when rotated; with a second
    /// wing, both canvases side by side.
    pub fn map_size(&self) -> (u32, u32) {
        // The tolerance keeps 0 and 360 degrees from growing the map by a rounding error.
        let side = |v: f64| libm::ceil(v - 1e-6).max(1.0) as u32;
        let first = self.extent(self.angle());
        match self.wing_angle() {
            None => (side(first.0), side(first.1)),
            Some(b) => {
                let second = self.extent(b);
                (side(first.0 + second.0), side(first.1.max(second.1)))
            }
        }
    }

    /// Width and height of the canvas turned by `angle` radians (its bounding box).
    fn extent(&self, angle: f64) -> (f64, f64) {
        turned_extent((self.width, self.height), angle)
    }

    /// Validates and converts to cells; the error names the first bad field found.
    pub(super) fn cells(&self) -> Result<Cells, SynthError> {
        let (mw, mh) = self.check_canvas()?;
        self.check_counts()?;
        let resolution = self.resolution;
        let span = |name: &str, r: [f64; 2]| span(name, r, resolution);
        let corridor = span("corridor_width", self.corridor_width)?;
        let room = span("room_width", self.room_width)?;
        let depth = span("room_depth", self.room_depth)?;
        let hall = span("hall_width", self.hall_width)?;
        let other = span("other_width", self.other_width)?;
        let door = span("door_width", self.door_width)?;
        let wall = self.wall_thickness as i32;
        let narrowest = corridor.lo.min(room.lo).min(depth.lo).min(hall.lo).min(other.lo);
        if wall * 2 > narrowest {
            return config_err(
                "wall_thickness",
                format!(
                    "is {wall} cells; accepted: at most half the narrowest unit ({narrowest} cells, the least of the \
                     corridor, room, hall and other widths and the room depth)"
                ),
            );
        }
        if door.lo + 2 * DOOR_CLEARANCE > narrowest {
            return config_err(
                "door_width",
                format!(
                    "lower bound is {} cells; accepted: at most {} cells, so that a door and {DOOR_CLEARANCE} cells at \
                     either end fit the narrowest unit ({narrowest} cells)",
                    door.lo,
                    narrowest - 2 * DOOR_CLEARANCE
                ),
            );
        }
        self.check_probabilities()?;
        Ok(Cells {
            canvas: (self.width as i32, self.height as i32),
            map_size: (mw, mh),
            angle: self.angle(),
            resolution,
            margin: self.margin as i32,
            wall,
            corridors: self.corridors,
            halls: self.halls,
            others: self.others,
            rooms: self.rooms,
            corridor,
            room,
            depth,
            hall,
            other,
            door,
            open_hubs: self.open_hubs,
        })
    }

    /// The canvas: size, resolution, rotation, margin; the map's size.
    fn check_canvas(&self) -> Result<(u32, u32), SynthError> {
        let err = config_err;
        for (name, v) in [("width", self.width), ("height", self.height)] {
            if !(16..=MAX_SIDE).contains(&v) {
                return err(name, format!("is {v}; accepted: 16 to {MAX_SIDE} cells"));
            }
        }
        if self.width as u64 * self.height as u64 > DEFAULT_MAX_CELLS as u64 {
            return err(
                "width x height",
                format!("is {} x {} cells; accepted: at most {DEFAULT_MAX_CELLS} cells", self.width, self.height),
            );
        }
        let resolution = self.resolution;
        if !resolution.is_finite() || !(0.005..=0.5).contains(&resolution) {
            return err("resolution", format!("is {resolution}; accepted: 0.005 to 0.5 m per cell"));
        }
        if !self.rotation_deg.is_finite() || !(-360.0..=360.0).contains(&self.rotation_deg) {
            return err("rotation_deg", format!("is {}; accepted: -360 to 360 degrees", self.rotation_deg));
        }
        let wing = self.wing_deg;
        if !wing.is_finite() || !(wing == 0.0 || (10.0..=80.0).contains(&libm::fabs(wing))) {
            return err("wing_deg", format!("is {wing}; accepted: 0 (one building), or 10 to 80 degrees either way"));
        }
        let (mw, mh) = self.map_size();
        if mw as u64 * mh as u64 > DEFAULT_MAX_CELLS as u64 {
            return err(
                "rotation_deg",
                format!(
                    "makes the map {mw} x {mh} cells; accepted: at most {DEFAULT_MAX_CELLS} cells (shrink width or height)"
                ),
            );
        }
        let min_side = self.width.min(self.height);
        if self.margin > min_side / 4 {
            return err(
                "margin",
                format!("is {}; accepted: 0 to {} cells (a quarter of the canvas)", self.margin, min_side / 4),
            );
        }
        Ok((mw, mh))
    }

    /// The wall thickness and the numbers of corridors, halls, others and rooms.
    fn check_counts(&self) -> Result<(), SynthError> {
        let err = config_err;
        if !(1..=20).contains(&self.wall_thickness) {
            return err("wall_thickness", format!("is {}; accepted: 1 to 20 cells", self.wall_thickness));
        }
        if let Some(c) = self.corridors {
            if !(1..=2).contains(&c) {
                return err("corridors", format!("is {c}; accepted: 1, 2 or null (automatic)"));
            }
        }
        if self.halls > 2 {
            return err("halls", format!("is {}; accepted: 0 to 2", self.halls));
        }
        if self.others > 200 {
            return err("others", format!("is {}; accepted: 0 to 200", self.others));
        }
        let [rlo, rhi] = self.rooms;
        if rlo > rhi || rhi > 10_000 {
            return err("rooms", format!("is [{rlo}, {rhi}]; accepted: [low, high] with low <= high <= 10000"));
        }
        Ok(())
    }

    /// The noise probabilities.
    fn check_probabilities(&self) -> Result<(), SynthError> {
        let err = config_err;
        for (name, p, hi) in [
            ("extra_doors", self.extra_doors, 1.0),
            ("speckle_occupied", self.speckle_occupied, 1.0),
            ("speckle_unknown", self.speckle_unknown, 1.0),
            ("wall_roughness", self.wall_roughness, 1.0),
            ("wall_gaps", self.wall_gaps, 1.0),
            ("clutter", self.clutter, 0.5),
            ("unexplored", self.unexplored, 1.0),
            ("peek", self.peek, 1.0),
            ("glass", self.glass, 1.0),
            ("open_hubs", self.open_hubs, 1.0),
        ] {
            if !p.is_finite() || !(0.0..=hi).contains(&p) {
                return err(name, format!("is {p}; accepted: 0 to {hi}"));
            }
        }
        if self.speckle_occupied + self.speckle_unknown > 1.0 {
            return err(
                "speckle_occupied + speckle_unknown",
                format!("is {}; accepted: at most 1", self.speckle_occupied + self.speckle_unknown),
            );
        }
        Ok(())
    }
}

fn config_err<T>(field: &str, m: String) -> Result<T, SynthError> {
    Err(SynthError::new(format!("synth config: {field} {m}")))
}

/// A `[low, high]` range of metres in cells at `resolution` metres per cell.
fn span(name: &str, r: [f64; 2], resolution: f64) -> Result<Span, SynthError> {
    let [lo, hi] = r;
    if !lo.is_finite() || !hi.is_finite() || lo <= 0.0 || lo > hi || hi > 1000.0 {
        return Err(SynthError::new(format!(
            "synth config: {name} is [{lo}, {hi}]; accepted: [low, high] metres with 0 < low <= high <= 1000"
        )));
    }
    let to_cells = |m: f64| libm::round(m / resolution) as i32;
    let s = Span { lo: to_cells(lo), hi: to_cells(hi) };
    let least = if name == "door_width" { 2 } else { 3 };
    if s.lo < least {
        return Err(SynthError::new(format!(
                "synth config: {name} [{lo}, {hi}] m is [{}, {}] cells at {resolution} m per cell; accepted: at least {least} cells",
                s.lo, s.hi
            )));
    }
    Ok(s)
}
