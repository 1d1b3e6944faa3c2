//! `ksmcmc render` as a user runs it: good maps make PNGs, bad input makes a clear message and
//! a non-zero exit code, never a panic.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::sync::OnceLock;

/// Generated stand-ins for two real maps, encoded as they are, so that these tests run on a
/// fresh clone: `cartesium.png` is 1237x672 16-bit RGBA with unexplored space in gray 230 (as
/// the Radish map), `lab_a_scan.png` 8-bit gray with anti-aliased wall edges (as the Bormann
/// maps). Both hold two walled rooms. Written once per test run.
fn fixtures() -> &'static (String, String) {
    static FIXTURES: OnceLock<(String, String)> = OnceLock::new();
    FIXTURES.get_or_init(|| {
        let dir = temp_dir("fixtures");
        let gray = |x: u32, y: u32, outside: u16| -> u16 {
            let room = |x0: u32, y0: u32, x1: u32, y1: u32| (x0..=x1).contains(&x) && (y0..=y1).contains(&y);
            let wall = |x0: u32, y0: u32, x1: u32, y1: u32| {
                room(x0, y0, x1, y1) && (x <= x0 + 2 || x >= x1 - 2 || y <= y0 + 2 || y >= y1 - 2)
            };
            let (a, b) = ((100, 100, 600, 500), (598, 100, 1000, 400));
            if wall(a.0, a.1, a.2, a.3) || wall(b.0, b.1, b.2, b.3) {
                if x % 7 == 0 {
                    120
                } else {
                    0
                } // a few anti-aliased edge pixels
            } else if room(a.0, a.1, a.2, a.3) || room(b.0, b.1, b.2, b.3) {
                255
            } else {
                outside
            }
        };
        let cartesium = dir.join("cartesium.png");
        let rgba: Vec<u16> = (0..672)
            .flat_map(|y| (0..1237).flat_map(move |x| [gray(x, y, 230) * 257; 3].into_iter().chain([65535])))
            .collect();
        std::fs::write(&cartesium, encode_png(1237, 672, png::ColorType::Rgba, png::BitDepth::Sixteen, &rgba)).unwrap();
        let lab_a = dir.join("lab_a_scan.png");
        let g: Vec<u16> = (0..600).flat_map(|y| (0..1100).map(move |x| gray(x, y, 205))).collect();
        std::fs::write(&lab_a, encode_png(1100, 600, png::ColorType::Grayscale, png::BitDepth::Eight, &g)).unwrap();
        (cartesium.display().to_string(), lab_a.display().to_string())
    })
}

fn cartesium() -> &'static str {
    &fixtures().0
}

fn lab_a() -> &'static str {
    &fixtures().1
}

fn encode_png(w: u32, h: u32, color: png::ColorType, depth: png::BitDepth, samples: &[u16]) -> Vec<u8> {
    let mut out = Vec::new();
    let mut enc = png::Encoder::new(&mut out, w, h);
    enc.set_color(color);
    enc.set_depth(depth);
    let data: Vec<u8> = match depth {
        png::BitDepth::Sixteen => samples.iter().flat_map(|s| s.to_be_bytes()).collect(),
        _ => samples.iter().map(|&s| s as u8).collect(),
    };
    enc.write_header().unwrap().write_image_data(&data).unwrap();
    out
}

/// A fresh, empty folder for one test.
fn temp_dir(test: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("ksmcmc-cli-render-{}-{test}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("create temp dir");
    dir
}

fn ksmcmc(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_ksmcmc")).args(args).output().expect("run ksmcmc")
}

fn text(out: &Output) -> String {
    format!("{}{}", String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr))
}

/// Runs `ksmcmc render ARGS`, expects exit code `code` and a message containing `needle`.
fn fails(args: &[&str], code: i32, needle: &str) -> String {
    let mut all = vec!["render"];
    all.extend_from_slice(args);
    let out = ksmcmc(&all);
    let msg = text(&out);
    assert_eq!(out.status.code(), Some(code), "ksmcmc {all:?} said:\n{msg}");
    assert!(msg.contains(needle), "ksmcmc {all:?}: expected {needle:?} in:\n{msg}");
    assert!(!msg.contains("panicked") && !msg.contains("internal error"), "ksmcmc {all:?} panicked:\n{msg}");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.starts_with("ksmcmc: "), "the message goes to stderr: {msg}");
    msg
}

fn s(p: &Path) -> &str {
    p.to_str().expect("temp paths are UTF-8")
}

/// The width and height a PNG's header declares.
fn png_size(bytes: &[u8]) -> (u32, u32) {
    assert!(bytes.starts_with(b"\x89PNG\r\n\x1a\n"), "not a PNG");
    let be = |i: usize| u32::from_be_bytes([bytes[i], bytes[i + 1], bytes[i + 2], bytes[i + 3]]);
    (be(16), be(20))
}

/// A world.json for a map of the given size, with one unit of the given geometry.
fn world_json(angle: f64, world: [u32; 2], map: [u32; 2], unit: [i32; 4]) -> String {
    format!(
        r#"{{"format": "ksmcmc-world/1",
            "frame": {{"angle": {angle:?}, "world_size": [{}, {}], "map_size": [{}, {}]}},
            "units": [{{"id": 1, "x": {}, "y": {}, "w": {}, "h": {}, "type": "room"}}]}}"#,
        world[0], world[1], map[0], map[1], unit[0], unit[1], unit[2], unit[3]
    )
}

fn renders_at_its_size(map_path: &str, name: &str) {
    let dir = temp_dir(name);
    let out = dir.join("sub/out.png");
    let run = ksmcmc(&["render", map_path, "--out", s(&out)]);
    assert!(run.status.success(), "{}", text(&run));
    let png = std::fs::read(&out).expect("the PNG was written, folders created");
    let map = ksmcmc::grid::OccupancyMap::load(Path::new(map_path), &Default::default()).expect("map");
    assert_eq!(png_size(&png), (map.width() as u32, map.height() as u32));
    // The picture is the classified map.
    let back = tiny_skia::Pixmap::decode_png(&png).expect("decodes");
    assert_eq!(back.data(), ksmcmc::render::draw_map(map.classified()).data());
}

#[test]
fn renders_a_map_at_its_size() {
    renders_at_its_size(lab_a(), "fixture");
}

#[test]
fn renders_a_dataset_map_at_its_size() {
    let Some(datasets) = crate::common::datasets("renders_a_dataset_map_at_its_size") else { return };
    renders_at_its_size(s(&datasets.join("bormann2016/lab_a_scan.png")), "dataset");
}

#[test]
fn renders_a_world_at_a_scale() {
    let dir = temp_dir("world");
    let world = dir.join("world.json");
    // The Cartesium map is 1237x672 and leans by about 20 degrees.
    std::fs::write(&world, world_json(0.35, [1400, 900], [1237, 672], [400, 300, 200, 120])).expect("write");
    let out = dir.join("out.png");
    let run = ksmcmc(&["render", cartesium(), "--world", s(&world), "--out", s(&out), "--scale", "2"]);
    assert!(run.status.success(), "{}", text(&run));
    let png = std::fs::read(&out).expect("written");
    assert_eq!(png_size(&png), (2474, 1344));
    let pixmap = tiny_skia::Pixmap::decode_png(&png).expect("decodes");
    let blue = pixmap.pixels().iter().filter(|p| [p.red(), p.green(), p.blue()] == [0, 0, 255]).count();
    assert!(blue > 2000, "only {blue} wall pixels");

    // --no-labels and --no-legend each give a different picture, and the same arguments give
    // the same bytes.
    let plain = dir.join("plain.png");
    let bare = dir.join("bare.png");
    let again = dir.join("again.png");
    for (path, extra) in [(&plain, Some("--no-labels")), (&bare, Some("--no-legend")), (&again, None)] {
        let mut args = vec!["render", cartesium(), "--world", s(&world), "--out", s(path), "--scale", "2"];
        args.extend(extra);
        assert!(ksmcmc(&args).status.success());
    }
    assert_ne!(std::fs::read(&plain).expect("plain"), png);
    assert_ne!(std::fs::read(&bare).expect("bare"), png);
    assert_eq!(std::fs::read(&again).expect("again"), png);
}

#[test]
fn renders_a_map_yaml() {
    let dir = temp_dir("yaml");
    std::fs::copy(lab_a(), dir.join("lab.png")).expect("copy");
    let yaml = dir.join("map.yaml");
    std::fs::write(
        &yaml,
        "image: lab.png\nresolution: 0.05\norigin: [0.0, 0.0, 0.0]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n",
    )
    .expect("write");
    let out = dir.join("out.png");
    let run = ksmcmc(&["render", s(&yaml), "--out", s(&out), "--no-labels"]);
    assert!(run.status.success(), "{}", text(&run));
    let map = ksmcmc::grid::OccupancyMap::load(Path::new(lab_a()), &Default::default()).expect("map");
    assert_eq!(png_size(&std::fs::read(&out).expect("written")), (map.width() as u32, map.height() as u32));
}

#[test]
fn help_prints_usage() {
    let out = ksmcmc(&["render", "--help"]);
    assert!(out.status.success());
    let msg = text(&out);
    assert!(msg.contains("Usage: ksmcmc render MAP") && msg.contains("--scale N"), "{msg}");
}

#[test]
fn unreadable_maps_fail_with_a_reason() {
    let dir = temp_dir("bad-maps");
    let out = dir.join("out.png");
    let out = s(&out);
    let write = |name: &str, bytes: &[u8]| {
        let p = dir.join(name);
        std::fs::write(&p, bytes).expect("write");
        p
    };
    let real_png = std::fs::read(cartesium()).expect("fixture map");

    let missing = dir.join("no-such-map.pgm");
    fails(&[s(&missing), "--out", out], 1, "No such file");
    fails(&[s(&write("empty.pgm", b"")), "--out", out], 1, "data is empty");
    fails(&[s(&write("cut.png", &real_png[..100])), "--out", out], 1, "cannot decode PNG");
    fails(&[s(&write("cut.pgm", b"P5\n10 10\n255\n\x00\x01\x02")), "--out", out], 1, "truncated PGM");
    fails(&[s(&write("hello.pgm", b"hello")), "--out", out], 1, "not an occupancy map");
    fails(&[s(&write("zero.pgm", b"P5\n0 10\n255\n")), "--out", out], 1, "0x10");

    // An absurd header is refused from the header alone: quickly, without allocating 10 GB.
    let huge = write("huge.pgm", b"P5\n100000 100000\n255\n");
    fails(&[s(&huge), "--out", out], 1, "over the limit");

    let yaml = write("map.yaml", b"image: nowhere.pgm\nresolution: 0.05\norigin: [0, 0, 0]\n");
    fails(&[s(&yaml), "--out", out], 1, "does not exist");
    let latin1 = write("latin1.yaml", b"image: caf\xe9.pgm\nresolution: 0.05\n");
    fails(&[s(&latin1), "--out", out], 1, "not UTF-8");

    assert!(!Path::new(out).exists(), "no output is written for a bad map");
}

#[test]
fn worlds_that_do_not_fit_the_map_fail_with_a_reason() {
    let dir = temp_dir("bad-worlds");
    let out = dir.join("out.png");
    let out = s(&out);
    let write = |name: &str, text: &str| {
        let p = dir.join(name);
        std::fs::write(&p, text).expect("write");
        p
    };
    let render_with =
        |world: &Path, code: i32, needle: &str| fails(&[cartesium(), "--world", s(world), "--out", out], code, needle);

    render_with(&write("cut.json", r#"{"format": "ksmcmc-world/1", "frame": "#), 1, "world.json");
    render_with(&write("typo.json", r#"{"format": "ksmcmc-world/1", "frame": {}, "unitz": []}"#), 1, "world.json");
    let bytes = dir.join("latin1.json");
    std::fs::write(&bytes, b"{\"format\": \"caf\xe9\"}").expect("write");
    render_with(&bytes, 1, "not UTF-8");
    render_with(&dir.join("no-such-world.json"), 1, "No such file");

    // A unit hanging over the right edge of the 1237x672 map (and world).
    let msg = render_with(
        &write("outside.json", &world_json(0.0, [1237, 672], [1237, 672], [1200, 10, 100, 20])),
        1,
        "unit 1",
    );
    assert!(msg.contains("outside"), "{msg}");
    // A larger world frame: the unit is inside the world but misses the map altogether.
    let msg = render_with(
        &write("offmap.json", &world_json(0.0, [3000, 2000], [1237, 672], [2800, 1800, 50, 50])),
        1,
        "unit 1",
    );
    assert!(msg.contains("entirely outside the 1237x672 map"), "{msg}");
    // A world made for another map.
    let msg = render_with(&write("other.json", &world_json(0.0, [100, 80], [100, 80], [10, 10, 20, 20])), 1, "100x80");
    assert!(msg.contains("1237x672") && msg.contains("different map"), "{msg}");

    assert!(!Path::new(out).exists(), "no output is written for a bad world");
}

#[test]
fn bad_command_lines_are_usage_errors() {
    let dir = temp_dir("usage");
    let out = dir.join("out.png");
    let out = s(&out);
    fails(&[cartesium(), "--out", out, "--scale", "0"], 2, "--scale: 0 is out of range");
    fails(&[cartesium(), "--out", out, "--scale", "999"], 2, "use 1 to 16");
    fails(&[cartesium(), "--out", out, "--scale", "abc"], 2, "--scale");
    fails(&[cartesium(), "--out", out, "--scale", "-3"], 2, "--scale");
    fails(&[cartesium(), "--out", out, "--scale"], 2, "--scale");
    fails(&[cartesium()], 2, "needs --out");
    fails(&["--out", out], 2, "needs a MAP");
    fails(&[cartesium(), "--out", out, "--frobnicate"], 2, "--frobnicate");
    fails(&[cartesium(), lab_a(), "--out", out], 2, "lab_a_scan.png");
    assert!(!Path::new(out).exists());
}

#[test]
fn outputs_over_the_pixel_limit_name_a_scale_that_fits() {
    let dir = temp_dir("too-large");
    let out = dir.join("out.png");
    // 1237x672 at 16 pixels per cell is 213 million pixels.
    fails(&[cartesium(), "--out", s(&out), "--scale", "16"], 1, "use a scale of at most 8");
    assert!(!out.exists());
}

#[test]
fn unwritable_output_fails() {
    let dir = temp_dir("unwritable");
    let blocker = dir.join("file");
    std::fs::write(&blocker, b"x").expect("write");
    // A folder cannot be created under a file.
    let out = blocker.join("out.png");
    fails(&[lab_a(), "--out", s(&out)], 1, s(&blocker));
}
