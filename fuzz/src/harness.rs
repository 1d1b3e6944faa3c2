//! The bodies of the fuzz targets, one function per reader.
//!
//! Each function takes the raw input and feeds it to the same core entry point the CLI and
//! the WebAssembly bindings use. A panic, an abort or an allocation over libFuzzer's RSS limit
//! is a bug; an `Err` is the expected answer to hostile input.
//!
//! The main crate's integration tests include this file (`tests/it/fuzz_regressions.rs`) and
//! replay every input kept under `fuzz/regressions/TARGET/` through these same functions, so
//! `cargo test` on stable covers the crashes found, without nightly or libFuzzer.

use ksmcmc::floorplan::{knowledge, metrics, rooms, Door, Frame, Unit, UnitType, World};
use ksmcmc::grid::{Cell, Grid, Limits, OccupancyMap};
use ksmcmc::mln::{Database, GroundConfig, Mln, Network};

/// A fuzz target's body.
pub type Target = fn(&[u8]);

/// Every target: its name (the directory under `fuzz/regressions/` and `fuzz/seeds/`) and body.
pub const TARGETS: &[(&str, Target)] = &[
    ("pgm", pgm),
    ("png", png),
    ("ros_yaml", ros_yaml),
    ("mln", mln),
    ("db", db),
    ("world_json", world_json),
    ("world_arbitrary", world_arbitrary),
    ("scene_json", scene_json),
    ("chain_config", chain_config),
    ("synth_config", synth_config),
    ("edits", edits),
];

/// Maps the world targets score against stay small, so that one input runs in milliseconds.
const SCORE_MAX_CELLS: u64 = 1 << 16;

/// Grounding limits small enough for a fuzzer's time budget; the refusals are what is tested.
fn small_ground() -> GroundConfig {
    GroundConfig { max_atoms: 2_000, max_clauses: 20_000, max_groundings: 200_000, ..Default::default() }
}

fn text(data: &[u8]) -> Option<&str> {
    std::str::from_utf8(data).ok()
}

/// A PGM (P2 or P5) through the PGM decoder, then classified as a map.
pub fn pgm(data: &[u8]) {
    let limits = Limits { max_cells: 1 << 20 };
    if let Ok(raster) = ksmcmc::grid::pgm::decode(data, &limits) {
        let _ = OccupancyMap::from_raster(raster, ksmcmc::grid::MapYaml::for_image("map.pgm"), Default::default());
    }
}

/// A PNG through the PNG decoder, then classified as a map.
pub fn png(data: &[u8]) {
    let limits = Limits { max_cells: 1 << 20 };
    if let Ok(raster) = ksmcmc::grid::png::decode(data, &limits) {
        let _ = OccupancyMap::from_raster(raster, ksmcmc::grid::MapYaml::for_image("map.png"), Default::default());
    }
}

/// A ROS `map.yaml` and its image: the bytes up to the first NUL are the YAML (UTF-8), the
/// rest the image. Loaded maps are written back as PGM + YAML and read again.
pub fn ros_yaml(data: &[u8]) {
    let split = data.iter().position(|&b| b == 0).unwrap_or(data.len());
    let Some(yaml) = text(&data[..split]) else { return };
    let image = data.get(split + 1..).unwrap_or(&[]);
    let limits = Limits { max_cells: 1 << 20 };
    if let Ok(map) = OccupancyMap::from_yaml_and_image(yaml, image, &limits) {
        let back = OccupancyMap::from_yaml_and_image(&map.to_yaml("map.pgm"), &map.to_pgm(), &limits)
            .expect("a map written by to_pgm/to_yaml reads back");
        assert_eq!(back.classified(), map.classified(), "classes survive a PGM + YAML round trip");
    }
}

/// A knowledge base (`.mln`), grounded without evidence when it parses.
pub fn mln(data: &[u8]) {
    let Some(t) = text(data) else { return };
    if let Ok(mln) = Mln::parse(t) {
        let _ = Network::ground(&mln, &Database::new(), &small_ground());
    }
}

/// An evidence database (`.db`) against the built-in indoor knowledge base, then grounded.
pub fn db(data: &[u8]) {
    let Some(t) = text(data) else { return };
    static MLN: std::sync::OnceLock<Mln> = std::sync::OnceLock::new();
    let mln = MLN.get_or_init(|| Mln::parse(knowledge::BUILTIN_INDOOR).expect("the built-in knowledge base parses"));
    if let Ok(db) = Database::parse(t, mln) {
        let _ = Network::ground(mln, &db, &GroundConfig { query: vec!["Room".into()], ..small_ground() });
    }
}

/// `world.json` text, parsed and validated, then scored against a map of its `map_size`.
pub fn world_json(data: &[u8]) {
    let Some(t) = text(data) else { return };
    if let Ok(world) = World::from_json(t) {
        exercise_world(world);
    }
}

/// A valid world on a small map: rendered, exported (JSON, scene graph, knowledge evidence),
/// given its room layer and scored. Worlds whose map is too big for a fuzzer's pace are
/// skipped after validation.
fn exercise_world(mut world: World) {
    let [mw, mh] = world.frame.map_size;
    let [ww, wh] = world.frame.world_size;
    // The room layer turns the map by the frame's angle, which a long thin map makes large.
    let [tw, th] = ksmcmc::geometry::Frame::turned(mw, mh, world.frame.angle).world_size;
    if [(mw, mh), (ww, wh), (tw, th)].iter().any(|&(w, h)| w as u64 * h as u64 > SCORE_MAX_CELLS) {
        return;
    }
    let json = world.to_json();
    let back = World::from_json(&json).expect("a valid world reads back from its own JSON");
    assert_eq!(back.to_json(), json, "world.json round trip");
    let (mw, mh) = (mw as usize, mh as usize);
    let map =
        Grid::from_vec(mw, mh, (0..mw * mh).map(|i| [Cell::Free, Cell::Occupied, Cell::Unknown][i % 3]).collect())
            .expect("sized above");
    let k = metrics::prediction_rate(&map, &world);
    assert!((0.0..=1.0).contains(&k), "K(W, M) = {k}");
    let options = ksmcmc::render::RenderOptions { scale: 2, labels: true, legend: true };
    let _ = ksmcmc::render::try_render(&map, Some(&world), &options);
    let _ = ksmcmc::floorplan::graph::world_json(&world);
    let _ = knowledge::evidence(&world, 0.05, &Default::default());
    let world_map = ksmcmc::vision::orientation::to_world_frame(&map, world.frame.angle).0;
    if world_map.width() == ww as usize && world_map.height() == wh as usize {
        let c = rooms::RoomConfig::default();
        let maps = rooms::RoomMaps { map: &map, world_map: &world_map, resolution: 0.05 };
        let _ = rooms::RoomLayer::without_knowledge(c).explain(
            &mut world,
            maps,
            rooms::Grouping::Units(&Default::default()),
        );
    }
}

/// Little-endian reader of a structured input: each call takes the next bytes, zero past the end.
struct Bytes<'a>(&'a [u8]);

impl Bytes<'_> {
    fn u8(&mut self) -> u8 {
        let (b, rest) = self.0.split_first().map(|(b, r)| (*b, r)).unwrap_or((0, &[]));
        self.0 = rest;
        b
    }

    fn u16(&mut self) -> u16 {
        u16::from_le_bytes([self.u8(), self.u8()])
    }

    /// A small signed coordinate, mostly inside a map of `side` cells, sometimes just outside.
    fn coord(&mut self, side: u32) -> i32 {
        (self.u16() % (side as u16 + 8)) as i32 - 4
    }
}

/// A structured world: a small map and frame, units, doors and object cells decoded from the
/// bytes (the same role as an `arbitrary` derive, but replayable without it). Worlds that fail
/// validation are refused as hostile JSON would be; valid ones go through [`exercise_world`].
pub fn world_arbitrary(data: &[u8]) {
    let mut b = Bytes(data);
    let (mw, mh) = (1 + b.u8() as u32 % 160, 1 + b.u8() as u32 % 160);
    let angle = [0.0, 0.3, -0.7, std::f64::consts::FRAC_PI_2, 3.0][b.u8() as usize % 5];
    let (s, c) = (f64::sin(angle).abs(), f64::cos(angle).abs());
    let ww = ((mw as f64 * c + mh as f64 * s).ceil() as u32).max(1);
    let wh = ((mw as f64 * s + mh as f64 * c).ceil() as u32).max(1);
    let mut world = World::empty(mw, mh);
    world.frame = Frame { angle, world_size: [ww, wh], map_size: [mw, mh] };
    world.wall_thickness = 1 + b.u8() as i32 % 3;
    let types = UnitType::ALL;
    for id in 1..=(b.u8() % 24) as u32 {
        let (x, y) = (b.coord(ww), b.coord(wh));
        let (w, h) = (1 + b.u8() as i32 % 64, 1 + b.u8() as i32 % 64);
        world.units.push(Unit::new(id, x, y, w, h, types[b.u8() as usize % types.len()]));
    }
    let n = world.units.len() as u32;
    for id in 1..=(b.u8() % 16) as u32 {
        let units = [1 + b.u8() as u32 % n.max(1), 1 + b.u8() as u32 % n.max(1)];
        let (x0, y0) = (b.coord(ww), b.coord(wh));
        let (dx, dy) = (b.u8() as i32 % 8, b.u8() as i32 % 8);
        world.doors.push(Door { id, units, x0, y0, x1: x0 + dx, y1: y0 + dy, opening: false });
    }
    for _ in 0..b.u8() % 32 {
        world.object_cells.push([b.coord(ww), b.coord(wh)]);
    }
    if world.validate().is_ok() {
        exercise_world(world);
    }
}

/// A table-top `scene.json`, parsed and validated, then written and read back.
pub fn scene_json(data: &[u8]) {
    let Some(t) = text(data) else { return };
    if let Ok(scene) = ksmcmc::tabletop::scene::Scene::from_json(t) {
        let back = ksmcmc::tabletop::scene::Scene::from_json(&scene.to_json());
        assert!(back.is_ok(), "a valid scene reads back from its own JSON: {back:?}");
    }
}

/// A chain configuration, as the floor-plan chain and the table-top chain read it.
pub fn chain_config(data: &[u8]) {
    let Some(t) = text(data) else { return };
    let _ = ksmcmc::floorplan::ChainConfig::from_json(t);
    if let Ok(c) = serde_json::from_str::<ksmcmc::tabletop::ChainConfig>(t) {
        let _ = c.validate();
    }
}

/// A synth configuration, floor plan and table top; small valid floor plans are generated.
pub fn synth_config(data: &[u8]) {
    let Some(t) = text(data) else { return };
    if let Ok(c) = ksmcmc::floorplan::synth::SynthConfig::from_json(t) {
        let (w, h) = c.map_size();
        if w as u64 * h as u64 <= SCORE_MAX_CELLS
            && c.rooms[1] as u64 + c.halls as u64 + c.corridors.unwrap_or(0) as u64 + c.others as u64 <= 16
        {
            let _ = ksmcmc::floorplan::synth::generate(&c, 1);
        }
    }
    if let Ok(c) = serde_json::from_str::<ksmcmc::tabletop::synth::SynthConfig>(t) {
        let _ = c.validate();
    }
}

/// `--edits` / `Mapper.setEdits`: parsed, checked against a small map, and applied to its
/// labels and to a world with a rotated frame (the split walls in both frames).
pub fn edits(data: &[u8]) {
    let Some(t) = text(data) else { return };
    let Ok(e) = ksmcmc::floorplan::edits::Edits::parse(t) else { return };
    assert_eq!(ksmcmc::floorplan::edits::Edits::parse(&e.to_json()).as_ref(), Ok(&e), "edits round trip");
    let (w, h) = (64usize, 48usize);
    if e.check_map(w, h).is_err() {
        return;
    }
    let map = Grid::from_vec(w, h, (0..w * h).map(|i| if i % 17 == 0 { Cell::Occupied } else { Cell::Free }).collect())
        .expect("sized above");
    let mut labels = Grid::from_vec(w, h, (0..w * h).map(|i| (i % w / 16 + 1) as u16).collect()).expect("sized above");
    e.apply_to_labels(&mut labels, &map);
    let mut world = World::empty(w as u32, h as u32);
    world.frame = Frame { angle: 0.3, world_size: [w as u32 + 20, h as u32 + 20], map_size: [w as u32, h as u32] };
    let _ = e.world_wall_cells(&map, &world.frame);
    world.units.push(Unit::new(1, 2, 2, 30, 20, UnitType::Room));
    let _ = knowledge::edit_facts(&e, &world);
    let _ = e.merged_units(&world);
    let _ = e.respected_by(&world, &labels, &map);
}
