//! `ksmcmc floorplan` and `ksmcmc score` end to end: outputs, determinism, bad input.

use crate::common::run_cli as run;
use ksmcmc::floorplan::World;
use ksmcmc::grid::{Limits, OccupancyMap};
use std::path::{Path, PathBuf};

fn tmp(name: &str) -> PathBuf {
    crate::common::tmp_dir("cli-fp", name)
}

fn sample(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("samples").join(name)
}

#[test]
fn floorplan_writes_every_output_and_scores_its_labels() {
    let d = tmp("outputs");
    let map = sample("office-small/map.yaml");
    let out = run(&["floorplan", map.to_str().unwrap(), "--out", d.to_str().unwrap(), "--iterations", "6000"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let m = OccupancyMap::load(&map, &Limits::default()).unwrap();
    let world = World::from_json(&std::fs::read_to_string(d.join("world.json")).unwrap()).unwrap();
    assert!(world.units.len() >= 5, "{} units", world.units.len());
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(d.join("report.json")).unwrap()).unwrap();
    for key in [
        "iterations",
        "seconds",
        "iterations_per_second",
        "cell_prediction_rate",
        "units",
        "doors",
        "rooms",
        "log_posterior",
        "seed",
    ] {
        assert!(report.get(key).is_some(), "report.json lacks {key}");
    }
    assert_eq!(report["iterations"], 6000);
    assert_eq!(report["unexplained_areas"].as_u64(), Some(world.unexplained.len() as u64));
    let n_cells: u64 = world.unexplained.iter().map(|a| a.cells as u64).sum();
    assert_eq!(report["unexplained_cells"].as_u64(), Some(n_cells));
    assert!(report["cell_prediction_rate"].as_f64().unwrap() > 0.9);
    // labels.pgm: 16-bit, map-sized, rooms numbered 1..=n.
    let labels = std::fs::read(d.join("labels.pgm")).unwrap();
    let header = format!("P5\n{} {}\n65535\n", m.width(), m.height());
    assert!(labels.starts_with(header.as_bytes()));
    let ids: Vec<u16> = labels[header.len()..].chunks(2).map(|c| u16::from_be_bytes([c[0], c[1]])).collect();
    assert_eq!(ids.len(), m.width() * m.height());
    let n = report["rooms"].as_u64().unwrap() as u16;
    assert_eq!(*ids.iter().max().unwrap(), n);
    // A label on a non-free cell is clutter the room encloses (RoomConfig::clutter_in_rooms):
    // every cell around it carries the same label, so no wall and no other room is beside it.
    let (w, h) = (m.width(), m.height());
    for (i, &id) in ids.iter().enumerate() {
        if id != 0 && m.classified().cells()[i] != ksmcmc::grid::Cell::Free {
            let (x, y) = (i % w, i / w);
            for ny in y.saturating_sub(1)..=(y + 1).min(h - 1) {
                for nx in x.saturating_sub(1)..=(x + 1).min(w - 1) {
                    assert_eq!(
                        ids[ny * w + nx],
                        id,
                        "label {id} on a non-free cell ({x}, {y}) not enclosed by its room"
                    );
                }
            }
        }
    }
    let trace = std::fs::read_to_string(d.join("trace.csv")).unwrap();
    assert!(trace.starts_with("iteration,log_posterior,acceptance,units\n") && trace.lines().count() > 10);
    let overlay = OccupancyMap::from_bytes(&std::fs::read(d.join("overlay.png")).unwrap()).unwrap();
    assert_eq!((overlay.width(), overlay.height()), (m.width(), m.height()));
    let graph: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(d.join("graph.json")).unwrap()).unwrap();
    assert_eq!(graph["nodes"].as_array().unwrap().len(), world.units.len());
    // The vector exports: a unit feature per room, an opening per door, a shape per room.
    let geojson: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(d.join("world.geojson")).unwrap()).unwrap();
    let count = |t: &str| geojson["features"].as_array().unwrap().iter().filter(|f| f["feature_type"] == t).count();
    assert_eq!((count("level"), count("unit"), count("opening")), (1, world.rooms.len(), world.doors.len()));
    let svg = std::fs::read_to_string(d.join("world.svg")).unwrap();
    assert!(svg.starts_with("<?xml") && svg.ends_with("</svg>\n"));
    assert_eq!(svg.matches("<path data-room=").count(), world.rooms.len());
    // Scored against the generator's truth, the segmentation is good.
    let truth = sample("office-small/truth_labels.pgm");
    let out =
        run(&["score", d.join("labels.pgm").to_str().unwrap(), truth.to_str().unwrap(), "--truth", "labels", "--json"]);
    assert!(out.status.success());
    let s: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert!(s["precision"].as_f64().unwrap() > 0.9 && s["recall"].as_f64().unwrap() > 0.85, "{s}");
}

#[test]
fn same_seed_same_world() {
    let map = sample("office-rotated/map.yaml");
    let worlds: Vec<String> = (0..2)
        .map(|i| {
            let d = tmp(&format!("seed{i}"));
            let out = run(&[
                "floorplan",
                map.to_str().unwrap(),
                "--out",
                d.to_str().unwrap(),
                "--iterations",
                "3000",
                "--seed",
                "9",
            ]);
            assert!(out.status.success());
            std::fs::read_to_string(d.join("world.json")).unwrap()
        })
        .collect();
    assert_eq!(worlds[0], worlds[1]);
    let w = World::from_json(&worlds[0]).unwrap();
    assert!((w.frame.angle.to_degrees().abs() - 20.0).abs() < 1.0, "rotation {}", w.frame.angle.to_degrees());
}

#[test]
fn bad_input_is_a_clear_error() {
    let d = tmp("bad");
    let out_dir = d.join("out");
    let o = out_dir.to_str().unwrap();
    std::fs::write(
        d.join("walls.pgm"),
        b"P2 20 20 255\n".iter().chain(b"0 ".repeat(400).iter()).copied().collect::<Vec<u8>>(),
    )
    .unwrap();
    std::fs::write(d.join("one.pgm"), b"P2 1 1 255 255").unwrap();
    std::fs::write(d.join("huge.pgm"), b"P5 100000 100000 255\n").unwrap();
    std::fs::write(d.join("nan.json"), br#"{"posterior": {"temperature": -1}}"#).unwrap();
    std::fs::write(d.join("broken.json"), b"{ not json").unwrap();
    let map = sample("office-small/map.yaml");
    let m = map.to_str().unwrap();
    let p = |f: &str| d.join(f).to_str().unwrap().to_string();
    let cases: Vec<(Vec<String>, i32, &str)> = vec![
        (vec!["floorplan".into(), p("walls.pgm"), "--out".into(), o.into()], 1, "no free cells"),
        (vec!["floorplan".into(), p("one.pgm"), "--out".into(), o.into()], 1, "1x1"),
        (vec!["floorplan".into(), p("huge.pgm"), "--out".into(), o.into()], 1, "over the limit"),
        (
            vec!["floorplan".into(), m.into(), "--out".into(), o.into(), "--config".into(), p("nan.json")],
            1,
            "temperature",
        ),
        (
            vec!["floorplan".into(), m.into(), "--out".into(), o.into(), "--config".into(), p("broken.json")],
            1,
            "broken.json",
        ),
        (
            vec!["floorplan".into(), m.into(), "--out".into(), o.into(), "--time-limit".into(), "-3".into()],
            2,
            "time-limit",
        ),
        (
            vec!["floorplan".into(), m.into(), "--out".into(), o.into(), "--iterations".into(), "many".into()],
            2,
            "iterations",
        ),
        (vec!["floorplan".into(), m.into()], 2, "--out"),
        (
            vec!["floorplan".into(), m.into(), "--out".into(), o.into(), "--classify".into(), "magic".into()],
            2,
            "classify",
        ),
        (
            vec!["floorplan".into(), m.into(), "--out".into(), o.into(), "--georef".into(), "53.1,8.8".into()],
            2,
            "is not three numbers separated by commas; a georeference is LAT,LON,BEARING",
        ),
        (
            vec!["floorplan".into(), m.into(), "--out".into(), o.into(), "--georef".into(), "53.1,188,0".into()],
            2,
            "longitude 188 is not between -180 and 180",
        ),
        (vec!["score".into(), p("one.pgm")], 2, "TRUTH"),
        (
            vec!["score".into(), p("one.pgm"), sample("office-small/truth_labels.pgm").to_str().unwrap().into()],
            1,
            "same map",
        ),
        (vec!["score".into(), p("missing.pgm"), p("one.pgm")], 1, "missing.pgm"),
    ];
    for (args, code, needle) in cases {
        let out = run(&args.iter().map(String::as_str).collect::<Vec<_>>());
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(code), "{args:?}: {err}");
        assert!(err.contains(needle), "{args:?}: {err}");
    }
}

#[test]
fn region_of_interest_scores_only_its_cells() {
    let d = tmp("region");
    let map = sample("office-small/map.yaml");
    let m = OccupancyMap::load(&map, &Limits::default()).unwrap();
    // The region: the left half of the map.
    let (w, h) = (m.width(), m.height());
    let samples: Vec<u8> = (0..w * h).map(|i| if i % w < w / 2 { 255 } else { 0 }).collect();
    std::fs::write(d.join("roi.pgm"), ksmcmc::grid::pgm::encode_u8(w, h, &samples)).unwrap();
    let o = d.join("out");
    let out = run(&[
        "floorplan",
        map.to_str().unwrap(),
        "--out",
        o.to_str().unwrap(),
        "--iterations",
        "3000",
        "--region",
        d.join("roi.pgm").to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(o.join("report.json")).unwrap()).unwrap();
    let world = World::from_json(&std::fs::read_to_string(o.join("world.json")).unwrap()).unwrap();
    let mask = ksmcmc::grid::Grid::from_vec(w, h, samples.iter().map(|&s| s > 0).collect()).unwrap();
    let expected = ksmcmc::floorplan::metrics::prediction_rate_in(m.classified(), &world, Some(&mask));
    // serde_json's default float parser may be one ulp off.
    assert!((report["cell_prediction_rate_region"].as_f64().unwrap() - expected).abs() < 1e-12);
    assert!(
        (report["cell_prediction_rate"].as_f64().unwrap() - expected).abs() > 1e-6,
        "the region differs from the map"
    );
    // A region of another size is refused.
    std::fs::write(d.join("small.pgm"), ksmcmc::grid::pgm::encode_u8(3, 3, &[255; 9])).unwrap();
    let out = run(&[
        "floorplan",
        map.to_str().unwrap(),
        "--out",
        o.to_str().unwrap(),
        "--region",
        d.join("small.pgm").to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("the region is 3x3"));
}

#[test]
fn knowledge_modes() {
    let d = tmp("knowledge");
    let map = sample("office-small/map.yaml");
    for mode in ["builtin", "none"] {
        let o = d.join(mode);
        let out = run(&[
            "floorplan",
            map.to_str().unwrap(),
            "--out",
            o.to_str().unwrap(),
            "--iterations",
            "4000",
            "--knowledge",
            mode,
        ]);
        assert!(out.status.success(), "{mode}: {}", String::from_utf8_lossy(&out.stderr));
        let report: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(o.join("report.json")).unwrap()).unwrap();
        assert_eq!(report["knowledge"], mode == "builtin");
        // Both modes type the final world; the weak mode only at the end.
        let types = report["types"].as_object().unwrap();
        assert!(types.keys().any(|k| k != "unknown"), "{mode}: {types:?}");
        assert!(report.get("defects").is_some());
    }
    std::fs::write(d.join("bad.mln"), "Room(unit)\nRoom(x) =>\n").unwrap();
    let out = run(&[
        "floorplan",
        map.to_str().unwrap(),
        "--out",
        d.join("x").to_str().unwrap(),
        "--knowledge",
        d.join("bad.mln").to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(1));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("bad.mln") && err.contains("line 2"), "{err}");
}

#[test]
fn evaluate_pairs_knowledge_with_the_weak_prior_and_refuses_unknown_sets() {
    let out = run(&["evaluate", "--only", "nonsense"]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("--only nonsense") && err.contains("paired"), "{err}");

    let out = run(&["evaluate", "--only", "paired", "--seeds", "2", "--iterations", "1500"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let text = String::from_utf8_lossy(&out.stdout);
    let rows: Vec<Vec<&str>> = text
        .lines()
        .filter(|l| l.starts_with("| ") && !l.starts_with("| kind"))
        .map(|l| l.split('|').map(str::trim).filter(|c| !c.is_empty()).collect())
        .collect();
    assert_eq!(rows.len(), 7, "one row per synthetic kind (two of them two-wing):\n{text}");
    for r in &rows {
        let k: f64 = r[1].parse().unwrap();
        let weak: f64 = r[2].parse().unwrap();
        let diff: f64 = r[3].split_whitespace().next().unwrap().parse().unwrap();
        assert!((0.5..=1.0).contains(&k) && (0.5..=1.0).contains(&weak), "{r:?}");
        // The difference is of the unrounded means: within the columns' rounding.
        assert!((diff - (k - weak)).abs() <= 1e-4 + 1e-9, "{r:?}");
        let (better, worse) = r[4].split_once(" / ").unwrap();
        assert!(better.parse::<u32>().unwrap() + worse.parse::<u32>().unwrap() <= 2, "{r:?}");
    }
}

#[test]
fn evaluate_counts_cartesiums_rooms_and_their_types_per_seed() {
    let Some(dir) = crate::common::datasets("evaluate_counts_cartesiums_rooms_and_their_types_per_seed") else {
        return;
    };
    let dir = dir.to_str().unwrap();
    let out = run(&["evaluate", "--datasets", dir, "--only", "cartesium", "--seeds", "2", "--iterations", "1500"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let text = String::from_utf8_lossy(&out.stdout);
    let rows: Vec<Vec<&str>> = text
        .lines()
        .skip_while(|l| !l.starts_with("| seed"))
        .filter(|l| l.starts_with("| ") && !l.starts_with("| seed"))
        .map(|l| l.split('|').map(str::trim).filter(|c| !c.is_empty()).collect())
        .collect();
    assert_eq!(rows.len(), 2, "one row per seed:\n{text}");
    for (seed, r) in rows.iter().enumerate() {
        assert_eq!(r[0], (seed + 1).to_string());
        let k: f64 = r[1].parse().unwrap();
        assert!((0.5..=1.0).contains(&k), "{r:?}");
        let n: usize = r[2].parse().unwrap();
        let types: Vec<usize> = r[3..8].iter().map(|c| c.parse().unwrap()).collect();
        assert!(n > 0 && types.iter().sum::<usize>() == n, "the types count every room: {r:?}");
        let share: f64 = r[8].parse().unwrap();
        assert!((share - types[3] as f64 / n as f64).abs() <= 0.005 + 1e-9, "{r:?}");
    }
}

#[test]
fn evaluate_reads_room_layer_settings_and_says_what_is_wrong_with_them() {
    let d = tmp("room-config");
    let missing = d.join("missing.json");
    let out = run(&["evaluate", "--only", "bormann", "--room-config", missing.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("missing.json"), "{err}");
    let bad = d.join("bad.json");
    std::fs::write(&bad, r#"{"max_wall_gap_m": 2.5, "max_wal_gap_m": 3}"#).unwrap();
    let out = run(&["evaluate", "--only", "bormann", "--also-room-config", bad.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("bad.json") && err.contains("room-layer settings") && err.contains("max_wal_gap_m"), "{err}");
    // Settings in cells, as older versions took them, are refused by name, not read as metres.
    std::fs::write(&bad, r#"{"max_wall_gap": 50}"#).unwrap();
    let out = run(&["evaluate", "--only", "bormann", "--room-config", bad.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("unknown field `max_wall_gap`"), "{err}");
    std::fs::write(&bad, r#"{"max_wall_share": 2}"#).unwrap();
    let out = run(&["evaluate", "--only", "bormann", "--room-config", bad.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("bad.json") && err.contains("max_wall_share is 2"), "{err}");
}

#[test]
fn edits_name_and_type_a_room_and_bad_edits_say_which() {
    let d = tmp("edits");
    let map = sample("office-small/map.yaml");
    let m = OccupancyMap::load(&map, &Limits::default()).unwrap();
    // The free cell nearest the map's centre: some room holds it after a short run.
    let (w, h) = (m.width() as i64, m.height() as i64);
    let free = |x: i64, y: i64| *m.classified().at(x as usize, y as usize) == ksmcmc::grid::Cell::Free;
    let (cx, cy) = (0..w * h)
        .map(|i| (i % w, i / w))
        .filter(|&(x, y)| free(x, y))
        .min_by_key(|&(x, y)| (x - w / 2).pow(2) + (y - h / 2).pow(2))
        .unwrap();
    let edits = d.join("edits.json");
    let text = format!(
        r#"[{{"op": "type", "at": [{cx}, {cy}], "type": "hall"}}, {{"op": "name", "at": [{cx}, {cy}], "name": "Atrium"}}]"#
    );
    std::fs::write(&edits, text).unwrap();
    let (m_s, d_s, e_s) = (map.to_str().unwrap(), d.to_str().unwrap(), edits.to_str().unwrap());
    let out = run(&["floorplan", m_s, "--out", d_s, "--iterations", "6000", "--edits", e_s]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let world = World::from_json(&std::fs::read_to_string(d.join("world.json")).unwrap()).unwrap();
    let named: Vec<_> = world.rooms.iter().filter(|r| r.name.as_deref() == Some("Atrium")).collect();
    assert_eq!(named.len(), 1, "one room is named");
    assert_eq!(named[0].kind, ksmcmc::floorplan::UnitType::Hall);

    std::fs::write(
        &edits,
        r#"[{"op": "name", "at": [1, 1], "name": "A"}, {"op": "split", "line": [[0, 0], [0, 99999]]}]"#,
    )
    .unwrap();
    let out = run(&["floorplan", m_s, "--out", d_s, "--iterations", "10", "--edits", e_s]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(err.contains("edit 2 (split): the point (0, 99999) is outside the"), "{err}");
    std::fs::write(&edits, r#"{"op": "name"}"#).unwrap();
    let err = String::from_utf8_lossy(&run(&["floorplan", m_s, "--out", d_s, "--edits", e_s]).stderr).to_string();
    assert!(err.contains("expected a list"), "{err}");
}

#[test]
fn floorplan_writes_the_3d_world_with_the_heights_asked_for() {
    let d = tmp("glb");
    let map = sample("office-small/map.yaml");
    let (m, o) = (map.to_str().unwrap(), d.to_str().unwrap());
    let out = run(&["floorplan", m, "--out", o, "--iterations", "2000", "--wall-height", "3", "--door-height", "2.1"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let glb = std::fs::read(d.join("world.glb")).unwrap();
    assert_eq!(&glb[..4], b"glTF");
    let json_len = u32::from_le_bytes(glb[12..16].try_into().unwrap()) as usize;
    let json: serde_json::Value = serde_json::from_slice(&glb[20..20 + json_len]).unwrap();
    let walls = json["nodes"].as_array().unwrap().iter().find(|n| n["name"] == "walls").unwrap();
    assert_eq!(
        (walls["extras"]["wall_height_m"].as_f64(), walls["extras"]["door_height_m"].as_f64()),
        (Some(3.0), Some(2.1))
    );
    // One slab node per room of world.json.
    let world = World::from_json(&std::fs::read_to_string(d.join("world.json")).unwrap()).unwrap();
    let slabs =
        json["nodes"].as_array().unwrap().iter().filter(|n| n["name"].as_str().unwrap().starts_with("room ")).count();
    assert_eq!(slabs, world.rooms.iter().filter(|r| !r.units.is_empty()).count());
    // Doors taller than walls are a usage error.
    let bad = run(&["floorplan", m, "--out", o, "--wall-height", "2", "--door-height", "2.5"]);
    assert_eq!(bad.status.code(), Some(2));
    assert!(
        String::from_utf8_lossy(&bad.stderr).contains("door height 2.5 m"),
        "{}",
        String::from_utf8_lossy(&bad.stderr)
    );
}

/// A map of two buildings at an angle is explained wing by wing by default (issue 13): units
/// at both angles, every file written, the report naming the wings; `--no-wings` keeps one
/// frame with the same labels.
#[test]
fn floorplan_explains_wings_at_an_angle_each_in_its_frame() {
    let d = tmp("wings");
    let synth = d.join("synth");
    let out = run(&["synth", "--seed", "5", "--wing", "30", "--out", synth.to_str().unwrap()]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let map = synth.join("map.yaml");
    let (wings, one) = (d.join("wings"), d.join("one"));
    for (dir, extra) in [(&wings, None), (&one, Some("--no-wings"))] {
        let mut args = vec!["floorplan", map.to_str().unwrap(), "--out", dir.to_str().unwrap(), "--iterations", "6000"];
        args.extend(extra);
        let out = run(&args);
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        for f in ["world.json", "overlay.png", "graph.json", "labels.pgm", "report.json", "world.svg", "world.glb"] {
            assert!(dir.join(f).exists(), "{f} missing in {}", dir.display());
        }
    }
    let read = |dir: &Path| World::from_json(&std::fs::read_to_string(dir.join("world.json")).unwrap()).unwrap();
    let (w, o) = (read(&wings), read(&one));
    assert!(w.units.iter().any(|u| u.angle.is_some()) && w.units.iter().any(|u| u.angle.is_none()));
    assert!(o.units.iter().all(|u| u.angle.is_none()));
    assert_eq!(std::fs::read(wings.join("labels.pgm")).unwrap(), std::fs::read(one.join("labels.pgm")).unwrap());
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(wings.join("report.json")).unwrap()).unwrap();
    assert_eq!(report["wings"].as_array().map(Vec::len), Some(2), "{report}");
    assert_eq!(report["iterations"], 18000, "three chains of 6000");
}

/// The gray levels of `samples/furnished/map.pgm` with what drawn maps add: furniture in a light
/// gray (211, as the benchmark's furnished floors draw it) and anti-aliased wall edges (a mid
/// gray beside each wall), which map_server's default `free_thresh` would call free.
fn drawn_map() -> (usize, usize, Vec<u8>) {
    let m = OccupancyMap::load(&sample("furnished/map.yaml"), &Limits::default()).unwrap();
    let (w, h) = (m.width(), m.height());
    let mut gray: Vec<u8> = m.raster().gray.cells().iter().map(|&g| (g / 257) as u8).collect();
    for y in 1..h - 1 {
        for x in 1..w - 1 {
            let i = y * w + x;
            if gray[i] == 254 && gray[i - 1] == 0 {
                gray[i] = 150;
            }
            if gray[i] == 254 && (x / 7 + y / 9) % 23 == 0 {
                gray[i] = 211;
            }
        }
    }
    (w, h, gray)
}

#[test]
fn the_same_pixels_as_png_pgm_and_map_yaml_give_the_same_labels() {
    let d = tmp("formats");
    let (w, h, gray) = drawn_map();
    let mut pgm = format!("P5\n{w} {h}\n255\n").into_bytes();
    pgm.extend_from_slice(&gray);
    std::fs::write(d.join("map.pgm"), &pgm).unwrap();
    let mut png_bytes = Vec::new();
    {
        let mut enc = png::Encoder::new(&mut png_bytes, w as u32, h as u32);
        enc.set_color(png::ColorType::Grayscale);
        enc.set_depth(png::BitDepth::Eight);
        enc.write_header().unwrap().write_image_data(&gray).unwrap();
    }
    std::fs::write(d.join("map.png"), &png_bytes).unwrap();
    let yaml = "image: map.pgm\nresolution: 0.05\norigin: [-3.0, 2.5, 0.0]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n";
    std::fs::write(d.join("map.yaml"), yaml).unwrap();
    // The cells: one rule for the three; the YAML's own thresholds read otherwise.
    let cells = |f: &str| {
        let mut m = OccupancyMap::load(&d.join(f), &Limits::default()).unwrap();
        let fixed = m.classified().clone();
        m.set_classifier(ksmcmc::grid::Classifier::for_map(m.yaml())).unwrap();
        (fixed, m.classified().clone())
    };
    let (yaml_fixed, yaml_auto) = cells("map.yaml");
    assert_eq!(cells("map.png").1, yaml_auto);
    assert_eq!(cells("map.pgm").1, yaml_auto);
    let differ = yaml_fixed.cells().iter().zip(yaml_auto.cells()).filter(|(a, b)| a != b).count();
    assert!(differ > 100, "map_server's thresholds read the drawn grays otherwise ({differ} cells)");
    // The rooms: the same labels.pgm and rooms from each file.
    let labels: Vec<Vec<u8>> = ["map.png", "map.pgm", "map.yaml"]
        .iter()
        .map(|f| {
            let out_dir = d.join(format!("out-{f}"));
            let path = d.join(f);
            let args = ["floorplan", path.to_str().unwrap(), "--out", out_dir.to_str().unwrap()];
            let out = run(&[&args[..], &["--iterations", "3000", "--seed", "4"]].concat());
            assert!(out.status.success(), "{f}: {}", String::from_utf8_lossy(&out.stderr));
            let note = String::from_utf8_lossy(&out.stderr).contains("has no map.yaml; reading it at 0.05 m a cell");
            assert_eq!(note, !f.ends_with(".yaml"), "{f}: {}", String::from_utf8_lossy(&out.stderr));
            std::fs::read(out_dir.join("labels.pgm")).unwrap()
        })
        .collect();
    assert_eq!(labels[0], labels[1], "PNG and PGM");
    assert_eq!(labels[0], labels[2], "PNG and map.yaml");
}

#[test]
fn resolution_sets_the_cell_size_of_a_plain_image() {
    let d = tmp("resolution");
    let map = sample("office-small/map.pgm");
    let area = |resolution: Option<&str>| {
        let out_dir = d.join(format!("out-{resolution:?}"));
        let mut args =
            vec!["floorplan", map.to_str().unwrap(), "--out", out_dir.to_str().unwrap(), "--iterations", "3000"];
        args.extend(resolution.map(|r| ["--resolution", r]).into_iter().flatten());
        let out = run(&args);
        let stderr = String::from_utf8_lossy(&out.stderr).to_string();
        assert!(out.status.success(), "{stderr}");
        assert_eq!(stderr.contains("has no map.yaml; reading it at 0.05 m"), resolution.is_none(), "{stderr}");
        let world: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out_dir.join("world.json")).unwrap()).unwrap();
        world["rooms"].as_array().unwrap().iter().map(|r| r["area_m2"].as_f64().unwrap()).sum::<f64>()
    };
    // The same cells at twice the cell size cover four times the floor.
    let ratio = area(Some("0.1")) / area(None);
    assert!((3.0..5.0).contains(&ratio), "rooms' area at 0.1 m over 0.05 m: {ratio}");
    for bad in ["0", "-1", "nan", "11"] {
        let out = run(&["floorplan", map.to_str().unwrap(), "--out", d.to_str().unwrap(), "--resolution", bad]);
        assert_eq!(out.status.code(), Some(2), "--resolution {bad}");
        assert!(String::from_utf8_lossy(&out.stderr).contains("--resolution"));
    }
}

/// A reader that closes the pipe (`ksmcmc info MAP | head -1`) ends the command as it ends
/// other tools, by SIGPIPE, never with "internal error".
#[cfg(all(target_os = "linux", target_env = "gnu"))]
#[test]
fn a_closed_pipe_ends_the_command_quietly() {
    use std::os::fd::FromRawFd;
    use std::os::unix::process::ExitStatusExt;
    let mut fds = [0i32; 2];
    // SAFETY: a fresh pipe; its read end is closed at once and its write end handed to the child.
    let writer = unsafe {
        assert_eq!(libc::pipe(fds.as_mut_ptr()), 0);
        libc::close(fds[0]);
        std::process::Stdio::from_raw_fd(fds[1])
    };
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_ksmcmc"))
        .arg("help")
        .stdout(writer)
        .stderr(std::process::Stdio::piped())
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!stderr.contains("internal error"), "{stderr}");
    assert_eq!(out.status.signal(), Some(libc::SIGPIPE), "{:?}", out.status);
}
