//! Placeholders (`floorplan::frontier`) in a plan: where they stand, what the files say of
//! them, and that a damaged list is refused.

use ksmcmc::floorplan::export::graph_json;
use ksmcmc::floorplan::run::{run, RunOptions};
use ksmcmc::floorplan::synth::{generate, SynthConfig};
use ksmcmc::floorplan::World;
use ksmcmc::grid::Cell;

/// A generated office floor with two in five rooms never entered, explained briefly.
fn partly_seen() -> (ksmcmc::floorplan::synth::Synthetic, ksmcmc::floorplan::run::Run) {
    let s = generate(&SynthConfig { unexplored: 0.4, ..Default::default() }, 17).unwrap();
    let options = RunOptions { iterations: 4000, ..Default::default() };
    let r = run(&s.map, &options).unwrap();
    (s, r)
}

#[test]
fn placeholders_stand_on_the_frontier_and_read_back() {
    let (s, r) = partly_seen();
    let world = &r.world;
    assert!(!world.placeholders.is_empty(), "rooms never entered leave frontiers");
    let map = s.map.classified();
    let (w, h) = (map.width(), map.height());
    for p in &world.placeholders {
        let (x, y) = (p.x as usize, p.y as usize);
        assert_eq!(*map.at(x, y), Cell::Free, "placeholder {} stands on free floor", p.id);
        let beside = [(x.wrapping_sub(1), y), (x + 1, y), (x, y.wrapping_sub(1)), (x, y + 1)];
        let on_frontier = beside.iter().any(|&(a, b)| a < w && b < h && *map.at(a, b) == Cell::Unknown);
        // The cell nearest the stretch's centroid; a ragged stretch's centre may sit a cell off.
        let near = (y.saturating_sub(2)..=(y + 2).min(h - 1))
            .any(|b| (x.saturating_sub(2)..=(x + 2).min(w - 1)).any(|a| *map.at(a, b) == Cell::Unknown));
        assert!(on_frontier || near, "placeholder {} at ({x}, {y}) is beside unseen space", p.id);
        assert!(p.width_m >= 0.5 && p.width_m <= 4.0 * std::f64::consts::SQRT_2 + 0.1, "{}", p.width_m);
        assert!(p.room == 0 || world.rooms.iter().any(|room| room.id == p.room));
    }
    let ids: Vec<u32> = world.placeholders.iter().map(|p| p.id).collect();
    assert_eq!(ids, (1..=ids.len() as u32).collect::<Vec<_>>());
    // world.json reads back to the same world; graph.json lists the same placeholders.
    let text = world.to_json();
    assert_eq!(&World::from_json(&text).unwrap(), world);
    let graph: serde_json::Value = serde_json::from_str(&graph_json(world)).unwrap();
    assert_eq!(graph["placeholders"].as_array().unwrap().len(), world.placeholders.len());
    assert_eq!(graph["placeholders"][0]["room"], world.placeholders[0].room);
}

#[test]
fn the_svg_draws_a_pie_per_placeholder() {
    let (s, r) = partly_seen();
    let svg = ksmcmc::render::svg::world_svg(&r.world, &r.labels, s.map.yaml().resolution).unwrap();
    assert_eq!(svg.matches("data-placeholder=").count(), r.world.placeholders.len());
    assert!(svg.contains(r#"<g id="placeholders""#));
    // Only the room shapes carry data-room and data-type: `[data-room]` is one element a room.
    assert_eq!(svg.matches("data-room=").count(), r.world.rooms.len());
    assert_eq!(svg.matches("data-type=").count(), r.world.rooms.len());
}

#[test]
fn rooms_never_entered_raise_more_likely_new_rooms() {
    // The same floor seen whole and with rooms never entered: the frontiers of the whole floor
    // are its outside and its wall gaps, and fewer of them promise a new room.
    let s = generate(&SynthConfig::default(), 17).unwrap();
    let r = run(&s.map, &RunOptions { iterations: 4000, ..Default::default() }).unwrap();
    let (_, partial) = partly_seen();
    let likely = |w: &World| w.placeholders.iter().filter(|p| p.p_new_room >= 0.5).count();
    assert!(likely(&r.world) < likely(&partial.world), "{} vs {}", likely(&r.world), likely(&partial.world));
}

#[test]
fn damaged_placeholders_are_refused() {
    let (_, r) = partly_seen();
    let text = r.world.to_json();
    let mut v: serde_json::Value = serde_json::from_str(&text).unwrap();
    v["placeholders"][0]["p_new_room"] = serde_json::json!(1.5);
    let e = World::from_json(&v.to_string()).unwrap_err().to_string();
    assert!(e.contains("placeholder 1") && e.contains("probability"), "{e}");
    let mut v: serde_json::Value = serde_json::from_str(&text).unwrap();
    v["placeholders"][0]["room"] = serde_json::json!(9999);
    let e = World::from_json(&v.to_string()).unwrap_err().to_string();
    assert!(e.contains("room 9999"), "{e}");
    let mut v: serde_json::Value = serde_json::from_str(&text).unwrap();
    v["placeholders"][0]["x"] = serde_json::json!(-3);
    assert!(World::from_json(&v.to_string()).is_err());
}

#[test]
fn a_route_can_end_at_a_placeholder() {
    use crate::common::run_cli as run;
    let d = crate::common::tmp_dir("frontier", "route");
    let (dir, map) = (d.to_str().unwrap(), d.join("map.yaml"));
    let synth = run(&["synth", "--seed", "17", "--unexplored", "0.4", "--out", dir]);
    assert!(synth.status.success(), "{}", String::from_utf8_lossy(&synth.stderr));
    let out = d.join("plan");
    let fp = run(&["floorplan", map.to_str().unwrap(), "--iterations", "4000", "--out", out.to_str().unwrap()]);
    assert!(fp.status.success(), "{}", String::from_utf8_lossy(&fp.stderr));
    let world = World::from_json(&std::fs::read_to_string(out.join("world.json")).unwrap()).unwrap();
    let (a, b) = (&world.placeholders[0], world.placeholders.last().unwrap());
    let wj = out.join("world.json");
    let labels = out.join("labels.pgm");
    let from = format!("{},{}", a.x, a.y);
    let base = ["route", map.to_str().unwrap(), wj.to_str().unwrap(), "--labels", labels.to_str().unwrap(), "--from"];
    let to = b.id.to_string();
    let r = run(&[&base[..], &[&from, "--to-placeholder", &to]].concat());
    let by_cell = run(&[&base[..], &[&from, "--to", &format!("{},{}", b.x, b.y)]].concat());
    // The same route as to the placeholder's cell (or the same reason there is none).
    assert_eq!(r.stdout, by_cell.stdout);
    assert_eq!(r.status.code(), by_cell.status.code());
    if r.status.success() {
        let v: serde_json::Value = serde_json::from_slice(&r.stdout).unwrap();
        let last = v["path"].as_array().unwrap().last().unwrap().clone();
        assert_eq!(last, serde_json::json!([b.x, b.y]));
    }
    let missing = run(&[&base[..], &[&from, "--to-placeholder", "99999"]].concat());
    assert_eq!(missing.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&missing.stderr).contains("no placeholder 99999"));
}

#[test]
fn a_chains_own_frontier_and_room_rules_reach_the_plan_input() {
    use ksmcmc::floorplan::frontier::FRONTIER_RULES;
    use ksmcmc::floorplan::plan_input::PlanInput;
    use ksmcmc::floorplan::rooms::RoomConfig;
    use ksmcmc::floorplan::{Chain, ChainConfig};
    let s = generate(&SynthConfig { unexplored: 0.4, ..Default::default() }, 17).unwrap();
    let mut config = ChainConfig::default();
    config.knowledge.frontier_kb = Some(FRONTIER_RULES.to_string());
    let mut chain = Chain::new(&s.map, config, 1).unwrap();
    chain.step(3000);
    let (own, labels) = chain.best_world_with_rooms(&RoomConfig::default()).unwrap();
    // What the browser hands between its modules: the plan input as JSON text.
    let input = PlanInput::from_json(&PlanInput::of(&mut chain, 0.0).to_json()).unwrap();
    assert_eq!(input.frontier_kb.as_deref(), Some(FRONTIER_RULES));
    let (world, again) = input.explain(&s.map, None).unwrap();
    assert_eq!(again, labels);
    assert!(!own.placeholders.is_empty());
    assert_eq!(world.placeholders, own.placeholders);
    // The hand-set rules weigh them otherwise than the built-in ones the input used to fall
    // back to.
    let builtin = PlanInput { frontier_kb: None, ..input };
    let (plain, _) = builtin.explain(&s.map, None).unwrap();
    let p = |w: &World| w.placeholders.iter().map(|p| p.p_new_room).collect::<Vec<_>>();
    assert_ne!(p(&plain), p(&world));
}
