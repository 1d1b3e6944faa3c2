//! The summary of a run, `report.json`, shared by the command line and the browser so that
//! both write the same fields.

use crate::floorplan::metrics;
use crate::floorplan::metrics::defects;
use crate::floorplan::schedule::Kernel;
use crate::floorplan::world::World;
use crate::floorplan::{Chain, RunRecord};
use crate::grid::{Grid, OccupancyMap};
use crate::vision::orientation::WallProfile;
use serde::{Deserialize, Serialize};

/// `report.json` for a chain's typed best `world` on `map`, with its room `labels` and the
/// `seconds` spent iterating: iterations and speed, K(W,M) and the confusion counts, units,
/// doors, unexplained areas ("N") and their cells, rooms, types, defects, log posterior, seed,
/// rotation, the directions the map's walls follow (`wall_directions`, strongest first: units
/// follow only the rotation, so several directions say where they fit badly), wall thickness,
/// knowledge status and per-kernel counts.
pub fn report(chain: &Chain, map: &OccupancyMap, world: &World, labels: &Grid<u16>, seconds: f64) -> serde_json::Value {
    let mut r = summary(chain, map, world, seconds);
    add_rooms(&mut r, world, labels);
    r
}

/// Sets `rooms` (the room layer's count, or the labels' when the world has no room layer),
/// `room_types` (rooms per type), `openings` (doors that are openings within a room) and
/// `doors_in_one_room` (doors whose two units the room layer put in one room, openings
/// aside) in a report.
pub fn add_rooms(r: &mut serde_json::Value, world: &World, labels: &Grid<u16>) {
    r["rooms"] = if world.rooms.is_empty() {
        labels.cells().iter().copied().max().unwrap_or(0) as usize
    } else {
        world.rooms.len()
    }
    .into();
    let mut types = std::collections::BTreeMap::new();
    for room in &world.rooms {
        *types.entry(room.kind.name()).or_insert(0u32) += 1;
    }
    r["room_types"] = serde_json::json!(types);
    // Doors within one room (crate::floorplan::openings): openings, and doors of rooms merged across them.
    r["openings"] = world.doors.iter().filter(|d| d.opening).count().into();
    r["doors_in_one_room"] = crate::floorplan::rooms::doors_in_one_room(world).into();
}

/// [`report`] without `rooms`, which needs the room labels: a caller short of memory can
/// drop the chain before computing them ([`crate::floorplan::export::RoomInput`]) and then
/// [`add_rooms`]. `map` is the map the chain was made for: the wall directions are read off
/// the chain's own Hough profile ([`Chain::wall_profile`]) when it has one.
pub fn summary(chain: &impl RunRecord, map: &OccupancyMap, world: &World, seconds: f64) -> serde_json::Value {
    report_of(&ChainSummary::of(chain, seconds), map, world, chain.wall_profile())
}

/// What `report.json` needs of the chain itself: its counts, times, seed, frame and knowledge
/// status. A plain record, so that a caller without the chain (the browser's plan module,
/// [`super::plan_input`]) can make the report from it, the map and the world.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ChainSummary {
    /// Iterations run.
    pub iterations: u64,
    /// Seconds spent iterating.
    #[serde(deserialize_with = "crate::json::exact")]
    pub seconds: f64,
    /// The best log posterior and the iteration it was found at.
    #[serde(deserialize_with = "crate::json::exact")]
    pub log_posterior: f64,
    /// The iteration of the best world.
    pub best_iteration: u64,
    /// The chain's seed.
    pub seed: u64,
    /// The map's rotation, degrees.
    #[serde(deserialize_with = "crate::json::exact")]
    pub rotation_deg: f64,
    /// Depth of the units' wall rings, cells.
    pub wall_thickness: i32,
    /// Whether knowledge supervision is on, why it failed if it did, and how many inferences ran.
    pub knowledge: bool,
    /// Why the knowledge base failed, if it did.
    pub knowledge_error: Option<String>,
    /// Markov logic inferences run (cache misses).
    pub inferences: u64,
    /// Unit pairs the last inference found of the same length.
    pub same_length_pairs: usize,
    /// Proposals and acceptances per kernel, in the order of [`Kernel::ALL`].
    pub proposed: Vec<u64>,
    /// Acceptances per kernel, in the order of [`Kernel::ALL`].
    pub accepted: Vec<u64>,
}

impl ChainSummary {
    /// The summary of `chain` with `seconds` spent iterating.
    pub fn of(chain: &impl RunRecord, seconds: f64) -> ChainSummary {
        let t = chain.trace();
        ChainSummary {
            iterations: chain.iteration(),
            seconds,
            log_posterior: chain.best_log_posterior(),
            best_iteration: chain.best_iteration(),
            seed: chain.seed(),
            rotation_deg: chain.frame().angle.to_degrees(),
            wall_thickness: chain.wall_thickness(),
            knowledge: chain.config().knowledge.enabled,
            knowledge_error: chain.knowledge_error().map(str::to_string),
            inferences: chain.inferences(),
            same_length_pairs: chain.inferred().same_length.len(),
            proposed: Kernel::ALL.iter().map(|k| t.proposed[k.index()]).collect(),
            accepted: Kernel::ALL.iter().map(|k| t.accepted[k.index()]).collect(),
        }
    }
}

/// Adds a building's wings to the `report` of its first chain ([`crate::floorplan::wings`]): their
/// chains' summaries, one per wing in order, each with its direction, iterations and the
/// units of `world` it explains (the first wing's units are those without an angle of their
/// own), and `iterations` and `iterations_per_second` over all the chains in `seconds`.
/// Nothing for a building of one wing.
///
/// ```
/// use ksmcmc::floorplan::report::{add_wings, ChainSummary};
/// use ksmcmc::floorplan::{Unit, UnitType, World};
/// let mut world = World::empty(100, 100);
/// world.units = vec![Unit::new(1, 0, 0, 20, 20, UnitType::Room), Unit::new(2, 30, 0, 20, 20, UnitType::Room)];
/// world.units[1].angle = Some(0.5);
/// let chain = |rotation_deg: f64, iterations| ChainSummary {
///     iterations, seconds: 1.0, log_posterior: 0.0, best_iteration: 0, seed: 1, rotation_deg,
///     wall_thickness: 1, knowledge: false, knowledge_error: None, inferences: 0,
///     same_length_pairs: 0, proposed: vec![], accepted: vec![],
/// };
/// let mut report = serde_json::json!({"iterations": 100});
/// add_wings(&mut report, &world, &[chain(0.0, 100), chain(0.5f64.to_degrees(), 100)], 2.0);
/// assert_eq!(report["iterations"], 300); // the first chain's and the wings'
/// assert_eq!(report["wings"][1]["units"], 1);
/// ```
pub fn add_wings(report: &mut serde_json::Value, world: &World, wings: &[ChainSummary], seconds: f64) {
    if wings.len() < 2 {
        return;
    }
    let first = report["iterations"].as_u64().unwrap_or(0);
    let iterations = first + wings.iter().map(|c| c.iterations).sum::<u64>();
    let per_wing: Vec<serde_json::Value> = wings
        .iter()
        .enumerate()
        .map(|(k, c)| {
            let units = world
                .units
                .iter()
                .filter(|u| u.angle.map_or(k == 0, |a| k > 0 && a.to_degrees() == c.rotation_deg))
                .count();
            serde_json::json!({"rotation_deg": c.rotation_deg, "iterations": c.iterations, "units": units})
        })
        .collect();
    report["iterations"] = iterations.into();
    report["iterations_per_second"] = (iterations as f64 / seconds.max(1e-9)).into();
    report["wings"] = per_wing.into();
}

/// A note for a report whose map has walls in several directions: whether its wings were
/// explained each in its own direction (`report.json`'s `wings`, [`crate::floorplan::wings`]) or the
/// units follow the map's one rotation; `None` for one direction or none.
///
/// ```
/// use ksmcmc::floorplan::report::several_directions_note;
/// let one = serde_json::json!({"wall_directions": [{"angle_deg": 0.0, "strength": 1.0}]});
/// assert_eq!(several_directions_note(&one), None);
/// let two = serde_json::json!({"wall_directions": [
///     {"angle_deg": 1.8, "strength": 1.0}, {"angle_deg": -43.5, "strength": 0.55}]});
/// let note = several_directions_note(&two).unwrap();
/// assert!(note.contains("2 directions (1.8°, -43.5°)") && note.contains("only the first"), "{note}");
/// let mut wings = two.clone();
/// wings["wings"] = serde_json::json!([{"rotation_deg": 1.8}, {"rotation_deg": -43.5}]);
/// assert!(several_directions_note(&wings).unwrap().contains("2 wings were explained"));
/// ```
pub fn several_directions_note(r: &serde_json::Value) -> Option<String> {
    let angles: Vec<f64> = r["wall_directions"].as_array()?.iter().filter_map(|d| d["angle_deg"].as_f64()).collect();
    if angles.len() < 2 {
        return None;
    }
    let list: Vec<String> = angles.iter().map(|a| format!("{a:.1}°")).collect();
    let what = match r["wings"].as_array() {
        Some(wings) if wings.len() > 1 => format!(
            "{} wings were explained each in its own direction, their units at their angles in every output",
            wings.len()
        ),
        _ => "the units follow only the first, so rooms along the others are explained by several rectangles and \
              may come out cut in pieces"
            .into(),
    };
    Some(format!("note: the walls of this map follow {} directions ({}); {what}", angles.len(), list.join(", ")))
}

/// The least strength of a wall direction `report.json` lists
/// ([`crate::vision::orientation::wall_directions`]): 0.3 of the strongest.
pub const MIN_DIRECTION: f64 = 0.3;

/// [`summary`] from a chain's [`ChainSummary`].
pub fn summary_of(c: &ChainSummary, map: &OccupancyMap, world: &World) -> serde_json::Value {
    report_of(c, map, world, None)
}

/// [`summary_of`], the wall directions read off `walls` (the chain's [`WallProfile`] of `map`)
/// when given, else found on `map`.
fn report_of(c: &ChainSummary, map: &OccupancyMap, world: &World, walls: Option<&WallProfile>) -> serde_json::Value {
    let count = |v: &[u64], i: usize| v.get(i).copied().unwrap_or(0);
    let kernels: serde_json::Map<String, serde_json::Value> = Kernel::ALL
        .iter()
        .enumerate()
        .map(|(i, k)| {
            let (proposed, accepted) = (count(&c.proposed, i), count(&c.accepted, i));
            (k.name().to_lowercase(), serde_json::json!({"proposed": proposed, "accepted": accepted}))
        })
        .collect();
    // K(W, M) is the confusion matrix's diagonal over its total: one prediction of the map.
    let confusion = metrics::confusion(map.classified(), world);
    let total: u64 = confusion.iter().flatten().sum();
    let hits: u64 = (0..3).map(|c| confusion[c][c]).sum();
    let cell_prediction_rate = if total == 0 { 0.0 } else { hits as f64 / total as f64 };
    let mut types = std::collections::BTreeMap::new();
    for u in &world.units {
        *types.entry(u.kind.name()).or_insert(0u32) += 1;
    }
    let found = match walls {
        Some(w) => w.directions(MIN_DIRECTION),
        None => crate::vision::orientation::wall_directions(map.classified(), MIN_DIRECTION),
    };
    let directions: Vec<serde_json::Value> =
        found.iter().map(|d| serde_json::json!({"angle_deg": d.angle.to_degrees(), "strength": d.strength})).collect();
    serde_json::json!({
        "iterations": c.iterations,
        "seconds": c.seconds,
        "iterations_per_second": c.iterations as f64 / c.seconds.max(1e-9),
        "cell_prediction_rate": cell_prediction_rate,
        "confusion": confusion,
        "units": world.units.len(),
        "doors": world.doors.len(),
        "unexplained_areas": world.unexplained.len(),
        "unexplained_cells": world.unexplained.iter().map(|a| a.cells as u64).sum::<u64>(),
        "types": types,
        "defects": defects(world),
        "log_posterior": c.log_posterior,
        "best_iteration": c.best_iteration,
        "seed": c.seed,
        "rotation_deg": c.rotation_deg,
        "wall_directions": directions,
        "wall_thickness": c.wall_thickness,
        "knowledge": c.knowledge,
        "knowledge_error": c.knowledge_error,
        "inferences": c.inferences,
        "same_length_pairs": c.same_length_pairs,
        "kernels": kernels,
    })
}
