//! The summary of a run, `report.json`, shared by the command line and the browser so that
//! both write the same fields.

use super::metrics;
use super::metrics::defects;
use super::schedule::Kernel;
use super::world::World;
use super::Chain;
use crate::grid::{Grid, OccupancyMap};

/// `report.json` for a chain's typed best `world` on `map`, with its room `labels` and the
/// `seconds` spent iterating: iterations and speed, K(W,M) and the confusion counts, units,
/// doors, unexplained areas ("N") and their cells, rooms, types, defects, log posterior, seed, rotation, wall thickness, knowledge
/// status and per-kernel counts.
pub fn report(chain: &Chain, map: &OccupancyMap, world: &World, labels: &Grid<u16>, seconds: f64) -> serde_json::Value {
    let mut r = summary(chain, map, world, seconds);
    add_rooms(&mut r, world, labels);
    r
}

/// Sets `rooms` (the room layer's count, or the labels' when the world has no room layer)
/// and `room_types` (rooms per type) in a report.
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
}

/// [`report`] without `rooms`, which needs the room labels: a caller short of memory can
/// drop the chain before computing them ([`super::export::RoomInput`]) and then
/// [`add_rooms`].
pub fn summary(chain: &Chain, map: &OccupancyMap, world: &World, seconds: f64) -> serde_json::Value {
    let t = chain.trace();
    let kernels: serde_json::Map<String, serde_json::Value> = Kernel::ALL
        .iter()
        .map(|k| {
            (
                k.name().to_lowercase(),
                serde_json::json!({"proposed": t.proposed[k.index()], "accepted": t.accepted[k.index()]}),
            )
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
    serde_json::json!({
        "iterations": chain.iteration(),
        "seconds": seconds,
        "iterations_per_second": chain.iteration() as f64 / seconds.max(1e-9),
        "cell_prediction_rate": cell_prediction_rate,
        "confusion": confusion,
        "units": world.units.len(),
        "doors": world.doors.len(),
        "unexplained_areas": world.unexplained.len(),
        "unexplained_cells": world.unexplained.iter().map(|a| a.cells as u64).sum::<u64>(),
        "types": types,
        "defects": defects(world),
        "log_posterior": chain.best_log_posterior(),
        "best_iteration": chain.best_iteration(),
        "seed": chain.seed(),
        "rotation_deg": chain.frame().angle.to_degrees(),
        "wall_thickness": chain.wall_thickness(),
        "knowledge": chain.config().knowledge.enabled,
        "knowledge_error": chain.knowledge_error(),
        "inferences": chain.inferences(),
        "same_length_pairs": chain.inferred().same_length.len(),
        "kernels": kernels,
    })
}
