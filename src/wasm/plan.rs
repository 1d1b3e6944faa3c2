//! The floor plan of a best world in the browser: the room layer and everything made from it,
//! as the JavaScript class `Plan` of the plan module (`ksmcmc_plan.js`).
//!
//! The chain runs in the mapper module (`ksmcmc.js`); modules share no memory, so a plan is
//! made from plain inputs: the map as its PGM and YAML, and the text `mapper.planInput()`
//! writes ([`PlanInput`]). The rooms are found as the chain would find them
//! ([`PlanInput::explain`]), so every export is byte for byte what `ksmcmc floorplan` writes
//! after as many iterations with the same seed:
//!
//! ```js
//! const plan = await import('./pkg/ksmcmc_plan.js');
//! await plan.default();
//! const map = mapper.map;                 // the map the chain explains
//! const p = new plan.Plan(map.toPgm(), map.toYaml('map.pgm'), mapper.planInput());
//! p.worldJson(); p.geojson(); p.route(10, 20, 300, 40);
//! // overlay.png: the mapper module draws, this one encodes.
//! const r = renderMapperRgba(mapper, { world: p.worldJson() });
//! const png = plan.encodePng(r.width, r.height, r.rgba);
//! ```
//!
//! The module has no `Map` class, no renderer and no PNG decoder: the pictures are the mapper
//! module's. As in the rest of this layer there is no logic here beyond converting and
//! checking arguments.

use super::route::ends;
use crate::floorplan::geojson::world_geojson;
use crate::floorplan::georef::Georef;
use crate::floorplan::plan_input::PlanInput;
use crate::floorplan::rooms::{room_marginals, room_types};
use crate::floorplan::route::RoutePlanner;
use crate::floorplan::wings::{wing_rotation_deg, WingLayout};
use crate::floorplan::{export, World};
use crate::grid::{Grid, Limits, OccupancyMap};
use crate::render;
use tiny_skia::{ColorU8, Pixmap};
use wasm_bindgen::prelude::*;

fn err(e: impl std::fmt::Display) -> JsError {
    JsError::new(&e.to_string())
}

/// A best world with its room layer, and its exports.
#[wasm_bindgen]
pub struct Plan {
    map: OccupancyMap,
    input: PlanInput,
    /// The world with its rooms.
    world: World,
    labels: Grid<u16>,
    /// The route planner, made by the first route: its room graph and the distances inside
    /// rooms are reused by the next.
    planner: Option<RoutePlanner>,
    /// The wings' chains' inputs this plan was made with (none for one chain).
    wings: Vec<PlanInput>,
    /// The building's wings when it has several and the plan was made without their chains.
    layout: Option<WingLayout>,
}

#[wasm_bindgen]
impl Plan {
    /// The floor plan of `inputJson` (the text of `Mapper.planInput()`, or a `{"world": ...}`
    /// object with a saved typed world) on the map the chain ran on, as its PGM and YAML (the
    /// mapper module's `map.toPgm()` and `map.toYaml('map.pgm')`). While edits are in force,
    /// `previousLabels` (the `roomLabels()` of the plan shown before) keeps the rooms' ids.
    ///
    /// A building whose walls follow several directions is explained wing by wing, as
    /// `ksmcmc floorplan` does: a plan made without `wingInputs` says how many wing chains it
    /// needs (`wingCount`); run a `Mapper` on each wing's map (`wingMapPgm(k)` with the same
    /// YAML) turned by its direction (`detectors.rotation_deg` = `wingRotationDeg(k)` in its
    /// `configJson`, the rest as the first chain's), with the first chain's seed and
    /// iterations, and pass their `planInput()` texts in order as `wingInputs`: the plan is
    /// then `ksmcmc floorplan`'s, units at their angles.
    ///
    /// Throws if the map, the input or the labels are not valid, the input was made on
    /// another map, or the wings' inputs do not fit the building's wings.
    #[wasm_bindgen(constructor)]
    pub fn new(
        #[wasm_bindgen(js_name = mapPgm)] map_pgm: &[u8],
        #[wasm_bindgen(js_name = mapYaml)] map_yaml: &str,
        #[wasm_bindgen(js_name = inputJson)] input_json: &str,
        #[wasm_bindgen(js_name = previousLabels)] previous_labels: Option<Vec<u16>>,
        #[wasm_bindgen(js_name = wingInputs)] wing_inputs: Option<Vec<String>>,
    ) -> Result<Plan, JsError> {
        let map = OccupancyMap::from_yaml_and_pgm(map_yaml, map_pgm, &Limits::default())?;
        let input = PlanInput::from_json(input_json).map_err(err)?;
        let previous = match previous_labels {
            Some(cells) => Some(Grid::from_vec(map.width(), map.height(), cells).ok_or_else(|| {
                JsError::new(&format!(
                    "previousLabels: give the {} room ids of the map's cells",
                    map.width() * map.height()
                ))
            })?),
            None => None,
        };
        let wings = wing_inputs.unwrap_or_default();
        let wings: Vec<PlanInput> = wings
            .iter()
            .enumerate()
            .map(|(k, text)| PlanInput::from_json(text).map_err(|e| JsError::new(&format!("wingInputs[{k}]: {e}"))))
            .collect::<Result<_, _>>()?;
        if !wings.is_empty() {
            let (world, labels) = input.explain_wings(&map, &wings).map_err(err)?;
            return Ok(Plan { map, input, world, labels, planner: None, wings, layout: None });
        }
        let (world, labels) = input.explain(&map, previous.as_ref()).map_err(err)?;
        let layout = input.wing_layout(&map, &labels);
        Ok(Plan { map, input, world, labels, planner: None, wings, layout })
    }

    /// How many wing chains the building needs before the plan is `ksmcmc floorplan`'s (see
    /// the constructor): 0 for a building of one wall direction, while edits are in force, and
    /// for a plan made with its wings' inputs.
    #[wasm_bindgen(getter, js_name = wingCount)]
    pub fn wing_count(&self) -> u32 {
        self.layout.as_ref().map_or(0, |l| l.angles.len() as u32)
    }

    /// The map wing `k`'s chain explains, as PGM bytes (with the map's YAML): the other
    /// wings' free cells unknown. Throws for `k` not below `wingCount`.
    #[wasm_bindgen(js_name = wingMapPgm)]
    pub fn wing_map_pgm(&self, k: u32) -> Result<Vec<u8>, JsError> {
        Ok(self.layout(k)?.wing_map(&self.map, k as usize).to_pgm())
    }

    /// Wing `k`'s direction in degrees: its chain's `detectors.rotation_deg`. Throws for `k`
    /// not below `wingCount`.
    #[wasm_bindgen(js_name = wingRotationDeg)]
    pub fn wing_rotation_deg(&self, k: u32) -> Result<f64, JsError> {
        Ok(wing_rotation_deg(self.layout(k)?.angles[k as usize]))
    }

    /// The world with its rooms as `world.json` text: what `ksmcmc floorplan` writes.
    #[wasm_bindgen(js_name = worldJson)]
    pub fn world_json(&self) -> String {
        self.world.to_json()
    }

    /// The rooms as JSON text: the `rooms` of `world.json`, each with its `id` (its value in
    /// `labelsPgm`), `type`, `units`, `area_m2`, `doors` and `opens_to`.
    #[wasm_bindgen(js_name = roomsJson)]
    pub fn rooms_json(&self) -> String {
        export::rooms_json(&self.world)
    }

    /// The placeholders as JSON text: the `placeholders` of `world.json` (`[]` for a map with
    /// no frontier), each with its `id`, its cell `x`, `y` (column, row), `width_m`, the `room`
    /// it opens from (0: none), `p_new_room` (the probability that it leads to a room not yet
    /// in the map) and `types` (`{"room", "corridor", "hall", "other"}`, the probability of each
    /// for the space beyond, summing to 1).
    #[wasm_bindgen(js_name = placeholdersJson)]
    pub fn placeholders_json(&self) -> String {
        export::placeholders_json(&self.world)
    }

    /// The room segmentation as a 16-bit binary PGM of the map's size (room id per free cell,
    /// 0 elsewhere): `labels.pgm` of `ksmcmc floorplan`.
    #[wasm_bindgen(js_name = labelsPgm)]
    pub fn labels_pgm(&self) -> Vec<u8> {
        export::labels_pgm(&self.labels)
    }

    /// The room of every map cell, row-major (`width` x `height` values): the room's id as in
    /// `roomsJson`, 0 for none. The samples of `labelsPgm`.
    #[wasm_bindgen(js_name = roomLabels)]
    pub fn room_labels(&self) -> Vec<u16> {
        self.labels.cells().to_vec()
    }

    /// What the knowledge base believes about each room's type, as JSON text: per room of
    /// `roomsJson` (same order), `{"id", "marginals": {"room", "corridor", "hall", "other"} |
    /// null, "units": [{"id", "type", "marginals"}]}`. With knowledge supervision a room's
    /// marginals are `P(Room)`, `P(Corr)`, `P(Hall)` and `P(Other)` of the indoor rules applied
    /// to the room as one space (which make its type, but for a room of rays, typed unknown
    /// whatever they say); without, its units' averaged by their interiors' areas. The four
    /// are separate atoms of the knowledge base and need not add up to 1.
    #[wasm_bindgen(js_name = roomTypesJson)]
    pub fn room_types_json(&self) -> String {
        let resolution = self.map.yaml().resolution;
        let own = if self.input.knowledge {
            room_marginals(&self.world, &self.world.rooms, &self.labels, resolution, &Default::default())
                .unwrap_or_default()
        } else {
            Default::default()
        };
        export::room_types_json(&room_types(&self.world, &self.input.inferred().unwrap_or_default(), &own))
    }

    /// The scene graph as `graph.json` text: `{"nodes": [{"id", "type"}], "edges": [{"from",
    /// "to", "kind", "door"?}], "rooms": [...]}`.
    #[wasm_bindgen(js_name = graphJson)]
    pub fn graph_json(&self) -> String {
        export::graph_json(&self.world)
    }

    /// The rooms and doors as `world.geojson` text (an RFC 7946 FeatureCollection in IMDF
    /// shape), what `ksmcmc floorplan` writes. Coordinates are metres in the map's frame, or
    /// longitude/latitude with `georef`, `"LAT,LON,BEARING"` in degrees as the CLI's
    /// `--georef` (throws if it is not).
    pub fn geojson(
        &self,
        #[wasm_bindgen(unchecked_optional_param_type = "string")] georef: Option<String>,
    ) -> Result<String, JsError> {
        let georef = match georef.as_deref() {
            Some(text) => Some(text.parse::<Georef>().map_err(|e| JsError::new(&format!("georef: {e}")))?),
            None => None,
        };
        Ok(world_geojson(&self.world, &self.labels, &self.map, georef.as_ref())?)
    }

    /// The plan as `world.svg` text: a vector drawing in map cells, with layers `rooms`,
    /// `walls`, `doors` and `labels`; what `ksmcmc floorplan` writes.
    pub fn svg(&self) -> Result<String, JsError> {
        Ok(render::svg::world_svg(&self.world, &self.labels, self.map.yaml().resolution)?)
    }

    /// The plan in 3D, as the `world.glb` (glTF 2.0 binary) `ksmcmc floorplan` writes: walls
    /// with openings at the doors, a floor slab per room in its type's colour, metres, Y up.
    /// `options`: `{ wallHeight?: number = 2.5, doorHeight?: number = 2.0 }` in metres;
    /// out-of-range heights are errors.
    #[wasm_bindgen(js_name = worldGlb)]
    pub fn world_glb(
        &self,
        #[wasm_bindgen(unchecked_optional_param_type = "{ wallHeight?: number; doorHeight?: number }")] options: Option<
            JsValue,
        >,
    ) -> Result<Vec<u8>, JsError> {
        let options = super::model3d::options(options.as_ref())?;
        Ok(render::model3d::world_glb(&self.world, self.map.yaml().resolution, &options)?)
    }

    /// The route from cell (`fromX`, `fromY`) to (`toX`, `toY`) (column, row) through the
    /// rooms and doors, as JSON text: `{"rooms": [...], "doors": [...], "path": [[x, y], ...],
    /// "length_m": ...}`, what `ksmcmc route` prints for `worldJson` and `labelsPgm`. Throws,
    /// with the reason, for ends off the map or not free, or a goal no free path reaches.
    pub fn route(
        &mut self,
        #[wasm_bindgen(js_name = fromX)] from_x: f64,
        #[wasm_bindgen(js_name = fromY)] from_y: f64,
        #[wasm_bindgen(js_name = toX)] to_x: f64,
        #[wasm_bindgen(js_name = toY)] to_y: f64,
    ) -> Result<String, JsError> {
        let (from, to) = ends(from_x, from_y, to_x, to_y)?;
        if self.planner.is_none() {
            let (map, labels) = (self.map.classified().clone(), self.labels.clone());
            self.planner = Some(RoutePlanner::new(map, labels, &self.world, self.map.yaml().resolution)?);
        }
        let planner = self.planner.as_mut().expect("just made");
        Ok(planner.route(from, to)?.to_json())
    }

    /// A summary of the run as JSON text, with the fields of `ksmcmc floorplan`'s
    /// `report.json` (the map's path aside): iterations, seconds, K(W,M), confusion counts,
    /// units, doors, rooms, best log posterior and iteration, seed, rotation, wall thickness
    /// and per-kernel counts. Throws for a plan of a saved world (no chain, no report).
    #[wasm_bindgen(js_name = reportJson)]
    pub fn report_json(&self) -> Result<String, JsError> {
        let r = if self.wings.is_empty() {
            self.input.report(&self.map, &self.world, &self.labels)
        } else {
            self.input.report_wings(&self.map, &self.world, &self.labels, &self.wings)
        };
        let r = r.ok_or_else(|| {
            JsError::new("reportJson: this plan was made without a chain; make it from mapper.planInput()")
        })?;
        Ok(export::report_json(&r))
    }
}

impl Plan {
    /// The wings' layout, if wing `k` is one of them.
    fn layout(&self, k: u32) -> Result<&WingLayout, JsError> {
        self.layout
            .as_ref()
            .filter(|l| (k as usize) < l.angles.len())
            .ok_or_else(|| JsError::new(&format!("wing {k}: this plan needs {} wing chains", self.wing_count())))
    }
}

/// Straight (not premultiplied) RGBA pixels, `4 * width * height` bytes as the mapper
/// module's `renderMapperRgba` and `renderRgba` give them, as PNG bytes: the encoder of
/// `ksmcmc floorplan`, so an opaque picture (every picture of a map is) gives its bytes:
/// `renderMapperRgba(mapper, { world: plan.worldJson() })` encoded is its `overlay.png`.
#[wasm_bindgen(js_name = encodePng)]
pub fn encode_png(width: u32, height: u32, rgba: &[u8]) -> Result<Vec<u8>, JsError> {
    if width == 0 || height == 0 || rgba.len() as u64 != 4 * width as u64 * height as u64 {
        return Err(JsError::new(&format!(
            "encodePng: a {width}x{height} picture needs {} bytes of RGBA, but {} were given",
            4 * width as u64 * height as u64,
            rgba.len()
        )));
    }
    let mut data = Vec::with_capacity(rgba.len());
    for p in rgba.chunks_exact(4) {
        let c = ColorU8::from_rgba(p[0], p[1], p[2], p[3]).premultiply();
        data.extend_from_slice(&[c.red(), c.green(), c.blue(), c.alpha()]);
    }
    let size = tiny_skia::IntSize::from_wh(width, height).ok_or_else(|| JsError::new("encodePng: bad size"))?;
    let pixmap = Pixmap::from_vec(data, size).ok_or_else(|| JsError::new("encodePng: bad size"))?;
    Ok(render::encode_png(&pixmap))
}

/// The scene graph of any `world.json` text as `graph.json` text (as `Plan.graphJson` gives
/// it for a plan): e.g. of a `Mapper`'s current world, `graphJson(mapper.worldJson())`.
#[wasm_bindgen(js_name = graphJson)]
pub fn graph_json(#[wasm_bindgen(js_name = worldJson)] world_json: &str) -> Result<String, JsError> {
    Ok(export::graph_json(&World::from_json(world_json)?))
}
