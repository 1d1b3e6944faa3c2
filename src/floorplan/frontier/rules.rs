//! The frontier rules: a Markov logic network that says what lies beyond each placeholder
//! (query `NewRoom` and the `Beyond*` kinds), and the evidence it is given.

use super::stretches::Stretch;
use crate::floorplan::world::{UnitType, World};
use crate::mln::{Database, Evidence, GroundConfig, InferenceConfig, Mln, MlnError, Network};

/// The hand-weighted frontier rules (`samples/knowledge/frontier.mln`).
pub const FRONTIER_RULES: &str = include_str!("../../../samples/knowledge/frontier.mln");

/// The built-in frontier rules: the same rules with weights learned from simulated
/// explorations of generated floors (`samples/knowledge/frontier-learned.mln`).
pub const BUILTIN_FRONTIER_RULES: &str = include_str!("../../../samples/knowledge/frontier-learned.mln");

/// The query predicates of the frontier rules: `NewRoom`, then the kinds of space beyond in
/// the order room, corridor, hall, other, none.
pub const FRONTIER_QUERY: [&str; 6] =
    ["NewRoom", "BeyondRoom", "BeyondCorr", "BeyondHall", "BeyondOther", "BeyondNone"];

/// Frontier at most this wide stands in a doorway (`Narrow`), m: 1.5 m, the widest single door
/// leaf building codes provide for (1.2 m) with its frame and the scan's blur.
const NARROW_M: f64 = 1.5;
/// Frontier at least this wide is a space's whole side (`Wide`), m: 3 m, the narrowest side
/// of an office and wider than any double door.
const WIDE_M: f64 = 3.0;
/// Unseen floor behind a stretch that leaves room for a room (`Space`), m²: 4 m², a 2 m x 2 m
/// store, the smallest space that is a room in the generator and the dissertation's Tab. 3.6.
const SPACE_M2: f64 = 4.0;
/// Unseen floor behind a stretch that is open floor (`BigSpace`), m²: 25 m², a third of the
/// half disc [`BEHIND_M`](super::BEHIND_M) deep, more than an office's floor within that reach.
const BIG_SPACE_M2: f64 = 25.0;
/// A room smaller than this is a fragment of what lies beyond, not a space already explored
/// (`SmallFrom`), m²: 6 m², less than the smallest office (2 m x 3 m); the fan of free cells a
/// scan leaves through a door is such a fragment.
const SMALL_FROM_M2: f64 = 6.0;
/// Share of the unseen space behind a stretch inside the building's seen extent that counts
/// as inside it (`Inside`): most of it, 3 in 4.
const INSIDE_SHARE: f64 = 0.75;

/// Frontier narrower than this is a sliver (`Sliver`), m: 0.8 m, the narrowest door leaf
/// building codes allow into a room; narrower is a gap between furniture or a ray's slit.
const SLIVER_M: f64 = 0.8;
/// Frontier at least this wide is broader than any door (`Broad`), m: 2 m, a double door
/// (1.8 m) with its frame.
const BROAD_M: f64 = 2.0;
/// Unseen floor behind a stretch that holds an office (`Deep`), m²: 10 m², an office of
/// 3 m x 3.3 m.
const DEEP_M2: f64 = 10.0;
/// The room it opens from is more than a small office (`MidFrom`), m²: 15 m², an office for
/// two.
const MID_FROM_M2: f64 = 15.0;
/// The room it opens from is larger than any office (`LargeFrom`), m²: 40 m², a seminar room
/// or 20 m of corridor.
const LARGE_FROM_M2: f64 = 40.0;
/// The room it opens from is a hall's floor (`HugeFrom`), m²: 100 m², a lobby or a lecture
/// hall.
const HUGE_FROM_M2: f64 = 100.0;
/// Placeholders of the same room at which it is seen only in part (`TwoWays`, `FourWays`,
/// `EightWays`): another one, one on each side of a box, and twice that, a room seen in
/// stretches along its length.
const WAYS: [(usize, &str); 3] = [(2, "TwoWays"), (4, "FourWays"), (8, "EightWays")];

/// Share of the unseen space behind a stretch inside the plan's units (`Planned`), or inside
/// the units of the room it opens from (`Own`), at which the plan reaches past the frontier:
/// a twentieth, more than the sliver a unit's edge leaves behind a frontier drawn a cell or
/// two inside it. Chosen on the training seeds' placeholders (`evaluate --only frontier`),
/// where the share leading to a new room falls from 0.56 below it to 0.24 just above it.
const PLANNED_SHARE: f64 = 0.05;

/// The frontier rules (module docs). Any knowledge base that declares the six query
/// predicates of [`FRONTIER_QUERY`] over one argument works; the evidence predicates it may use
/// are those of [`FRONTIER_EVIDENCE`].
#[derive(Debug, Clone)]
pub struct FrontierRules {
    mln: Mln,
}

impl FrontierRules {
    /// The built-in rules ([`BUILTIN_FRONTIER_RULES`]).
    pub fn builtin() -> FrontierRules {
        FrontierRules::parse(BUILTIN_FRONTIER_RULES).expect("the built-in frontier rules parse")
    }

    /// Rules from text, refused if they do not parse or lack a query predicate.
    pub fn parse(text: &str) -> Result<FrontierRules, MlnError> {
        let mln = Mln::parse(text)?;
        for q in FRONTIER_QUERY {
            if mln.predicate(q).is_none_or(|p| mln.argument_types(p).len() != 1) {
                return Err(MlnError::config(format!(
                    "the frontier rules must declare the query {q}(place), as samples/knowledge/frontier.mln does"
                )));
            }
        }
        Ok(FrontierRules { mln })
    }

    /// The network.
    pub fn mln(&self) -> &Mln {
        &self.mln
    }

    /// Per stretch of `world`'s map, `P(NewRoom)` and the probability of each type (room,
    /// corridor, hall, other) given that some space lies beyond.
    pub fn weigh(&self, world: &World, stretches: &[Stretch]) -> Result<Vec<(f64, [f64; 4])>, MlnError> {
        if stretches.is_empty() {
            return Ok(Vec::new());
        }
        let mut db = Database::new();
        self.insert_evidence(&mut db, world, stretches)?;
        let mut ground = GroundConfig::query(&FRONTIER_QUERY);
        ground.closed_world =
            EVIDENCE.iter().filter(|p| self.mln.predicate(p).is_some()).map(|p| p.to_string()).collect();
        let places: Vec<String> = (0..stretches.len()).map(place).collect();
        let new_room = self.mln.predicate("NewRoom").expect("checked by parse");
        let ty = self.mln.argument_types(new_room)[0].to_string();
        ground.domains.push((ty, places.clone()));
        let net = Network::ground(&self.mln, &db, &ground)?;
        let m = net.infer_marginals(&InferenceConfig::default())?;
        let p = |pred: &str, c: &str| m.get(pred, &[c]).unwrap_or(0.0);
        Ok(places
            .iter()
            .map(|c| {
                let kinds = [1, 2, 3, 4].map(|k| p(FRONTIER_QUERY[k], c));
                let sum: f64 = kinds.iter().sum();
                let types = if sum > 1e-9 { kinds.map(|k| k / sum) } else { [0.25; 4] };
                (p("NewRoom", c), types)
            })
            .collect())
    }

    /// Inserts the true evidence atoms of every stretch (closed world: the rest are false).
    pub(crate) fn insert_evidence(
        &self,
        db: &mut Database,
        world: &World,
        stretches: &[Stretch],
    ) -> Result<(), MlnError> {
        for (i, s) in stretches.iter().enumerate() {
            let c = place(i);
            for pred in evidence(world, s) {
                if self.mln.predicate(pred).is_some() {
                    db.insert(&self.mln, pred, &[&c], Evidence::True)?;
                }
            }
        }
        Ok(())
    }
}

/// Every evidence predicate the frontier rules may use.
pub const FRONTIER_EVIDENCE: [&str; 26] = [
    "Narrow",
    "Wide",
    "AtDoor",
    "Space",
    "BigSpace",
    "Pocket",
    "Inside",
    "FromRoom",
    "FromCorr",
    "FromHall",
    "FromOther",
    "FromRays",
    "FromNone",
    "SmallFrom",
    "Jambs",
    "Planned",
    "Own",
    "Sliver",
    "Broad",
    "Deep",
    "MidFrom",
    "LargeFrom",
    "HugeFrom",
    "TwoWays",
    "FourWays",
    "EightWays",
];
use FRONTIER_EVIDENCE as EVIDENCE;

/// The constant naming the `i`-th placeholder.
pub(crate) fn place(i: usize) -> String {
    format!("P{}", i + 1)
}

/// The true evidence predicates of stretch `s` of `world`'s map (the others are false).
pub fn evidence(world: &World, s: &Stretch) -> Vec<&'static str> {
    let mut out = Vec::new();
    let mut say = |yes: bool, pred: &'static str| {
        if yes {
            out.push(pred);
        }
    };
    say(s.width_m <= NARROW_M, "Narrow");
    say(s.width_m >= WIDE_M, "Wide");
    say(s.at_door, "AtDoor");
    say(s.jambs, "Jambs");
    say(s.behind_m2 >= SPACE_M2, "Space");
    say(s.behind_m2 >= BIG_SPACE_M2, "BigSpace");
    say(s.pocket, "Pocket");
    say(s.inside >= INSIDE_SHARE, "Inside");
    say(s.planned >= PLANNED_SHARE, "Planned");
    say(s.own >= PLANNED_SHARE, "Own");
    say(s.width_m < SLIVER_M, "Sliver");
    say(s.width_m >= BROAD_M, "Broad");
    say(s.behind_m2 >= DEEP_M2, "Deep");
    for (least, pred) in WAYS {
        say(s.ways >= least, pred);
    }
    let room = world.rooms.iter().find(|r| r.id == s.room);
    let kind = room.map(|r| r.kind);
    let from = [
        (UnitType::Room, "FromRoom"),
        (UnitType::Corridor, "FromCorr"),
        (UnitType::Hall, "FromHall"),
        (UnitType::Other, "FromOther"),
    ];
    for (t, pred) in from {
        say(kind == Some(t), pred);
    }
    say(kind == Some(UnitType::Unknown), "FromRays");
    say(room.is_none(), "FromNone");
    say(room.is_some_and(|r| r.area_m2 < SMALL_FROM_M2), "SmallFrom");
    say(room.is_some_and(|r| r.area_m2 >= MID_FROM_M2), "MidFrom");
    say(room.is_some_and(|r| r.area_m2 >= LARGE_FROM_M2), "LargeFrom");
    say(room.is_some_and(|r| r.area_m2 >= HUGE_FROM_M2), "HugeFrom");
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::floorplan::world::Room;

    fn stretch(width_m: f64, behind_m2: f64, pocket: bool, at_door: bool) -> Stretch {
        Stretch {
            cells: vec![0],
            at: (0, 0),
            width_m,
            behind_m2,
            pocket,
            inside: 1.0,
            room: 0,
            at_door,
            jambs: false,
            planned: 0.0,
            own: 0.0,
            ways: 0,
        }
    }

    #[test]
    fn evidence_reads_widths_room_sizes_and_ways_in_metres_and_counts() {
        let mut world = World::empty(10, 10);
        let room = |id, area_m2| Room {
            id,
            kind: UnitType::Corridor,
            units: vec![],
            area_m2,
            doors: vec![],
            opens_to: vec![],
            name: None,
        };
        world.rooms = vec![room(1, 50.0), room(2, 120.0)];
        let sliver = Stretch { room: 1, ways: 4, ..stretch(0.6, 12.0, false, false) };
        let e = evidence(&world, &sliver);
        for yes in ["Sliver", "Narrow", "Space", "Deep", "FromCorr", "MidFrom", "LargeFrom", "TwoWays", "FourWays"] {
            assert!(e.contains(&yes), "{yes}: {e:?}");
        }
        for no in ["Broad", "Wide", "BigSpace", "HugeFrom", "EightWays", "SmallFrom"] {
            assert!(!e.contains(&no), "{no}: {e:?}");
        }
        let broad = Stretch { room: 2, ways: 8, ..stretch(2.5, 8.0, false, false) };
        let e = evidence(&world, &broad);
        for yes in ["Broad", "Space", "HugeFrom", "EightWays"] {
            assert!(e.contains(&yes), "{yes}: {e:?}");
        }
        for no in ["Sliver", "Narrow", "Wide", "Deep"] {
            assert!(!e.contains(&no), "{no}: {e:?}");
        }
        // Every predicate evidence gives is one the rules may use, and the rules declare it.
        let rules = FrontierRules::builtin();
        for pred in evidence(&world, &sliver).into_iter().chain(evidence(&world, &broad)) {
            assert!(FRONTIER_EVIDENCE.contains(&pred) && rules.mln().predicate(pred).is_some(), "{pred}");
        }
    }

    #[test]
    fn rules_without_a_query_predicate_are_refused() {
        let e = FrontierRules::parse("Narrow(place)\nNarrow(p).\n").unwrap_err().to_string();
        assert!(e.contains("NewRoom(place)"), "{e}");
        let two = FRONTIER_RULES
            .replace("NewRoom(place)\n", "NewRoom(place, place)\n")
            .replace("NewRoom(p)", "NewRoom(p, p)");
        let e = FrontierRules::parse(&two).unwrap_err().to_string();
        assert!(e.contains("NewRoom(place)"), "{e}");
    }

    #[test]
    fn a_doorway_onto_a_closed_pocket_is_likelier_a_new_room_than_a_wide_frontier() {
        let rules = FrontierRules::parse(FRONTIER_RULES).unwrap();
        let world = World::empty(10, 10);
        let s = [stretch(1.0, 12.0, true, true), stretch(3.5, 30.0, false, false)];
        let out = rules.weigh(&world, &s).unwrap();
        assert!(out[0].0 > 0.5 && out[1].0 < 0.5, "{out:?}");
        for (_, types) in &out {
            assert!((types.iter().sum::<f64>() - 1.0).abs() < 1e-9);
        }
        // Beyond the doorway a room is the likeliest kind of space.
        assert!(out[0].1[0] > out[0].1[1] && out[0].1[0] > out[0].1[2], "{:?}", out[0].1);
    }

    #[test]
    fn the_built_in_rules_find_a_new_room_less_likely_where_the_plan_reaches_past_the_frontier() {
        // Two doorways onto room-sized unseen space, alike but for the plan's units: behind the
        // second, the room it opens from already holds a tenth of the unseen floor.
        let rules = FrontierRules::builtin();
        let world = World::empty(10, 10);
        let open = stretch(1.2, 12.0, false, true);
        let planned = Stretch { planned: 0.1, own: 0.1, ..open.clone() };
        let out = rules.weigh(&world, &[open, planned]).unwrap();
        assert!(out[1].0 < out[0].0 - 0.1, "{out:?}");
    }

    #[test]
    fn probabilities_match_exact_enumeration_for_one_placeholder() {
        // One placeholder with no true evidence: the hand-written rules' marginal of NewRoom by
        // brute force over the 2^6 query worlds equals the engine's.
        let rules = FrontierRules::parse(FRONTIER_RULES).unwrap();
        let out = rules.weigh(&World::empty(10, 10), &[stretch(2.0, 1.0, false, false)]).unwrap();
        let lw = |p: f64| (p / (1.0 - p)).ln();
        // The rules whose truth the query atoms decide, with this evidence (Space false, Inside
        // true, FromNone true as the stretch opens from no room): the NewRoom prior,
        // `!Space => BeyondNone`, `FromNone => BeyondNone` and `NewRoom => BeyondRoom`; the
        // other weights are log 1.
        let (mut z, mut new) = (0.0, 0.0);
        for kind in 0..5 {
            for newroom in [false, true] {
                if kind == 4 && newroom {
                    continue; // BeyondNone => !NewRoom is hard
                }
                let mut logw = if newroom { lw(0.30) } else { 0.0 };
                if kind == 4 {
                    logw += lw(0.80) + lw(0.60);
                }
                if !newroom || kind == 0 {
                    logw += lw(0.60);
                }
                let wt = f64::exp(logw);
                z += wt;
                if newroom {
                    new += wt;
                }
            }
        }
        assert!((out[0].0 - new / z).abs() < 1e-9, "{} vs {}", out[0].0, new / z);
    }
}
