//! Knowledge supervision of the floor-plan chain (section 3.8): evidence from the world, unit
//! types and same-length relations from Markov logic, and the terms they add to the posterior.
//!
//! * Evidence (Tab. 3.3): `RoLi`/`CoLi`/`HaLi` from the size and aspect-ratio classifier of
//!   Tab. 3.6, `MulDoor` from the doors, `Adj` from the relation detector (facing walls close
//!   together, the dissertation's dilated-walls test).
//! * Queries (Tab. 3.4): `Room`/`Corr`/`Hall`/`Other` give unit types; `SaLe(p, q)` says two
//!   adjacent units should have connecting walls of the same length.
//! * Prior (eqs. 3.33 - 3.34): for pairs with `P(SaLe) > threshold`, a Gaussian factor on the
//!   difference `d` of the connecting walls' lengths, `exp(-d² / 2σ²)`.
//! * Semantic sensor model (the companion paper's 3x4 table): inside rooms, halls and other
//!   units a cell the map does not see as free may be an *object* (furniture) and is scored
//!   by `p(C_M | object)`; inside corridors it is a mismatch as before.

use super::world::{Unit, UnitType, World};
use crate::geometry::{facing, Axis};
use crate::setting::{check, InvalidSetting};
use serde::{Deserialize, Serialize};

/// The geometry classifier of Tab. 3.6.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct GeometryClassifier {
    /// Free area (m², inside the walls) above which a unit is big: hall-like.
    pub hall_area_m2: f64,
    /// Length / width ratio above which a small unit is corridor-like rather than room-like.
    pub corridor_ratio: f64,
    /// Free area (m²) below which a unit is `Small`: a store, a stairwell, a shaft. Not in
    /// Tab. 3.6; knowledge bases that do not declare `Small` never see it.
    pub small_area_m2: f64,
    /// Free width (m, the shorter side inside the walls) below which a unit is `Narrow`: a
    /// store, a stairwell, a corridor; offices are wider. Not in Tab. 3.6; knowledge bases that
    /// do not declare `Narrow` never see it.
    pub narrow_m: f64,
}

impl Default for GeometryClassifier {
    /// Halls from 60 m²; corridors at least 3.5 times as long as they are wide; small under
    /// 10 m²; narrow under 2.5 m wide.
    fn default() -> Self {
        GeometryClassifier { hall_area_m2: 60.0, corridor_ratio: 3.5, small_area_m2: 10.0, narrow_m: 2.5 }
    }
}

/// The geometry class of a unit.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Geometry {
    /// `RoLi`: small and compact.
    RoomLike,
    /// `CoLi`: small and elongated.
    CorridorLike,
    /// `HaLi`: big.
    HallLike,
}

impl GeometryClassifier {
    /// The free area inside a unit's walls (`t` cells deep), m².
    pub fn free_area_m2(&self, u: &Unit, t: i32, resolution: f64) -> f64 {
        let (w, h) = ((u.w - 2 * t).max(1) as f64, (u.h - 2 * t).max(1) as f64);
        w * h * resolution * resolution
    }

    /// The free width inside a unit's walls (`t` cells deep): its shorter side, m.
    pub fn free_width_m(&self, u: &Unit, t: i32, resolution: f64) -> f64 {
        (u.w - 2 * t).min(u.h - 2 * t).max(1) as f64 * resolution
    }

    /// Classifies a unit whose walls are `t` cells deep, at `resolution` metres per cell.
    pub fn classify(&self, u: &Unit, t: i32, resolution: f64) -> Geometry {
        let (w, h) = ((u.w - 2 * t).max(1) as f64, (u.h - 2 * t).max(1) as f64);
        let area = w * h * resolution * resolution;
        let ratio = w.max(h) / w.min(h);
        if area >= self.hall_area_m2 {
            Geometry::HallLike
        } else if ratio >= self.corridor_ratio {
            Geometry::CorridorLike
        } else {
            Geometry::RoomLike
        }
    }
}

/// The constant naming unit `id` in the knowledge base: `U1`, `U2`, ...
pub fn constant(id: u32) -> String {
    format!("U{id}")
}

/// Whether two units are adjacent: facing walls at most two wall depths apart with a shared
/// stretch (the relation R of eq. 3.31).
pub fn adjacent(a: &Unit, b: &Unit, t: i32) -> bool {
    [Axis::Horizontal, Axis::Vertical].iter().any(|&axis| {
        facing(a.rect(), b.rect(), axis, 2 * t, t).is_some() || facing(b.rect(), a.rect(), axis, 2 * t, t).is_some()
    })
}

/// `log b(u_p, u_q)`, the same-length factor of eq. 3.34 for connecting walls differing by
/// `d` cells, with the SaLe atom marginalised rather than thresholded:
/// `b = P(SaLe) · exp(-d² / 2σ²) + (1 - P(SaLe))`.
///
/// Eq. 3.34 applies the full Gaussian whenever `P(SaLe)` passes a threshold, so a pair the
/// network thinks is only 70 % likely to share a wall length is pulled together as if it
/// certainly did, and the pull grows without bound with `d`: early, fragmented worlds then
/// freeze, because merging or resizing a unit breaks the lengths of all its pairs at once.
/// Summing over the atom's two values, `p(U | T, R) = Σ_SaLe p(U | SaLe) P(SaLe)` with a flat
/// `p(U | ¬SaLe)`, keeps eq. 3.34's Gaussian where SaLe holds and bounds the penalty of a
/// pair at `-log(1 - P(SaLe))`, what the knowledge base's own doubt allows.
pub fn same_length_log_factor(d: f64, sigma: f64, p_same: f64) -> f64 {
    let gauss = libm::exp(-d * d / (2.0 * sigma * sigma));
    libm::log(p_same * gauss + (1.0 - p_same)).max(-1e6)
}

/// One ground evidence atom: predicate, arguments, truth value.
pub type Fact = (&'static str, Vec<String>, bool);

/// The evidence predicates [`evidence`] supplies: complete for every world, so closed world
/// wherever a knowledge base declares them.
pub const EVIDENCE_PREDICATES: [&str; 8] = ["RoLi", "CoLi", "HaLi", "MulDoor", "Adj", "Small", "Narrow", "Circ"];

/// Spaces a unit opens to through doors, of which at least this many make it a link of the
/// building's circulation (`Circ`): a corridor or hall serves many spaces, while a store, a
/// stairwell or an office is entered from one side and at most reaches a neighbour too.
pub const CIRCULATION_SPACES: usize = 3;

/// Corridor- or hall-like spaces a unit opens to, of which at least this many make it a link
/// of the circulation (`Circ`): a passage joins two circulation spaces, a dead end joins one.
pub const CIRCULATION_HUBS: usize = 2;

/// Whether unit `u` links the circulation (`Circ`): it opens through doors to at least
/// [`CIRCULATION_SPACES`] distinct spaces, or to at least [`CIRCULATION_HUBS`] units whose
/// geometry (Tab. 3.6, by `classifier`) is corridor- or hall-like. A space that is no unit of
/// `world` counts as a space, not as a hub.
pub fn links_circulation(world: &World, u: &Unit, resolution: f64, classifier: &GeometryClassifier) -> bool {
    // The space door `d` leads `u` to, if it is one of `u`'s doors.
    let beyond = |d: &super::world::Door| match d.units {
        [a, b] if a == u.id && b != u.id => Some(b),
        [a, b] if b == u.id && a != u.id => Some(a),
        _ => None,
    };
    let (mut spaces, mut hubs) = (0, 0);
    for (i, d) in world.doors.iter().enumerate() {
        let Some(s) = beyond(d) else { continue };
        if world.doors[..i].iter().any(|e| beyond(e) == Some(s)) {
            continue;
        }
        spaces += 1;
        let unit = world.units.iter().find(|v| v.id == s);
        hubs += unit.is_some_and(|v| classifier.classify(v, world.wall_thickness, resolution) != Geometry::RoomLike)
            as usize;
    }
    spaces >= CIRCULATION_SPACES || hubs >= CIRCULATION_HUBS
}

/// The evidence a world gives (Tab. 3.3), with the world's units named by [`constant`]:
/// the seven unit predicates of every unit, true or false, and the true `Adj` atoms only (the
/// others are false by the closed world), so that it grows linearly with the units and their
/// adjacencies, not with their pairs.
pub fn evidence(world: &World, resolution: f64, classifier: &GeometryClassifier) -> Vec<Fact> {
    let t = world.wall_thickness;
    let mut facts = Vec::new();
    for u in &world.units {
        let g = classifier.classify(u, t, resolution);
        let c = constant(u.id);
        facts.push(("Circ", vec![c.clone()], links_circulation(world, u, resolution, classifier)));
        facts.push(("RoLi", vec![c.clone()], g == Geometry::RoomLike));
        facts.push(("CoLi", vec![c.clone()], g == Geometry::CorridorLike));
        facts.push(("HaLi", vec![c.clone()], g == Geometry::HallLike));
        facts.push(("Small", vec![c.clone()], classifier.free_area_m2(u, t, resolution) < classifier.small_area_m2));
        facts.push(("Narrow", vec![c.clone()], classifier.free_width_m(u, t, resolution) < classifier.narrow_m));
        let doors = world.doors.iter().filter(|d| d.units.contains(&u.id)).count();
        facts.push(("MulDoor", vec![c], doors >= 2));
    }
    // Only the true Adj atoms: Adj is closed world (Knowledge::infer), so the false ones add
    // nothing, and listing them made the evidence quadratic in units (two strings per ordered
    // pair, which a large world turned into gigabytes in wasm).
    // Units at different angles (issue 13) are compared in no common frame: not adjacent here.
    for a in &world.units {
        for b in &world.units {
            if a.id != b.id && world.unit_frame(a) == world.unit_frame(b) && adjacent(a, b, t) {
                facts.push(("Adj", vec![constant(a.id), constant(b.id)], true));
            }
        }
    }
    facts
}

pub use super::metrics::{connecting_walls, same_length, SAME_LENGTH_TOLERANCE};

/// A training world for weight learning: the [`evidence`] facts of a labelled world plus the
/// true query atoms, `Room`/`Corr`/`Hall`/`Other` of every unit from its type (all false for
/// an untyped unit) and `SaLe(p, q)` of every ordered pair from [`same_length`].
pub fn training_facts(world: &World, resolution: f64, classifier: &GeometryClassifier) -> Vec<Fact> {
    let t = world.wall_thickness;
    let mut facts = evidence(world, resolution, classifier);
    for u in &world.units {
        for (q, kind) in TYPE_PREDICATES {
            facts.push((q, vec![constant(u.id)], u.kind == kind));
        }
    }
    for a in &world.units {
        for b in world.units.iter().filter(|b| b.id != a.id) {
            let same = world.unit_frame(a) == world.unit_frame(b) && same_length(a, b, t);
            facts.push(("SaLe", vec![constant(a.id), constant(b.id)], same));
        }
    }
    facts
}

/// Learns the weights of `kb` from labelled worlds (every unit typed; `resolution` metres per
/// cell): each world becomes a training database ([`training_facts`], only the predicates `kb`
/// declares), then [`crate::mln::learn_weights`] learns with `config`, whose query predicates
/// default to those of the indoor rules that `kb` declares. Returns the knowledge base text
/// with the learned weights, `header` as its leading comment.
///
/// ```
/// use ksmcmc::floorplan::knowledge::{learn_from_worlds, HAND_SET_INDOOR};
/// use ksmcmc::floorplan::synth::{generate, SynthConfig};
/// use ksmcmc::mln::{LearnConfig, Mln};
///
/// let truth = generate(&SynthConfig::default(), 3).unwrap().truth;
/// let text = learn_from_worlds(HAND_SET_INDOOR, &[truth], 0.05, &LearnConfig::default(), "learned").unwrap();
/// assert!(text.starts_with("// learned"));
/// assert_eq!(Mln::parse(&text).unwrap().formulas().len(), Mln::parse(HAND_SET_INDOOR).unwrap().formulas().len());
/// // Each soft formula says what its weight was before learning.
/// assert!(text.contains("// was 2.1972"));
/// ```
pub fn learn_from_worlds(
    kb: &str,
    worlds: &[World],
    resolution: f64,
    config: &crate::mln::LearnConfig,
    header: &str,
) -> Result<String, crate::mln::MlnError> {
    use crate::mln::{learn_weights, Database, Mln};
    let mln = Mln::parse(kb)?;
    let classifier = GeometryClassifier::default();
    let dbs = worlds
        .iter()
        .map(|w| {
            let mut facts = training_facts(w, resolution, &classifier);
            facts.retain(|f| mln.predicate(f.0).is_some());
            Database::parse(&database_text(&facts), &mln)
        })
        .collect::<Result<Vec<_>, _>>()?;
    let mut config = config.clone();
    if config.query.is_empty() {
        config.query = ["Room", "Corr", "Hall", "Other", "SaLe"]
            .into_iter()
            .filter(|q| mln.predicate(q).is_some())
            .map(String::from)
            .collect();
    }
    Ok(learn_weights(&mln, &dbs, &config)?.to_mln(&mln, header))
}

/// Facts as an evidence database (`ksmcmc::mln::Database::parse` reads it): one true atom
/// per line, in the order given. False atoms are left out, since training worlds and the
/// predicates they mention are closed world.
pub fn database_text(facts: &[Fact]) -> String {
    let mut out = String::new();
    for (pred, args, value) in facts {
        if *value {
            out.push_str(&format!("{pred}({})\n", args.join(",")));
        }
    }
    out
}

/// Type evidence from a person's edits: for every unit a type edit lies in
/// ([`super::edits::Edits::typed_units`]), its four type atoms (`Room`, `Corr`, `Hall`,
/// `Other`), true for the edit's type and false for the others.
pub fn edit_facts(edits: &super::edits::Edits, world: &World) -> Vec<Fact> {
    edits
        .typed_units(world)
        .into_iter()
        .flat_map(|(id, kind)| TYPE_PREDICATES.map(|(p, t)| (p, vec![constant(id)], t == kind)))
        .collect()
}

/// Whether `mln` can serve as the room rules: it declares the query `SameRoom(unit, unit)`
/// (the room layer's [`super::rooms::RoomKnowledge`] reads rules only through this check, so
/// that a configuration is refused as soon as it is read, by the same words).
pub fn check_room_rules(mln: &crate::mln::Mln) -> Result<(), crate::mln::MlnError> {
    match mln.predicate("SameRoom") {
        Some(_) => Ok(()),
        None => Err(crate::mln::MlnError::config("the room rules must declare the query SameRoom(unit, unit)")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::floorplan::metrics::{defect_pairs, defects};

    fn unit(id: u32, x: i32, y: i32, w: i32, h: i32, kind: UnitType) -> Unit {
        Unit::new(id, x, y, w, h, kind)
    }

    #[test]
    fn classifier_follows_tab_3_6() {
        let c = GeometryClassifier::default();
        // At 5 cm: a 4 x 5 m room, a 2 x 20 m corridor, a 10 x 12 m hall.
        assert_eq!(c.classify(&unit(1, 0, 0, 82, 102, UnitType::Unknown), 1, 0.05), Geometry::RoomLike);
        assert_eq!(c.classify(&unit(1, 0, 0, 42, 402, UnitType::Unknown), 1, 0.05), Geometry::CorridorLike);
        assert_eq!(c.classify(&unit(1, 0, 0, 202, 242, UnitType::Unknown), 1, 0.05), Geometry::HallLike);
    }

    #[test]
    fn the_inference_cache_keeps_the_latest_results_only() {
        let mut k = Knowledge::new(&KnowledgeConfig::default()).unwrap();
        let world = |id: u32| {
            let mut w = World::empty(200, 100);
            w.units = vec![unit(id, 0, 0, 60, 80, UnitType::Unknown)];
            w
        };
        for id in 1..=100 {
            k.infer(&world(id), 0.05).unwrap();
            assert!(k.cached() <= CACHE_ENTRIES);
        }
        assert_eq!((k.inferences, k.cached()), (100, CACHE_ENTRIES));
        // The latest are hits (no work), the oldest were evicted and run again.
        k.infer(&world(100), 0.05).unwrap();
        assert_eq!((k.inferences, k.last_work), (100, 0));
        k.infer(&world(1), 0.05).unwrap();
        assert_eq!(k.inferences, 101);
        assert!(k.last_work > 0);
    }

    #[test]
    fn same_length_factor_marginalises_the_atom() {
        assert_eq!(same_length_log_factor(0.0, 10.0, 0.7), 0.0);
        let d = 10.0;
        let expected = libm::log(0.7 * libm::exp(-0.5) + 0.3);
        assert!((same_length_log_factor(d, 10.0, 0.7) - expected).abs() < 1e-12);
        // Far apart, the penalty is the doubt of the knowledge base, not unbounded.
        assert!((same_length_log_factor(1e4, 10.0, 0.7) - libm::log(0.3)).abs() < 1e-12);
        assert!(same_length_log_factor(1e4, 10.0, 1.0) >= -1e6);
    }

    #[test]
    fn evidence_and_defects() {
        let mut w = World::empty(200, 100);
        w.units = vec![
            unit(1, 0, 0, 60, 80, UnitType::Room),
            unit(2, 59, 0, 60, 80, UnitType::Room),  // same height: no defect
            unit(3, 118, 0, 60, 40, UnitType::Room), // half the height: a defect
        ];
        let facts = evidence(&w, 0.05, &GeometryClassifier::default());
        let has = |p: &str, a: &[&str], v: bool| facts.iter().any(|f| f.0 == p && f.1 == a && f.2 == v);
        assert!(has("Adj", &["U1", "U2"], true) && has("Adj", &["U2", "U1"], true));
        // Adj is closed world: only its true atoms are listed.
        assert!(!facts.iter().any(|f| f.0 == "Adj" && (f.1 == ["U1", "U3"] || !f.2)));
        assert!(has("RoLi", &["U1"], true) && has("MulDoor", &["U1"], false));
        assert_eq!(defects(&w), Some(0.5));
        assert_eq!(defect_pairs(&w), (1, 2));
        w.units[2].kind = UnitType::Corridor;
        assert_eq!(defects(&w), Some(0.0));
    }

    #[test]
    fn circulation_is_three_spaces_or_two_hubs_through_doors() {
        use crate::floorplan::world::Door;
        // At 5 cm cells: 1 and 2 are 4 x 4 m offices, 3 a 2 x 20 m corridor, 4 a 12 x 12 m
        // hall, 5 a 2 x 3 m store.
        let mut w = World::empty(1000, 1000);
        w.wall_thickness = 1;
        w.units = vec![
            unit(1, 0, 0, 82, 82, UnitType::Unknown),
            unit(2, 100, 0, 82, 82, UnitType::Unknown),
            unit(3, 0, 100, 402, 42, UnitType::Unknown),
            unit(4, 500, 0, 242, 242, UnitType::Unknown),
            unit(5, 200, 0, 42, 62, UnitType::Unknown),
        ];
        let door = |id, a, b| Door { id, units: [a, b], x0: 0, y0: 0, x1: 0, y1: 0, opening: false };
        let circ = |w: &World| {
            let facts = evidence(w, 0.05, &GeometryClassifier::default());
            w.units
                .iter()
                .filter(|u| facts.iter().any(|f| f.0 == "Circ" && f.1 == [constant(u.id)] && f.2))
                .map(|u| u.id)
                .collect::<Vec<_>>()
        };
        // The store opens to the corridor and to office 1: a dead end with a second door.
        // Two doors between the same two spaces are one space reached.
        w.doors = vec![door(1, 5, 3), door(2, 5, 1), door(3, 1, 3), door(4, 1, 3)];
        assert_eq!(circ(&w), Vec::<u32>::new());
        // A door to the hall too: the store joins two circulation spaces.
        w.doors.push(door(5, 5, 4));
        assert_eq!(circ(&w), vec![5]);
        // The corridor reaches three spaces (office 2 now too); the store still joins two hubs.
        w.doors.push(door(6, 2, 3));
        assert_eq!(circ(&w), vec![3, 5]);
        // A space that is no unit (beyond the world) counts as a space, not as a hub.
        w.doors = vec![door(1, 1, 2), door(2, 1, 99)];
        assert_eq!(circ(&w), Vec::<u32>::new());
        w.doors.push(door(3, 1, 3));
        assert_eq!(circ(&w), vec![1]);
    }

    #[test]
    fn the_chain_parses_the_builtin_rules_without_their_comments() {
        use crate::mln::Mln;
        assert!(!BUILTIN_INDOOR_FORMULAS.contains("//") && BUILTIN_INDOOR.contains("// was"));
        assert!(BUILTIN_INDOOR_FORMULAS.len() < BUILTIN_INDOOR.len() * 3 / 4);
        let (full, bare) = (Mln::parse(BUILTIN_INDOOR).unwrap(), Mln::parse(BUILTIN_INDOOR_FORMULAS).unwrap());
        assert_eq!(full.formulas().len(), bare.formulas().len());
        // The same formulas and weights; only where each stands in the text differs.
        let key = |m: &Mln| {
            m.formulas().iter().map(|f| format!("{} {:?} {:?}", f.text, f.weight, f.expr)).collect::<Vec<_>>()
        };
        assert_eq!(key(&full), key(&bare));
        // Code is kept to its comment; a line that is all comment goes.
        let text = b"// head\nRoom(unit)  // a query\n\n2.5 Room(x)\n// tail";
        assert_eq!(uncommented(text, &mut []), 23);
        let mut out = [0u8; 23];
        assert_eq!(uncommented(text, &mut out), 23);
        assert_eq!(&out, b"Room(unit)\n2.5 Room(x)\n");
        // A buffer too short holds the beginning.
        let mut short = [0u8; 4];
        assert_eq!(uncommented(text, &mut short), 23);
        assert_eq!(&short, b"Room");
    }

    /// Marginals of every query atom, inferred from `facts` as [`Knowledge::infer`] grounds them.
    fn marginals_of(world: &World, facts: &[Fact]) -> Vec<(String, f64)> {
        use crate::mln::{Database, Evidence, GroundConfig, InferenceConfig, Mln, Network};
        let mln = Mln::parse(BUILTIN_INDOOR).unwrap();
        let mut db = Database::new();
        for (pred, args, value) in facts {
            let args: Vec<&str> = args.iter().map(String::as_str).collect();
            db.insert(&mln, pred, &args, if *value { Evidence::True } else { Evidence::False }).unwrap();
        }
        let queries = ["Room", "Corr", "Hall", "Other", "SaLe"];
        let mut ground = GroundConfig::query(&queries);
        ground.closed_world = EVIDENCE_PREDICATES.map(String::from).to_vec();
        let ty = mln.argument_types(mln.predicate("Room").unwrap())[0].to_string();
        ground.domains.push((ty, world.units.iter().map(|u| constant(u.id)).collect()));
        let net = Network::ground(&mln, &db, &ground).unwrap();
        let m = net.infer_marginals(&InferenceConfig::default()).unwrap();
        let mut out = Vec::new();
        for a in &world.units {
            for q in &queries[..4] {
                out.push((format!("{q}(U{})", a.id), m.get(q, &[constant(a.id).as_str()]).unwrap()));
            }
            for b in world.units.iter().filter(|b| b.id != a.id) {
                let p = m.get("SaLe", &[constant(a.id).as_str(), constant(b.id).as_str()]).unwrap();
                out.push((format!("SaLe(U{},U{})", a.id, b.id), p));
            }
        }
        out
    }

    #[test]
    fn evidence_without_false_adj_atoms_infers_the_same_marginals() {
        let mut w = World::empty(300, 200);
        w.units = vec![
            unit(1, 0, 0, 60, 80, UnitType::Unknown),
            unit(2, 59, 0, 60, 80, UnitType::Unknown),
            unit(3, 118, 0, 160, 40, UnitType::Unknown),
            unit(4, 0, 79, 278, 21, UnitType::Unknown),
            unit(5, 200, 150, 30, 30, UnitType::Unknown),
        ];
        w.doors.push(crate::floorplan::Door { id: 1, units: [1, 4], x0: 10, y0: 79, x1: 14, y1: 79, opening: false });
        w.doors.push(crate::floorplan::Door { id: 2, units: [2, 4], x0: 70, y0: 79, x1: 74, y1: 79, opening: false });
        let facts = evidence(&w, 0.05, &GeometryClassifier::default());
        // The evidence as it was before: every ordered pair's Adj atom, true or false.
        let mut all_pairs = facts.clone();
        for a in &w.units {
            for b in w.units.iter().filter(|b| b.id != a.id && !adjacent(a, b, 1)) {
                all_pairs.push(("Adj", vec![constant(a.id), constant(b.id)], false));
            }
        }
        assert!(all_pairs.len() > facts.len() + 10, "the world has non-adjacent pairs");
        assert_eq!(marginals_of(&w, &facts), marginals_of(&w, &all_pairs));
    }

    #[test]
    fn training_worlds_add_the_true_types_and_same_length_pairs() {
        use crate::mln::{learn_weights, Database, LearnConfig, Mln};
        let mut w = World::empty(200, 100);
        w.units = vec![
            unit(1, 0, 0, 60, 80, UnitType::Room),
            unit(2, 59, 0, 60, 80, UnitType::Room),
            unit(3, 118, 0, 60, 76, UnitType::Hall), // within 10 % of unit 2's height
            unit(4, 0, 79, 178, 21, UnitType::Unknown),
        ];
        let facts = training_facts(&w, 0.05, &GeometryClassifier::default());
        let value = |p: &str, a: &[&str]| facts.iter().find(|f| f.0 == p && f.1 == a).map(|f| f.2);
        assert_eq!(value("Room", &["U1"]), Some(true));
        assert_eq!(value("Hall", &["U1"]), Some(false));
        assert_eq!(value("Hall", &["U3"]), Some(true));
        assert_eq!(TYPE_PREDICATES.map(|(q, _)| value(q, &["U4"])), [Some(false); 4], "untyped");
        assert_eq!(value("SaLe", &["U1", "U2"]), Some(true));
        assert_eq!(value("SaLe", &["U3", "U2"]), Some(true), "76 vs 80 cells");
        assert_eq!(value("SaLe", &["U1", "U3"]), Some(false), "not adjacent");
        assert_eq!(value("SaLe", &["U1", "U4"]), Some(false), "60 vs 178 cells");
        assert_eq!(value("Adj", &["U1", "U4"]), Some(true));
        // The database reads back and satisfies the indoor rules' hard formulas.
        let text = database_text(&facts);
        assert!(text.contains("SaLe(U1,U2)\nSaLe(U2,U1)\n") && !text.contains("Hall(U1)"), "{text}");
        let mln = Mln::parse(BUILTIN_INDOOR).unwrap();
        let db = Database::parse(&text, &mln).unwrap();
        assert!(learn_weights(&mln, &[db], &LearnConfig::default()).is_ok());
    }
}

/// Inference work ([`crate::mln::Marginals::work`]) that takes about as long as one chain
/// iteration: measured on this project's bench machine, MC-SAT visits about 20 million clauses
/// a second and the junction tree fills about 30 million table entries, while the chain runs
/// 20 000 - 28 000 iterations a second on Radish maps (BENCHMARKS.md).
pub const WORK_PER_ITERATION: f64 = 1000.0;

/// The built-in knowledge base: the indoor rules of Tab. 3.3 - 3.5 and a few more
/// (`indoor-rules.mln`), with weights learned discriminatively from labelled synthetic floors
/// (`samples/knowledge/learn-indoor.sh`, `ksmcmc mln learn`).
pub const BUILTIN_INDOOR: &str = include_str!("../../samples/knowledge/indoor-learned.mln");

/// [`BUILTIN_INDOOR`] without its comments, made at compile time: the same declarations,
/// formulas and weights, which the chain parses when no knowledge base is given. The comments
/// (where the weights came from, what each was before learning) are for a reader, who gets
/// [`BUILTIN_INDOOR`]; the live mapper's first WebAssembly module, which must stay under
/// 500 kB gzipped (issue 12), carries only this.
const BUILTIN_INDOOR_FORMULAS: &str = {
    const TEXT: &[u8] = BUILTIN_INDOOR.as_bytes();
    const LEN: usize = uncommented(TEXT, &mut []);
    const BYTES: [u8; LEN] = {
        let mut out = [0u8; LEN];
        uncommented(TEXT, &mut out);
        out
    };
    match core::str::from_utf8(&BYTES) {
        Ok(text) => text,
        Err(_) => panic!("a comment ended inside a character"),
    }
};

/// Writes `text` without its `//` comments into `out`, as far as `out` holds it, and returns
/// how many bytes that takes (so an empty `out` measures): of each line its code up to a `//`,
/// without the spaces before it, and the line's end; lines left empty are dropped.
const fn uncommented(text: &[u8], out: &mut [u8]) -> usize {
    let (mut at, mut line) = (0, 0);
    while line < text.len() {
        let (end, next) = line_code(text, line);
        if end > line {
            let mut i = line;
            while i <= end {
                if at < out.len() {
                    out[at] = if i < end { text[i] } else { b'\n' };
                }
                at += 1;
                i += 1;
            }
        }
        line = next;
    }
    at
}

/// For the line starting at `start`: where its code ends (before a `//` and the spaces before
/// it) and where the next line starts.
const fn line_code(text: &[u8], start: usize) -> (usize, usize) {
    let mut i = start;
    let mut code = usize::MAX;
    while i < text.len() && text[i] != b'\n' {
        if code == usize::MAX && text[i] == b'/' && i + 1 < text.len() && text[i + 1] == b'/' {
            code = i;
        }
        i += 1;
    }
    let mut end = if code == usize::MAX { i } else { code };
    while end > start && (text[end - 1] == b' ' || text[end - 1] == b'\t' || text[end - 1] == b'\r') {
        end -= 1;
    }
    (end, if i < text.len() { i + 1 } else { i })
}

/// The indoor rules of Tab. 3.3 - 3.5 with hand-set weights ("very sure" 0.9, "relatively
/// sure" 0.7): the dissertation's knowledge base as transcribed, beside the learned default.
pub const HAND_SET_INDOOR: &str = include_str!("../../samples/knowledge/indoor.mln");

/// How knowledge supervises the chain.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct KnowledgeConfig {
    /// Use knowledge in the chain (the default; false: the weak-prior mode of the first
    /// paper, whose types are inferred on the final world only). On our maps it cuts the
    /// defects and the unit-count error on synthetic maps, not the defects on
    /// ubremen-cartesium, and ties the weak prior on K(W, M) except on furnished and partly
    /// unexplored maps (-0.0012 and -0.0005), where rooms reaching across furniture cover
    /// unknown cells that eq. 3.39 counts as errors (BENCHMARKS.md, `evaluate --only paired`).
    pub enabled: bool,
    /// Knowledge base text in the Alchemy format; `None` is [`BUILTIN_INDOOR`]. Any knowledge
    /// base works whose evidence predicates are among [`EVIDENCE_PREDICATES`] (`RoLi`, `CoLi`,
    /// `HaLi`, `MulDoor`, `Adj`, `Small`, `Narrow`, `Circ`) and whose query predicates are
    /// among `Room`, `Corr`, `Hall`, `Other`, `SaLe`; others are left to the open world.
    pub kb: Option<String>,
    /// The room rules in the Alchemy format (query `SameRoom`, see
    /// [`super::rooms::RoomKnowledge::parse`]); `None` is
    /// [`super::rooms::BUILTIN_ROOM_RULES`]. They decide which units are one room when
    /// knowledge is on; the chain itself never uses them.
    pub room_kb: Option<String>,
    /// The frontier rules in the Alchemy format (queries `NewRoom` and the `Beyond*` kinds,
    /// see [`crate::floorplan::frontier::FrontierRules::parse`]); `None` is
    /// [`crate::floorplan::frontier::BUILTIN_FRONTIER_RULES`]. They weigh the placeholders of
    /// every plan, with knowledge supervision or without.
    pub frontier_kb: Option<String>,
    /// Share of the map's free cells the world must cover before knowledge switches on.
    pub coverage: f64,
    /// Iterations between inferences (results are cached by their evidence), at least.
    pub every: u64,
    /// Largest share of the chain's time that inference may take: after an inference of work
    /// `w` ([`crate::mln::Marginals::work`]) the next waits at least
    /// `w / (WORK_PER_ITERATION * time_share)` iterations. Large worlds, whose networks are
    /// too wide for exact inference, are then inferred less often instead of slowing every
    /// iteration tenfold; 1 infers every `every` iterations whatever the cost.
    pub time_share: f64,
    /// `P(SaLe)` above which a pair's connecting walls are pulled to the same length.
    pub same_length_threshold: f64,
    /// `σ` of the same-length factor (eq. 3.34), cells.
    pub same_length_sigma: f64,
    /// `p(C_M | object)` for map classes free, unknown, occupied: how the semantic sensor
    /// model (eq. 3.37) scores a non-free cell inside a room, hall or other unit that may be an
    /// object ([`ObjectCells`](crate::vision::objects::ObjectCells)). Default `[0.1, 0.1, 0.45]`: an occupied outline is evidence of
    /// furniture, but an unknown cell is as likely unexplored space as an object's shadow, so
    /// it gets no more than the free-world reading `p(unknown | free) = 0.1` of Tab. 3.1.
    /// Forgiving unknown cells too (`0.45`) let units spread over unexplored pockets and cost
    /// K(W, M) on every map we measured (BENCHMARKS.md).
    pub object: [f64; 3],
    /// Largest share of a unit's interior that may be object cells: furniture fills part of
    /// a room; a "room" whose interior is mostly unseen is not furnished, it is too big.
    pub object_share: f64,
    /// Longest object (furniture) the semantic sensor model forgives, metres: occupied cells on
    /// straight runs at least this long are walls (see [`ObjectCells`](crate::vision::objects::ObjectCells)).
    pub max_object_m: f64,
    /// The geometry classifier (Tab. 3.6).
    pub geometry: GeometryClassifier,
    /// MC-SAT samples when the network is too large for exact inference.
    pub samples: u32,
}

impl Default for KnowledgeConfig {
    fn default() -> Self {
        KnowledgeConfig {
            enabled: true,
            kb: None,
            room_kb: None,
            frontier_kb: None,
            coverage: 0.8,
            every: 500,
            time_share: 0.2,
            same_length_threshold: 0.4,
            same_length_sigma: 10.0,
            object: [0.1, 0.1, 0.45],
            object_share: 0.15,
            max_object_m: 2.0,
            geometry: GeometryClassifier::default(),
            samples: 2000,
        }
    }
}

impl KnowledgeConfig {
    /// Checks every number.
    pub fn validate(&self) -> Result<(), InvalidSetting> {
        self.check_numbers().map_err(|e| e.within("knowledge"))
    }

    fn check_numbers(&self) -> Result<(), InvalidSetting> {
        let shares = [
            ("coverage", self.coverage),
            ("same_length_threshold", self.same_length_threshold),
            ("object_share", self.object_share),
        ];
        for (name, v) in shares {
            check(v.is_finite() && (0.0..=1.0).contains(&v), name, v, "in [0, 1]")?;
        }
        let positive = [
            ("max_object_m", self.max_object_m),
            ("same_length_sigma", self.same_length_sigma),
            ("geometry.hall_area_m2", self.geometry.hall_area_m2),
        ];
        for (name, v) in positive {
            check(v.is_finite() && v > 0.0, name, v, "a positive number")?;
        }
        let t = self.time_share;
        check(t.is_finite() && t > 0.0 && t <= 1.0, "time_share", t, "in (0, 1]")?;
        check(self.every > 0, "every", self.every as f64, "at least 1")?;
        check(self.samples > 0, "samples", self.samples as f64, "at least 1")?;
        let r = self.geometry.corridor_ratio;
        check(r.is_finite() && r >= 1.0, "geometry.corridor_ratio", r, "at least 1")?;
        for &p in &self.object {
            check(p.is_finite() && p > 0.0 && p <= 1.0, "object", p, "probabilities in (0, 1]")?;
        }
        let rules = "rules that parse, with SameRoom";
        if let Some(text) = &self.room_kb {
            let mln = crate::mln::Mln::parse(text).map_err(|e| InvalidSetting::unreadable("room_kb", rules, e))?;
            check_room_rules(&mln).map_err(|e| InvalidSetting::unreadable("room_kb", rules, e))?;
        }
        if let Some(text) = &self.frontier_kb {
            crate::floorplan::frontier::FrontierRules::parse(text)
                .map_err(|e| InvalidSetting::unreadable("frontier_kb", "rules that parse", e))?;
        }
        Ok(())
    }
}

/// The indoor knowledge that supervises a chain, by the names `ksmcmc floorplan --knowledge`
/// and the Python package's `knowledge=` take, so that both read a name the same way.
#[derive(Debug, Clone, PartialEq)]
pub enum IndoorKnowledge {
    /// `builtin`: [`BUILTIN_INDOOR`], the rules with weights learned from labelled floors.
    Builtin,
    /// `handset`: [`HAND_SET_INDOOR`], Tab. 3.5 with its hand-set weights.
    HandSet,
    /// `none`: the weak prior of the first paper, knowledge supervision off.
    None,
    /// Any other name: the path of a knowledge base in the Alchemy format, read and parsed.
    Rules(String),
}

impl IndoorKnowledge {
    /// The knowledge `name` gives: `builtin`, `handset`, `none`, or else the path of a
    /// knowledge base, which `read` reads (the caller's file system: the library does no
    /// I/O) and which is parsed at once, so that broken rules are reported with their file's
    /// name rather than when the chain first needs them.
    ///
    /// ```
    /// use ksmcmc::floorplan::knowledge::{IndoorKnowledge, KnowledgeConfig};
    ///
    /// let none = IndoorKnowledge::named("none", |_| unreachable!())?;
    /// let mut config = KnowledgeConfig::default();
    /// none.apply_to(&mut config);
    /// assert!(!config.enabled);
    /// let rules = IndoorKnowledge::named("my.mln", |_| Ok("Room(unit)\n1.5 Room(x)\n".into()))?;
    /// rules.apply_to(&mut config);
    /// assert!(config.enabled && config.kb.as_deref() == Some("Room(unit)\n1.5 Room(x)\n"));
    /// let e = IndoorKnowledge::named("broken.mln", |_| Ok("Room(unit\n".into())).unwrap_err();
    /// assert!(e.to_string().starts_with("broken.mln: line 1"), "{e}");
    /// assert!(std::error::Error::source(&e).is_some());
    /// # Ok::<(), ksmcmc::floorplan::knowledge::KnowledgeFileError>(())
    /// ```
    pub fn named(
        name: &str,
        read: impl FnOnce(&str) -> std::io::Result<String>,
    ) -> Result<IndoorKnowledge, KnowledgeFileError> {
        Ok(match name {
            "builtin" => IndoorKnowledge::Builtin,
            "handset" => IndoorKnowledge::HandSet,
            "none" => IndoorKnowledge::None,
            path => {
                let failed = |kind| KnowledgeFileError { path: path.to_owned(), kind };
                let text = read(path).map_err(|e| failed(KnowledgeFileErrorKind::Read(e)))?;
                crate::mln::Mln::parse(&text).map_err(|e| failed(KnowledgeFileErrorKind::Rules(e)))?;
                IndoorKnowledge::Rules(text)
            }
        })
    }

    /// Sets `config` to supervise the chain with this knowledge (or, for
    /// [`IndoorKnowledge::None`], not at all). Its other settings stay.
    pub fn apply_to(self, config: &mut KnowledgeConfig) {
        config.enabled = self != IndoorKnowledge::None;
        match self {
            IndoorKnowledge::Builtin | IndoorKnowledge::None => {}
            IndoorKnowledge::HandSet => config.kb = Some(HAND_SET_INDOOR.to_string()),
            IndoorKnowledge::Rules(text) => config.kb = Some(text),
        }
    }
}

/// A knowledge base file [`IndoorKnowledge::named`] could not use: it could not be read, or
/// its rules do not parse. Displays as `PATH: the reason`; the reason is its `source()`.
#[derive(Debug)]
pub struct KnowledgeFileError {
    path: String,
    kind: KnowledgeFileErrorKind,
}

#[derive(Debug)]
enum KnowledgeFileErrorKind {
    Read(std::io::Error),
    Rules(crate::mln::MlnError),
}

impl KnowledgeFileError {
    /// The path given.
    pub fn path(&self) -> &str {
        &self.path
    }

    /// Whether the file could not be read (else its rules do not parse).
    pub fn is_unreadable(&self) -> bool {
        matches!(self.kind, KnowledgeFileErrorKind::Read(_))
    }
}

impl std::fmt::Display for KnowledgeFileError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match &self.kind {
            KnowledgeFileErrorKind::Read(e) => write!(f, "{}: {e}", self.path),
            KnowledgeFileErrorKind::Rules(e) => write!(f, "{}: {e}", self.path),
        }
    }
}

impl std::error::Error for KnowledgeFileError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match &self.kind {
            KnowledgeFileErrorKind::Read(e) => Some(e),
            KnowledgeFileErrorKind::Rules(e) => Some(e),
        }
    }
}

/// What inference said about a world.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Inferred {
    /// Unit id -> type (the most probable of Room, Corr, Hall, Other) and the four marginals.
    pub types: std::collections::BTreeMap<u32, (UnitType, [f64; 4])>,
    /// Unit pairs `(p, q)`, `p < q`, with `P(SaLe(p, q))` above the threshold.
    pub same_length: Vec<(u32, u32, f64)>,
}

/// How many inference results a [`Knowledge`] keeps, keyed by their evidence. The chain asks
/// about its current world and its best one; a few dozen cover the worlds it returns to.
pub const CACHE_ENTRIES: usize = 64;

/// A knowledge base ready to answer for worlds, with a cache keyed by evidence.
#[derive(Debug, Clone)]
pub struct Knowledge {
    mln: crate::mln::Mln,
    config: KnowledgeConfig,
    queries: Vec<&'static str>,
    cache: std::collections::HashMap<String, Inferred>,
    /// Cache keys, oldest first: the cache keeps the last [`CACHE_ENTRIES`], so that a chain
    /// left running in a browser tab does not grow without bound.
    cache_order: std::collections::VecDeque<String>,
    /// How many inferences ran (cache misses).
    pub inferences: u64,
    /// The work of the last [`Knowledge::infer`] call ([`crate::mln::Marginals::work`]; 0 for
    /// a cache hit). A deterministic
    /// stand-in for its time, so that the chain can space inferences out by their cost and
    /// still run the same natively and in wasm.
    pub last_work: u64,
}

/// The unit-type predicates of the knowledge bases (Tab. 3.3), with the type each stands for:
/// the indoor rules' query atoms, the room rules' evidence and the atoms a type edit fixes.
pub(crate) const TYPE_PREDICATES: [(&str, UnitType); 4] =
    [("Room", UnitType::Room), ("Corr", UnitType::Corridor), ("Hall", UnitType::Hall), ("Other", UnitType::Other)];

impl Knowledge {
    /// Parses the configured knowledge base.
    pub fn new(config: &KnowledgeConfig) -> Result<Knowledge, crate::mln::MlnError> {
        let mln = crate::mln::Mln::parse(config.kb.as_deref().unwrap_or(BUILTIN_INDOOR_FORMULAS))?;
        let queries =
            ["Room", "Corr", "Hall", "Other", "SaLe"].into_iter().filter(|q| mln.predicate(q).is_some()).collect();
        Ok(Knowledge {
            mln,
            config: config.clone(),
            queries,
            cache: Default::default(),
            cache_order: Default::default(),
            inferences: 0,
            last_work: 0,
        })
    }

    /// How many inference results are cached (at most [`CACHE_ENTRIES`]).
    pub fn cached(&self) -> usize {
        self.cache.len()
    }

    /// The configuration.
    pub fn config(&self) -> &KnowledgeConfig {
        &self.config
    }

    /// Types and same-length pairs for `world` (unit ids as constants `U<id>`).
    pub fn infer(&mut self, world: &World, resolution: f64) -> Result<Inferred, crate::mln::MlnError> {
        self.infer_given(world, resolution, &[])
    }

    /// [`Knowledge::infer`] with further evidence: `given` fixes query atoms, such as the types
    /// a person set ([`edit_facts`]).
    pub fn infer_given(
        &mut self,
        world: &World,
        resolution: f64,
        given: &[Fact],
    ) -> Result<Inferred, crate::mln::MlnError> {
        use crate::mln::{Database, Evidence, GroundConfig, InferenceConfig, Network};
        let facts: Vec<Fact> = evidence(world, resolution, &self.config.geometry)
            .into_iter()
            .chain(given.iter().cloned())
            .filter(|f| self.mln.predicate(f.0).is_some())
            .collect();
        let mut key = String::new();
        for f in &facts {
            key.push_str(&format!("{}({}){};", f.0, f.1.join(","), f.2 as u8));
        }
        if let Some(hit) = self.cache.get(&key) {
            self.last_work = 0;
            return Ok(hit.clone());
        }
        let mut db = Database::new();
        for (pred, args, value) in &facts {
            let args: Vec<&str> = args.iter().map(String::as_str).collect();
            db.insert(&self.mln, pred, &args, if *value { Evidence::True } else { Evidence::False })?;
        }
        let mut ground = GroundConfig::query(&self.queries);
        // Evidence is complete for the predicates the world supplies: closed world.
        ground.closed_world =
            EVIDENCE_PREDICATES.iter().filter(|p| self.mln.predicate(p).is_some()).map(|p| p.to_string()).collect();
        let units: Vec<String> = world.units.iter().map(|u| constant(u.id)).collect();
        if let Some(p) = self.mln.predicate("Room").or_else(|| self.mln.predicate("SaLe")) {
            if let Some(ty) = self.mln.argument_types(p).first() {
                ground.domains.push((ty.to_string(), units.clone()));
            }
        }
        let net = Network::ground(&self.mln, &db, &ground)?;
        let marginals = net.infer_marginals(&InferenceConfig { samples: self.config.samples, ..Default::default() })?;
        self.last_work = marginals.work();
        let mut out = Inferred::default();
        for u in &world.units {
            let c = constant(u.id);
            let p = TYPE_PREDICATES.map(|(q, _)| marginals.get(q, &[c.as_str()]).unwrap_or(0.0));
            let best = (0..4).max_by(|&a, &b| p[a].total_cmp(&p[b])).unwrap_or(0);
            let kind = if p[best] > 0.0 { TYPE_PREDICATES[best].1 } else { UnitType::Unknown };
            out.types.insert(u.id, (kind, p));
        }
        for (i, a) in world.units.iter().enumerate() {
            for b in &world.units[i + 1..] {
                let p = marginals.get("SaLe", &[constant(a.id).as_str(), constant(b.id).as_str()]).unwrap_or(0.0);
                if p > self.config.same_length_threshold {
                    out.same_length.push((a.id.min(b.id), a.id.max(b.id), p));
                }
            }
        }
        self.inferences += 1;
        if self.cache_order.len() >= CACHE_ENTRIES {
            if let Some(old) = self.cache_order.pop_front() {
                self.cache.remove(&old);
            }
        }
        self.cache_order.push_back(key.clone());
        self.cache.insert(key, out.clone());
        Ok(out)
    }
}

/// What a knowledge base makes of a world, as the rules page shows it: the evidence the world
/// gives, the unit types with their four marginals, and the same-length pairs above the
/// threshold. Serialises as `{evidence: [{predicate, args, value}], types: {U1: {kind, room,
/// corr, hall, other}}, sameLength: [{p, q, probability}]}`.
///
/// ```
/// use ksmcmc::floorplan::knowledge::{WorldInference, BUILTIN_INDOOR};
/// use ksmcmc::floorplan::{Unit, World};
/// let mut w = World::empty(100, 60);
/// w.units.push(Unit::new(1, 2, 2, 80, 12, Default::default()));
/// let inf = WorldInference::new(BUILTIN_INDOOR, &w, 0.05).unwrap();
/// assert!(inf.types.contains_key("U1"));
/// assert!(inf.to_json().starts_with(r#"{"evidence":["#));
/// assert!(WorldInference::new("Room(unit", &w, 0.05).is_err());
/// ```
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct WorldInference {
    /// The evidence atoms of the world.
    pub evidence: Vec<EvidenceFact>,
    /// Per unit constant (`U1`, ...), its most probable type and the marginals.
    pub types: std::collections::BTreeMap<String, TypeMarginals>,
    /// Unit pairs that should have connecting walls of the same length.
    #[serde(rename = "sameLength")]
    pub same_length: Vec<SameLengthPair>,
}

/// One evidence atom of a [`WorldInference`].
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct EvidenceFact {
    /// The predicate, e.g. `RoLi`.
    pub predicate: &'static str,
    /// Its arguments, unit constants.
    pub args: Vec<String>,
    /// Whether the atom is true.
    pub value: bool,
}

/// A unit's type marginals in a [`WorldInference`].
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TypeMarginals {
    /// The most probable type, e.g. `Room`.
    pub kind: String,
    /// P(Room).
    pub room: f64,
    /// P(Corr).
    pub corr: f64,
    /// P(Hall).
    pub hall: f64,
    /// P(Other).
    pub other: f64,
}

/// A same-length pair of a [`WorldInference`].
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SameLengthPair {
    /// The first unit's constant.
    pub p: String,
    /// The second unit's constant.
    pub q: String,
    /// P(SaLe(p, q)).
    pub probability: f64,
}

impl WorldInference {
    /// Infers with the knowledge base `rules` (Alchemy text) on `world` at `resolution` metres
    /// per cell; the error is the knowledge base's, with line and column.
    pub fn new(rules: &str, world: &World, resolution: f64) -> Result<WorldInference, crate::mln::MlnError> {
        let config = KnowledgeConfig { kb: Some(rules.to_string()), ..Default::default() };
        let inferred = Knowledge::new(&config)?.infer(world, resolution)?;
        let evidence = evidence(world, resolution, &config.geometry)
            .into_iter()
            .map(|(predicate, args, value)| EvidenceFact { predicate, args, value })
            .collect();
        let types = inferred
            .types
            .iter()
            .map(|(id, (kind, p))| {
                let row = TypeMarginals { kind: format!("{kind:?}"), room: p[0], corr: p[1], hall: p[2], other: p[3] };
                (constant(*id), row)
            })
            .collect();
        let same_length = inferred
            .same_length
            .iter()
            .map(|&(p, q, probability)| SameLengthPair { p: constant(p), q: constant(q), probability })
            .collect();
        Ok(WorldInference { evidence, types, same_length })
    }

    /// The compact JSON text.
    pub fn to_json(&self) -> String {
        serde_json::to_string(self).expect("an inference serialises")
    }
}
