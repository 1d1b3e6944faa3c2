//! Hostile input (issue 16): the caps on what readers accept, and a replay of every input the
//! fuzzers keep (`fuzz/regressions/TARGET/`, crashes found and fixed; `fuzz/seeds/TARGET/`)
//! through the fuzz targets' own bodies, so that stable `cargo test` covers them without
//! nightly or libFuzzer.

#[path = "../../fuzz/src/harness.rs"]
#[allow(dead_code)]
mod harness;

use ksmcmc::floorplan::world::{MAX_UNITS, MAX_WORLD_CELLS};
use ksmcmc::floorplan::{metrics, Unit, World};
use std::path::Path;

/// Runs every file under `fuzz/<dir>/<target>/` through its target; returns how many ran.
fn replay(dir: &str) -> usize {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("fuzz").join(dir);
    let mut ran = 0;
    for (name, body) in harness::TARGETS {
        let Ok(entries) = std::fs::read_dir(root.join(name)) else { continue };
        let mut paths: Vec<_> = entries.map(|e| e.unwrap().path()).collect();
        paths.sort();
        for path in paths {
            let data = std::fs::read(&path).unwrap();
            let outcome = std::panic::catch_unwind(|| body(&data));
            assert!(outcome.is_ok(), "fuzz target {name} panics on {}", path.display());
            ran += 1;
        }
    }
    ran
}

#[test]
fn fuzz_regressions_replay_without_panics() {
    replay("regressions");
}

#[test]
fn fuzz_seeds_replay_without_panics() {
    assert!(replay("seeds") >= harness::TARGETS.len(), "every target has seeds");
}

/// The issue's case: a million units is refused while parsing, with a message naming the cap,
/// before the list is held in memory.
#[test]
fn a_million_unit_world_is_refused_with_the_cap_named() {
    let mut text = String::from(
        r#"{"format":"ksmcmc-world/1","frame":{"angle":0.0,"world_size":[10,10],"map_size":[10,10]},"units":["#,
    );
    for id in 1..=1_000_000 {
        if id > 1 {
            text.push(',');
        }
        text.push_str(&format!(r#"{{"id":{id},"x":0,"y":0,"w":3,"h":3}}"#));
    }
    text.push_str("]}");
    let err = World::from_json(&text).unwrap_err().to_string();
    assert!(err.contains(&format!("too many units: over the cap of {MAX_UNITS}")), "{err}");
    // A world built in code is held to the same cap by validate().
    let mut w = World::empty(10, 10);
    w.units = (1..=MAX_UNITS as u32 + 1).map(|id| Unit::new(id, 0, 0, 3, 3, Default::default())).collect();
    assert!(w.validate().unwrap_err().to_string().contains("over the limit of 10000 units"));
}

#[test]
fn oversized_texts_are_refused_before_parsing() {
    let big = " ".repeat(ksmcmc::floorplan::world::MAX_WORLD_JSON_BYTES + 1);
    assert!(World::from_json(&big).unwrap_err().to_string().contains("MAX_WORLD_JSON_BYTES"));
    let yaml = "#".repeat(ksmcmc::grid::MAX_YAML_BYTES + 1);
    assert!(ksmcmc::grid::MapYaml::parse(&yaml).unwrap_err().to_string().contains("MAX_YAML_BYTES"));
    let kb = " ".repeat(ksmcmc::mln::MAX_KB_BYTES + 1);
    assert!(ksmcmc::mln::Mln::parse(&kb).unwrap_err().to_string().contains("MAX_KB_BYTES"));
    let scene = " ".repeat(ksmcmc::tabletop::scene::MAX_SCENE_JSON_BYTES + 1);
    assert!(ksmcmc::tabletop::scene::Scene::from_json(&scene).unwrap_err().to_string().contains("bytes"));
    let config = " ".repeat(ksmcmc::floorplan::chain::MAX_CONFIG_JSON_BYTES + 1);
    assert!(ksmcmc::floorplan::ChainConfig::from_json(&config).unwrap_err().to_string().contains("MAX_CONFIG"));
    assert!(ksmcmc::floorplan::synth::SynthConfig::from_json(&config).unwrap_err().to_string().contains("MAX_CONFIG"));
}

/// `frame.world_size` is checked against the map it claims (and an absolute cap) before
/// anything is sized by it.
#[test]
fn a_world_frame_larger_than_its_map_is_refused() {
    let mut w = World::empty(10, 10);
    w.frame.world_size = [60_000, 60_000];
    let err = w.validate().unwrap_err().to_string();
    assert!(err.contains("over the limit of") && err.contains("MAX_WORLD_CELLS"), "{err}");
    w.frame.world_size = [49, 10];
    let err = w.validate().unwrap_err().to_string();
    assert!(err.contains("far larger than the 10x10 map"), "{err}");
    w.frame.world_size = [48, 48];
    assert!(w.validate().is_ok(), "up to WORLD_FRAME_SLACK times (10 + 2) a side is allowed");
    const { assert!(60_000u64 * 60_000 > MAX_WORLD_CELLS) };
}

/// predicted_map sizes its raster by the map, not by a world frame built in code without
/// validation: a 10x10 map with a 4e9-cell world frame takes a few bytes.
#[test]
fn predicted_map_allocates_by_the_map_not_the_world_frame() {
    let mut w = World::empty(10, 10);
    w.frame.world_size = [u32::MAX, u32::MAX];
    w.frame.angle = 0.25;
    w.units.push(Unit::new(1, 0, 0, 1 << 20, 1 << 20, Default::default()));
    let p = metrics::predicted_map(10, 10, &w);
    assert_eq!((p.width(), p.height()), (10, 10));
}

/// A world of the most units, each at its own angle, with the most doors: validated, drawn and
/// scored frame by frame in one pass over each list (not once per frame), and a unit whose
/// angle is no number is drawn in no frame instead of stalling or panicking.
#[test]
fn units_at_ten_thousand_angles_are_grouped_not_searched() {
    use ksmcmc::floorplan::world::{MAX_DOORS, MAX_UNITS};
    use ksmcmc::floorplan::Door;
    use ksmcmc::grid::{Cell, Grid};
    let mut w = World::empty(200, 150);
    w.units = (1..=MAX_UNITS as u32)
        .map(|id| Unit { angle: Some(id as f64 * 1e-4), ..Unit::new(id, 60, 50, 40, 30, Default::default()) })
        .collect();
    w.doors = (1..=MAX_DOORS as u32)
        .map(|id| {
            let u = 1 + (id - 1) % MAX_UNITS as u32;
            Door { id, units: [u, u], x0: 70, y0: 50, x1: 75, y1: 50, opening: false }
        })
        .collect();
    w.validate().unwrap();
    let groups = w.frame_groups();
    assert_eq!(groups.len(), MAX_UNITS + 1, "the world frame and one per angle");
    assert_eq!(groups.iter().map(|g| g.doors.len()).sum::<usize>(), MAX_DOORS);
    let map = Grid::new(200, 150, Cell::Free);
    let k = ksmcmc::floorplan::metrics::prediction_rate(&map, &w);
    assert!((0.0..=1.0).contains(&k), "{k}");
    let picture = ksmcmc::render::render(&map, Some(&w), &Default::default());
    assert_eq!((picture.width(), picture.height()), (200, 150));
    w.units[0].angle = Some(f64::NAN);
    assert!(w.validate().is_err());
    assert_eq!(w.frame_groups().iter().map(|g| g.units.len()).sum::<usize>(), MAX_UNITS - 1);
    let _ = ksmcmc::render::render(&map, Some(&w), &Default::default());
}
