//! `world.json`: round trips and every way a file can be refused.

use ksmcmc::floorplan::{Door, UnexplainedArea, Unit, World};

fn world() -> World {
    let mut w = World::empty(40, 30);
    w.units.push(Unit::new(1, 0, 0, 20, 30, Default::default()));
    w.units.push(Unit::new(2, 19, 0, 21, 12, Default::default()));
    w.doors.push(Door { id: 1, units: [1, 2], x0: 19, y0: 4, x1: 19, y1: 8, opening: false });
    w.object_cells = vec![[3, 4], [3, 5]];
    w.unexplained.push(UnexplainedArea {
        id: 1,
        cells: 5,
        x0: 25,
        y0: 20,
        x1: 27,
        y1: 21,
        runs: vec![[20, 25, 27], [21, 26, 27]],
    });
    w
}

#[test]
fn a_world_round_trips_and_empty_lists_are_optional() {
    let w = world();
    w.validate().unwrap();
    assert_eq!(World::from_json(&w.to_json()).unwrap(), w);
    let bare = r#"{"format": "ksmcmc-world/1", "frame": {"angle": 0.0, "world_size": [4, 4], "map_size": [4, 4]}, "units": []}"#;
    let b = World::from_json(bare).unwrap();
    assert!(b.doors.is_empty() && b.object_cells.is_empty() && b.unexplained.is_empty());
    assert_eq!(b.wall_thickness, 1);
    // No unexplained areas: the field is left out rather than written empty.
    assert!(!World::empty(4, 4).to_json().contains("unexplained"));
}

#[test]
fn every_bad_world_is_refused_with_a_message_naming_the_problem() {
    let edit = |f: &dyn Fn(&mut World)| {
        let mut w = world();
        f(&mut w);
        w.validate().unwrap_err().to_string()
    };
    let cases: Vec<(String, &str)> = vec![
        (edit(&|w| w.format = "other/1".into()), "format"),
        (edit(&|w| w.frame.angle = f64::NAN), "angle"),
        (edit(&|w| w.frame.world_size = [0, 3]), "non-zero"),
        (edit(&|w| w.wall_thickness = 0), "wall_thickness"),
        (edit(&|w| w.units[1].id = 1), "appears twice"),
        (edit(&|w| w.units[0].w = 0), "size"),
        (edit(&|w| w.units[1].x = 30), "outside the 40x30 world"),
        (edit(&|w| w.units[0].y = -1), "outside"),
        (edit(&|w| w.doors[0].units = [1, 7]), "unit 7, which does not exist"),
        (edit(&|w| w.doors[0].x1 = 40), "outside the world"),
        (edit(&|w| w.object_cells.push([-1, 0])), "object cell"),
        (edit(&|w| w.unexplained[0].cells = 6), "says 6 cells but its runs hold 5"),
        (edit(&|w| w.unexplained[0].runs[0] = [20, 27, 25]), "reversed"),
        (edit(&|w| w.unexplained[0].runs[1] = [22, 26, 27]), "outside its box"),
        (edit(&|w| (w.unexplained[0].x1, w.unexplained[0].runs[0][2]) = (45, 45)), "outside the world"),
    ];
    for (err, needle) in cases {
        assert!(err.starts_with("world.json: "), "{err}");
        assert!(err.contains(needle), "expected {needle:?} in {err:?}");
    }
    for (text, needle) in [
        ("{", "world.json"),
        ("[]", "world.json"),
        (
            r#"{"format": "ksmcmc-world/1", "frame": {"angle": 0, "world_size": [4, 4], "map_size": [4, 4]}, "units": [], "colour": 1}"#,
            "colour",
        ),
        (
            r#"{"format": "ksmcmc-world/1", "frame": {"angle": 0, "world_size": [4, 4], "map_size": [4, 4]}, "units": [{"id": 1, "x": 0, "y": 0, "w": 2, "h": 2, "type": "kitchen"}]}"#,
            "kitchen",
        ),
    ] {
        let err = World::from_json(text).unwrap_err().to_string();
        assert!(err.contains(needle), "expected {needle:?} in {err:?}");
    }
}

/// Units at an angle of their own (issue 13): validated in their own frame, doors in their
/// first unit's frame, no wall shared across frames in the scene graph or the evidence, and
/// the tools that work in the world frame alone refuse them saying so.
#[test]
fn units_at_their_own_angle_are_checked_in_their_frame_and_refused_where_unsupported() {
    use ksmcmc::floorplan::{graph, knowledge, route::RoutePlanner, shapes, synth};
    let s = synth::generate(&synth::SynthConfig { wing_deg: 30.0, ..Default::default() }, 4).unwrap();
    let w = &s.truth;
    w.validate().unwrap();
    // A turned unit moved to where only its own frame holds it is still valid; past that, not.
    let i = w.units.iter().position(|u| u.angle.is_some()).unwrap();
    let [fw, _] = w.unit_frame(&w.units[i]).world_size;
    let mut far = w.clone();
    far.units[i].x = fw as i32 - far.units[i].w;
    far.doors.retain(|d| !d.units.contains(&far.units[i].id));
    far.validate().unwrap();
    far.units[i].x += 1;
    assert!(far.validate().unwrap_err().to_string().contains("outside"));
    // A door between units of two frames (where wings meet) lies in its first unit's frame.
    let mut mixed = w.clone();
    let (a, b) = (mixed.units[0].id, mixed.units[i].id);
    mixed.doors[0].units = [b, a];
    mixed.doors[0].x1 = fw as i32 - 1;
    mixed.validate().unwrap();
    mixed.doors[0].x1 = fw as i32;
    let e = mixed.validate().unwrap_err().to_string();
    assert!(e.contains("outside the world"), "{e}");
    // No wall adjacency and no Adj evidence between the wings.
    let g = graph::scene_graph(w);
    let turned = |id: u32| w.unit(id).unwrap().angle.is_some();
    for e in g.edge_indices() {
        let (p, q) = g.edge_endpoints(e).unwrap();
        assert_eq!(turned(g[p].id), turned(g[q].id), "edge across the wings");
    }
    let facts = knowledge::evidence(w, 0.05, &Default::default());
    let adj: Vec<_> = facts.iter().filter(|f| f.0 == "Adj").collect();
    assert!(!adj.is_empty());
    for (_, args, _) in adj {
        let id = |c: &str| c[1..].parse::<u32>().unwrap();
        assert_eq!(turned(id(&args[0])), turned(id(&args[1])));
    }
    // The world-frame tools say why they refuse.
    let labels = s.labels.clone();
    // Routes take them (they plan on the labels and the rooms' links, doors in their frame).
    assert!(RoutePlanner::new(s.map.classified().clone(), labels.clone(), w, 0.05).is_ok());
    let room_input = ksmcmc::floorplan::export::RoomInput::for_map(w.clone(), &s.map, true, Default::default());
    let e = room_input.err().unwrap().to_string();
    assert!(e.contains("issue 13"), "{e}");
    // The floor shapes take them (tests/it/world.rs, `floor_shapes_draw_units_at_their_own_angle`).
    assert!(shapes::floor_shapes(w, &labels).is_ok());
}

/// In a world of units at several angles the floor shapes outline each room from its label
/// cells in the frame of its units: a room of turned units exactly as in a world turned by
/// that angle, an upright room on the cell edges. `world.svg` draws walls and doors in their
/// units' frames and turns each room's label with its room. In a world of two wings every
/// room has a shape in its units' frame.
#[test]
fn floor_shapes_draw_units_at_their_own_angle() {
    use ksmcmc::floorplan::shapes::floor_shapes;
    use ksmcmc::floorplan::{synth, Frame, Room, UnitType};
    use ksmcmc::grid::Grid;
    let angle = 30f64.to_radians();
    let room = |id: u32, units: Vec<u32>| Room {
        id,
        kind: UnitType::Room,
        units,
        area_m2: 1.0,
        doors: vec![],
        opens_to: vec![],
        name: None,
    };
    let frame = Frame::turned(200, 150, angle);
    let units = vec![Unit::new(1, 60, 50, 31, 40, UnitType::Room), Unit::new(2, 90, 50, 31, 40, UnitType::Room)];
    let door = Door { id: 1, units: [1, 2], x0: 90, y0: 65, x1: 90, y1: 72, opening: false };
    // Labels: each turned unit's interior, and an upright square room 3.
    let mut labels = Grid::new(200, 150, 0u16);
    for my in 0..150 {
        for mx in 0..200 {
            let (x, y) = frame.to_world(mx as f64 + 0.5, my as f64 + 0.5);
            for u in &units {
                let r = u.rect();
                if x > (r.x + 1) as f64
                    && x < (r.right() - 1) as f64
                    && y > (r.y + 1) as f64
                    && y < (r.bottom() - 1) as f64
                {
                    *labels.at_mut(mx, my) = u.id as u16;
                }
            }
            if (150..180).contains(&mx) && (110..140).contains(&my) {
                *labels.at_mut(mx, my) = 3;
            }
        }
    }
    let mut turned = World::empty(200, 150);
    turned.frame = frame;
    turned.units = units.clone();
    turned.doors = vec![door];
    turned.rooms = vec![room(1, vec![]), room(2, vec![])];
    let mut own = World::empty(200, 150);
    own.units = units.iter().map(|u| Unit { angle: Some(angle), ..*u }).collect();
    own.units.push(Unit::new(3, 149, 109, 32, 32, UnitType::Corridor));
    own.doors = vec![door];
    own.rooms = vec![room(1, vec![1]), room(2, vec![2]), room(3, vec![3])];
    let (a, b) = (floor_shapes(&own, &labels).unwrap(), floor_shapes(&turned, &labels).unwrap());
    for k in 0..2 {
        assert!(!a.rooms[k].polygons.is_empty());
        assert_eq!(a.rooms[k].polygons, b.rooms[k].polygons, "room {}", k + 1);
        assert_eq!(a.rooms[k].angle, angle);
    }
    assert_eq!(a.doors, b.doors);
    assert_eq!(a.rooms[2].angle, 0.0);
    assert_eq!(a.rooms[2].polygons[0].exterior, vec![(150.0, 110.0), (150.0, 140.0), (180.0, 140.0), (180.0, 110.0)]);
    // world.svg: the turned units' walls and the door are the turned world's paths.
    let (sa, sb) = (ksmcmc::render::svg::svg(&a, &own, 0.05), ksmcmc::render::svg::svg(&b, &turned, 0.05));
    let door_path = |svg: &str| svg.lines().find(|l| l.contains("data-door=\"1\"")).unwrap().to_string();
    assert_eq!(door_path(&sa), door_path(&sb));
    let walls = |svg: &str| {
        let layer = svg.split("id=\"walls\"").nth(1).unwrap().split("</g>").next().unwrap().to_string();
        layer.split(" d=\"").nth(1).unwrap().split('"').next().unwrap().to_string()
    };
    assert!(walls(&sa).starts_with(&walls(&sb)), "{}\n{}", walls(&sa), walls(&sb));
    assert!(walls(&sa).len() > walls(&sb).len(), "and the upright unit's walls");
    assert!(sa.contains("rotate(30 "), "room labels turn with their rooms");

    // A generated floor of two wings, its truth labels as rooms: every room has a shape.
    let s = synth::generate(&synth::SynthConfig { wing_deg: 45.0, ..Default::default() }, 2).unwrap();
    let mut w = s.truth.clone();
    w.rooms = w.units.iter().map(|u| room(u.id, vec![u.id])).collect();
    let shapes = floor_shapes(&w, &s.labels).unwrap();
    assert_eq!(shapes.rooms.len(), w.rooms.len());
    for (r, u) in shapes.rooms.iter().zip(&w.units) {
        assert!(!r.polygons.is_empty(), "room {}", r.id);
        assert_eq!(r.angle, w.unit_frame(u).angle, "room {} in its unit's frame", r.id);
    }
}
