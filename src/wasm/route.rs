//! Routes in the browser: `planRoute` on a map and a `world.json`, and the coordinate checks
//! that `Plan.route` shares. In the plan module (`ksmcmc_plan.js`). The planning is
//! [`crate::floorplan::route`]'s.

use crate::floorplan::route::{saved_labels, RoutePlanner};
use crate::floorplan::World;
use crate::grid::{pgm, Limits, OccupancyMap};
use wasm_bindgen::prelude::*;

/// A cell coordinate from JavaScript: a whole number (any sign: one off the map is the
/// planner's error, which says where the map ends).
pub(crate) fn coordinate(what: &str, v: f64) -> Result<i64, JsError> {
    if v.is_finite() && v.fract() == 0.0 && v.abs() < 9_007_199_254_740_992.0 {
        Ok(v as i64)
    } else {
        Err(JsError::new(&format!("{what}: {v} is not a cell coordinate; give a whole number of cells")))
    }
}

/// A cell: column and row.
type At = (i64, i64);

/// The start and goal cells of a route from four JavaScript numbers.
pub(crate) fn ends(from_x: f64, from_y: f64, to_x: f64, to_y: f64) -> Result<(At, At), JsError> {
    Ok((
        (coordinate("fromX", from_x)?, coordinate("fromY", from_y)?),
        (coordinate("toX", to_x)?, coordinate("toY", to_y)?),
    ))
}

/// The route from cell (`fromX`, `fromY`) to (`toX`, `toY`) (column, row) through the rooms and
/// doors of `worldJson`, a world made for the map `mapPgm` + `mapYaml` (as the mapper module's
/// `map.toPgm()` and `map.toYaml('map.pgm')` give it), as `ksmcmc route` prints it:
/// `{"rooms": [...], "doors": [...], "path": [[x, y], ...], "length_m": ...}`. `labelsPgm`
/// is the room labels written with the world (`labels.pgm`); without it they are found again
/// from the map and the world. Throws, with the reason, for ends off the map or not free, a
/// goal no free path reaches, or a world or labels of another map.
#[wasm_bindgen(js_name = planRoute)]
#[allow(clippy::too_many_arguments)]
pub fn plan_route(
    #[wasm_bindgen(js_name = mapPgm)] map_pgm: &[u8],
    #[wasm_bindgen(js_name = mapYaml)] map_yaml: &str,
    #[wasm_bindgen(js_name = worldJson)] world_json: &str,
    #[wasm_bindgen(js_name = fromX)] from_x: f64,
    #[wasm_bindgen(js_name = fromY)] from_y: f64,
    #[wasm_bindgen(js_name = toX)] to_x: f64,
    #[wasm_bindgen(js_name = toY)] to_y: f64,
    #[wasm_bindgen(js_name = labelsPgm)] labels_pgm: Option<Vec<u8>>,
) -> Result<String, JsError> {
    let (from, to) = ends(from_x, from_y, to_x, to_y)?;
    let map = &OccupancyMap::from_yaml_and_pgm(map_yaml, map_pgm, &Limits::default())?;
    let world = World::from_json(world_json)?;
    let labels = match labels_pgm {
        Some(bytes) => {
            pgm::decode(&bytes, &Limits::default()).map_err(|e| JsError::new(&format!("labelsPgm: {e}")))?.gray
        }
        None => saved_labels(&world, map)?,
    };
    let mut planner = RoutePlanner::new(map.classified().clone(), labels, &world, map.yaml().resolution)?;
    Ok(planner.route(from, to)?.to_json())
}
