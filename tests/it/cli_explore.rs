//! `ksmcmc explore` end to end: the files it writes, what they say, and its errors.

use crate::common::run_cli as run;
use ksmcmc::floorplan::World;
use ksmcmc::grid::{Limits, OccupancyMap};
use std::path::{Path, PathBuf};

fn tmp(name: &str) -> PathBuf {
    crate::common::tmp_dir("cli-explore", name)
}

#[test]
fn explore_writes_the_world_timeline_and_report() {
    let d = tmp("office");
    let map = Path::new(env!("CARGO_MANIFEST_DIR")).join("samples/office-small/map.yaml");
    let args = ["explore", map.to_str().unwrap(), "--out", d.to_str().unwrap(), "--iterations", "1000"];
    let out = run(&[&args[..], &["--update-every", "4", "--range", "4"]].concat());
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(d.join("report.json")).unwrap()).unwrap();
    let timeline: Vec<serde_json::Value> =
        serde_json::from_str(&std::fs::read_to_string(d.join("timeline.json")).unwrap()).unwrap();
    let updates = report["updates"].as_u64().unwrap();
    assert!(updates >= 3, "{report}");
    assert_eq!(timeline.len() as u64, updates);
    // The summed iterations are the timeline's, and each is within the budget.
    let sum = |key: &str| timeline.iter().map(|r| r[key].as_u64().unwrap()).sum::<u64>();
    assert_eq!(report["warm_iterations"].as_u64().unwrap(), sum("warm_iterations"));
    assert_eq!(report["cold_iterations"].as_u64().unwrap(), sum("cold_iterations"));
    assert!(timeline.iter().all(|r| r["warm_iterations"].as_u64().unwrap() <= 1000));
    // The robot drove on, and the updates are in order.
    let metres: Vec<f64> = timeline.iter().map(|r| r["travelled_m"].as_f64().unwrap()).collect();
    assert!(metres.windows(2).all(|w| w[0] <= w[1]), "{metres:?}");
    let k = report["cell_prediction_rate"].as_f64().unwrap();
    assert!(k > 0.8 && k <= 1.0, "{k}");
    // world.json is a world of the map, and labels.pgm is its size.
    let truth = OccupancyMap::load(&map, &Limits::default()).unwrap();
    let world = World::from_json(&std::fs::read_to_string(d.join("world.json")).unwrap()).unwrap();
    world.fits(truth.width(), truth.height()).unwrap();
    assert!(!world.units.is_empty() && !world.rooms.is_empty());
    let labels = ksmcmc::grid::decode_image(&std::fs::read(d.join("labels.pgm")).unwrap(), &Limits::default()).unwrap();
    assert_eq!((labels.width(), labels.height()), (truth.width(), truth.height()));
    // Same seed, same files.
    let d2 = tmp("office-again");
    let mut again = args.to_vec();
    again[3] = d2.to_str().unwrap();
    assert!(run(&[&again[..], &["--update-every", "4", "--range", "4"]].concat()).status.success());
    for f in ["world.json", "timeline.json"] {
        assert_eq!(std::fs::read(d.join(f)).unwrap(), std::fs::read(d2.join(f)).unwrap(), "{f}");
    }
}

#[test]
fn a_goal_is_looked_for_by_both_policies() {
    let d = tmp("goal");
    let map = Path::new(env!("CARGO_MANIFEST_DIR")).join("samples/office-small/map.yaml");
    let args = ["explore", map.to_str().unwrap(), "--out", d.to_str().unwrap(), "--iterations", "1000"];
    let out = run(&[&args[..], &["--update-every", "4", "--range", "4", "--goal", "new-room", "--no-cold"]].concat());
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(d.join("report.json")).unwrap()).unwrap();
    let goal = &report["goal"];
    assert_eq!(goal["goal"], "new-room", "{report}");
    for (key, name) in [("expected_value", "expected value"), ("nearest_frontier", "nearest frontier")] {
        let p = &goal[key];
        assert_eq!(p["policy"], name);
        assert!(p["travelled_m"].as_f64().unwrap() > 0.0 && p["goals"].as_u64().unwrap() >= 1, "{p}");
        // Found, the robot stopped there: it drove no farther than where it found it.
        if let Some(m) = p["found_at_m"].as_f64() {
            assert!((m - p["travelled_m"].as_f64().unwrap()).abs() < 1e-9, "{p}");
        }
    }
    assert_eq!(goal["expected_value"]["travelled_m"], report["travelled_m"]);
}

#[test]
fn explore_errors_say_what_is_wrong() {
    let d = tmp("errors");
    let map = Path::new(env!("CARGO_MANIFEST_DIR")).join("samples/office-small/map.yaml");
    let (m, o) = (map.to_str().unwrap(), d.to_str().unwrap());
    for (args, code, says) in [
        (vec!["explore", m, "--out", o, "--start", "0,0"], 1, "not a free cell"),
        (vec!["explore", m, "--out", o, "--start", "nine"], 2, "--start must be X,Y"),
        (vec!["explore", m, "--out", o, "--range", "0"], 2, "range_m"),
        (vec!["explore", m, "--out", o, "--update-every", "-3"], 2, "update_every_m"),
        (vec!["explore", m, "--out", o, "--goal", "kitchen"], 2, "unknown goal \"kitchen\""),
        (vec!["explore", m], 2, "--out DIR"),
        (vec!["explore", "/nonexistent.pgm", "--out", o], 1, "nonexistent"),
    ] {
        let out = run(&args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(code), "{args:?}: {err}");
        assert!(err.contains(says), "{args:?}: {err}");
    }
}
