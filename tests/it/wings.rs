//! A chain per wing (`floorplan::wings`, issue 13): on two buildings at an angle, units at both
//! angles that explain the map better than one chain's, with the one chain's segmentation.

use ksmcmc::floorplan::metrics::prediction_rate;
use ksmcmc::floorplan::synth::{generate, SynthConfig};
use ksmcmc::floorplan::wings::{WingConfig, Wings};
use ksmcmc::floorplan::{Chain, ChainConfig};

const ITERATIONS: u64 = 8000;

#[test]
fn two_wings_are_explained_each_in_its_own_frame() {
    let rooms = Default::default();
    for (wing, seed) in [(30.0, 11), (-45.0, 12)] {
        let s = generate(&SynthConfig { wing_deg: wing, ..SynthConfig::default() }, seed).unwrap();
        let w = Wings::run(&s.map, &ChainConfig::default(), &WingConfig::default(), 1, ITERATIONS, &rooms).unwrap();
        assert_eq!(w.chains.len(), 3, "wing {wing}: the first chain and one per wing");
        w.world.validate().unwrap();
        let frames: std::collections::BTreeSet<String> =
            w.world.units.iter().map(|u| format!("{:.6}", w.world.unit_frame(u).angle)).collect();
        assert_eq!(frames.len(), 2, "wing {wing}: units at {frames:?}");
        // The segmentation is the one chain's, bit for bit.
        let mut one = Chain::new(&s.map, ChainConfig::default(), 1).unwrap();
        one.step(ITERATIONS);
        let (single, labels) = one.best_world_with_rooms(&rooms).unwrap();
        assert!(w.labels == labels, "wing {wing}: the labels differ from the one chain's");
        assert_eq!(w.world.rooms.len(), single.rooms.len());
        // Units upright in each wing explain the map better than one frame's.
        let (k_one, k_wings) =
            (prediction_rate(s.map.classified(), &single), prediction_rate(s.map.classified(), &w.world));
        assert!(k_wings > k_one + 0.01, "wing {wing}: K {k_wings:.4} with wings, {k_one:.4} with one chain");
        // Every room's units lie in the room (most of their interior carries its label).
        let in_rooms = w.world.rooms.iter().map(|r| r.units.len()).sum::<usize>();
        assert!(
            in_rooms as f64 >= 0.8 * w.world.units.len() as f64,
            "{in_rooms} of {} units in rooms",
            w.world.units.len()
        );
        // The wings are joined where the building's passage leads from one into the other: a
        // door between units of the two angles.
        let turned = |id: u32| w.world.unit(id).unwrap().angle.is_some();
        let across = w.world.doors.iter().filter(|d| turned(d.units[0]) != turned(d.units[1])).count();
        assert!(across >= 1, "wing {wing}: no door between the wings");
        // Same seed, same world.
        let again = Wings::run(&s.map, &ChainConfig::default(), &WingConfig::default(), 1, ITERATIONS, &rooms).unwrap();
        assert_eq!(again.world.to_json(), w.world.to_json());
    }
}

#[test]
fn a_building_in_one_direction_is_one_chain() {
    let s = generate(&SynthConfig { rotation_deg: 20.0, ..SynthConfig::default() }, 3).unwrap();
    let rooms = Default::default();
    let w = Wings::run(&s.map, &ChainConfig::default(), &WingConfig::default(), 2, 3000, &rooms).unwrap();
    assert_eq!(w.chains.len(), 1);
    let mut one = Chain::new(&s.map, ChainConfig::default(), 2).unwrap();
    one.step(3000);
    let (world, labels) = one.best_world_with_rooms(&rooms).unwrap();
    assert_eq!(w.world, world);
    assert!(w.labels == labels);
}

/// Routes run across the wings of a wings world: from a room of the first wing to one of the
/// second, on free cells, 8-connected, through the doors of both wings' units.
#[test]
fn routes_cross_from_one_wing_to_the_other() {
    use ksmcmc::floorplan::route::RoutePlanner;
    use ksmcmc::grid::Cell;
    let s = generate(&SynthConfig { wing_deg: 30.0, ..SynthConfig::default() }, 13).unwrap();
    let w = Wings::run(&s.map, &ChainConfig::default(), &WingConfig::default(), 1, ITERATIONS, &Default::default())
        .unwrap();
    let g = s.map.classified();
    let mut planner = RoutePlanner::new(g.clone(), w.labels.clone(), &w.world, 0.05).unwrap();
    // A free cell in the middle of each truth wing's largest room.
    let centre = |turned: bool| {
        let (i, u) = s
            .truth
            .units
            .iter()
            .enumerate()
            .filter(|(_, u)| u.angle.is_some() == turned)
            .max_by_key(|(_, u)| u.w * u.h)
            .unwrap();
        let want = i as u16 + 1;
        let cells: Vec<usize> = (0..g.cells().len())
            .filter(|&c| s.labels.cells()[c] == want && g.cells()[c] == Cell::Free && w.labels.cells()[c] > 0)
            .collect();
        assert!(!cells.is_empty(), "unit {} has no labelled free cell", u.id);
        let c = cells[cells.len() / 2];
        ((c % g.width()) as i64, (c / g.width()) as i64)
    };
    let (from, to) = (centre(false), centre(true));
    let route = planner.route(from, to).unwrap();
    assert_eq!(route.path.first().copied(), Some([from.0 as u32, from.1 as u32]));
    assert_eq!(route.path.last().copied(), Some([to.0 as u32, to.1 as u32]));
    for pair in route.path.windows(2) {
        let ([ax, ay], [bx, by]) = (pair[0], pair[1]);
        assert!(ax.abs_diff(bx) <= 1 && ay.abs_diff(by) <= 1, "a jump in the path");
    }
    assert!(route.path.iter().all(|&[x, y]| *g.at(x as usize, y as usize) == Cell::Free), "the path leaves free space");
    assert!(route.rooms.len() >= 2, "{:?}", route.rooms);
}

/// The doors between the wings keep to the chains' door limits, natively and in the plan
/// input the browser composes the wings from: none where every passage between the wings is
/// narrower than the shortest door allowed (3 m).
#[test]
fn doors_between_the_wings_keep_to_the_door_limits() {
    use ksmcmc::floorplan::plan_input::PlanInput;
    use ksmcmc::floorplan::DoorSizes;
    let s = generate(&SynthConfig { wing_deg: 30.0, ..SynthConfig::default() }, 11).unwrap();
    let doors = DoorSizes { min_m: 3.0, max_m: 4.0, ..DoorSizes::default() };
    let config = ChainConfig { doors, ..ChainConfig::default() };
    let w = Wings::run(&s.map, &config, &WingConfig::default(), 1, ITERATIONS, &Default::default()).unwrap();
    assert_eq!(w.chains.len(), 3);
    let turned = |id: u32| w.world.unit(id).unwrap().angle.is_some();
    let across = w.world.doors.iter().filter(|d| turned(d.units[0]) != turned(d.units[1])).count();
    assert_eq!(across, 0, "no door between the wings under 3 m");
    let mut first = Chain::new(&s.map, config, 1).unwrap();
    let input = PlanInput::from_json(&PlanInput::of(&mut first, 0.0).to_json()).unwrap();
    assert_eq!(input.doors, doors, "the plan input carries the chain's door limits");
}

/// The browser's way to a building's wings: the first chain's plan input finds the layout,
/// each wing's chain runs on the wing's map as PGM and YAML with its settings as JSON text,
/// and the plan inputs compose the world `Wings::run` makes, with the same room labels.
#[test]
fn plan_inputs_of_the_wings_compose_the_world_of_wings_run() {
    use ksmcmc::floorplan::plan_input::PlanInput;
    use ksmcmc::grid::{Limits, OccupancyMap};
    let s = generate(&SynthConfig { wing_deg: 30.0, width: 240, height: 160, ..Default::default() }, 1).unwrap();
    let (seed, iterations) = (2, 1500);
    let config = ChainConfig::default();
    let wings = Wings::run(&s.map, &config, &WingConfig::default(), seed, iterations, &Default::default()).unwrap();
    assert_eq!(wings.chains.len(), 3, "the first chain, then one per wing");

    let text = |chain: &mut Chain| PlanInput::from_json(&PlanInput::of(chain, 0.0).to_json()).unwrap();
    let mut first = Chain::new(&s.map, config.clone(), seed).unwrap();
    first.step(iterations);
    let input = text(&mut first);
    let (_, labels) = input.explain(&s.map, None).unwrap();
    let layout = input.wing_layout(&s.map, &labels).expect("two wings");
    let mut inputs = Vec::new();
    for k in 0..layout.angles.len() {
        let wing = layout.wing_map(&s.map, k);
        let map =
            OccupancyMap::from_yaml_and_pgm(&wing.to_yaml("map.pgm"), &wing.to_pgm(), &Limits::default()).unwrap();
        assert_eq!(map.classified(), wing.classified(), "wing {k}'s map reads back from its PGM");
        let deg = layout.wing_config(&config, k).detectors.rotation_deg.unwrap();
        let json = format!(r#"{{"detectors": {{"rotation_deg": {}}}}}"#, serde_json::to_string(&deg).unwrap());
        let c = ChainConfig::from_json(&json).unwrap();
        assert_eq!(c, layout.wing_config(&config, k), "wing {k}'s settings read back from {json}");
        let mut chain = Chain::new(&map, c, seed).unwrap();
        chain.step(iterations);
        inputs.push(text(&mut chain));
    }
    let (world, labels) = input.explain_wings(&s.map, &inputs).unwrap();
    assert!(world == wings.world, "the composed world is Wings::run's");
    assert!(labels == wings.labels, "and so are its room labels");
    // Wings that do not fit the layout are refused, saying why.
    let err = input.explain_wings(&s.map, &inputs[..1]).unwrap_err().to_string();
    assert!(err.contains("2 wings, but 1 wing chains"), "{err}");
    let err = input.explain_wings(&s.map, &[inputs[1].clone(), inputs[0].clone()]).unwrap_err().to_string();
    assert!(err.contains("rotation_deg"), "{err}");
}

/// A wing's direction as a chain's setting reads back from JSON text to the same bits, which
/// 17-digit numbers do not always do (serde_json's fast reader).
#[test]
fn wing_directions_read_back_from_json_exactly() {
    use ksmcmc::floorplan::wings::wing_rotation_deg;
    let mut x: u64 = 0x9e37_79b9_7f4a_7c15;
    for _ in 0..20_000 {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        let angle = (x >> 11) as f64 / (1u64 << 53) as f64 * std::f64::consts::PI - std::f64::consts::FRAC_PI_2;
        let deg = wing_rotation_deg(angle);
        assert!((deg - angle.to_degrees()).abs() <= 5e-7);
        let json = format!(r#"{{"detectors": {{"rotation_deg": {}}}}}"#, serde_json::to_string(&deg).unwrap());
        let back = ChainConfig::from_json(&json).unwrap().detectors.rotation_deg.unwrap();
        assert_eq!(back.to_bits(), deg.to_bits(), "{json}");
    }
}

/// The room layer by the walls is the same from a chain and from its plan input.
#[test]
fn rooms_by_the_walls_are_the_same_from_a_chain_and_from_its_room_input() {
    use ksmcmc::floorplan::export::RoomInput;
    use ksmcmc::floorplan::rooms::RoomConfig;
    let s = generate(&SynthConfig { wing_deg: 30.0, width: 240, height: 160, ..Default::default() }, 4).unwrap();
    let mut chain = Chain::new(&s.map, ChainConfig::default(), 1).unwrap();
    chain.step(1500);
    let rooms = RoomConfig::default();
    let angles = [30f64.to_radians()];
    let (mut world, _) = chain.best_world_with_rooms(&rooms).unwrap();
    let labels = chain.rooms_by_walls(&mut world, &rooms, &angles).unwrap();
    let input = RoomInput::for_map(chain.best_world_typed(), &s.map, true, Default::default()).unwrap();
    let (other, other_labels) = input.by_walls(&angles).explain(&rooms).unwrap();
    assert!(other == world && other_labels == labels);
    assert!(world.rooms.len() > 3, "{} rooms", world.rooms.len());
}

/// A stopped chain (`Chain::stop`, which frees the sampling tables before the rooms are read)
/// reports, types and groups its best world exactly as the running chain did, by units and by
/// the walls, with or without knowledge supervision.
#[test]
fn a_stopped_chain_keeps_its_record_its_types_and_its_rooms() {
    use ksmcmc::floorplan::report::ChainSummary;
    use ksmcmc::floorplan::rooms::RoomConfig;
    let s = generate(&SynthConfig { wing_deg: 30.0, width: 240, height: 160, ..Default::default() }, 4).unwrap();
    let (rooms, angles) = (RoomConfig::default(), [30f64.to_radians()]);
    for knowledge in [true, false] {
        let mut config = ChainConfig::default();
        config.knowledge.enabled = knowledge;
        let mut chain = Chain::new(&s.map, config, 1).unwrap();
        chain.step(1500);
        let typed = chain.best_world_typed();
        let (mut world, labels) = chain.best_world_with_rooms(&rooms).unwrap();
        let by_walls = chain.rooms_by_walls(&mut world.clone(), &rooms, &angles).unwrap();
        let (summary, untyped) = (ChainSummary::of(&chain, 1.0), chain.best_world());
        let mut stopped = chain.stop();
        assert_eq!(ChainSummary::of(&stopped, 1.0), summary, "knowledge {knowledge}");
        assert!(*stopped.best_world() == untyped && stopped.best_world_typed() == typed);
        assert!(stopped.best_world_with_rooms(&rooms).unwrap() == (world.clone(), labels));
        assert_eq!(stopped.rooms_by_walls(&mut world, &rooms, &angles).unwrap(), by_walls);
        assert!(world.rooms.len() > 3, "{} rooms", world.rooms.len());
    }
}
