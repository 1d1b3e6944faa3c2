//! Knowledge supervision against the weak prior on a synthetic map with ground truth (the
//! comparison of Fig. 3.34).

#![allow(clippy::field_reassign_with_default)] // configs are built by adjusting defaults

use ksmcmc::floorplan::metrics::defects;
use ksmcmc::floorplan::synth::{generate, SynthConfig};
use ksmcmc::floorplan::{Chain, ChainConfig, UnitType, World};

fn explain(map: &ksmcmc::grid::OccupancyMap, knowledge: bool) -> World {
    let mut c = ChainConfig::default();
    c.knowledge.enabled = knowledge;
    let mut chain = Chain::new(map, c, 2).unwrap();
    chain.step(20_000);
    assert!(chain.knowledge_error().is_none(), "{:?}", chain.knowledge_error());
    chain.best_world_typed()
}

/// Synthetic office 201 (the knowledge table of `ksmcmc evaluate`, second seed): the weak prior
/// keeps a room split at a desk (one part has a door, and units with doors never MERGE); with
/// the semantic sensor model the desk's outline is an object and the room stays whole.
#[test]
fn knowledge_cuts_the_defects_of_the_weak_prior_and_types_the_corridor() {
    let s = generate(&SynthConfig::default(), 201).unwrap();
    let weak = explain(&s.map, false);
    let known = explain(&s.map, true);
    let (dw, dk) = (defects(&weak).unwrap_or(0.0), defects(&known).unwrap_or(0.0));
    assert!(dk < dw, "defects: knowledge {dk} weak {dw}");
    let truth_n = s.truth.units.len() as i64;
    let err = |w: &World| (w.units.len() as i64 - truth_n).abs();
    assert!(err(&known) < err(&weak), "unit count error: knowledge {} weak {}", err(&known), err(&weak));
    // The unit that best overlaps the true corridor is typed a corridor.
    let corridor = s.truth.units.iter().find(|u| u.kind == UnitType::Corridor).unwrap().rect();
    let best = known.units.iter().max_by_key(|u| u.rect().intersection(&corridor).map_or(0, |i| i.area())).unwrap();
    assert_eq!(best.kind, UnitType::Corridor, "{best:?}");
    let k = |w: &World| ksmcmc::floorplan::metrics::prediction_rate(s.map.classified(), w);
    assert!(k(&known) >= k(&weak), "K(W,M): knowledge {} weak {}", k(&known), k(&weak));
}

/// Knowledge supervision is the default, and inferences are spaced out by their work: with a
/// smaller share of the time for inference, fewer run, and the same settings give the same chain.
#[test]
fn knowledge_is_on_by_default_and_inference_keeps_to_its_time_share() {
    assert!(ChainConfig::default().knowledge.enabled);
    let s = generate(&SynthConfig { width: 700, height: 400, ..SynthConfig::default() }, 5).unwrap();
    let run = |share: f64| {
        let mut c = ChainConfig::default();
        c.knowledge.time_share = share;
        let mut chain = Chain::new(&s.map, c, 1).unwrap();
        chain.step(12_000);
        (chain.inferences(), chain.best_log_posterior(), chain.best_world_typed())
    };
    let (all, _, _) = run(1.0);
    let (few, lp, world) = run(0.001);
    assert!(all > few && few >= 1, "inferences: share 1 -> {all}, share 0.001 -> {few}");
    let (again, lp2, world2) = run(0.001);
    assert_eq!((few, lp.to_bits()), (again, lp2.to_bits()));
    assert_eq!(world, world2);
    let mut bad = ChainConfig::default();
    for share in [0.0, -1.0, 1.5, f64::NAN] {
        bad.knowledge.time_share = share;
        let Err(err) = Chain::new(&s.map, bad.clone(), 1) else { panic!("time_share {share} was accepted") };
        let err = err.to_string();
        assert!(err.contains("time_share"), "{err}");
    }
}

/// The rooms' type marginals on a real run: one row per room of the room layer, in its order,
/// each unit typed by its most probable marginal, and (from the units) a one-unit room
/// carrying exactly its unit's marginals. The same inference typed the world, so asking for
/// it changes nothing. The rules applied to the rooms themselves give each room its type.
#[test]
fn room_type_marginals_follow_the_units_inference() {
    use ksmcmc::floorplan::rooms::{room_marginals, room_types};
    let s = generate(&SynthConfig::default(), 201).unwrap();
    let mut chain = Chain::new(&s.map, ChainConfig::default(), 2).unwrap();
    chain.step(20_000);
    let (world, labels) = chain.best_world_with_rooms(&Default::default()).unwrap();
    let (typed, inferred) = chain.best_world_inferred();
    let inferred = inferred.expect("the built-in rules infer");
    assert_eq!(typed.units, world.units, "the rooms' world is the inferred one");
    let rooms = room_types(&world, &inferred, &Default::default());
    assert_eq!(rooms.iter().map(|r| r.id).collect::<Vec<_>>(), world.rooms.iter().map(|r| r.id).collect::<Vec<_>>());
    let order = [UnitType::Room, UnitType::Corridor, UnitType::Hall, UnitType::Other];
    let mut single = 0;
    for (room, row) in world.rooms.iter().zip(&rooms) {
        assert_eq!(row.units.iter().map(|u| u.id).collect::<Vec<_>>(), room.units);
        for u in &row.units {
            let p = u.marginals.expect("every unit of the best world was inferred");
            let p = [p.room, p.corridor, p.hall, p.other];
            assert!(p.iter().all(|v| (0.0..=1.0).contains(v)), "{p:?}");
            let top = (0..4).max_by(|&a, &b| p[a].total_cmp(&p[b])).unwrap();
            assert_eq!(u.kind, order[top], "unit {} typed by its most probable marginal {p:?}", u.id);
        }
        if let [only] = row.units.as_slice() {
            single += 1;
            let (a, b) = (row.marginals.unwrap(), only.marginals.unwrap());
            let d = [a.room - b.room, a.corridor - b.corridor, a.hall - b.hall, a.other - b.other];
            assert!(d.iter().all(|d| d.abs() < 1e-12), "room {:?} unit {:?}", a, b);
        }
    }
    assert!(single >= 1, "a run of office 201 has one-unit rooms: {rooms:?}");
    let own = room_marginals(&world, &world.rooms, &labels, s.map.yaml().resolution, &Default::default()).unwrap();
    assert!(!own.is_empty());
    for (room, row) in world.rooms.iter().zip(room_types(&world, &inferred, &own)).filter(|(r, _)| !r.units.is_empty())
    {
        let p = row.marginals.expect("every room with units was inferred");
        let p = [p.room, p.corridor, p.hall, p.other];
        let top = (0..4).max_by(|&a, &b| p[a].total_cmp(&p[b])).unwrap();
        assert_eq!(room.kind, order[top], "room {} typed by its own most probable marginal {p:?}", room.id);
    }
}
