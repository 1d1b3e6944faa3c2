//! The room rules: a Markov logic network that decides which units with no wall between them
//! are one room (query `SameRoom`), and the evidence it is given about a world.

use super::pairs::OpenPair;
use crate::floorplan::knowledge::{constant, Fact, KnowledgeConfig, TYPE_PREDICATES};
use crate::floorplan::world::{UnitType, World};
use crate::mln::{Database, Evidence, GroundConfig, InferenceConfig, Mln, MlnError, Network};

/// The built-in room rules (`samples/knowledge/rooms.mln`, weights set by hand; the same
/// rules with weights learned from generated floors are `rooms-learned.mln`).
pub const BUILTIN_ROOM_RULES: &str = include_str!("../../../samples/knowledge/rooms.mln");

/// The unit-type evidence predicates of the room rules, with the type each stands for.
const TYPES: [(&str, UnitType); 4] = TYPE_PREDICATES;

/// A knowledge base that decides which open-adjacent units are one room (query `SameRoom`).
#[derive(Debug, Clone)]
pub struct RoomKnowledge {
    mln: Mln,
    /// The indoor rules and geometry classifier that type the rooms
    /// ([`super::types::type_rooms`]).
    types: KnowledgeConfig,
}

impl RoomKnowledge {
    /// The indoor rules and geometry classifier that type the rooms.
    pub(crate) fn types(&self) -> &KnowledgeConfig {
        &self.types
    }

    /// The built-in rules.
    pub fn builtin() -> RoomKnowledge {
        RoomKnowledge::parse(BUILTIN_ROOM_RULES).expect("the built-in room rules parse")
    }

    /// The rules of a knowledge configuration: its `room_kb`, or the built-in ones; its
    /// indoor knowledge base and geometry classifier type the rooms.
    pub fn configured(config: &KnowledgeConfig) -> Result<RoomKnowledge, MlnError> {
        let mut k = RoomKnowledge::parse(config.room_kb.as_deref().unwrap_or(BUILTIN_ROOM_RULES))?;
        k.types = config.clone();
        Ok(k)
    }

    /// Rules from text: they must declare `SameRoom(unit, unit)`; they may use the evidence
    /// predicates `Open`, `Flush`, `Closed`, `Room`, `Corr`, `Hall` and `Other`. The built-in
    /// indoor rules type the rooms.
    pub fn parse(text: &str) -> Result<RoomKnowledge, MlnError> {
        let mln = Mln::parse(text)?;
        crate::floorplan::knowledge::check_room_rules(&mln)?;
        Ok(RoomKnowledge { mln, types: Default::default() })
    }

    /// `P(SameRoom)` of every pair in `pairs` (unit indices into `world.units`), in order, with
    /// `SameRoom` evidence: `given` lists unit index pairs with their value (a person's merge
    /// or split, [`crate::floorplan::edits`]).
    pub(crate) fn same_room_given(
        &self,
        world: &World,
        pairs: &[OpenPair],
        given: &[(usize, usize, bool)],
    ) -> Result<Vec<f64>, MlnError> {
        if pairs.is_empty() {
            return Ok(Vec::new());
        }
        let mut db = Database::new();
        let mut closed = Vec::new();
        for pred in TYPES.iter().map(|t| t.0).chain(["Open", "Flush", "Closed"]) {
            if self.mln.predicate(pred).is_some() {
                closed.push(pred.to_string());
            }
        }
        for (pred, args, _) in room_evidence(world, pairs) {
            if self.mln.predicate(pred).is_some() {
                let args: Vec<&str> = args.iter().map(String::as_str).collect();
                db.insert(&self.mln, pred, &args, Evidence::True)?;
            }
        }
        for &(a, b, value) in given {
            let (a, b) = (constant(world.units[a].id), constant(world.units[b].id));
            let v = if value { Evidence::True } else { Evidence::False };
            db.insert(&self.mln, "SameRoom", &[&a, &b], v)?;
            db.insert(&self.mln, "SameRoom", &[&b, &a], v)?;
        }
        let mut ground = GroundConfig::query(&["SameRoom"]);
        ground.closed_world = closed;
        let units: Vec<String> = world.units.iter().map(|u| constant(u.id)).collect();
        if let Some(ty) = self.mln.predicate("SameRoom").and_then(|p| self.mln.argument_types(p).first().cloned()) {
            ground.domains.push((ty.to_string(), units));
        }
        let net = Network::ground(&self.mln, &db, &ground)?;
        let marginals = net.infer_marginals(&InferenceConfig::default())?;
        Ok(pairs
            .iter()
            .map(|p| {
                let (a, b) = (constant(world.units[p.a].id), constant(world.units[p.b].id));
                marginals.get("SameRoom", &[a.as_str(), b.as_str()]).unwrap_or(0.0)
            })
            .collect())
    }
}

/// The evidence the room rules are given about `world` and its open pairs `pairs` (unit
/// indices, [`open_pairs`]), units named by [`constant`]: each typed unit's type predicate
/// (`Room`, `Corr`, `Hall`, `Other`) and `Open` (and `Flush` where the pair is flush) of every
/// pair both ways. Only true facts: the evidence is closed world, so it grows with the units
/// and their open pairs, never with all pairs of units.
pub(crate) fn room_evidence(world: &World, pairs: &[OpenPair]) -> Vec<Fact> {
    let mut facts = Vec::new();
    for u in &world.units {
        if let Some((pred, _)) = TYPES.iter().find(|t| t.1 == u.kind) {
            facts.push((*pred, vec![constant(u.id)], true));
        }
    }
    for p in pairs {
        let (a, b) = (constant(world.units[p.a].id), constant(world.units[p.b].id));
        for (x, y) in [(&a, &b), (&b, &a)] {
            facts.push(("Open", vec![x.clone(), y.clone()], true));
            if p.flush {
                facts.push(("Flush", vec![x.clone(), y.clone()], true));
            }
            if p.closed {
                facts.push(("Closed", vec![x.clone(), y.clone()], true));
            }
        }
    }
    facts
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::floorplan::Unit;

    #[test]
    fn evidence_is_the_types_and_the_open_pairs_both_ways() {
        let mut world = World::empty(80, 40);
        for (id, x) in [(1, 0), (2, 40)] {
            world.units.push(Unit::new(id, x, 0, 40, 40, UnitType::Room));
        }
        let facts = room_evidence(&world, &[OpenPair { a: 0, b: 1, flush: true, closed: false }]);
        let text: Vec<String> = facts.iter().map(|(p, a, _)| format!("{p}({})", a.join(","))).collect();
        assert_eq!(text, ["Room(U1)", "Room(U2)", "Open(U1,U2)", "Flush(U1,U2)", "Open(U2,U1)", "Flush(U2,U1)"]);
    }
}
