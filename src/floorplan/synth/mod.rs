//! Synthetic floor plans with ground truth.
//!
//! Real SLAM maps come without the floor plan that produced them, so the chain's accuracy can
//! only be measured on maps whose truth is known. [`generate`] draws a small office building
//! (rooms on both sides of one or two corridors, optionally halls at the ends and small "other"
//! units such as storage or stairs, all joined by doors), then maps it the way a robot with a
//! 2D laser would have: walls as seen from where the robot went, gaps in walls, furniture
//! blobs, rooms never entered, speckle, and optionally the whole map rotated against the image
//! axes. Everything is drawn from one seeded [`Rng`] (ChaCha8, the chains' generator) with
//! platform-independent draws and
//! `libm` arithmetic, so a config and a seed give the same bytes natively and in wasm.
//!
//! # What the truth means
//!
//! * [`Synthetic::truth`] is a [`World`] in the world frame: the canvas of
//!   [`SynthConfig::width`] x [`SynthConfig::height`] cells, upright. Its `frame.angle` is the
//!   rotation in radians and its `frame.map_size` the map's size; with no rotation the frame is
//!   the identity.
//! * Each unit's rectangle is its **free interior expanded by one cell on every side**, so its
//!   border ring (eq. 3.8's wall cells `S_w`) lies on the inner face of its walls. This is the
//!   rectangle the likelihood of eq. 3.6 favours: every ring cell is a wall cell and every
//!   inside cell is free. Neighbouring units are separated by one wall of
//!   [`SynthConfig::wall_thickness`] `t` cells, so their rings are `t - 1` cells apart (they
//!   coincide when `t` is 1) and units never share interior cells.
//! * Each door joins units `[a, b]` (1-based ids), `a` left of or above the wall. The door is
//!   an opening of free cells through the whole wall; its `world.json` run is the opening's
//!   row or column on the wall's centre line, `(t - 1) / 2` cells past `a`'s ring, so it lies
//!   on `a`'s ring for `t` <= 2 and on both rings for `t` = 1.
//! * `object_cells` are the furniture cells (world frame, row by row): the blobs' footprints,
//!   whose map cells read occupied (seen outline) or unknown. Furniture is placed only in
//!   explored rooms and halls, never in corridors, and keeps door fronts clear.
//! * Units the robot never entered are still in the truth; [`Synthetic::explored`] says which.
//!
//! [`Synthetic::labels`] has the map's size and frame: for every map cell whose centre, taken
//! into the world frame by the inverse of [`Frame::to_map`], falls on the interior (ring
//! excluded) of unit `i` of `truth.units`, the value `i + 1`; 0 everywhere else (walls, door
//! openings, outside). With no rotation, world and map cells coincide.
//!
//! ```
//! use ksmcmc::floorplan::synth::{generate, SynthConfig};
//!
//! let s = generate(&SynthConfig::default(), 7).unwrap();
//! assert_eq!((s.map.width(), s.map.height()), (400, 300));
//! assert!(s.truth.units.len() >= 3);
//! // Same seed, same bytes.
//! assert_eq!(generate(&SynthConfig::default(), 7).unwrap().map_pgm(), s.map_pgm());
//! // Bad configs are errors that name the field.
//! let bad = SynthConfig { wall_thickness: 0, ..SynthConfig::default() };
//! assert!(generate(&bad, 7).unwrap_err().to_string().contains("wall_thickness"));
//! ```

mod config;
mod layout;
mod scan;
mod wings;

pub use config::SynthConfig;

use super::{Frame, Unit, UnitType, World, WORLD_FORMAT};
use crate::grid::{Cell, Classifier, Grid, MapYaml, Mode, OccupancyMap, Raster};
use crate::mcmc::Rng;

/// Why a configuration was refused: the message names the field and the accepted range.
#[derive(Debug, Clone, PartialEq)]
pub struct SynthError {
    message: String,
}

impl SynthError {
    /// The error with `message`, which says what was refused and how to put it right.
    pub(crate) fn new(message: impl Into<String>) -> SynthError {
        SynthError { message: message.into() }
    }
}

impl std::fmt::Display for SynthError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for SynthError {}

/// A generated map with its ground truth (conventions in the [module docs](self)).
#[derive(Debug, Clone)]
pub struct Synthetic {
    /// The occupancy map a SLAM system would have produced.
    pub map: OccupancyMap,
    /// The true world (units with types, doors, furniture cells), in `world.json` form.
    pub truth: World,
    /// Per map cell: index + 1 of the truth unit whose interior it lies in, 0 elsewhere.
    pub labels: Grid<u16>,
    /// Per truth unit: whether the robot entered it (unexplored units read unknown).
    pub explored: Vec<bool>,
}

impl Synthetic {
    /// `map.pgm` bytes: 8-bit binary PGM, occupied 0, unknown 205, free 254.
    pub fn map_pgm(&self) -> Vec<u8> {
        self.map.to_pgm()
    }

    /// `map.yaml` text naming `map.pgm`, with the configured resolution.
    pub fn map_yaml(&self) -> String {
        self.map.to_yaml("map.pgm")
    }

    /// `truth.json` text: the truth world.
    pub fn truth_json(&self) -> String {
        self.truth.to_json()
    }

    /// `truth_labels.pgm` bytes: 16-bit binary PGM (maxval 65535), unit index + 1 per cell.
    pub fn labels_pgm(&self) -> Vec<u8> {
        crate::grid::pgm::encode_u16(self.labels.width(), self.labels.height(), self.labels.cells())
    }
}

/// Generates a synthetic floor plan; same config and seed, same result on every platform.
///
/// Fails, without panicking, when the config is invalid or the building cannot hold what it
/// asks for; random choices that happen not to fit are redrawn a few times first.
///
/// ```
/// use ksmcmc::floorplan::synth::{generate, SynthConfig};
/// use ksmcmc::grid::Cell;
///
/// let config = SynthConfig { rotation_deg: 20.0, clutter: 0.1, ..SynthConfig::default() };
/// let s = generate(&config, 42).unwrap();
/// assert!((s.truth.frame.angle - 20f64.to_radians()).abs() < 1e-12);
/// assert!(s.map.width() > 400 && s.map.height() > 300); // grown to hold the rotated canvas
/// assert!(!s.truth.object_cells.is_empty());
/// assert_eq!(s.map.classified().at(0, 0), &Cell::Unknown); // outside the building
/// ```
pub fn generate(config: &SynthConfig, seed: u64) -> Result<Synthetic, SynthError> {
    let cells = config.cells()?;
    let mut rng = Rng::seed(seed);
    let noise = noise_of(config);
    if let Some(second) = config.wing_angle() {
        return generate_wings(config, &cells, &noise, second, &mut rng);
    }
    let plan = layout::plan(&cells, config.extra_doors, &mut rng)?;
    let explored = choose_explored(&plan.spaces, config.unexplored, &mut rng);
    let observed = scan::observe(&plan, &explored, &cells, &noise, &mut rng);
    let (map_cells, labels) = scan::to_map(&observed, &cells, &noise, &mut rng);

    let units = plan
        .spaces
        .iter()
        .enumerate()
        .map(|(i, s)| Unit::new(i as u32 + 1, s.inner.x - 1, s.inner.y - 1, s.inner.w + 2, s.inner.h + 2, s.kind))
        .collect();
    let doors = plan.openings.iter().enumerate().map(|(i, o)| o.door(i as u32 + 1, cells.wall)).collect();
    // -0 degrees would otherwise be written as an angle of -0.0.
    let angle = if cells.angle == 0.0 { 0.0 } else { cells.angle };
    let truth = World {
        format: WORLD_FORMAT.to_string(),
        frame: Frame {
            angle,
            world_size: [config.width, config.height],
            map_size: [cells.map_size.0, cells.map_size.1],
        },
        wall_thickness: 1,
        units,
        doors,
        object_cells: observed.objects,
        // Each truth unit is a room of its own (its id in `labels`): no room layer needed.
        rooms: Vec::new(),
        // The truth explains the building by construction; what a scan leaves outside it is
        // not part of the plan.
        unexplained: Vec::new(),
        placeholders: Vec::new(),
    };
    Ok(Synthetic { map: occupancy_map(map_cells, config.resolution), truth, labels, explored })
}

/// The scan's noise settings of a configuration.
fn noise_of(config: &SynthConfig) -> scan::Noise {
    scan::Noise {
        speckle_occupied: config.speckle_occupied,
        speckle_unknown: config.speckle_unknown,
        wall_roughness: config.wall_roughness,
        // A chance per 5 cm of wall, so per cell at 5 cm (`resolution / GAP_STEP_M` is exactly 1).
        wall_gaps: config.wall_gaps * (config.resolution / scan::GAP_STEP_M),
        clutter: config.clutter,
        peek: config.peek,
        glass: config.glass * config.resolution,
        resolution: config.resolution,
    }
}

/// Two buildings of `config`, the second turned to `second` radians, side by side on one map
/// and joined by a passage ([`wings`]). The truth's frame is the first wing's; the second
/// wing's units and doors lie in the frame [`Frame::turned`] gives for its angle, and its
/// units carry that angle. The passage is not a door of the truth (doors join units of one
/// frame), and the second wing's furniture cells are given in the first wing's frame.
fn generate_wings(
    config: &SynthConfig,
    cells: &config::Cells,
    noise: &scan::Noise,
    second: f64,
    rng: &mut Rng,
) -> Result<Synthetic, SynthError> {
    let mut plans = Vec::new();
    let mut observed = Vec::new();
    let mut explored = Vec::new();
    for _ in 0..2 {
        let plan = layout::plan(cells, config.extra_doors, rng)?;
        let seen = choose_explored(&plan.spaces, config.unexplored, rng);
        observed.push(scan::observe(&plan, &seen, cells, noise, rng));
        explored.extend(seen);
        plans.push(plan);
    }
    let first_units = plans[0].spaces.len();
    let angles = [cells.angle, second];
    let door = (cells.door.lo + cells.door.hi) / 2;
    let composed = wings::compose([&observed[0], &observed[1]], angles, first_units as u16, cells, door);
    let (mw, mh) = (cells.map_size.0 as usize, cells.map_size.1 as usize);
    let mut map_cells = composed.cells.cells().to_vec();
    scan::degrade(&mut map_cells, mw, mh, noise, rng);
    let mut units = Vec::new();
    let mut doors = Vec::new();
    for (k, plan) in plans.iter().enumerate() {
        let (ox, oy) = composed.offsets[k];
        let first_id = units.len() as u32;
        units.extend(plan.spaces.iter().enumerate().map(|(i, s)| {
            let (x, y, w, h) = (s.inner.x - 1 + ox, s.inner.y - 1 + oy, s.inner.w + 2, s.inner.h + 2);
            Unit { angle: (k == 1).then_some(second), ..Unit::new(first_id + i as u32 + 1, x, y, w, h, s.kind) }
        }));
        for o in &plan.openings {
            let d = o.door(doors.len() as u32 + 1, cells.wall);
            let [a, b] = d.units;
            doors.push(super::Door {
                units: [a + first_id, b + first_id],
                x0: d.x0 + ox,
                y0: d.y0 + oy,
                x1: d.x1 + ox,
                y1: d.y1 + oy,
                ..d
            });
        }
    }
    let object_cells = wing_objects(&observed, &composed);
    let frame = composed.frames[0];
    let truth = World {
        format: WORLD_FORMAT.to_string(),
        frame: Frame { angle: if frame.angle == 0.0 { 0.0 } else { frame.angle }, ..frame },
        wall_thickness: 1,
        units,
        doors,
        object_cells,
        rooms: Vec::new(),
        unexplained: Vec::new(),
        placeholders: Vec::new(),
    };
    let labels = composed.labels;
    let map = Grid::from_vec(mw, mh, map_cells).expect("map size");
    Ok(Synthetic { map: occupancy_map(map, config.resolution), truth, labels, explored })
}

/// Both wings' furniture cells in the first wing's frame (through the map), row by row.
fn wing_objects(observed: &[scan::Observed], composed: &wings::Composed) -> Vec<[i32; 2]> {
    let [first, _] = composed.frames;
    let [ww, wh] = first.world_size;
    let mut out = std::collections::BTreeSet::new();
    for (k, o) in observed.iter().enumerate() {
        let (ox, oy) = composed.offsets[k];
        for &[x, y] in &o.objects {
            let (mx, my) = composed.frames[k].to_map((x + ox) as f64 + 0.5, (y + oy) as f64 + 0.5);
            let (wx, wy) = first.to_world(mx, my);
            let (wx, wy) = (libm::floor(wx), libm::floor(wy));
            if wx >= 0.0 && wy >= 0.0 && wx < ww as f64 && wy < wh as f64 {
                out.insert([wy as i32, wx as i32]);
            }
        }
    }
    out.into_iter().map(|[y, x]| [x, y]).collect()
}

/// Picks which units the robot never entered: a fraction of the rooms, halls and "other"
/// units, never a corridor (the robot drives through those).
fn choose_explored(spaces: &[layout::Space], unexplored: f64, rng: &mut Rng) -> Vec<bool> {
    let mut pool: Vec<usize> = (0..spaces.len()).filter(|&i| spaces[i].kind != UnitType::Corridor).collect();
    let n = (libm::round(unexplored * pool.len() as f64) as usize).min(pool.len());
    let mut explored = vec![true; spaces.len()];
    for k in 0..n {
        let j = k + rng.index(pool.len() - k);
        pool.swap(k, j);
        explored[pool[k]] = false;
    }
    explored
}

/// Wraps classified cells as a map in the ROS convention with the given resolution.
fn occupancy_map(cells: Grid<Cell>, resolution: f64) -> OccupancyMap {
    let gray = cells.map(|c| crate::grid::gray_of(*c) as u16 * 257);
    let yaml = MapYaml { resolution, ..MapYaml::for_image("map.pgm") };
    let classifier =
        Classifier::MapServer { negate: false, occupied_thresh: 0.65, free_thresh: 0.196, mode: Mode::Trinary };
    let map = OccupancyMap::from_raster(Raster { gray, alpha: None }, yaml, classifier);
    debug_assert_eq!(map.classified(), &cells);
    map
}
