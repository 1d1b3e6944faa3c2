//! `world.geojson` and `world.svg` read back with an independent GeoJSON parser (the `geojson`
//! crate) and checked against the world they came from: one level, a unit per room, an
//! opening per door, unique ids, closed rings turning the RFC 7946 way, and areas that match
//! the rooms'.

use geojson::{feature::Id, Feature, GeoJson};
use ksmcmc::floorplan::export::RoomInput;
use ksmcmc::floorplan::georef::Georef;
use ksmcmc::floorplan::rooms::RoomConfig;
use ksmcmc::floorplan::{report, synth, Chain, ChainConfig, Room, Unit, UnitType, World};
use ksmcmc::grid::{Cell, Grid, Limits, OccupancyMap};
use ksmcmc::render::Outputs;
use std::collections::{BTreeMap, HashSet};
use std::path::Path;

/// A run of `iterations` on `map`, seed 1: the world with its rooms and the eight files.
fn run(map: &OccupancyMap, iterations: u64, georef: Option<&Georef>) -> (World, Outputs) {
    let mut chain = Chain::new(map, ChainConfig::default(), 1).unwrap();
    chain.step(iterations);
    let trace = ksmcmc::floorplan::export::trace_csv(chain.trace());
    let input = RoomInput::of(&mut chain);
    let mut summary = report::summary(&chain, map, input.world(), 1.0);
    drop(chain);
    let (world, labels) = input.explain(&RoomConfig::default()).unwrap();
    report::add_rooms(&mut summary, &world, &labels);
    let out = Outputs::new(map, &world, &labels, &summary, trace, georef, &Default::default()).unwrap();
    (world, out)
}

/// Twice the signed area of a closed ring (positive: counter-clockwise, x right, y up).
fn area2(ring: &[Vec<f64>]) -> f64 {
    ring.windows(2).map(|w| w[0][0] * w[1][1] - w[1][0] * w[0][1]).sum()
}

/// The polygons of a unit or level: rings as position lists.
fn polygons(f: &Feature) -> Vec<Vec<Vec<Vec<f64>>>> {
    match &f.geometry.as_ref().expect("a geometry").value {
        geojson::Value::Polygon(p) => vec![p.clone()],
        geojson::Value::MultiPolygon(m) => m.clone(),
        other => panic!("not a polygon: {other:?}"),
    }
}

fn feature_type(f: &Feature) -> &str {
    f.foreign_members.as_ref().and_then(|m| m.get("feature_type")).and_then(|v| v.as_str()).expect("feature_type")
}

/// Parses `text` and checks what holds for every export: a FeatureCollection of one level, one
/// unit per room (in order, with its category), one opening per door, unique ids, closed
/// rings with counter-clockwise exteriors and clockwise holes. Returns each unit's area (in
/// the output's units squared) by room id.
fn check(text: &str, world: &World) -> BTreeMap<u32, f64> {
    let GeoJson::FeatureCollection(fc) = text.parse::<GeoJson>().expect("valid GeoJSON") else {
        panic!("not a FeatureCollection");
    };
    let kinds: Vec<&str> = fc.features.iter().map(feature_type).collect();
    assert_eq!(kinds.iter().filter(|k| **k == "level").count(), 1);
    let units: Vec<&Feature> = fc.features.iter().filter(|f| feature_type(f) == "unit").collect();
    let openings: Vec<&Feature> = fc.features.iter().filter(|f| feature_type(f) == "opening").collect();
    assert_eq!(units.len(), world.rooms.len(), "a unit per room");
    assert_eq!(openings.len(), world.doors.len(), "an opening per door");
    assert_eq!(kinds.len(), 1 + units.len() + openings.len());
    let ids: HashSet<String> = fc
        .features
        .iter()
        .map(|f| match &f.id {
            Some(Id::String(s)) => s.clone(),
            other => panic!("id {other:?}"),
        })
        .collect();
    assert_eq!(ids.len(), fc.features.len(), "unique ids");
    let level_id = fc.features[0].id.clone();
    let mut areas = BTreeMap::new();
    for (unit, room) in units.iter().zip(&world.rooms) {
        let props = unit.properties.as_ref().unwrap();
        let want = match room.kind {
            UnitType::Room => "room",
            UnitType::Corridor => "walkway",
            UnitType::Hall => "lobby",
            UnitType::Other | UnitType::Unknown => "unspecified",
        };
        assert_eq!(props["category"], want);
        assert_eq!(Some(Id::String(props["level_id"].as_str().unwrap().into())), level_id);
        assert!((props["area"].as_f64().unwrap() - room.area_m2).abs() < 1e-3);
        let mut area = 0.0;
        for p in polygons(unit) {
            for (k, ring) in p.iter().enumerate() {
                assert!(ring.len() >= 4 && ring.first() == ring.last(), "closed ring: {ring:?}");
                let a = area2(ring) / 2.0;
                assert!(if k == 0 { a > 0.0 } else { a < 0.0 }, "exterior counter-clockwise, holes clockwise: {a}");
                area += a;
            }
        }
        areas.insert(room.id, area);
    }
    for o in &openings {
        assert_eq!(o.properties.as_ref().unwrap()["category"], "pedestrian");
        let geojson::Value::LineString(line) = &o.geometry.as_ref().unwrap().value else { panic!("not a line") };
        assert_eq!(line.len(), 2);
        assert_ne!(line[0], line[1]);
    }
    let level = polygons(&fc.features[0]);
    assert_eq!(level.len(), 1);
    assert!(area2(&level[0][0]) > 0.0);
    areas
}

/// Room polygons include half of the walls around them and any furniture, and leave out free
/// cells beyond the units that the label image gives the room (`area_m2` counts free labelled
/// cells). On the maps below each room's polygon lies within 0.75 to 1.6 times its `area_m2`,
/// and all of them together within 20 % of the total (the half walls: about 10 %).
fn check_areas(areas: &BTreeMap<u32, f64>, world: &World, what: &str) {
    let (mut poly, mut free) = (0.0, 0.0);
    for r in &world.rooms {
        let a = areas[&r.id];
        assert!(
            a >= 0.75 * r.area_m2 && a <= 1.6 * r.area_m2,
            "{what}: room {} polygon {a} m², area_m2 {}",
            r.id,
            r.area_m2
        );
        poly += a;
        free += r.area_m2;
    }
    assert!((poly / free - 1.0).abs() < 0.2, "{what}: polygons {poly} m², rooms {free} m²");
}

#[test]
fn geojson_of_samples_and_synthetic_floors_has_a_unit_per_room_and_an_opening_per_door() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("samples");
    let mut maps: Vec<(String, OccupancyMap)> = ["office-rotated", "building-large", "furnished"]
        .iter()
        .map(|s| (s.to_string(), OccupancyMap::load(&dir.join(s).join("map.yaml"), &Limits::default()).unwrap()))
        .collect();
    for seed in [3, 11] {
        let s = synth::generate(&synth::SynthConfig { width: 300, height: 200, ..Default::default() }, seed).unwrap();
        maps.push((format!("synth {seed}"), s.map));
    }
    for (name, map) in &maps {
        let (world, out) = run(map, 4000, None);
        assert!(world.rooms.len() >= 2, "{name}: {} rooms", world.rooms.len());
        let areas = check(&out.world_geojson, &world);
        check_areas(&areas, &world, name);
        assert_eq!(out.world_svg.matches("<path data-room=").count(), world.rooms.len(), "{name}");
        assert_eq!(out.world_svg.matches("<path data-door=").count(), world.doors.len(), "{name}");
    }
}

#[test]
fn georeferenced_geojson_lies_around_the_georeference_and_keeps_the_shapes() {
    let map = OccupancyMap::load(
        &Path::new(env!("CARGO_MANIFEST_DIR")).join("samples/office-rotated/map.yaml"),
        &Limits::default(),
    )
    .unwrap();
    let g = Georef::new(53.1059, 8.8521, 30.0).unwrap();
    let (world, out) = run(&map, 3000, Some(&g));
    let (_, metres) = run(&map, 3000, None);
    let degrees = check(&out.world_geojson, &world);
    let plain = check(&metres.world_geojson, &world);
    // A degree of latitude here is 111 288.26 m and of longitude 66 972.84 m (WGS 84): the
    // local plane is linear, so areas convert back to the metres' within the rounding (10^-8
    // degrees, about a millimetre, moves the area of a 40 m² room by up to some 0.02 m²).
    let (m_per_deg_lat, m_per_deg_lon) = (111_288.26, 66_972.84);
    for (id, a) in &degrees {
        let back = a * m_per_deg_lat * m_per_deg_lon;
        assert!((back / plain[id] - 1.0).abs() < 1e-3, "room {id}: {back} m² vs {} m²", plain[id]);
    }
    let fc: serde_json::Value = serde_json::from_str(&out.world_geojson).unwrap();
    let p = &fc["features"][1]["properties"]["display_point"]["coordinates"];
    let (lon, lat) = (p[0].as_f64().unwrap(), p[1].as_f64().unwrap());
    assert!((lon - 8.8521).abs() < 0.001 && (lat - 53.1059).abs() < 0.001, "{lon} {lat}");
}

/// A hand-made floor at 10 cm cells, origin (-1, -2): an L-shaped corridor of two units and an
/// office beside it, walls 1 cell deep, one door.
fn hand_made() -> (OccupancyMap, World, Grid<u16>) {
    let yaml = "image: m.pgm\nresolution: 0.1\norigin: [-1.0, -2.0, 0.0]\n";
    let image = ksmcmc::grid::pgm::encode_u8(40, 30, &[254; 1200]);
    let map = OccupancyMap::from_yaml_and_image(yaml, &image, &Limits::default()).unwrap();
    let mut world = World::empty(40, 30);
    let unit = |id, x, y, w, h, kind| Unit::new(id, x, y, w, h, kind);
    world.units = vec![
        unit(1, 0, 0, 31, 11, UnitType::Corridor),
        unit(2, 0, 10, 11, 20, UnitType::Corridor),
        unit(3, 10, 10, 21, 20, UnitType::Room),
    ];
    world.doors =
        vec![ksmcmc::floorplan::Door { id: 1, units: [1, 3], x0: 15, y0: 10, x1: 19, y1: 10, opening: false }];
    let room = |id, kind, units: Vec<u32>, area_m2| Room {
        id,
        kind,
        units,
        area_m2,
        doors: vec![1],
        opens_to: vec![],
        name: None,
    };
    world.rooms = vec![room(1, UnitType::Corridor, vec![1, 2], 4.0), room(2, UnitType::Room, vec![3], 3.0)];
    let labels = Grid::new(40, 30, 0u16);
    assert_eq!(map.classified().cells()[0], Cell::Free);
    (map, world, labels)
}

#[test]
fn a_hand_made_floor_gives_exact_rings_in_metres() {
    let (map, world, labels) = hand_made();
    let text = ksmcmc::floorplan::geojson::world_geojson(&world, &labels, &map, None).unwrap();
    let areas = check(&text, &world);
    // The corridor: floors (0.5, 0.5)-(30.5, 10.5) and (0.5, 10.5)-(10.5, 29.5) in cells,
    // 300 + 190 cells of 0.01 m²; the office (10.5, 10.5)-(30.5, 29.5), 380 cells.
    assert!((areas[&1] - 4.9).abs() < 1e-9 && (areas[&2] - 3.8).abs() < 1e-9, "{areas:?}");
    let fc: serde_json::Value = serde_json::from_str(&text).unwrap();
    // Cell (x, y) is metres (-1 + 0.1 x, -2 + 0.1 (30 - y)).
    let corridor = serde_json::json!([[
        [-0.95, 0.95],
        [-0.95, -1.95],
        [0.05, -1.95],
        [0.05, -0.05],
        [2.05, -0.05],
        [2.05, 0.95],
        [-0.95, 0.95]
    ]]);
    assert_eq!(fc["features"][1]["geometry"]["coordinates"], corridor);
    assert_eq!(fc["features"][3]["geometry"]["coordinates"], serde_json::json!([[0.5, -0.05], [1.0, -0.05]]));
    assert_eq!(fc["features"][3]["id"], "6b736d63-6d63-8002-8000-000000000001");
    assert_eq!(fc["features"][1]["properties"]["name"]["en"], "corridor 1");
    assert_eq!(fc["features"][1]["properties"]["alt_name"], serde_json::Value::Null);
    // A room a person named carries the name, and its generated one as the alternative.
    let mut named = world.clone();
    named.rooms[1].name = Some("Office \"A\" & Co".into());
    let text = ksmcmc::floorplan::geojson::world_geojson(&named, &labels, &map, None).unwrap();
    let fc: serde_json::Value = serde_json::from_str(&text).unwrap();
    assert_eq!(fc["features"][2]["properties"]["name"]["en"], "Office \"A\" & Co");
    assert_eq!(fc["features"][2]["properties"]["alt_name"]["en"], "room 2");
    // The level is the map's extent, 4 m x 3 m.
    assert_eq!(
        fc["features"][0]["geometry"]["coordinates"],
        serde_json::json!([[[-1.0, 1.0], [-1.0, -2.0], [3.0, -2.0], [3.0, 1.0], [-1.0, 1.0]]])
    );
}
