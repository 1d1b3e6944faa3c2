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
    assert_eq!(a.map().cells(), b.map().cells());
    assert!(a.map_pgm().starts_with(b"P5"));
    assert!(a.labels_pgm().starts_with(b"P5"));
    assert!(a.map_yaml().contains("map.pgm"));
    ksmcmc::floorplan::World::from_json(&a.truth_json()).expect("truth.json is a world");
    // The map getter is the map the files describe.
    assert_eq!(a.map().to_pgm(), a.map_pgm());
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
    let size = |s: &wasm::Synthetic| (s.map().width(), s.map().height());
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
