//! A running chain's best world as the room layer and the exports need it, written as JSON
//! text: the hand-off between the browser's WebAssembly modules.
//!
//! The live mapper's chain runs in one module (`ksmcmc.js`), the room layer and everything made
//! from it (`world.json` with its rooms, the labels, GeoJSON, SVG, glTF, routes, the report) in
//! another, loaded when first needed (`ksmcmc_plan.js`), so that a page starts with the
//! smaller one. Modules share no memory: the chain writes what the other needs as text (its
//! typed best world, the edits in force, whether knowledge supervision is on, the units' type
//! marginals and the chain's counts for the report) and the other module finds the rooms from that text and
//! the map, exactly as [`Chain::best_world_with_rooms`] does: the grids are made again as
//! [`Chain::new`] made them ([`RoomInput::for_map`]), and the numbers (the frame's angle, on
//! which the room labels are made, the marginals, the report's) are read back to the bits
//! they were written from (`crate::json::exact`).
//!
//! ```
//! use ksmcmc::floorplan::plan_input::PlanInput;
//! use ksmcmc::floorplan::{rooms::RoomConfig, synth, Chain, ChainConfig};
//! let s = synth::generate(&synth::SynthConfig { width: 160, height: 120, ..Default::default() }, 3).unwrap();
//! let mut chain = Chain::new(&s.map, ChainConfig::default(), 1).unwrap();
//! chain.step(300);
//! let text = PlanInput::of(&mut chain, 0.5).to_json();
//! let input = PlanInput::from_json(&text)?;
//! assert!(input.explain(&s.map, None)? == chain.best_world_with_rooms(&RoomConfig::default()).unwrap());
//! # Ok::<(), ksmcmc::floorplan::plan_input::PlanInputError>(())
//! ```

use super::report::{self, ChainSummary};
use crate::floorplan::edits::{self, Edits};
use crate::floorplan::export::RoomInput;
use crate::floorplan::knowledge::Inferred;
use crate::floorplan::rooms::{RoomConfig, RoomError, RoomLayer};
use crate::floorplan::wings::{wing_rotation_deg, WingConfig, WingLayout};
use crate::floorplan::world::World;
use crate::floorplan::{Chain, DoorSizes};
use crate::grid::{Grid, OccupancyMap};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// The longest plan input text read: a world of [`crate::floorplan::world::MAX_WORLD_JSON_BYTES`] and
/// room for the rest.
pub const MAX_PLAN_INPUT_BYTES: usize = crate::floorplan::world::MAX_WORLD_JSON_BYTES + (1 << 20);

/// What the room layer and the exports need of a chain (see the module docs).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlanInput {
    /// The typed best world ([`Chain::best_world_typed`]), without rooms.
    pub world: World,
    /// The edits in force: the text of the JSON list [`Edits::parse`] reads (default: none).
    #[serde(default = "no_edits")]
    pub edits: String,
    /// Whether knowledge supervision is on: the room rules then decide which units share a
    /// room (default: on, as the chain's default).
    #[serde(default = "on")]
    pub knowledge: bool,
    /// Unit id -> `P(Room)`, `P(Corr)`, `P(Hall)`, `P(Other)` of the best world's inference
    /// ([`Chain::best_world_inferred`]); none when there was none.
    #[serde(default, deserialize_with = "crate::json::exact_map")]
    pub marginals: Option<BTreeMap<u32, [f64; 4]>>,
    /// What `report.json` needs of the chain; none for a world without a chain.
    #[serde(default)]
    pub chain: Option<ChainSummary>,
    /// Seconds the chain spent setting up (orientation, detectors), if known: the report's
    /// `setup_seconds`.
    #[serde(default, deserialize_with = "crate::json::exact_opt")]
    pub setup_seconds: Option<f64>,
    /// The chain's door limits ([`crate::floorplan::ChainConfig::doors`]): the doors found between the
    /// units of two wings ([`PlanInput::explain_wings`]) keep to them too (default: the
    /// default limits).
    #[serde(default)]
    pub doors: DoorSizes,
    /// The chain's room rules ([`crate::floorplan::knowledge::KnowledgeConfig::room_kb`]), if
    /// it was given its own (default: the built-in ones).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub room_kb: Option<String>,
    /// The chain's frontier rules ([`crate::floorplan::knowledge::KnowledgeConfig::frontier_kb`]),
    /// if it was given its own (default: the built-in ones), which weigh the placeholders.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub frontier_kb: Option<String>,
}

fn no_edits() -> String {
    "[]".into()
}

fn on() -> bool {
    true
}

/// Why a plan input was refused, or its world does not fit the map.
#[derive(Debug, Clone, PartialEq)]
pub struct PlanInputError {
    message: String,
}

impl PlanInputError {
    /// The error with `message`, which says what was refused and how to put it right.
    pub(crate) fn new(message: impl Into<String>) -> PlanInputError {
        PlanInputError { message: message.into() }
    }
}

impl std::fmt::Display for PlanInputError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "plan input: {}", self.message)
    }
}

impl std::error::Error for PlanInputError {}

impl PlanInput {
    /// The input of `chain` now, with `seconds` spent iterating for the report.
    pub fn of(chain: &mut Chain, seconds: f64) -> PlanInput {
        let (world, inferred) = chain.best_world_inferred();
        // Inserted one by one: collecting into a map would sort, and each sort is code in the
        // wasm module that ships first.
        let marginals = inferred.map(|i| {
            let mut m = BTreeMap::new();
            for (id, (_, p)) in &i.types {
                m.insert(*id, *p);
            }
            m
        });
        PlanInput {
            world,
            edits: chain.edits().to_json(),
            knowledge: chain.config().knowledge.enabled,
            marginals,
            chain: Some(ChainSummary::of(chain, seconds)),
            setup_seconds: None,
            doors: chain.config().doors,
            room_kb: chain.config().knowledge.room_kb.clone(),
            frontier_kb: chain.config().knowledge.frontier_kb.clone(),
        }
    }

    /// The input as JSON text (pretty, as `world.json`: the same serialiser, no second copy of
    /// its code in the wasm module).
    pub fn to_json(&self) -> String {
        serde_json::to_string_pretty(self).expect("a plan input always serialises")
    }

    /// Reads plan input text: its world is checked as `world.json` is ([`World::validate`]),
    /// its edits as [`Edits::parse`] checks them.
    pub fn from_json(text: &str) -> Result<PlanInput, PlanInputError> {
        if text.len() > MAX_PLAN_INPUT_BYTES {
            return Err(PlanInputError::new(format!(
                "the text is {} bytes, over the limit of {MAX_PLAN_INPUT_BYTES}",
                text.len()
            )));
        }
        let input: PlanInput = serde_json::from_str(text).map_err(|e| PlanInputError::new(e.to_string()))?;
        input.world.validate().map_err(|e| PlanInputError::new(e.to_string()))?;
        input.edits()?;
        Ok(input)
    }

    /// The edits.
    pub fn edits(&self) -> Result<Edits, PlanInputError> {
        Edits::parse(&self.edits).map_err(|e| PlanInputError::new(format!("edits: {e}")))
    }

    /// The inference as [`crate::floorplan::rooms::room_types`] reads it (types from the world).
    pub fn inferred(&self) -> Option<Inferred> {
        let kind = |id: &u32| self.world.units.iter().find(|u| u.id == *id).map(|u| u.kind).unwrap_or_default();
        let types = self.marginals.as_ref()?.iter().map(|(id, p)| (*id, (kind(id), *p))).collect();
        Some(Inferred { types, same_length: Vec::new() })
    }

    /// The world with its room layer and the room labels on `map`, as
    /// [`Chain::best_world_with_rooms`] gives them. While edits are in force, room ids carry
    /// over from the `previous` labels handed out ([`edits::carry_ids`]), as the live mapper's
    /// do from one call to the next. Refused if the world or the edits do not fit the map.
    pub fn explain(
        &self,
        map: &OccupancyMap,
        previous: Option<&Grid<u16>>,
    ) -> Result<(World, Grid<u16>), PlanInputError> {
        let edits = self.edits()?;
        edits.check_map(map.width(), map.height()).map_err(|e| PlanInputError::new(format!("edits: {e}")))?;
        let carry = !edits.is_empty();
        let input = RoomInput::for_map(self.world.clone(), map, self.knowledge, edits)
            .map_err(|e| PlanInputError::new(e.to_string()))?
            .with_room_rules(self.room_kb.clone())
            .with_frontier_rules(self.frontier_kb.clone());
        let (mut world, mut labels) =
            input.explain(&RoomConfig::default()).map_err(|e| PlanInputError::new(e.to_string()))?;
        if let Some(previous) = previous.filter(|_| carry) {
            edits::carry_ids(previous, &mut labels, &mut world.rooms);
        }
        Ok((world, labels))
    }

    /// The wings of the building on `map` (a chain per wing, [`crate::floorplan::wings`]) given the room
    /// `labels` of this input's world ([`PlanInput::explain`]), as `ksmcmc floorplan` finds
    /// them; `None` for a building of one wing, and while edits are in force (the edits are
    /// made on the one chain's world).
    pub fn wing_layout(&self, map: &OccupancyMap, labels: &Grid<u16>) -> Option<WingLayout> {
        if !self.edits().is_ok_and(|e| e.is_empty()) {
            return None;
        }
        WingLayout::find(map, labels, self.world.frame.angle, &WingConfig::default())
    }

    /// The world of a building's wings and its room labels ([`WingLayout::compose`]), as
    /// [`crate::floorplan::wings::Wings::run`] gives them: this input is the first chain's, `wings` the
    /// inputs of the wings' chains, one per wing of [`PlanInput::wing_layout`] in order, each
    /// run on [`WingLayout::wing_map`] with [`WingLayout::wing_config`]. Refused if the map is
    /// one wing, or the wings' chains do not fit its layout.
    pub fn explain_wings(&self, map: &OccupancyMap, wings: &[PlanInput]) -> Result<(World, Grid<u16>), PlanInputError> {
        // One room input for the rooms the rules group and, where they go by the walls, for
        // those: the map turned into the world frame once.
        let input = RoomInput::for_map(self.world.clone(), map, self.knowledge, self.edits()?)
            .map_err(|e| PlanInputError::new(e.to_string()))?
            .with_room_rules(self.room_kb.clone())
            .with_frontier_rules(self.frontier_kb.clone());
        let (world, labels) =
            input.clone().explain(&RoomConfig::default()).map_err(|e| PlanInputError::new(e.to_string()))?;
        let layout = self.wing_layout(map, &labels).ok_or_else(|| {
            PlanInputError::new("wings: this map is explained by one chain (one wall direction, or edits in force)")
        })?;
        if wings.len() != layout.angles.len() {
            return Err(PlanInputError::new(format!(
                "wings: the map has {} wings, but {} wing chains were given",
                layout.angles.len(),
                wings.len()
            )));
        }
        for (k, w) in wings.iter().enumerate() {
            let want = wing_rotation_deg(layout.angles[k]);
            if w.world.frame.angle != want.to_radians() {
                return Err(PlanInputError::new(format!(
                    "wings: wing {k}'s chain is turned by {} degrees, but its direction is {want}: \
                     configure it with detectors.rotation_deg {want}",
                    w.world.frame.angle.to_degrees()
                )));
            }
            w.world.fits(map.width(), map.height()).map_err(|e| PlanInputError::new(format!("wing {k}: {e}")))?;
        }
        let worlds: Vec<World> = wings.iter().map(|w| w.world.clone()).collect();
        let by_walls = move |world: &mut World, others: &[f64]| {
            let (found, labels) = input.by_walls(others).explain(&RoomConfig::default())?;
            *world = found;
            Ok(labels)
        };
        let doors = self.doors.cells(map.yaml().resolution);
        let room_error = |e: RoomError| PlanInputError::new(e.to_string());
        let (mut world, labels) =
            layout.compose(map.classified(), world, labels, &worlds, &doors, by_walls).map_err(room_error)?;
        // Openings need only the layer's lengths, not its rules.
        RoomLayer::without_knowledge(RoomConfig::default()).mark_openings(
            &mut world,
            map.classified(),
            map.yaml().resolution,
        );
        Ok((world, labels))
    }

    /// `report.json` of the chain for `world` (the world with its rooms) and its `labels`, as
    /// `ksmcmc floorplan` writes it ([`report::summary`] of the typed world, then
    /// [`report::add_rooms`]); none without a chain.
    pub fn report(&self, map: &OccupancyMap, world: &World, labels: &Grid<u16>) -> Option<serde_json::Value> {
        let mut r = report::summary_of(self.chain.as_ref()?, map, &self.world);
        report::add_rooms(&mut r, world, labels);
        if let Some(s) = self.setup_seconds {
            r["setup_seconds"] = s.into();
        }
        Some(r)
    }

    /// `report.json` of a building's wings ([`PlanInput::explain_wings`]) for their `world`
    /// and `labels`, as `ksmcmc floorplan` writes it ([`report::add_wings`]): this input is the
    /// first chain's, `wings` the wings' chains'; none without a chain.
    pub fn report_wings(
        &self,
        map: &OccupancyMap,
        world: &World,
        labels: &Grid<u16>,
        wings: &[PlanInput],
    ) -> Option<serde_json::Value> {
        let first = self.chain.as_ref()?;
        let summaries: Option<Vec<ChainSummary>> = wings.iter().map(|w| w.chain.clone()).collect();
        let summaries = summaries?;
        let seconds = first.seconds + summaries.iter().map(|c| c.seconds).sum::<f64>();
        let mut r = report::summary_of(&ChainSummary { seconds, ..first.clone() }, map, world);
        report::add_rooms(&mut r, world, labels);
        report::add_wings(&mut r, world, &summaries, seconds);
        Some(r)
    }
}
