//! The WebAssembly bindings, run in headless Chromium by wasm-bindgen-test (`make test-wasm`).
//!
//! Everything goes through the functions the JavaScript API exports, called from Rust: loading,
//! painting, rendering to a real `<canvas>`, the synthetic generator, and above all that bad
//! input is a thrown `Error`, never a panic (which would kill the module).

#![cfg(target_arch = "wasm32")]

use ksmcmc::wasm::{self, Counts, Map};
use wasm_bindgen::{JsCast, JsError, JsValue};
use wasm_bindgen_test::*;

wasm_bindgen_test_configure!(run_in_browser);

/// The message of an error as JavaScript sees it.
fn message(e: JsError) -> String {
    let v: JsValue = e.into();
    v.dyn_into::<js_sys::Error>().expect("a JavaScript Error").message().into()
}

/// Asserts that loading failed with a message containing `needle`.
fn err_contains<T: std::fmt::Debug>(r: Result<T, JsError>, needle: &str) -> String {
    let m = message(r.expect_err("should be an error"));
    assert!(m.contains(needle), "{m:?} should contain {needle:?}");
    m
}

fn counts(map: &Map) -> Counts {
    serde_wasm_bindgen::from_value(map.counts().expect("counts")).expect("a {free, unknown, occupied} object")
}

/// A gray 8-bit PNG of `w x h` pixels.
fn gray_png(w: u32, h: u32, pixels: &[u8]) -> Vec<u8> {
    let mut out = Vec::new();
    {
        let mut enc = png::Encoder::new(&mut out, w, h);
        enc.set_color(png::ColorType::Grayscale);
        enc.set_depth(png::BitDepth::Eight);
        let mut writer = enc.write_header().unwrap();
        writer.write_image_data(pixels).unwrap();
    }
    out
}

#[wasm_bindgen_test]
fn version_is_the_crate_version() {
    assert_eq!(wasm::version(), env!("CARGO_PKG_VERSION"));
}

#[wasm_bindgen_test]
fn the_heap_size_counts_whole_pages_and_covers_what_is_allocated() {
    let before = wasm::wasm_heap_bytes();
    let block = vec![1u8; 16 << 20];
    let after = wasm::wasm_heap_bytes();
    assert_eq!(after % 65536.0, 0.0, "whole 64 KiB pages");
    assert!(after >= before, "memory never shrinks: {before} then {after}");
    assert!(after >= (16 << 20) as f64, "a 16 MiB block lives in the heap, which is {after} bytes");
    assert_eq!(block.iter().map(|&b| b as usize).sum::<usize>(), 16 << 20);
}

#[wasm_bindgen_test]
fn loads_a_pgm() {
    // 3x2: black (occupied), ROS gray (unknown), white (free) / white, white, black.
    let map = Map::from_bytes(b"P2\n3 2\n255\n0 205 255\n255 254 0\n").unwrap();
    assert_eq!((map.width(), map.height()), (3, 2));
    assert_eq!(counts(&map), Counts { free: 3, unknown: 1, occupied: 2 });
    assert_eq!(map.cells(), vec![2, 1, 0, 0, 0, 2]);

    let binary = Map::from_bytes(b"P5\n2 1\n255\n\x00\xff").unwrap();
    assert_eq!(binary.cells(), vec![2, 0]);
}

#[wasm_bindgen_test]
fn loads_a_png() {
    let bytes = gray_png(4, 3, &[0, 0, 255, 255, 205, 205, 255, 255, 255, 255, 255, 0]);
    let map = Map::from_bytes(&bytes).unwrap();
    assert_eq!((map.width(), map.height()), (4, 3));
    assert_eq!(counts(&map), Counts { free: 7, unknown: 2, occupied: 3 });
    assert_eq!(map.cells(), vec![2, 2, 0, 0, 1, 1, 0, 0, 0, 0, 0, 2]);
}

#[wasm_bindgen_test]
fn loads_a_yaml_pair_and_writes_it_back() {
    let yaml = "image: lab.pgm\nresolution: 0.05\norigin: [0.0, 0.0, 0.0]\nnegate: 0\n\
                occupied_thresh: 0.65\nfree_thresh: 0.196\n";
    let map = Map::from_yaml(yaml, b"P2\n3 1\n255\n0 205 254\n").unwrap();
    assert_eq!(map.cells(), vec![2, 1, 0]);

    let pgm = map.to_pgm();
    assert!(pgm.starts_with(b"P5"), "{:?}", &pgm[..2]);
    let text = map.to_yaml("saved.pgm");
    assert!(text.contains("saved.pgm"), "{text}");
    let again = Map::from_yaml(&text, &pgm).unwrap();
    assert_eq!(again.cells(), map.cells());
}

#[wasm_bindgen_test]
fn bad_yaml_is_an_error() {
    let pgm = b"P2\n1 1\n255\n0\n";
    err_contains(Map::from_yaml("this is not yaml", pgm), "map.yaml");
    err_contains(Map::from_yaml("image: a.pgm\nresolution: -1\norigin: [0, 0, 0]\n", pgm), "resolution");
    err_contains(Map::from_yaml("", pgm), "map.yaml");
    // A good YAML with a bad image is the image's error.
    let yaml = "image: a.pgm\nresolution: 0.05\norigin: [0, 0, 0]\n";
    err_contains(Map::from_yaml(yaml, b"hello"), "not an occupancy map");
    // A map.yaml given as the image says so.
    err_contains(Map::from_bytes(yaml.as_bytes()), "map.yaml");
}

#[wasm_bindgen_test]
fn malformed_bytes_are_errors_not_panics() {
    err_contains(Map::from_bytes(b""), "empty");
    err_contains(Map::from_bytes(b"hello"), "not an occupancy map");
    err_contains(Map::from_bytes(b"P5\n0 10\n255\n"), "0x10");
    err_contains(Map::from_bytes(b"P5\n100000 100000\n255\n"), "over the limit");
    err_contains(Map::from_bytes(b"P5\n99999999999999999999 2\n255\n"), "over the limit");
    err_contains(Map::from_bytes(b"P5\n4 4\n255\n\x00\x00"), "truncated");
    err_contains(Map::from_bytes(b"P2\n2 1\n255\n0 999\n"), "999");
    err_contains(Map::from_bytes(b"P6\n1 1\n255\n\x00\x00\x00"), "PGM");

    let png = gray_png(16, 16, &[128; 256]);
    for cut in [8, 20, 33, png.len() / 2, png.len() - 13] {
        let r = Map::from_bytes(&png[..cut]);
        assert!(r.is_err(), "a PNG cut to {cut} of {} bytes loaded", png.len());
    }
    // A PNG whose header claims an absurd size.
    let mut huge = gray_png(1, 1, &[0]);
    huge[16..20].copy_from_slice(&100_000u32.to_be_bytes());
    huge[20..24].copy_from_slice(&100_000u32.to_be_bytes());
    assert!(Map::from_bytes(&huge).is_err());
    // Random bytes after a PNG signature.
    let mut junk = b"\x89PNG\r\n\x1a\n".to_vec();
    junk.extend((0..200u32).map(|i| (i * 37 % 251) as u8));
    assert!(Map::from_bytes(&junk).is_err());
}

#[wasm_bindgen_test]
fn from_cells_builds_and_validates() {
    let map = Map::from_cells(3, 2, &[0, 1, 2, 2, 1, 0]).unwrap();
    assert_eq!((map.width(), map.height()), (3, 2));
    assert_eq!(map.cells(), vec![0, 1, 2, 2, 1, 0]);
    assert_eq!(counts(&map), Counts { free: 2, unknown: 2, occupied: 2 });
    // Painted maps save and load back to the same classes.
    assert_eq!(Map::from_bytes(&map.to_pgm()).unwrap().cells(), map.cells());

    err_contains(Map::from_cells(3, 2, &[0; 5]), "needs 6 cell codes, but 5");
    err_contains(Map::from_cells(3, 2, &[0; 7]), "needs 6 cell codes, but 7");
    err_contains(Map::from_cells(2, 2, &[0, 1, 2, 3]), "cell code 3 at (1, 1)");
    err_contains(Map::from_cells(1, 1, &[255]), "cell code 255");
    err_contains(Map::from_cells(0, 5, &[]), "0x5");
    err_contains(Map::from_cells(5, 0, &[]), "5x0");
    err_contains(Map::from_cells(u32::MAX, u32::MAX, &[]), "over the limit");
    err_contains(Map::from_cells(100_000, 100_000, &[0; 16]), "over the limit");
}

#[wasm_bindgen_test]
fn renders_rgba() {
    let map = Map::from_cells(3, 2, &[0, 1, 2, 2, 1, 0]).unwrap();
    let r = wasm::render_rgba(&map, None, None, None).unwrap();
    assert_eq!((r.width(), r.height()), (3, 2));
    let rgba = r.rgba().0;
    assert_eq!(rgba.len(), 4 * 3 * 2);
    assert_eq!(&rgba[0..4], &[255, 255, 255, 255], "a free cell is white");
    assert_eq!(&rgba[20..24], &[255, 255, 255, 255], "a free cell is white");
    assert!(rgba[8..11].iter().all(|&v| v < 64), "an occupied cell is dark: {:?}", &rgba[8..12]);
    assert_eq!(rgba.chunks(4).filter(|p| p[3] != 255).count(), 0, "opaque");

    let big = wasm::render_rgba(&map, None, Some(4), Some(false)).unwrap();
    assert_eq!((big.width(), big.height()), (12, 8));
    assert_eq!(big.rgba().0.len(), 4 * 12 * 8);

    let world = ksmcmc::floorplan::World::empty(3, 2).to_json();
    let with_world = wasm::render_rgba(&map, Some(world), None, None).unwrap();
    assert_eq!(with_world.rgba().0.len(), 4 * 3 * 2);
}

/// A world whose units carry their own angle (issue 13) renders in wasm as natively: each
/// unit in its own frame.
#[wasm_bindgen_test]
fn renders_units_at_their_own_angle_as_natively() {
    use ksmcmc::floorplan::{Unit, UnitType, World};
    let cells: Vec<u8> = (0..80 * 60).map(|i| if i % 7 == 0 { 2 } else { 0 }).collect();
    let map = Map::from_cells(80, 60, &cells).unwrap();
    let mut world = World::empty(80, 60);
    world.units.push(Unit::new(1, 5, 5, 20, 15, UnitType::Room));
    world.units.push(Unit { angle: Some(0.6), ..Unit::new(2, 40, 30, 25, 18, UnitType::Corridor) });
    world.validate().unwrap();
    let r = wasm::render_rgba(&map, Some(world.to_json()), Some(2), Some(true)).unwrap();
    let grid = ksmcmc::grid::Grid::from_vec(
        80,
        60,
        cells.iter().map(|&c| ksmcmc::grid::Cell::from_code(c).unwrap()).collect(),
    )
    .unwrap();
    let options = ksmcmc::render::RenderOptions { scale: 2, labels: true, legend: true };
    let native = ksmcmc::render::render(&grid, Some(&world), &options);
    assert!(r.rgba().0 == ksmcmc::render::to_rgba(&native), "wasm and native pictures differ");
}

#[wasm_bindgen_test]
fn bad_render_requests_are_errors() {
    let map = Map::from_cells(3, 2, &[0; 6]).unwrap();
    err_contains(wasm::render_rgba(&map, None, Some(0), None), "scale");
    err_contains(wasm::render_rgba(&map, None, Some(u32::MAX), None), "over the limit");
    assert!(wasm::render_rgba(&map, Some("{".into()), None, None).is_err());
    assert!(wasm::render_rgba(&map, Some("{\"format\": \"nope\"}".into()), None, None).is_err());
}

#[wasm_bindgen_test]
fn draws_the_same_pixels_on_a_canvas() {
    let document = web_sys::window().unwrap().document().unwrap();
    let canvas: web_sys::HtmlCanvasElement = document.create_element("canvas").unwrap().dyn_into().unwrap();
    let map = Map::from_cells(4, 3, &[0, 1, 2, 0, 2, 2, 1, 0, 0, 0, 1, 2]).unwrap();
    wasm::draw_to_canvas(&canvas, &map, None, Some(2), None).unwrap();
    assert_eq!((canvas.width(), canvas.height()), (8, 6));
    let ctx: web_sys::CanvasRenderingContext2d = canvas.get_context("2d").unwrap().unwrap().dyn_into().unwrap();
    let shown = ctx.get_image_data(0.0, 0.0, 8.0, 6.0).unwrap().data().0;
    let expected = wasm::render_rgba(&map, None, Some(2), None).unwrap().rgba().0;
    assert_eq!(shown, expected);

    // A failed draw leaves the canvas as it was.
    assert!(wasm::draw_to_canvas(&canvas, &map, None, Some(0), None).is_err());
    assert_eq!((canvas.width(), canvas.height()), (8, 6));
}

#[wasm_bindgen_test]
fn synth_is_deterministic() {
    let a = wasm::synth(JsValue::from(7), None).unwrap();
    let b = wasm::synth(JsValue::from(7.0), None).unwrap();
    assert_eq!(a.map_pgm(), b.map_pgm());
    assert_eq!(a.map_yaml(), b.map_yaml());
    assert_eq!(a.truth_json(), b.truth_json());
    assert_eq!(a.labels_pgm(), b.labels_pgm());
    assert!(a.map_pgm().starts_with(b"P5"));
    assert!(a.labels_pgm().starts_with(b"P5"));
    assert!(a.map_yaml().contains("map.pgm"));
    ksmcmc::floorplan::World::from_json(&a.truth_json()).expect("truth.json is a world");
    // The files describe the map: read back (as pages do, with the mapper module's `Map`),
    // it is the generator's.
    let read = Map::from_yaml(&a.map_yaml(), &a.map_pgm()).unwrap();
    let made = &a.inner().map;
    assert_eq!(read.inner().classified(), made.classified());
    assert_eq!(read.inner().yaml().resolution, made.yaml().resolution);
    // Exactly the library's result: what the native CLI writes.
    let native = ksmcmc::floorplan::synth::generate(&Default::default(), 7).unwrap();
    assert_eq!(a.map_pgm(), native.map_pgm());
    assert_eq!(a.truth_json(), native.truth_json());
    assert_eq!(a.labels_pgm(), native.labels_pgm());

    // A bigint seed is the same seed.
    let big = wasm::synth(JsValue::bigint_from_str("7"), None).unwrap();
    assert_eq!(big.map_pgm(), a.map_pgm());
    assert_eq!(big.truth_json(), a.truth_json());
    // The largest safe number and the largest bigint are accepted.
    let max_safe = wasm::seed_from_js(&JsValue::from(9_007_199_254_740_991.0)).unwrap();
    assert_eq!(max_safe, (1 << 53) - 1);
    assert_eq!(wasm::seed_from_js(&JsValue::bigint_from_str("18446744073709551615")).unwrap(), u64::MAX);
    assert_eq!(wasm::seed_from_js(&JsValue::from(0)).unwrap(), 0);
}

#[wasm_bindgen_test]
fn synth_config_is_merged_over_the_defaults() {
    // Unrotated (the default), the map is the canvas the config asks for.
    let defaults = ksmcmc::floorplan::synth::SynthConfig::default();
    let size = |s: &wasm::Synthetic| (s.inner().map.width() as u32, s.inner().map.height() as u32);
    let s = wasm::synth(JsValue::from(3), Some(r#"{"width": 500, "height": 320}"#.into())).unwrap();
    assert_eq!(size(&s), (500, 320));
    let s = wasm::synth(JsValue::from(3), Some(r#"{"width": 500}"#.into())).unwrap();
    assert_eq!(size(&s), (500, defaults.height));
    let s = wasm::synth(JsValue::from(3), Some("  ".into())).unwrap();
    assert_eq!(size(&s), (defaults.width, defaults.height));
    let s = wasm::synth(JsValue::from(3), Some("{}".into())).unwrap();
    assert_eq!(size(&s), (defaults.width, defaults.height));
}

#[wasm_bindgen_test]
fn bad_seeds_and_configs_are_errors() {
    err_contains(wasm::synth(JsValue::from(f64::NAN), None), "NaN");
    err_contains(wasm::synth(JsValue::from(-1), None), "negative");
    err_contains(wasm::synth(JsValue::from(1.5), None), "whole number");
    err_contains(wasm::synth(JsValue::from(f64::INFINITY), None), "2^53");
    err_contains(wasm::synth(JsValue::from(9_007_199_254_740_992.0), None), "bigint");
    err_contains(wasm::synth(JsValue::from("7"), None), "the string \"7\"");
    err_contains(wasm::synth(JsValue::UNDEFINED, None), "undefined");
    err_contains(wasm::synth(JsValue::NULL, None), "null");
    err_contains(wasm::synth(JsValue::bigint_from_str("-1"), None), "bigint");
    err_contains(wasm::synth(JsValue::bigint_from_str("18446744073709551616"), None), "bigint");

    let seed = || JsValue::from(1);
    err_contains(wasm::synth(seed(), Some("nope".into())), "synth config");
    err_contains(wasm::synth(seed(), Some("[1, 2]".into())), "JSON object");
    err_contains(wasm::synth(seed(), Some(r#"{"width": -1}"#.into())), "synth config");
    err_contains(wasm::synth(seed(), Some(r#"{"width": "wide"}"#.into())), "synth config");
    err_contains(wasm::synth(seed(), Some(r#"{"width": 0}"#.into())), "0x");
    err_contains(wasm::synth(seed(), Some(r#"{"width": 100000, "height": 100000}"#.into())), "over the limit");
}

// ---------------------------------------------------------------- the live mapper

use ksmcmc::floorplan::route::RoutePlanner;
use ksmcmc::floorplan::{Chain, ChainConfig, World};
use ksmcmc::wasm::{Mapper, Plan};

/// The plan module's `Plan` of a mapper's best world now, as the live mapper's worker makes
/// it: from the map's PGM and YAML and `planInput()`.
fn plan_of(map: &Map, m: &mut Mapper) -> Plan {
    Plan::new(&map.to_pgm(), &map.to_yaml("map.pgm"), &m.plan_input(), None, None).unwrap()
}

/// Two rooms side by side in a 64x40 map: walls all round, a wall between them with a door.
fn two_rooms() -> Map {
    let (w, h) = (64u32, 40u32);
    let mut codes = vec![0u8; (w * h) as usize];
    for y in 0..h {
        for x in 0..w {
            let wall = x == 0 || y == 0 || x == w - 1 || y == h - 1 || (x == 31 && !(15..25).contains(&y));
            if wall {
                codes[(y * w + x) as usize] = 2;
            }
        }
    }
    Map::from_cells(w, h, &codes).unwrap()
}

fn get(v: &JsValue, key: &str) -> JsValue {
    js_sys::Reflect::get(v, &JsValue::from_str(key)).unwrap()
}

#[wasm_bindgen_test]
fn mapper_runs_and_finds_units() {
    let map = two_rooms();
    let mut m = Mapper::new(&map, None, Some(JsValue::from(1))).unwrap();
    assert_eq!((m.width(), m.height(), m.iteration()), (64, 40, 0.0));
    let start = m.log_posterior();
    assert_eq!(m.best_units(), 0, "the chain starts from the empty world");
    assert_eq!(m.step(3000.0).unwrap(), 3000.0);
    assert_eq!(m.iteration(), 3000.0);
    assert!(m.best_log_posterior() > start, "{} should rise above {start}", m.best_log_posterior());
    assert!(m.best_log_posterior() >= m.log_posterior());
    assert!(m.best_units() >= 1 && m.units() >= 1, "units appeared");
    assert!((0.0..=1.0).contains(&m.acceptance()));
    assert!(m.best_prediction_rate() > 0.8, "K = {}", m.best_prediction_rate());
    assert!(m.elapsed_ms() >= 0.0 && m.setup_ms() >= 0.0);
    // The clock is checked every 16 iterations: whole slices, at least one (no wall-clock
    // figure here, so a loaded machine cannot fail it).
    let n = m.run_for(5.0).unwrap();
    assert!(n >= 16.0 && n % 16.0 == 0.0, "runFor ran {n} iterations, not whole slices of 16");

    // Both worlds are valid world.json for this map, and the best one is the library's.
    let current = World::from_json(&m.world_json()).expect("worldJson parses and validates");
    assert_eq!(current.units.len() as u32, m.units());
    let best = World::from_json(&plan_of(&map, &mut m).world_json()).expect("the plan's world parses and validates");
    assert_eq!(best.frame.map_size, [64, 40]);
    assert_eq!(best.units.len() as u32, m.best_units());
    assert_eq!(best.doors.len() as u32, m.best_doors());
    let mut chain = Chain::new(map.inner(), ChainConfig::default(), 1).unwrap();
    chain.step(3000);
    let mut fresh = Mapper::new(&map, None, None).unwrap();
    fresh.step(3000.0).unwrap();
    let (world, _) = chain.best_world_with_rooms(&Default::default()).unwrap();
    assert_eq!(plan_of(&map, &mut fresh).world_json(), world.to_json(), "seed 1 is the default");
    assert_eq!(fresh.seed(), 1);
}

#[wasm_bindgen_test]
fn mapper_matches_the_library_on_a_sample() {
    // The sample the browser test compares with the native CLI: same seed, same world.
    let map = Map::from_yaml(
        include_str!("../samples/office-small/map.yaml"),
        include_bytes!("../samples/office-small/map.pgm"),
    )
    .unwrap();
    let mut m = Mapper::new(&map, None, Some(JsValue::from(3))).unwrap();
    m.step(1500.0).unwrap();
    m.step(500.0).unwrap();
    let mut chain = Chain::new(map.inner(), ChainConfig::default(), 3).unwrap();
    chain.step(2000);
    // The exports carry the room layer, as `ksmcmc floorplan` writes them.
    let (world, labels) = chain.best_world_with_rooms(&Default::default()).unwrap();
    assert!(!world.rooms.is_empty());
    let plan = plan_of(&map, &mut m);
    assert_eq!(plan.world_json(), world.to_json());
    assert_eq!(plan.labels_pgm(), ksmcmc::grid::pgm::encode_u16(labels.width(), labels.height(), labels.cells()));
    assert!(m.best_units() >= 3, "{} units", m.best_units());
    // overlay.png: the mapper module draws the plan's world, the plan module encodes it.
    let opts = js_sys::Object::new();
    js_sys::Reflect::set(&opts, &"world".into(), &plan.world_json().into()).unwrap();
    let r = wasm::render_mapper_rgba(&mut m, Some(opts.into())).unwrap();
    let png = wasm::encode_png(r.width(), r.height(), r.rgba_bytes()).unwrap();
    assert_eq!(png, ksmcmc::render::overlay_png(map.inner().classified(), &world).unwrap());
}

#[wasm_bindgen_test]
fn mapper_labels_rooms_and_units_only_when_asked() {
    // Rooms first (issue 33): the chain's own world has no rooms, so `labels` alone draws no
    // labels on it; `unitLabels` labels its units; a plan's world is labelled room by room.
    let (map, mut m, mut chain, _, _) = office_small_after_2000();
    let draw = |m: &mut Mapper, pairs: &[(&str, JsValue)]| {
        let opts = js_sys::Object::new();
        js_sys::Reflect::set(&opts, &"show".into(), &"best".into()).unwrap();
        for (k, v) in pairs {
            js_sys::Reflect::set(&opts, &(*k).into(), v).unwrap();
        }
        wasm::render_mapper_rgba(m, Some(opts.into())).unwrap().rgba_bytes().to_vec()
    };
    let native = |world: &World, labels: bool, legend: bool| {
        let options = ksmcmc::render::RenderOptions { scale: 1, labels, legend };
        ksmcmc::render::to_rgba(&ksmcmc::render::render(map.inner().classified(), Some(world), &options))
    };
    // The mapper draws the chain's best world typed by the rules, as the library gives it.
    let best = chain.best_world_typed();
    assert!(best.rooms.is_empty() && best.units.len() >= 3);
    let plain = draw(&mut m, &[]);
    assert_eq!(plain, native(&best, false, true), "no rooms, no labels");
    let units = draw(&mut m, &[("unitLabels", JsValue::TRUE)]);
    assert_eq!(units, native(&best, true, true), "unit labels when asked");
    assert_ne!(units, plain);
    assert_eq!(draw(&mut m, &[("unitLabels", JsValue::TRUE), ("labels", JsValue::FALSE)]), plain);
    assert_eq!(draw(&mut m, &[("legend", JsValue::FALSE)]), native(&best, false, false), "no legend when asked");
    // A plan's world: its rooms labelled, or its units with unitLabels.
    let plan = plan_of(&map, &mut m);
    let planned = World::from_json(&plan.world_json()).unwrap();
    assert!(!planned.rooms.is_empty());
    let text: JsValue = plan.world_json().into();
    assert_eq!(draw(&mut m, &[("world", text.clone())]), native(&planned, true, true), "room labels");
    let mut bare = planned.clone();
    bare.rooms.clear();
    assert_eq!(draw(&mut m, &[("world", text), ("unitLabels", JsValue::TRUE)]), native(&bare, true, true));
    // The page's legend lists every row the renderer can draw, in its order.
    let rows: Vec<serde_json::Value> = serde_json::from_str(&wasm::legend_json()).unwrap();
    let names: Vec<&str> = rows.iter().map(|r| r["name"].as_str().unwrap()).collect();
    let palette = ksmcmc::render::legend_palette();
    assert_eq!(names, palette.iter().map(|p| p.0).collect::<Vec<_>>());
    assert_eq!(rows[0]["rgba"], serde_json::json!(palette[0].1));
}

#[wasm_bindgen_test]
fn the_whole_map_table_rescores_the_mapper_as_the_library_does() {
    // The end of an exploration on the page: the exploring chain (range-sensor table) takes the
    // whole-map table and goes on, as `Chain::set_sensor` does natively.
    let map = Map::from_yaml(
        include_str!("../samples/office-small/map.yaml"),
        include_bytes!("../samples/office-small/map.pgm"),
    )
    .unwrap();
    let mut m = Mapper::new(&map, Some(wasm::chain_config_online()), Some(JsValue::from(3))).unwrap();
    m.step(1500.0).unwrap();
    let mut chain = Chain::new(map.inner(), ChainConfig::online(), 3).unwrap();
    chain.step(1500);
    assert_eq!(m.best_log_posterior(), chain.best_log_posterior());
    m.use_whole_map_sensor();
    chain.set_sensor(ksmcmc::floorplan::posterior::SensorModel::default());
    assert_eq!(m.best_log_posterior(), chain.best_log_posterior(), "rescored alike");
    m.step(500.0).unwrap();
    chain.step(500);
    assert_eq!((m.best_log_posterior(), m.iteration()), (chain.best_log_posterior(), 2000.0));
}

/// The office-small sample in a `Mapper` and in the library's chain, both seed 3 and 2,000
/// iterations, with the chain's best world and room labels.
fn office_small_after_2000() -> (Map, Mapper, Chain, World, ksmcmc::grid::Grid<u16>) {
    let map = Map::from_yaml(
        include_str!("../samples/office-small/map.yaml"),
        include_bytes!("../samples/office-small/map.pgm"),
    )
    .unwrap();
    let mut m = Mapper::new(&map, None, Some(JsValue::from(3))).unwrap();
    m.step(2000.0).unwrap();
    let mut chain = Chain::new(map.inner(), ChainConfig::default(), 3).unwrap();
    chain.step(2000);
    let (world, labels) = chain.best_world_with_rooms(&Default::default()).unwrap();
    (map, m, chain, world, labels)
}

#[wasm_bindgen_test]
fn routes_match_the_library() {
    // The best world's route, as the library plans it on the same world and labels, and as
    // planRoute plans it from the world's JSON (with the labels, and finding them again).
    let (map, mut m, _, world, labels) = office_small_after_2000();
    let mut planner = RoutePlanner::new(map.inner().classified().clone(), labels, &world, 0.05).unwrap();
    let (from, to) = ((200.0, 100.0), (60.0, 250.0));
    let native = planner.route((200, 100), (60, 250)).unwrap().to_json();
    let mut plan = plan_of(&map, &mut m);
    let json = plan.route(from.0, from.1, to.0, to.1).unwrap();
    assert_eq!(json, native);
    let r: serde_json::Value = serde_json::from_str(&json).unwrap();
    assert_eq!(r["path"][0], serde_json::json!([200, 100]));
    let world_json = plan.world_json();
    let (pgm, yaml) = (map.to_pgm(), map.to_yaml("map.pgm"));
    let saved = |labels| wasm::plan_route(&pgm, &yaml, &world_json, from.0, from.1, to.0, to.1, labels);
    assert_eq!(saved(Some(plan.labels_pgm())).unwrap(), native);
    assert_eq!(saved(None).unwrap(), native);
    // Bad ends are thrown errors that say why.
    err_contains(plan.route(0.0, 0.0, to.0, to.1), "the start (0, 0) is an unknown cell");
    err_contains(plan.route(f64::NAN, 0.0, to.0, to.1), "fromX: NaN is not a cell coordinate");
    err_contains(plan.route(1.5, 0.0, to.0, to.1), "fromX: 1.5 is not a cell coordinate");
    err_contains(plan.route(from.0, from.1, 9999.0, to.1), "the goal (9999, 250) lies outside the 400x300 map");
    err_contains(wasm::plan_route(&pgm, &yaml, "{}", from.0, from.1, to.0, to.1, None), "world.json");
    err_contains(saved(Some(vec![1, 2, 3])), "labelsPgm");
    err_contains(wasm::plan_route(b"P5 nope", &yaml, &world_json, from.0, from.1, to.0, to.1, None), "PGM");
}

#[wasm_bindgen_test]
fn world_glb_matches_the_library() {
    // The best world in 3D: the bytes `ksmcmc floorplan` writes to world.glb for that world,
    // from the Mapper and from the saved world.json alike.
    let map = two_rooms();
    let mut m = Mapper::new(&map, None, None).unwrap();
    m.step(1500.0).unwrap();
    let plan = plan_of(&map, &mut m);
    let world = World::from_json(&plan.world_json()).unwrap();
    let options = ksmcmc::render::model3d::Model3dOptions { wall_height: 3.0, door_height: 2.2 };
    let native = ksmcmc::render::model3d::world_glb(&world, 0.05, &options).unwrap();
    let heights = js_sys::JSON::parse(r#"{"wallHeight": 3, "doorHeight": 2.2}"#).unwrap();
    assert_eq!(plan.world_glb(Some(heights.clone())).unwrap(), native);
    assert_eq!(wasm::world_glb(&plan.world_json(), 0.05, Some(heights)).unwrap(), native);
    let defaults = ksmcmc::render::model3d::world_glb(&world, 0.05, &Default::default()).unwrap();
    assert_eq!(plan.world_glb(None).unwrap(), defaults);
    assert!(defaults.starts_with(b"glTF"));
    let bad = |json: &str| js_sys::JSON::parse(json).unwrap();
    err_contains(plan.world_glb(Some(bad(r#"{"wallHeight": 2, "doorHeight": 3}"#))), "door height 3 m");
    err_contains(plan.world_glb(Some(bad(r#"{"wallheight": 2}"#))), "wallHeight and doorHeight");
    err_contains(plan.world_glb(Some(JsValue::from(3))), "expected an object");
    err_contains(wasm::world_glb("{", 0.05, None), "world.json");
    err_contains(wasm::world_glb(&plan.world_json(), f64::NAN, None), "resolution NaN");
}

#[wasm_bindgen_test]
fn mapper_gives_room_labels_and_type_marginals_as_the_library() {
    let (map, mut m, mut chain, world, labels) = office_small_after_2000();
    let plan = plan_of(&map, &mut m);
    assert_eq!(plan.room_labels(), labels.cells().to_vec());
    assert_eq!(plan.rooms_json(), ksmcmc::floorplan::export::rooms_json(&world));
    let inferred = chain.best_world_inferred().1.unwrap();
    use ksmcmc::floorplan::rooms::{room_marginals, room_types};
    // Knowledge is on: the rooms' own marginals (the rules applied to each room).
    let own = room_marginals(&world, &world.rooms, &labels, 0.05, &Default::default()).unwrap();
    assert_eq!(own.len(), world.rooms.iter().filter(|r| !r.units.is_empty()).count());
    let expected = ksmcmc::floorplan::export::room_types_json(&room_types(&world, &inferred, &own));
    assert_eq!(plan.room_types_json(), expected, "the marginals cross to the plan module bit for bit");
    let rooms: serde_json::Value = serde_json::from_str(&plan.room_types_json()).unwrap();
    assert_eq!(rooms.as_array().unwrap().len(), world.rooms.len());
    assert!(rooms[0]["marginals"]["corridor"].is_f64(), "{rooms}");
    // Asking changed nothing: the best world is the one it was.
    assert_eq!(plan_of(&map, &mut m).world_json(), world.to_json());
}

#[wasm_bindgen_test]
fn plans_of_a_rotated_map_are_the_chains_bit_for_bit() {
    // A map turned by 20 degrees: the world's frame angle has all 17 digits, which JSON
    // text alone does not carry back exactly; the room labels are made on the map turned by it.
    let map = Map::from_yaml(
        include_str!("../samples/office-rotated/map.yaml"),
        include_bytes!("../samples/office-rotated/map.pgm"),
    )
    .unwrap();
    let mut m = Mapper::new(&map, None, Some(JsValue::from(2))).unwrap();
    m.step(1500.0).unwrap();
    let mut chain = Chain::new(map.inner(), ChainConfig::default(), 2).unwrap();
    chain.step(1500);
    let (world, labels) = chain.best_world_with_rooms(&Default::default()).unwrap();
    assert!(world.frame.angle != 0.0 && !world.rooms.is_empty());
    let plan = plan_of(&map, &mut m);
    assert_eq!(plan.world_json(), world.to_json());
    assert_eq!(plan.room_labels(), labels.cells().to_vec());
    let native = ksmcmc::floorplan::geojson::world_geojson(&world, &labels, map.inner(), None).unwrap();
    assert_eq!(plan.geojson(None).unwrap(), native);
    // The report: the chain's numbers as the library reports them.
    let typed = chain.best_world_typed();
    let mut want = ksmcmc::floorplan::report::summary(&chain, map.inner(), &typed, 0.0);
    ksmcmc::floorplan::report::add_rooms(&mut want, &world, &labels);
    let mut got: serde_json::Value = serde_json::from_str(&plan.report_json().unwrap()).unwrap();
    for k in ["seconds", "iterations_per_second", "setup_seconds"] {
        got.as_object_mut().unwrap().remove(k);
        want.as_object_mut().unwrap().remove(k);
    }
    assert_eq!(got, want);
}

#[wasm_bindgen_test]
fn plans_of_an_empty_world_have_only_unexplained_rooms() {
    // Before any unit: the free space is rooms of no unit and no type (the live mapper's page
    // lists no rooms until the best world has units, and loads the plan module only then).
    let map = two_rooms();
    let mut m = Mapper::new(&map, None, None).unwrap();
    assert_eq!(m.best_units(), 0);
    let plan = plan_of(&map, &mut m);
    let rooms: serde_json::Value = serde_json::from_str(&plan.rooms_json()).unwrap();
    let rooms = rooms.as_array().unwrap();
    assert!(!rooms.is_empty());
    for r in rooms {
        assert_eq!((r["type"].as_str(), r["units"].as_array().map(Vec::len)), (Some("unknown"), Some(0)), "{r}");
    }
    let labels = plan.room_labels();
    let free: Vec<bool> = map.cells().iter().map(|&c| c == 0).collect();
    assert!(labels.iter().zip(&free).all(|(&id, &f)| id == 0 || f), "rooms lie on free cells");
    assert_eq!(labels.len(), 64 * 40);
}

#[wasm_bindgen_test]
fn plans_keep_room_ids_through_edits_with_the_previous_labels() {
    let (map, mut m, mut chain, _, _) = office_small_after_2000();
    let edits = r#"[{"op": "name", "at": [200, 100], "name": "Hall A"}]"#;
    m.set_edits(edits).unwrap();
    chain.set_edits(ksmcmc::floorplan::edits::Edits::parse(edits).unwrap()).unwrap();
    let first = plan_of(&map, &mut m);
    m.step(1500.0).unwrap();
    chain.step(1500);
    let (pgm, yaml) = (map.to_pgm(), map.to_yaml("map.pgm"));
    let second = Plan::new(&pgm, &yaml, &m.plan_input(), Some(first.room_labels()), None).unwrap();
    // The library: the chain's rooms, ids carried over from the labels shown before.
    let (mut world, mut labels) = chain.best_world_with_rooms(&Default::default()).unwrap();
    let previous = ksmcmc::grid::Grid::from_vec(400, 300, first.room_labels()).unwrap();
    ksmcmc::floorplan::edits::carry_ids(&previous, &mut labels, &mut world.rooms);
    assert_eq!(second.world_json(), world.to_json());
    assert_eq!(second.room_labels(), labels.cells().to_vec());
    assert!(world.rooms.iter().any(|r| r.name.as_deref() == Some("Hall A")), "the name edit holds");
    // Without edits in force the previous labels change nothing.
    m.set_edits("[]").unwrap();
    let a = Plan::new(&pgm, &yaml, &m.plan_input(), Some(first.room_labels()), None).unwrap();
    assert_eq!(a.room_labels(), plan_of(&map, &mut m).room_labels());
}

#[wasm_bindgen_test]
fn plans_refuse_bad_inputs() {
    let map = two_rooms();
    let mut m = Mapper::new(&map, None, None).unwrap();
    m.step(500.0).unwrap();
    let (pgm, yaml, input) = (map.to_pgm(), map.to_yaml("map.pgm"), m.plan_input());
    let plan = |pgm: &[u8], input: &str, previous| Plan::new(pgm, &yaml, input, previous, None).map(|_| ());
    err_contains(plan(&pgm, "{", None), "plan input");
    err_contains(plan(&pgm, "{}", None), "missing field `world`");
    err_contains(plan(&pgm, r#"{"world": {}}"#, None), "plan input");
    err_contains(plan(b"\x89PNG\r\n\x1a\n", &input, None), "PGM");
    err_contains(plan(&pgm, &input, Some(vec![0; 3])), "previousLabels: give the 2560 room ids");
    // A world of another map.
    let other = Map::from_cells(50, 40, &[0; 2000]).unwrap();
    err_contains(Plan::new(&other.to_pgm(), &other.to_yaml("map.pgm"), &input, None, None).map(|_| ()), "map");
    // Edits off the map.
    let mut v: serde_json::Value = serde_json::from_str(&input).unwrap();
    v["edits"] = r#"[{"op": "name", "at": [500, 5], "name": "x"}]"#.into();
    err_contains(plan(&pgm, &v.to_string(), None), "edits");
    // A saved typed world alone is a plan without a report.
    let world = serde_json::json!({"world": v["world"]});
    let saved = Plan::new(&pgm, &yaml, &world.to_string(), None, None).unwrap();
    assert!(saved.world_json().contains("\"rooms\""));
    err_contains(saved.report_json(), "without a chain");
    // A building of one direction needs no wing chains, and takes none.
    let one = Plan::new(&pgm, &yaml, &input, None, None).unwrap();
    assert_eq!(one.wing_count(), 0);
    err_contains(one.wing_map_pgm(0), "needs 0 wing chains");
    err_contains(Plan::new(&pgm, &yaml, &input, None, Some(vec![input.clone()])).map(|_| ()), "one chain");
    err_contains(Plan::new(&pgm, &yaml, &input, None, Some(vec!["{".into()])).map(|_| ()), "wingInputs[0]");
}

#[wasm_bindgen_test]
fn mapper_exports_trace_samples_labels_graph_and_report() {
    let map = two_rooms();
    let mut m = Mapper::new(&map, Some(r#"{"output": {"trace_every": 50}}"#.into()), None).unwrap();
    m.step(2000.0).unwrap();

    let trace = m.trace(None).unwrap();
    let it: js_sys::Float64Array = get(&trace, "iteration").dyn_into().unwrap();
    let lp: js_sys::Float64Array = get(&trace, "logPosterior").dyn_into().unwrap();
    let acc: js_sys::Float64Array = get(&trace, "acceptance").dyn_into().unwrap();
    let units: js_sys::Uint32Array = get(&trace, "units").dyn_into().unwrap();
    assert_eq!(m.trace_length(), 40);
    for a in [it.length(), lp.length(), acc.length(), units.length()] {
        assert_eq!(a, 40);
    }
    assert_eq!((it.get_index(0), it.get_index(39)), (50.0, 2000.0));
    let tail = m.trace(Some(38)).unwrap();
    let tail_it: js_sys::Float64Array = get(&tail, "iteration").dyn_into().unwrap();
    assert_eq!(tail_it.to_vec(), vec![1950.0, 2000.0]);
    assert_eq!(get(&m.trace(Some(999)).unwrap(), "iteration").dyn_into::<js_sys::Float64Array>().unwrap().length(), 0);

    let samples = m.samples().unwrap();
    let rects: js_sys::Int32Array = get(&samples, "rects").dyn_into().unwrap();
    let offsets: js_sys::Uint32Array = get(&samples, "offsets").dyn_into().unwrap();
    let offsets = offsets.to_vec();
    assert!(offsets.len() >= 2, "accepted samples were kept");
    assert_eq!(offsets[0], 0);
    assert!(offsets.windows(2).all(|w| w[0] <= w[1]));
    assert_eq!(*offsets.last().unwrap() * 4, rects.length());
    let frame = get(&samples, "frame");
    assert_eq!(get(&frame, "angle").as_f64(), Some(0.0));
    let size: js_sys::Array = get(&frame, "mapSize").dyn_into().unwrap();
    assert_eq!((size.get(0).as_f64(), size.get(1).as_f64()), (Some(64.0), Some(40.0)));

    let plan = plan_of(&map, &mut m);
    let pgm = plan.labels_pgm();
    let header = b"P5\n64 40\n65535\n";
    assert!(pgm.starts_with(header), "{:?}", String::from_utf8_lossy(&pgm[..16]));
    assert_eq!(pgm.len(), header.len() + 64 * 40 * 2);

    let graph: serde_json::Value = serde_json::from_str(&plan.graph_json()).unwrap();
    assert_eq!(graph["nodes"].as_array().unwrap().len() as u32, m.best_units());
    let current: serde_json::Value = serde_json::from_str(&wasm::graph_json(&m.world_json()).unwrap()).unwrap();
    assert_eq!(current["nodes"].as_array().unwrap().len() as u32, m.units());
    err_contains(wasm::graph_json("{"), "world.json");

    let report: serde_json::Value = serde_json::from_str(&plan.report_json().unwrap()).unwrap();
    assert_eq!(report["iterations"], 2000);
    assert_eq!(report["seed"], 1);
    assert_eq!(report["units"].as_u64().unwrap() as u32, m.best_units());
    assert!(report["kernels"]["add"]["proposed"].as_u64().unwrap() > 0);
    assert!(report["setup_seconds"].as_f64().unwrap() >= 0.0);
}

#[wasm_bindgen_test]
fn mapper_refuses_bad_maps_configs_and_arguments() {
    let map = two_rooms();
    let seed = || Some(JsValue::from(1));
    let bad = |json: &str| Mapper::new(&map, Some(json.into()), seed()).map(|_| ());
    err_contains(bad("{"), "chain config");
    err_contains(bad("[1, 2]"), "JSON object");
    err_contains(bad(r#"{"posterior": {"temperature": NaN}}"#), "NaN");
    err_contains(bad(r#"{"posterior": {"temperature": -1}}"#), "temperature -1");
    err_contains(bad(r#"{"posterior": {"temperature": 0}}"#), "positive");
    err_contains(bad(r#"{"posterior": {"unit_cost": -5}}"#), "unit_cost");
    err_contains(bad(r#"{"posterior": {"temprature": 2}}"#), "unknown field `posterior.temprature`");
    err_contains(bad(r#"{"iterations": 5}"#), "unknown field `iterations`");
    err_contains(bad(r#"{"output": {"samples": -1}}"#), "-1");
    err_contains(bad(r#"{"kernels": {"min_side": "big"}}"#), "chain config");
    // Whitespace and an empty object are the defaults.
    Mapper::new(&map, Some(" ".into()), seed()).unwrap();
    Mapper::new(&map, Some("{}".into()), seed()).unwrap();

    err_contains(Mapper::new(&map, None, Some(JsValue::from(f64::NAN))).map(|_| ()), "NaN");
    err_contains(Mapper::new(&map, None, Some(JsValue::from(-2))).map(|_| ()), "negative");

    let one = Map::from_cells(1, 1, &[0]).unwrap();
    err_contains(Mapper::new(&one, None, seed()).map(|_| ()), "1x1");
    let walls = Map::from_cells(50, 50, &[2; 2500]).unwrap();
    err_contains(Mapper::new(&walls, None, seed()).map(|_| ()), "no free cells");
    let unknown = Map::from_cells(50, 50, &[1; 2500]).unwrap();
    err_contains(Mapper::new(&unknown, None, seed()).map(|_| ()), "no free cells");
    let huge = Map::from_cells(4097, 2048, &vec![0; 4097 * 2048]).unwrap();
    err_contains(Mapper::new(&huge, None, seed()).map(|_| ()), "at most 8388608");

    let mut m = Mapper::new(&map, None, seed()).unwrap();
    for n in [f64::NAN, -1.0, 1.5, f64::INFINITY, 1e12] {
        err_contains(m.step(n), "step");
    }
    for ms in [f64::NAN, -1.0, f64::INFINITY, 1e9] {
        err_contains(m.run_for(ms), "runFor");
    }
    err_contains(m.reset(Some(JsValue::from(-1))), "negative");
    assert_eq!(m.iteration(), 0.0, "failed calls change nothing");
    m.step(10.0).unwrap();
    assert_eq!(m.iteration(), 10.0, "and the mapper still works");
}

#[wasm_bindgen_test]
fn mapper_reset_replays_the_same_chain() {
    let map = two_rooms();
    let mut m = Mapper::new(&map, None, Some(JsValue::from(5))).unwrap();
    m.step(1500.0).unwrap();
    let first = m.plan_input();
    m.reset(None).unwrap();
    assert_eq!((m.iteration(), m.best_units(), m.trace_length()), (0.0, 0, 0));
    m.step(1000.0).unwrap();
    m.step(500.0).unwrap();
    let world = |input: &str| serde_json::from_str::<serde_json::Value>(input).unwrap()["world"].clone();
    assert_eq!(world(&m.plan_input()), world(&first), "same seed, same chunks or not: same result");
    m.reset(Some(JsValue::from(6))).unwrap();
    assert_eq!(m.seed(), 6);
    m.step(1500.0).unwrap();
    m.reset(Some(JsValue::bigint_from_str("5"))).unwrap();
    m.step(1500.0).unwrap();
    assert_eq!(world(&m.plan_input()), world(&first));
}

#[wasm_bindgen_test]
fn mapper_reference_worlds_are_checked() {
    let mut m = Mapper::new(&two_rooms(), None, None).unwrap();
    err_contains(m.set_reference(Some("{".into())), "world.json");
    err_contains(m.set_reference(Some("{\"format\": \"nope\"}".into())), "world.json");
    let mut other = World::empty(100, 100);
    err_contains(m.set_reference(Some(other.to_json())), "explains a 100x100 map, but the map is 64x40");
    other = World::empty(64, 40);
    other.units.push(ksmcmc::floorplan::Unit::new(1, 60, 0, 10, 10, Default::default()));
    err_contains(m.set_reference(Some(other.to_json())), "outside");
    assert!(!m.has_reference());
    other.units[0].x = 0;
    other.units[0].w = 32;
    other.units[0].h = 40;
    m.set_reference(Some(other.to_json())).unwrap();
    assert!(m.has_reference());
    let opts = |show: &str| {
        let o = js_sys::Object::new();
        js_sys::Reflect::set(&o, &"show".into(), &show.into()).unwrap();
        js_sys::Reflect::set(&o, &"labels".into(), &false.into()).unwrap();
        Some(JsValue::from(o))
    };
    // The reference's unit has a blue wall ring at (5, 0); with no world the map is black there.
    let shown = wasm::render_mapper_rgba(&mut m, opts("reference")).unwrap().rgba().0;
    assert_eq!(&shown[5 * 4..5 * 4 + 4], &[0, 0, 255, 255]);
    let bare = wasm::render_mapper_rgba(&mut m, opts("none")).unwrap().rgba().0;
    assert_eq!(&bare[5 * 4..5 * 4 + 4], &[0, 0, 0, 255]);
    m.set_reference(None).unwrap();
    assert!(!m.has_reference());
}

#[wasm_bindgen_test]
fn mapper_draws_on_canvases() {
    let document = web_sys::window().unwrap().document().unwrap();
    let canvas: web_sys::HtmlCanvasElement = document.create_element("canvas").unwrap().dyn_into().unwrap();
    let mut m = Mapper::new(&two_rooms(), None, None).unwrap();
    m.step(3000.0).unwrap();
    let opts = |json: &str| Some(js_sys::JSON::parse(json).unwrap());

    wasm::draw_mapper(&canvas, &mut m, opts(r#"{"show": "best", "cloud": true, "scale": 3}"#)).unwrap();
    assert_eq!((canvas.width(), canvas.height()), (192, 120));
    let ctx: web_sys::CanvasRenderingContext2d = canvas.get_context("2d").unwrap().unwrap().dyn_into().unwrap();
    let shown = ctx.get_image_data(0.0, 0.0, 192.0, 120.0).unwrap().data().0;
    let want = wasm::render_mapper_rgba(&mut m, opts(r#"{"show": "best", "cloud": true, "scale": 3}"#)).unwrap();
    assert_eq!(shown, want.rgba().0);
    let blue = shown.chunks(4).filter(|p| p == &[0, 0, 255, 255]).count();
    assert!(blue > 100, "the best world's walls are drawn: {blue} blue pixels");
    let magenta = |rgba: &[u8]| {
        rgba.chunks(4).filter(|p| p[0] as u16 > p[1] as u16 + 60 && p[2] as u16 > p[1] as u16 + 30).count()
    };
    assert!(magenta(&shown) > 50, "the cloud is drawn");
    let plain = wasm::render_mapper_rgba(&mut m, opts(r#"{"show": "best", "scale": 3}"#)).unwrap();
    assert_eq!(magenta(&plain.rgba().0), 0, "no cloud unless asked for");
    // A world given as text is drawn instead of show's (here the current world, twice).
    let given = js_sys::Object::new();
    js_sys::Reflect::set(&given, &"world".into(), &m.world_json().into()).unwrap();
    let current = wasm::render_mapper_rgba(&mut m, opts(r#"{"show": "current"}"#)).unwrap();
    assert_eq!(wasm::render_mapper_rgba(&mut m, Some(given.into())).unwrap().rgba().0, current.rgba().0);
    err_contains(wasm::draw_mapper(&canvas, &mut m, opts(r#"{"world": "{"}"#)), "world.json");
    // As PNG: opaque pixels come back from the PNG as they went in.
    let png = wasm::encode_png(plain.width(), plain.height(), plain.rgba_bytes()).unwrap();
    assert!(png.starts_with(b"\x89PNG"));
    let back = ksmcmc::grid::png::decode(&png, &Default::default());
    assert!(back.is_ok(), "{back:?}");
    err_contains(wasm::encode_png(2, 2, &[0; 15]), "needs 16 bytes");
    err_contains(wasm::encode_png(0, 2, &[]), "0x2");
    // Defaults: current world, scale 1.
    wasm::draw_mapper(&canvas, &mut m, None).unwrap();
    assert_eq!((canvas.width(), canvas.height()), (64, 40));

    // Bad options are errors, and the canvas keeps its picture.
    err_contains(wasm::draw_mapper(&canvas, &mut m, opts(r#"{"show": "worst"}"#)), "unknown variant `worst`");
    err_contains(wasm::draw_mapper(&canvas, &mut m, opts(r#"{"scale": 0}"#)), "scale 0");
    err_contains(wasm::draw_mapper(&canvas, &mut m, opts(r#"{"scale": 100000}"#)), "over the limit");
    err_contains(wasm::draw_mapper(&canvas, &mut m, opts(r#"{"colour": "red"}"#)), "unknown field `colour`");
    err_contains(wasm::draw_mapper(&canvas, &mut m, opts(r#"{"cloud": "yes"}"#)), "options");
    err_contains(wasm::draw_mapper(&canvas, &mut m, Some(JsValue::from(3))), "expected an object");
    assert_eq!((canvas.width(), canvas.height()), (64, 40));

    // The scene graph: the canvas's size by default; nodes in their types' colours (the best
    // world is typed with the built-in rules).
    let graph: web_sys::HtmlCanvasElement = document.create_element("canvas").unwrap().dyn_into().unwrap();
    graph.set_width(200);
    graph.set_height(130);
    wasm::draw_scene_graph(&graph, &mut m, opts(r#"{"show": "best"}"#)).unwrap();
    assert_eq!((graph.width(), graph.height()), (200, 130));
    let gctx: web_sys::CanvasRenderingContext2d = graph.get_context("2d").unwrap().unwrap().dyn_into().unwrap();
    let pixels = gctx.get_image_data(0.0, 0.0, 200.0, 130.0).unwrap().data().0;
    let nodes: Vec<[u8; 3]> =
        ksmcmc::floorplan::UnitType::ALL.iter().map(|&t| ksmcmc::render::unit_type_rgb(t)).collect();
    assert!(pixels.chunks(4).filter(|p| nodes.iter().any(|n| p[..3] == *n)).count() > 20, "nodes are drawn");
    let same = wasm::render_scene_graph_rgba(&mut m, 200, 130, Some("best".into())).unwrap();
    assert_eq!(pixels, same.rgba().0);
    wasm::draw_scene_graph(&graph, &mut m, opts(r#"{"width": 90, "height": 60}"#)).unwrap();
    assert_eq!((graph.width(), graph.height()), (90, 60));
    err_contains(wasm::draw_scene_graph(&graph, &mut m, opts(r#"{"width": 0}"#)), "scene graph");
    err_contains(wasm::render_scene_graph_rgba(&mut m, 10, 10, Some("all".into())), "show");
}

#[wasm_bindgen_test]
fn maps_reclassify_like_the_cli() {
    // A gray PNG whose background gray (230) the fixed rule calls unknown.
    let mut pixels = vec![230u8; 20 * 10];
    pixels[..20].fill(0);
    pixels[45] = 255;
    let map = Map::from_bytes(&gray_png(20, 10, &pixels)).unwrap();
    let fixed = map.reclassify("fixed").unwrap();
    assert_eq!(fixed.cells(), map.cells(), "fixed is what fromBytes does");
    let auto = map.reclassify("auto").unwrap();
    assert_eq!((auto.width(), auto.height()), (20, 10));
    let mut native = ksmcmc::grid::OccupancyMap::from_bytes(&gray_png(20, 10, &pixels)).unwrap();
    native.set_classifier(ksmcmc::grid::Classifier::auto()).unwrap();
    let codes: Vec<u8> = native.classified().cells().iter().map(|c| c.code()).collect();
    assert_eq!(auto.cells(), codes);
    err_contains(map.reclassify("smart"), "neither 'auto' nor 'fixed'");
}

#[wasm_bindgen_test]
fn chain_config_defaults_parse_back() {
    let text = wasm::chain_config_defaults();
    let config = wasm::chain_config(Some(&text)).unwrap();
    assert_eq!(config, ChainConfig::default());
}

#[wasm_bindgen_test]
fn chain_config_online_parses_back_with_the_range_sensor_table() {
    let config = wasm::chain_config(Some(&wasm::chain_config_online())).unwrap();
    assert_eq!(config, ChainConfig::online());
    assert_ne!(config.posterior.sensor, ChainConfig::default().posterior.sensor);
}

#[wasm_bindgen_test]
fn tabletop_bad_scene_is_an_error() {
    use ksmcmc::wasm::tabletop::Tabletop;
    err_contains(Tabletop::new("{", None, None, None).map(|_| ()), "");
    let good = ksmcmc::wasm::tabletop::tabletop_synth(Some(JsValue::from(2)), None).unwrap();
    let bad = good.replacen("\"objects\"", "\"objekts\"", 1);
    err_contains(Tabletop::new(&bad, None, None, None).map(|_| ()), "objekts");
    err_contains(Tabletop::new(&good, None, None, Some("stable(obj)\n".into())).map(|_| ()), "rules");
}

#[wasm_bindgen_test]
fn tabletop_constructs_steps_and_analyses() {
    use ksmcmc::wasm::tabletop::{check_rules, tabletop_rules_default, tabletop_synth, Tabletop};
    let scene = tabletop_synth(Some(JsValue::from(5)), Some(r#"{"min_objects": 8, "max_objects": 8}"#.into())).unwrap();
    let mut tt = Tabletop::new(&scene, None, Some(JsValue::from(1)), None).unwrap();
    tt.step(50.0).unwrap();
    assert_eq!(tt.iteration(), 50.0);
    assert!(tt.step(0.5).is_err());
    let a: serde_json::Value = serde_json::from_str(&tt.analysis_json().unwrap()).unwrap();
    let objects = a["objects"].as_array().unwrap();
    assert_eq!(objects.len(), tt.objects() as usize);
    for o in objects {
        let p = o["p_hidden"].as_f64().unwrap();
        assert!((0.0..=1.0).contains(&p));
    }
    assert!(check_rules(&tabletop_rules_default()).unwrap().is_null());
    let e = check_rules("stable(obj)\n\n  hidden(x) =>\n").unwrap();
    assert!(!e.is_null());
    assert!(tt.set_rules("not ( rules").is_err());
    assert_eq!(tt.rules(), tabletop_rules_default(), "the last good rules stay");
}

#[wasm_bindgen_test]
fn rules_learn_from_a_labelled_world() {
    use ksmcmc::wasm::knowledge::{hand_set_indoor_rules, learn_rules};
    let truth = include_str!("../samples/office-small/truth.json");
    let learned = learn_rules(&hand_set_indoor_rules(), truth, 0.05, None).unwrap();
    assert!(learned.contains("// was 2.1972"), "{learned}");
    assert!(ksmcmc::mln::Mln::parse(&learned).is_ok());
    assert_ne!(learned, hand_set_indoor_rules(), "the weights move");
    // A world that does not parse, and an unknown method, are errors, not panics.
    assert!(learn_rules(&hand_set_indoor_rules(), "{", 0.05, None).is_err());
    assert!(learn_rules(&hand_set_indoor_rules(), truth, 0.05, Some("magic".into())).is_err());
}

#[wasm_bindgen_test]
fn update_map_follows_the_library_and_checks_sizes() {
    let full = Map::from_yaml(
        include_str!("../samples/office-small/map.yaml"),
        include_bytes!("../samples/office-small/map.pgm"),
    )
    .unwrap();
    let (w, h) = (full.width(), full.height());
    let mut codes = full.cells();
    for (i, c) in codes.iter_mut().enumerate() {
        if i as u32 % w >= w / 2 {
            *c = 1;
        }
    }
    let half = Map::from_cells(w, h, &codes).unwrap();
    let mut m = Mapper::new(&half, None, Some(JsValue::from(3))).unwrap();
    m.step(2000.0).unwrap();
    let changed = m.update_map(&full).unwrap();
    assert!(changed > 0.0);
    assert_eq!(m.iteration(), 2000.0, "the chain goes on, it does not restart");
    assert_eq!(m.update_map(&full).unwrap(), 0.0, "the same map again changes nothing");
    m.step(2000.0).unwrap();
    let mut chain = Chain::new(half.inner(), ChainConfig::default(), 3).unwrap();
    chain.step(2000);
    chain.update_map(full.inner()).unwrap();
    chain.step(2000);
    // The plan is made on the mapper's map, which is the new one.
    let now = m.map();
    assert_eq!(now.cells(), full.cells());
    assert_eq!(
        plan_of(&now, &mut m).world_json(),
        chain.best_world_with_rooms(&Default::default()).unwrap().0.to_json()
    );
    err_contains(m.update_map(&Map::from_cells(5, 5, &[0; 25]).unwrap()), "keep the map's size");
}

#[wasm_bindgen_test]
fn explorer_reveals_the_map_as_the_library_does() {
    let truth = Map::from_yaml(
        include_str!("../samples/office-small/map.yaml"),
        include_bytes!("../samples/office-small/map.pgm"),
    )
    .unwrap();
    let mut e = wasm::Explorer::new(&truth, Some(r#"{"range_m": 4}"#.into()), Some(JsValue::from(2))).unwrap();
    let first = e.snapshot();
    assert!(counts(&first).free > 0 && counts(&first).free < counts(&truth).free);
    while e.advance(200.0).unwrap() {}
    assert!(e.done() && e.travelled_m() > 1.0);
    assert_eq!(e.scan_cells(0).len(), 2 * e.scans() as usize);
    let mut robot = ksmcmc::explore::Explorer::new(
        truth.inner(),
        ksmcmc::explore::ExploreConfig { range_m: 4.0, ..Default::default() },
        2,
    )
    .unwrap();
    while robot.advance(200) {}
    assert_eq!(
        e.snapshot().cells(),
        robot.snapshot().classified().cells().iter().map(|&c| c as u8).collect::<Vec<_>>()
    );
    assert_eq!(e.seen_free(), counts(&e.snapshot()).free);
    err_contains(wasm::Explorer::new(&truth, Some(r#"{"range_m": -1}"#.into()), None), "range_m");
    err_contains(wasm::Explorer::new(&truth, Some(r#"{"start": [0, 0]}"#.into()), None), "not a free cell");
    err_contains(e.advance(-1.0), "advance");
}
