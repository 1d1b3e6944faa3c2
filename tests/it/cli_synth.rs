//! `ksmcmc synth` end to end: files, formats, determinism, errors, and the shipped samples.

use ksmcmc::floorplan::World;
use ksmcmc::grid::OccupancyMap;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

const FILES: [&str; 4] = ["map.pgm", "map.yaml", "truth.json", "truth_labels.pgm"];

fn ksmcmc(args: &[&str]) -> Output {
    let out = Command::new(env!("CARGO_BIN_EXE_ksmcmc")).args(args).output().expect("run ksmcmc");
    let text = format!("{}{}", String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
    assert!(!text.contains("panicked"), "ksmcmc {args:?} panicked: {text}");
    out
}

/// A fresh folder for one test.
fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("cli_synth").join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn read(dir: &Path, file: &str) -> Vec<u8> {
    std::fs::read(dir.join(file)).unwrap_or_else(|e| panic!("{}: {e}", dir.join(file).display()))
}

fn run_ok(args: &[&str]) -> String {
    let out = ksmcmc(args);
    assert!(out.status.success(), "ksmcmc {args:?} failed: {}", String::from_utf8_lossy(&out.stderr));
    String::from_utf8(out.stdout).unwrap()
}

#[test]
fn writes_four_consistent_files() {
    let dir = scratch("four");
    let d = dir.to_str().unwrap();
    let said = run_ok(&["synth", "--seed", "5", "--out", d, "--width", "320", "--height", "240", "--rotation", "15"]);
    assert!(said.contains("units"), "{said}");
    for f in FILES {
        assert!(dir.join(f).is_file(), "{f} missing");
    }
    let map = OccupancyMap::load(&dir.join("map.yaml"), &Default::default()).unwrap();
    let (w, h) = (map.width(), map.height());
    assert!(w > 320 && h > 240, "a rotated map grows: {w} x {h}");
    let pgm = read(&dir, "map.pgm");
    assert!(pgm.starts_with(format!("P5\n{w} {h}\n255\n").as_bytes()));
    let labels = read(&dir, "truth_labels.pgm");
    let head = format!("P5\n{w} {h}\n65535\n");
    assert!(labels.starts_with(head.as_bytes()));
    assert_eq!(labels.len(), head.len() + 2 * w * h);
    let truth = World::from_json(&String::from_utf8(read(&dir, "truth.json")).unwrap()).unwrap();
    assert_eq!(truth.frame.map_size, [w as u32, h as u32]);
    assert_eq!(truth.frame.world_size, [320, 240]);
    assert!((truth.frame.angle - 15f64.to_radians()).abs() < 1e-12);
    // The labels name units of the truth, and some cells of every explored unit.
    let max = labels[head.len()..].chunks(2).map(|b| u16::from_be_bytes([b[0], b[1]])).max().unwrap();
    assert_eq!(max as usize, truth.units.len());
    assert!(read(&dir, "map.yaml").starts_with(b"image: map.pgm\n"));
}

#[test]
fn same_seed_same_bytes() {
    let (a, b, c) = (scratch("same-a"), scratch("same-b"), scratch("same-c"));
    for (dir, seed) in [(&a, "77"), (&b, "77"), (&c, "78")] {
        run_ok(&["synth", "--seed", seed, "--out", dir.to_str().unwrap(), "--clutter", "0.1", "--unexplored", "0.3"]);
    }
    for f in FILES {
        assert_eq!(read(&a, f), read(&b, f), "{f} differs between runs");
    }
    assert_ne!(read(&a, "map.pgm"), read(&c, "map.pgm"));
}

#[test]
fn config_file_and_overrides() {
    let dir = scratch("config");
    let config = dir.join("config.json");
    std::fs::write(&config, r#"{ "width": 500, "height": 260, "halls": 1, "resolution": 0.04 }"#).unwrap();
    let out = dir.join("out");
    let (c, o) = (config.to_str().unwrap(), out.to_str().unwrap());
    run_ok(&["synth", "--seed", "1", "--config", c, "--height", "280", "--out", o]);
    let map = OccupancyMap::load(&out.join("map.yaml"), &Default::default()).unwrap();
    assert_eq!((map.width(), map.height()), (500, 280));
    assert_eq!(map.yaml().resolution, 0.04);
    let truth = World::from_json(&String::from_utf8(read(&out, "truth.json")).unwrap()).unwrap();
    assert_eq!(truth.units.iter().filter(|u| u.kind == ksmcmc::floorplan::UnitType::Hall).count(), 1);
    // --print-config shows the merged config.
    let shown = run_ok(&["synth", "--config", c, "--rotation", "20", "--print-config"]);
    let merged = ksmcmc::floorplan::synth::SynthConfig::from_json(&shown).unwrap();
    assert_eq!((merged.width, merged.rotation_deg, merged.halls), (500, 20.0, 1));
}

#[test]
fn bad_arguments_and_configs_fail_cleanly() {
    let dir = scratch("bad");
    let d = dir.join("out");
    let d = d.to_str().unwrap();
    let bad_json = dir.join("bad.json");
    std::fs::write(&bad_json, "{ \"width\": ").unwrap();
    let typo = dir.join("typo.json");
    std::fs::write(&typo, r#"{ "wall_thicknes": 3 }"#).unwrap();
    let array = dir.join("array.json");
    std::fs::write(&array, "[1, 2]").unwrap();
    let (bad_json, typo, array) = (bad_json.to_str().unwrap(), typo.to_str().unwrap(), array.to_str().unwrap());
    // The wasm `synth` reads configs through the same function and so says the same.
    let not_object = ksmcmc::floorplan::synth::SynthConfig::from_json("[1, 2]").unwrap_err().to_string();
    let cases: &[(&[&str], i32, &str)] = &[
        (&["synth", "--seed", "x", "--out", d], 2, "--seed"),
        (&["synth", "--seed", "-3", "--out", d], 2, "--seed"),
        (&["synth", "--out", d], 2, "--seed"),
        (&["synth", "--seed", "1"], 2, "--out"),
        (&["synth", "--seed", "1", "--out", d, "--frobnicate"], 2, "frobnicate"),
        (&["synth", "--seed", "1", "--out", d, "--width"], 2, "--width"),
        (&["synth", "--seed", "1", "--out", d, "--rotation", "abc"], 2, "--rotation"),
        (&["synth", "--seed", "1", "--out", d, "--width", "0"], 1, "width"),
        (&["synth", "--seed", "1", "--out", d, "--rotation", "NaN"], 1, "rotation_deg"),
        (&["synth", "--seed", "1", "--out", d, "--wall-thickness", "40"], 1, "wall_thickness"),
        (&["synth", "--seed", "1", "--out", d, "--clutter", "-1"], 1, "clutter"),
        (&["synth", "--seed", "1", "--out", d, "--width", "100000", "--height", "100000"], 1, "width"),
        (&["synth", "--seed", "1", "--out", d, "--config", bad_json], 1, "bad.json"),
        (&["synth", "--seed", "1", "--out", d, "--config", typo], 1, "wall_thicknes"),
        (&["synth", "--seed", "1", "--out", d, "--config", array], 1, &not_object),
        (&["synth", "--seed", "1", "--out", d, "--config", "/nonexistent/c.json"], 1, "c.json"),
    ];
    for (args, code, needle) in cases {
        let out = ksmcmc(args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(*code), "ksmcmc {args:?}: {err}");
        assert!(err.contains(needle), "ksmcmc {args:?} does not mention {needle}: {err}");
    }
    assert!(!Path::new(d).join("map.pgm").exists(), "a failed run wrote files");
    // Writing into a path that is a file fails with exit 1.
    let file = dir.join("file");
    std::fs::write(&file, "x").unwrap();
    let out = ksmcmc(&["synth", "--seed", "1", "--out", file.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1));
}

#[test]
fn help_lists_the_options() {
    let said = run_ok(&["synth", "--help"]);
    for opt in ["--seed", "--out", "--config", "--rotation", "--clutter", "--unexplored", "truth_labels.pgm"] {
        assert!(said.contains(opt), "help lacks {opt}");
    }
}

/// Every command in samples/README.md reproduces its sample byte for byte.
#[test]
fn samples_reproduce_byte_for_byte() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let readme = std::fs::read_to_string(root.join("samples/README.md")).unwrap();
    let commands: Vec<&str> = readme.lines().filter(|l| l.starts_with("ksmcmc synth ")).collect();
    assert!(commands.len() >= 4, "samples/README.md lists {} commands", commands.len());
    for line in commands {
        let args: Vec<&str> = line.split_whitespace().skip(1).collect();
        let at = args.iter().position(|a| *a == "--out").expect("--out") + 1;
        let sample = root.join(args[at]);
        let dir = scratch(&format!("sample-{}", sample.file_name().unwrap().to_string_lossy()));
        let mut args = args.clone();
        let d = dir.to_str().unwrap().to_string();
        args[at] = &d;
        run_ok(&args);
        for f in FILES {
            assert!(read(&sample, f) == read(&dir, f), "{}/{f} does not match `{line}`", sample.display());
        }
    }
}
