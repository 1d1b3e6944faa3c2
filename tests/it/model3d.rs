//! The 3D world (render::model3d, `world.glb`): the container, the nodes, the heights, the
//! openings at doors, the slabs' colours and where the model lies. (The Khronos validator
//! checks the files in the browser tests, tests/e2e/model3d.test.mjs.)

use ksmcmc::floorplan::{Door, Room, Unit, UnitType, World};
use ksmcmc::render::glb::linear;
use ksmcmc::render::model3d::{world_glb, Model3dOptions, SLAB_M};
use ksmcmc::render::unit_type_rgb;
use serde_json::Value;

/// A parsed `.glb`: its JSON and its binary chunk.
struct Glb {
    json: Value,
    bin: Vec<u8>,
}

fn parse(bytes: &[u8]) -> Glb {
    let u32_at = |i: usize| u32::from_le_bytes(bytes[i..i + 4].try_into().unwrap()) as usize;
    assert_eq!(&bytes[0..4], b"glTF");
    assert_eq!(u32_at(4), 2, "version 2");
    assert_eq!(u32_at(8), bytes.len(), "the header's length is the file's");
    let json_len = u32_at(12);
    assert_eq!(&bytes[16..20], b"JSON");
    assert_eq!(json_len % 4, 0);
    let json: Value = serde_json::from_slice(&bytes[20..20 + json_len]).unwrap();
    let at = 20 + json_len;
    if at == bytes.len() {
        return Glb { json, bin: Vec::new() }; // no meshes, no binary chunk
    }
    let bin_len = u32_at(at);
    assert_eq!(&bytes[at + 4..at + 8], b"BIN\0");
    assert_eq!(at + 8 + bin_len, bytes.len());
    Glb { json, bin: bytes[at + 8..].to_vec() }
}

impl Glb {
    fn node(&self, name: &str) -> Option<&Value> {
        self.json["nodes"].as_array().unwrap().iter().find(|n| n["name"] == name)
    }

    fn names(&self) -> Vec<String> {
        self.json["nodes"].as_array().unwrap().iter().map(|n| n["name"].as_str().unwrap().to_string()).collect()
    }

    /// The positions of a node's mesh (all primitives).
    fn positions(&self, name: &str) -> Vec<[f32; 3]> {
        let mesh = &self.json["meshes"][self.node(name).unwrap()["mesh"].as_u64().unwrap() as usize];
        let mut out = Vec::new();
        for p in mesh["primitives"].as_array().unwrap() {
            let a = &self.json["accessors"][p["attributes"]["POSITION"].as_u64().unwrap() as usize];
            let v = &self.json["bufferViews"][a["bufferView"].as_u64().unwrap() as usize];
            let off = v["byteOffset"].as_u64().unwrap() as usize;
            for k in 0..a["count"].as_u64().unwrap() as usize {
                let f = |j: usize| f32::from_le_bytes(self.bin[off + 12 * k + 4 * j..][..4].try_into().unwrap());
                out.push([f(0), f(1), f(2)]);
            }
        }
        out
    }

    /// The material colour of a node's first primitive.
    fn color(&self, name: &str) -> Vec<f64> {
        let mesh = &self.json["meshes"][self.node(name).unwrap()["mesh"].as_u64().unwrap() as usize];
        let m = mesh["primitives"][0]["material"].as_u64().unwrap() as usize;
        let c = &self.json["materials"][m]["pbrMetallicRoughness"]["baseColorFactor"];
        c.as_array().unwrap().iter().map(|v| v.as_f64().unwrap()).collect()
    }
}

/// Boxes (24 vertices each) as [min, max] corners.
fn boxes(p: &[[f32; 3]]) -> Vec<[[f32; 3]; 2]> {
    assert_eq!(p.len() % 24, 0);
    p.chunks(24)
        .map(|b| {
            let mut lo = [f32::INFINITY; 3];
            let mut hi = [f32::NEG_INFINITY; 3];
            for v in b {
                for k in 0..3 {
                    lo[k] = lo[k].min(v[k]);
                    hi[k] = hi[k].max(v[k]);
                }
            }
            [lo, hi]
        })
        .collect()
}

/// Two 21 x 20 units sharing the wall at column 20, a door through it at rows 8..=11, and a
/// room layer: room 1 (a room) holds unit 1, room 2 (a corridor) unit 2.
fn two_rooms() -> World {
    let mut world = World::empty(41, 20);
    world.units = vec![Unit::new(1, 0, 0, 21, 20, UnitType::Room), Unit::new(2, 20, 0, 21, 20, UnitType::Corridor)];
    world.doors = vec![Door { id: 1, units: [1, 2], x0: 20, y0: 8, x1: 20, y1: 11, opening: false }];
    let room = |id: u32, kind, opens_to| Room {
        id,
        kind,
        units: vec![id],
        area_m2: 1.0,
        doors: vec![1],
        opens_to,
        name: None,
    };
    world.rooms = vec![room(1, UnitType::Room, vec![2]), room(2, UnitType::Corridor, vec![1])];
    world
}

#[test]
fn walls_rise_to_the_wall_height_with_an_opening_and_a_lintel_at_the_door() {
    let r = 0.1;
    let glb = parse(&world_glb(&two_rooms(), r, &Model3dOptions { wall_height: 3.0, door_height: 2.2 }).unwrap());
    assert_eq!(glb.names(), ["walls", "lintels", "doors", "room 1 (room)", "room 2 (corridor)"]);
    assert_eq!(glb.node("walls").unwrap()["extras"]["wall_height_m"], 3.0);
    let walls = boxes(&glb.positions("walls"));
    // Every wall box stands on the floor and reaches 3 m.
    for [lo, hi] in &walls {
        assert!(lo[1].abs() < 1e-6 && (hi[1] - 3.0).abs() < 1e-6, "{lo:?} {hi:?}");
    }
    // The door cells (column 20, rows 8..=11: x 2.0..2.1 m, z 0.8..1.2 m) hold no wall...
    let inside = |b: &[[f32; 3]; 2], x: f32, z: f32| b[0][0] < x && x < b[1][0] && b[0][2] < z && z < b[1][2];
    for z in [0.85, 0.95, 1.05, 1.15] {
        assert!(!walls.iter().any(|b| inside(b, 2.05, z)), "a wall at the door, z {z}");
    }
    // ...but the wall above and below it does, and the outer walls all round.
    for (x, z) in [(2.05, 0.75), (2.05, 1.25), (0.05, 1.0), (4.05, 1.0), (1.0, 0.05), (3.0, 1.95)] {
        assert!(walls.iter().any(|b| inside(b, x, z)), "no wall at ({x}, {z})");
    }
    // The lintel spans the door from 2.2 m to 3 m; the threshold lies under it.
    let lintels = boxes(&glb.positions("lintels"));
    assert_eq!(lintels.len(), 1);
    let [lo, hi] = lintels[0];
    assert!((lo[1] - 2.2).abs() < 1e-6 && (hi[1] - 3.0).abs() < 1e-6);
    assert!(
        (lo[0] - 2.0).abs() < 1e-6
            && (hi[0] - 2.1).abs() < 1e-6
            && (lo[2] - 0.8).abs() < 1e-6
            && (hi[2] - 1.2).abs() < 1e-6
    );
    let [tlo, thi] = boxes(&glb.positions("doors"))[0];
    assert!((tlo[1] + SLAB_M as f32).abs() < 1e-6 && thi[1].abs() < 1e-6);
    // Doors as tall as the walls: no lintels.
    let open = parse(&world_glb(&two_rooms(), r, &Model3dOptions { wall_height: 2.0, door_height: 2.0 }).unwrap());
    assert!(open.node("lintels").is_none());
}

#[test]
fn each_room_has_a_slab_in_its_types_colour() {
    let glb = parse(&world_glb(&two_rooms(), 0.05, &Model3dOptions::default()).unwrap());
    let corridor = glb.node("room 2 (corridor)").unwrap();
    assert_eq!(corridor["extras"]["type"], "corridor");
    assert_eq!(corridor["extras"]["id"], 2);
    let rgb = unit_type_rgb(UnitType::Corridor);
    let want: Vec<f64> = rgb.iter().map(|&c| linear(c) as f64).chain([1.0]).collect();
    let near = |a: &[f64], b: &[f64]| a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-6);
    assert!(near(&glb.color("room 2 (corridor)"), &want), "{:?}", glb.color("room 2 (corridor)"));
    assert!(!near(&glb.color("room 1 (room)"), &want));
    // The slab covers unit 2's interior (columns 21..40, rows 1..19 at 5 cm), just below y = 0.
    let slab = boxes(&glb.positions("room 2 (corridor)"));
    let (lo, hi) = (
        slab.iter().map(|b| b[0]).fold([f32::INFINITY; 3], |a, b| [0, 1, 2].map(|k| a[k].min(b[k]))),
        slab.iter().map(|b| b[1]).fold([f32::NEG_INFINITY; 3], |a, b| [0, 1, 2].map(|k| a[k].max(b[k]))),
    );
    for (got, want) in lo.iter().zip([21.0 * 0.05, -SLAB_M, 0.05]).chain(hi.iter().zip([40.0 * 0.05, 0.0, 19.0 * 0.05]))
    {
        assert!((got - want as f32).abs() < 1e-5, "{lo:?} {hi:?}");
    }
    // Without a room layer, a slab per unit.
    let mut bare = two_rooms();
    bare.rooms.clear();
    let glb = parse(&world_glb(&bare, 0.05, &Model3dOptions::default()).unwrap());
    assert_eq!(&glb.names()[3..], ["unit 1 (room)", "unit 2 (corridor)"]);
}

#[test]
fn a_turned_world_is_turned_onto_the_map_and_every_position_is_bounded() {
    use ksmcmc::floorplan::synth::{generate, SynthConfig};
    let s = generate(&SynthConfig { rotation_deg: 20.0, ..SynthConfig::default() }, 2).unwrap();
    let r = s.map.yaml().resolution;
    let glb = parse(&world_glb(&s.truth, r, &Model3dOptions::default()).unwrap());
    let (w, h) = (s.map.width() as f32 * r as f32, s.map.height() as f32 * r as f32);
    for a in glb.json["accessors"].as_array().unwrap().iter().filter(|a| a.get("min").is_some()) {
        let (lo, hi) = (&a["min"], &a["max"]);
        let f = |v: &Value, k: usize| v[k].as_f64().unwrap() as f32;
        assert!(f(lo, 0) >= -1e-3 && f(hi, 0) <= w + 1e-3, "x within the map: {lo} {hi}");
        assert!(f(lo, 2) >= -1e-3 && f(hi, 2) <= h + 1e-3, "z within the map: {lo} {hi}");
        assert!(f(lo, 1) >= -SLAB_M as f32 - 1e-6 && f(hi, 1) <= 2.5 + 1e-6, "y: {lo} {hi}");
    }
    // Turned 20 degrees, the wall boxes are not axis-aligned: some corner has an x or z that is
    // neither the box's least nor its largest. Upright, every corner has.
    let turned = |glb: &Glb| {
        glb.positions("walls").chunks(24).any(|b| {
            let bb = boxes(b)[0];
            b.iter().any(|v| [0, 2].iter().any(|&k| (v[k] - bb[0][k]).abs() > 1e-3 && (v[k] - bb[1][k]).abs() > 1e-3))
        })
    };
    assert!(turned(&glb));
    let upright = generate(&SynthConfig::default(), 2).unwrap();
    assert!(!turned(&parse(&world_glb(&upright.truth, r, &Model3dOptions::default()).unwrap())));
    // Same world, same bytes.
    assert_eq!(
        world_glb(&s.truth, r, &Default::default()).unwrap(),
        world_glb(&s.truth, r, &Default::default()).unwrap()
    );
}

/// A unit at an angle of its own (issue 13) is drawn exactly as the same unit in a world
/// turned by that angle, and a world of two wings has a wall mesh per wing, all on the map.
#[test]
fn units_at_their_own_angle_are_drawn_in_their_frame() {
    use ksmcmc::floorplan::synth::{generate, SynthConfig};
    use ksmcmc::floorplan::Frame;
    let angle = 30f64.to_radians();
    let mut own = World::empty(200, 150);
    let frame = Frame::turned(200, 150, angle);
    own.units = vec![Unit { angle: Some(angle), ..Unit::new(1, 40, 30, 60, 40, UnitType::Room) }];
    let mut turned = World::empty(200, 150);
    turned.frame = frame;
    turned.units = vec![Unit::new(1, 40, 30, 60, 40, UnitType::Room)];
    let (a, b) = (
        parse(&world_glb(&own, 0.05, &Default::default()).unwrap()),
        parse(&world_glb(&turned, 0.05, &Default::default()).unwrap()),
    );
    assert_eq!(a.positions("walls"), b.positions("walls"));
    assert_eq!(a.positions("unit 1 (room)"), b.positions("unit 1 (room)"));
    assert!(!a.positions("walls").is_empty());

    let s = generate(&SynthConfig { wing_deg: 30.0, ..SynthConfig::default() }, 4).unwrap();
    let r = s.map.yaml().resolution;
    let glb = parse(&world_glb(&s.truth, r, &Model3dOptions::default()).unwrap());
    let walls = glb.node("walls").unwrap()["mesh"].as_u64().unwrap() as usize;
    assert_eq!(glb.json["meshes"][walls]["primitives"].as_array().unwrap().len(), 2, "a wall mesh per wing");
    let (w, h) = (s.map.width() as f32 * r as f32, s.map.height() as f32 * r as f32);
    for p in glb.positions("walls") {
        assert!((-1e-3..=w + 1e-3).contains(&p[0]) && (-1e-3..=h + 1e-3).contains(&p[2]), "{p:?} off the map");
    }
    // Every unit of the truth (it has no room layer) has its slab, the second wing's turned.
    assert!(s.truth.rooms.is_empty());
    for u in &s.truth.units {
        assert!(glb.names().contains(&format!("unit {} ({})", u.id, u.kind.name())), "unit {}", u.id);
    }
}

#[test]
fn bad_heights_and_resolutions_are_refused() {
    let w = two_rooms();
    for (wall, door, says) in [
        (0.0, 0.0, "wall height 0 m"),
        (f64::NAN, 2.0, "wall height NaN m"),
        (500.0, 2.0, "at most 100"),
        (2.5, 3.0, "door height 3 m"),
        (2.5, -1.0, "door height -1 m"),
    ] {
        let e = world_glb(&w, 0.05, &Model3dOptions { wall_height: wall, door_height: door }).unwrap_err();
        assert!(e.to_string().contains(says), "{e}");
    }
    assert!(world_glb(&w, 0.0, &Default::default()).unwrap_err().to_string().contains("resolution 0"));
    // An empty world is an empty scene, still a valid file.
    let empty = parse(&world_glb(&World::empty(10, 10), 0.05, &Default::default()).unwrap_or_else(|e| panic!("{e}")));
    assert!(empty.json.get("nodes").is_none());
}
