//! Routes through rooms and doors (floorplan::route): valid paths, the rooms and doors they
//! list, errors, and their length against the shortest free path on generated floors.

use ksmcmc::floorplan::knowledge::KnowledgeConfig;
use ksmcmc::floorplan::rooms::{Grouping, RoomConfig, RoomLayer, RoomMaps};
use ksmcmc::floorplan::route::study::{length, stretch};
use ksmcmc::floorplan::route::{Planned, Route, RouteError, RoutePlanner};
use ksmcmc::floorplan::synth::{generate, SynthConfig};
use ksmcmc::floorplan::{Door, Unit, UnitType, World};
use ksmcmc::grid::{Cell, Grid};
use ksmcmc::mcmc::Rng;

/// Checks what every route must be: starts at `from`, ends at `to`, 8-connected, every cell
/// free, no diagonal step past an occupied cell; and its length is its steps'.
fn assert_valid(route: &Route, map: &Grid<Cell>, from: [u32; 2], to: [u32; 2], resolution: f64) {
    let p = &route.path;
    assert_eq!((p[0], *p.last().unwrap()), (from, to), "ends");
    let cell = |c: [u32; 2]| *map.at(c[0] as usize, c[1] as usize);
    for &c in p {
        assert_eq!(cell(c), Cell::Free, "cell {c:?} is not free");
    }
    let mut len = 0.0;
    for s in p.windows(2) {
        let (dx, dy) = (s[1][0] as i64 - s[0][0] as i64, s[1][1] as i64 - s[0][1] as i64);
        assert!(dx.abs() <= 1 && dy.abs() <= 1 && (dx, dy) != (0, 0), "not 8-connected: {:?} -> {:?}", s[0], s[1]);
        if dx != 0 && dy != 0 {
            assert_ne!(cell([s[1][0], s[0][1]]), Cell::Occupied, "cuts a corner: {:?} -> {:?}", s[0], s[1]);
            assert_ne!(cell([s[0][0], s[1][1]]), Cell::Occupied, "cuts a corner: {:?} -> {:?}", s[0], s[1]);
            len += std::f64::consts::SQRT_2;
        } else {
            len += 1.0;
        }
    }
    assert!((route.length_m - len * resolution).abs() < 1e-9, "{} against {}", route.length_m, len * resolution);
}

/// A 100 x 60 floor: a corridor along the top (rows 1..19), three rooms below (columns 1..32,
/// 34..65, 67..98, rows 21..58), walls one cell thick; doors from the corridor into rooms 1
/// and 3 (columns 10..14 and 80..84 of row 20) and between rooms 1 and 2 (rows 40..44 of
/// column 33). Room 2 has no door to the corridor. Units are the rooms; the labels number the
/// corridor 1 and the rooms 2, 3, 4 (door cells take the room below or left of them).
fn floor() -> (Grid<Cell>, World, Grid<u16>) {
    let (w, h) = (100usize, 60usize);
    let mut map = Grid::new(w, h, Cell::Occupied);
    let mut labels = Grid::new(w, h, 0u16);
    let mut open = |x0: usize, x1: usize, y0: usize, y1: usize, l: u16| {
        for y in y0..y1 {
            for x in x0..x1 {
                *map.at_mut(x, y) = Cell::Free;
                *labels.at_mut(x, y) = l;
            }
        }
    };
    open(1, 99, 1, 20, 1);
    open(1, 33, 21, 59, 2);
    open(34, 66, 21, 59, 3);
    open(67, 99, 21, 59, 4);
    open(10, 15, 20, 21, 2);
    open(80, 85, 20, 21, 4);
    open(33, 34, 40, 45, 2);
    let mut world = World::empty(w as u32, h as u32);
    let unit = |id, x, y, w, h, kind| Unit::new(id, x, y, w, h, kind);
    world.units = vec![
        unit(1, 0, 0, 100, 21, UnitType::Corridor),
        unit(2, 0, 20, 34, 40, UnitType::Room),
        unit(3, 33, 20, 34, 40, UnitType::Room),
        unit(4, 66, 20, 34, 40, UnitType::Room),
    ];
    let door = |id, units, x0, y0, x1, y1| Door { id, units, x0, y0, x1, y1, opening: false };
    world.doors =
        vec![door(11, [1, 2], 10, 20, 14, 20), door(12, [1, 4], 80, 20, 84, 20), door(13, [2, 3], 33, 40, 33, 44)];
    (map, world, labels)
}

#[test]
fn a_route_lists_the_rooms_and_doors_it_passes() {
    let (map, world, labels) = floor();
    let mut planner = RoutePlanner::new(map.clone(), labels, &world, 0.05).unwrap();
    // From room 3 (label 3) to room 4 (label 4): through room 2, the corridor and door 12.
    let r = planner.route((50, 50), (90, 50)).unwrap();
    assert_valid(&r, &map, [50, 50], [90, 50], 0.05);
    assert_eq!(r.rooms, vec![3, 2, 1, 4]);
    assert_eq!(r.doors, vec![13, 11, 12]);
    assert_eq!(r.planned, Planned::Rooms);
    // No shorter free path exists: the route is the shortest path here.
    let w = map.width();
    let best = planner.shortest(50 * w + 50, 50 * w + 90).unwrap();
    assert!((r.length_m - length(&best, w) * 0.05).abs() < 1e-9);
    // Within one room: no door, one room.
    let r = planner.route((40, 30), (60, 55)).unwrap();
    assert_valid(&r, &map, [40, 30], [60, 55], 0.05);
    assert_eq!((r.rooms.clone(), r.doors.clone()), (vec![3], vec![]));
    // Start = goal: one cell, no length.
    let r = planner.route((5, 5), (5, 5)).unwrap();
    assert_eq!((r.path.clone(), r.rooms.clone(), r.length_m), (vec![[5, 5]], vec![1], 0.0));
    // The JSON has the four fields of `ksmcmc route`.
    let json: serde_json::Value = serde_json::from_str(&planner.route((50, 50), (90, 50)).unwrap().to_json()).unwrap();
    let keys: Vec<&str> = json.as_object().unwrap().keys().map(|k| k.as_str()).collect();
    assert_eq!(keys, ["doors", "length_m", "path", "rooms"]);
    assert_eq!(json["doors"], serde_json::json!([13, 11, 12]));
}

#[test]
fn the_room_graph_decides_which_rooms_a_route_may_pass() {
    let (map, mut world, labels) = floor();
    // A room layer in which room 2 (label 2) opens to the corridor only, not to room 3: the
    // route from room 3 then has no way on the room graph and is planned on cells.
    let room = |id: u32, opens_to: Vec<u32>| ksmcmc::floorplan::Room {
        id,
        kind: UnitType::Room,
        units: vec![id],
        area_m2: 1.0,
        doors: vec![],
        opens_to,
        name: None,
    };
    world.rooms = vec![room(1, vec![2, 4]), room(2, vec![1]), room(3, vec![]), room(4, vec![1])];
    let mut planner = RoutePlanner::new(map.clone(), labels.clone(), &world, 0.05).unwrap();
    let r = planner.route((50, 50), (90, 50)).unwrap();
    assert_eq!(r.planned, Planned::Cells);
    assert_valid(&r, &map, [50, 50], [90, 50], 0.05);
    assert_eq!(r.rooms, vec![3, 2, 1, 4], "the rooms its cells pass");
    // Between rooms the graph joins, it plans on rooms.
    let r = planner.route((20, 50), (90, 50)).unwrap();
    assert_eq!((r.planned, r.rooms.clone()), (Planned::Rooms, vec![2, 1, 4]));
}

#[test]
fn bad_ends_and_unreachable_goals_are_errors_that_say_why() {
    let (mut map, world, mut labels) = floor();
    // Close door 12: room 4 is then cut off.
    for x in 80..85 {
        *map.at_mut(x, 20) = Cell::Occupied;
        *labels.at_mut(x, 20) = 0;
    }
    *map.at_mut(50, 10) = Cell::Unknown;
    let mut planner = RoutePlanner::new(map, labels, &world, 0.05).unwrap();
    let e = planner.route((150, 5), (5, 5)).unwrap_err();
    assert!(matches!(e, RouteError::OffMap { .. }), "{e:?}");
    assert!(e.to_string().contains("start (150, 5) lies outside the 100x60 map"), "{e}");
    let e = planner.route((5, 5), (5, -1)).unwrap_err();
    assert!(e.to_string().contains("goal (5, -1) lies outside"), "{e}");
    let e = planner.route((0, 0), (5, 5)).unwrap_err();
    assert!(e.to_string().contains("start (0, 0) is an occupied cell"), "{e}");
    let e = planner.route((5, 5), (50, 10)).unwrap_err();
    assert!(e.to_string().contains("goal (50, 10) is an unknown cell"), "{e}");
    let e = planner.route((5, 5), (90, 50)).unwrap_err();
    assert_eq!(e, RouteError::Unreachable { from: (5, 5), to: (90, 50) });
    assert!(e.to_string().contains("no route from (5, 5) to (90, 50)"), "{e}");
}

#[test]
fn labels_and_worlds_of_other_maps_are_refused() {
    let (map, world, _) = floor();
    let e = RoutePlanner::new(map.clone(), Grid::new(10, 10, 0), &world, 0.05).unwrap_err();
    assert!(e.to_string().contains("labels are 10x10 but the map is 100x60"), "{e}");
    let other = World::empty(50, 50);
    let e = RoutePlanner::new(map, Grid::new(100, 60, 0), &other, 0.05).unwrap_err();
    assert!(e.to_string().contains("explains a 50x50 map"), "{e}");
}

/// The map resampled into `world`'s frame (nearest cell; unknown off the map).
fn in_frame(map: &Grid<Cell>, world: &World) -> Grid<Cell> {
    let [ww, wh] = world.frame.world_size.map(|v| v as usize);
    let mut out = Grid::new(ww, wh, Cell::Unknown);
    for y in 0..wh {
        for x in 0..ww {
            let (mx, my) = world.frame.to_map(x as f64 + 0.5, y as f64 + 0.5);
            if mx >= 0.0 && my >= 0.0 && (mx as usize) < map.width() && (my as usize) < map.height() {
                *out.at_mut(x, y) = *map.at(mx as usize, my as usize);
            }
        }
    }
    out
}

/// Checks routes between `pairs` pairs of free cells in different rooms of `labels` (drawn
/// with `seed`): each is valid, lists at least two rooms, and is at most 1.25 times the
/// shortest free path. Returns the mean and largest ratio.
fn check_routes(
    map: &Grid<Cell>,
    world: &World,
    labels: Grid<u16>,
    resolution: f64,
    pairs: usize,
    seed: u64,
) -> (f64, f64) {
    let mut planner = RoutePlanner::new(map.clone(), labels.clone(), world, resolution).unwrap();
    let w = map.width();
    // Free cells of rooms: a room's label also covers the clutter it encloses.
    let cells: Vec<usize> =
        (0..labels.len()).filter(|&i| labels.cells()[i] != 0 && map.cells()[i] == Cell::Free).collect();
    let mut rng = Rng::seed(seed);
    let (mut sum, mut max, mut n) = (0.0, 0.0f64, 0);
    while n < pairs {
        let (a, b) = (cells[rng.index(cells.len())], cells[rng.index(cells.len())]);
        if labels.cells()[a] == labels.cells()[b] {
            continue;
        }
        let xy = |i: usize| [(i % w) as u32, (i / w) as u32];
        let at = |i: usize| ((i % w) as i64, (i / w) as i64);
        let Some(best) = planner.shortest(a, b) else {
            assert!(matches!(planner.route(at(a), at(b)), Err(RouteError::Unreachable { .. })));
            continue;
        };
        let r = planner.route(at(a), at(b)).unwrap();
        assert_valid(&r, map, xy(a), xy(b), resolution);
        let ratio = r.length_m / (length(&best, w) * resolution);
        assert!(ratio >= 1.0 - 1e-4, "seed {seed}: shorter than the shortest path? {ratio}");
        assert!(ratio <= 1.25, "seed {seed}: route {:?} -> {:?} is {ratio:.3} times the shortest path", xy(a), xy(b));
        assert!(r.rooms.len() >= 2, "different rooms, so at least two: {:?}", r.rooms);
        sum += ratio;
        max = max.max(ratio);
        n += 1;
    }
    (sum / n as f64, max)
}

/// Routes on a generated floor's truth world, with its room layer.
/// The rooms of `world` by the default room layer with knowledge supervision.
fn rooms_with_knowledge(world: &mut World, maps: RoomMaps) -> Grid<u16> {
    let layer = RoomLayer::new(RoomConfig::default(), &KnowledgeConfig::default()).unwrap();
    layer.explain(world, maps, Grouping::Units(&Default::default())).unwrap()
}

fn routes_on_truth(config: &SynthConfig, seed: u64, pairs: usize) -> (f64, f64) {
    let s = generate(config, seed).unwrap();
    let map = s.map.classified();
    let resolution = s.map.yaml().resolution;
    let mut world = s.truth.clone();
    let world_map = in_frame(map, &world);
    let labels = rooms_with_knowledge(&mut world, RoomMaps { map, world_map: &world_map, resolution });
    assert!(world.rooms.len() >= 3, "seed {seed}: {} rooms", world.rooms.len());
    check_routes(map, &world, labels, resolution, pairs, seed)
}

#[test]
fn routes_on_generated_floors_stay_close_to_the_shortest_path() {
    let kinds = [
        SynthConfig::default(),
        SynthConfig { width: 500, height: 400, corridors: Some(2), ..SynthConfig::default() },
        SynthConfig { clutter: 0.1, ..SynthConfig::default() },
        SynthConfig { rotation_deg: 20.0, ..SynthConfig::default() },
    ];
    for (k, config) in kinds.iter().enumerate() {
        for seed in 1..=3 {
            let (mean, max) = routes_on_truth(config, seed, 40);
            println!("truth, kind {k} seed {seed}: ratio mean {mean:.4} max {max:.4}");
        }
    }
}

#[test]
fn the_stretch_study_measures_what_routes_are_measured_by() {
    let s = generate(&SynthConfig::default(), 5).unwrap();
    let map = s.map.classified();
    let mut world = s.truth.clone();
    let labels = rooms_with_knowledge(&mut world, RoomMaps { map, world_map: map, resolution: 0.05 });
    let mut planner = RoutePlanner::new(map.clone(), labels, &world, 0.05).unwrap();
    let st = stretch(&mut planner, 30, 2);
    assert_eq!(st.pairs + st.unreachable, 30);
    assert!(st.pairs > 0 && st.mean >= 1.0 - 1e-4 && st.max >= st.mean && st.max <= 1.25, "{st:?}");
    // The worst pair, routed again, has the largest ratio.
    let [a, b] = st.worst;
    let r = planner.route((a[0] as i64, a[1] as i64), (b[0] as i64, b[1] as i64)).unwrap();
    let w = map.width();
    let best = planner.shortest(a[1] as usize * w + a[0] as usize, b[1] as usize * w + b[0] as usize).unwrap();
    assert!((r.length_m / (length(&best, w) * 0.05) - st.max).abs() < 1e-9);
    // Same seed, same figures.
    assert_eq!(stretch(&mut planner, 30, 2), st);
}

/// Routes on floors the chain explained (its best world and room labels, as `ksmcmc
/// floorplan` writes them), as a robot would get them: the same checks.
#[test]
fn routes_on_explained_floors_stay_close_to_the_shortest_path() {
    use ksmcmc::floorplan::{Chain, ChainConfig};
    for seed in [1, 2] {
        let s = generate(&SynthConfig::default(), seed).unwrap();
        let mut chain = Chain::new(&s.map, ChainConfig::default(), seed).unwrap();
        chain.step(6000);
        let (world, labels) = chain.best_world_with_rooms(&RoomConfig::default()).unwrap();
        assert!(world.rooms.len() >= 3, "seed {seed}: {} rooms", world.rooms.len());
        let (mean, max) = check_routes(s.map.classified(), &world, labels, 0.05, 60, seed);
        println!("explained, seed {seed}: ratio mean {mean:.4} max {max:.4}");
    }
}

/// A saved world's labels are found again only when its rooms are those its units and doors
/// give: an edited room layer is refused, with a pointer to labels.pgm.
#[test]
fn saved_labels_are_found_again_only_for_the_worlds_own_rooms() {
    use ksmcmc::floorplan::route::saved_labels;
    use ksmcmc::floorplan::{Chain, ChainConfig};
    let s = generate(&SynthConfig::default(), 4).unwrap();
    let mut chain = Chain::new(&s.map, ChainConfig::default(), 4).unwrap();
    chain.step(3000);
    let (mut world, labels) = chain.best_world_with_rooms(&RoomConfig::default()).unwrap();
    assert!(saved_labels(&world, &s.map).unwrap() == labels);
    // Without knowledge supervision the rooms are found by the rule without it: found too.
    let mut config = ChainConfig::default();
    config.knowledge.enabled = false;
    let mut weak = Chain::new(&s.map, config, 4).unwrap();
    weak.step(3000);
    let (weak_world, weak_labels) = weak.best_world_with_rooms(&RoomConfig::default()).unwrap();
    assert!(saved_labels(&weak_world, &s.map).unwrap() == weak_labels);
    world.rooms[0].opens_to.push(9999);
    let e = saved_labels(&world, &s.map).unwrap_err();
    assert!(e.to_string().contains("pass the labels.pgm written with it"), "{e}");
}
