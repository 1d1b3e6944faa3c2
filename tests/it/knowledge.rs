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
