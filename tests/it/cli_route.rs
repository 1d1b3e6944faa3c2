//! `ksmcmc route` end to end: the JSON it prints, with and without labels.pgm, and its errors.

use crate::common::run_cli as run;
use ksmcmc::floorplan::World;
use ksmcmc::grid::{Cell, Limits, OccupancyMap};
use std::path::{Path, PathBuf};

fn tmp(name: &str) -> PathBuf {
    crate::common::tmp_dir("cli-route", name)
}

/// A floor plan of office-small (6000 iterations), written once for the tests of this file.
fn explained() -> &'static (PathBuf, PathBuf) {
    static DIR: std::sync::OnceLock<(PathBuf, PathBuf)> = std::sync::OnceLock::new();
    DIR.get_or_init(|| {
        let d = tmp("floor");
        let map = Path::new(env!("CARGO_MANIFEST_DIR")).join("samples/office-small/map.yaml");
        let out = run(&["floorplan", map.to_str().unwrap(), "--out", d.to_str().unwrap(), "--iterations", "6000"]);
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        (map, d)
    })
}

/// Two free cells of the map in different rooms of labels.pgm, far apart.
fn ends(map: &OccupancyMap, labels: &[u16]) -> ([usize; 2], [usize; 2]) {
    let w = map.width();
    let free: Vec<usize> =
        (0..labels.len()).filter(|&i| labels[i] != 0 && map.classified().cells()[i] == Cell::Free).collect();
    let a = free[0];
    let b = *free.iter().rev().find(|&&i| labels[i] != labels[a]).unwrap();
    ([a % w, a / w], [b % w, b / w])
}

#[test]
fn route_prints_rooms_doors_path_and_length() {
    let (map_path, d) = explained();
    let map = OccupancyMap::load(map_path, &Limits::default()).unwrap();
    let world = World::from_json(&std::fs::read_to_string(d.join("world.json")).unwrap()).unwrap();
    let pgm = std::fs::read(d.join("labels.pgm")).unwrap();
    let labels = ksmcmc::grid::decode_image(&pgm, &Limits::default()).unwrap().gray.into_cells();
    let (a, b) = ends(&map, &labels);
    let (from, to) = (format!("{},{}", a[0], a[1]), format!("{},{}", b[0], b[1]));
    let (m, wj, lp) = (map_path.to_str().unwrap(), d.join("world.json"), d.join("labels.pgm"));
    let base = ["route", m, wj.to_str().unwrap(), "--from", &from, "--to", &to];
    let out = run(&base);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let r: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let path: Vec<[usize; 2]> = serde_json::from_value(r["path"].clone()).unwrap();
    assert_eq!((path[0], *path.last().unwrap()), (a, b));
    let w = map.width();
    for p in &path {
        assert_eq!(map.classified().cells()[p[1] * w + p[0]], Cell::Free, "{p:?}");
    }
    assert!(path.windows(2).all(|s| s[0][0].abs_diff(s[1][0]) <= 1 && s[0][1].abs_diff(s[1][1]) <= 1));
    let rooms: Vec<u16> = serde_json::from_value(r["rooms"].clone()).unwrap();
    assert_eq!(rooms.first(), Some(&labels[a[1] * w + a[0]]));
    assert_eq!(rooms.last(), Some(&labels[b[1] * w + b[0]]));
    let doors: Vec<u32> = serde_json::from_value(r["doors"].clone()).unwrap();
    assert!(doors.iter().all(|d| world.doors.iter().any(|x| x.id == *d)), "{doors:?}");
    let length = r["length_m"].as_f64().unwrap();
    assert!(length >= (path.len() - 1) as f64 * 0.05 - 1e-9, "{length}");
    // labels.pgm given or found again: the same route.
    let with_labels = run(&[&base[..], &["--labels", lp.to_str().unwrap()]].concat());
    assert_eq!(with_labels.stdout, out.stdout);
}

#[test]
fn route_errors_say_what_is_wrong() {
    let (map_path, d) = explained();
    let (m, wj) = (map_path.to_str().unwrap(), d.join("world.json"));
    let wj = wj.to_str().unwrap();
    let fails = |args: &[&str], code: i32, says: &str| {
        let out = run(args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(code), "{args:?}: {err}");
        assert!(err.contains(says), "{args:?}: {err}");
    };
    fails(&["route", m, wj, "--from", "0,0", "--to", "1,1"], 1, "the start (0, 0) is an unknown cell");
    fails(&["route", m, wj, "--from", "5000,0", "--to", "1,1"], 1, "lies outside the");
    fails(&["route", m, wj, "--from", "3;4", "--to", "1,1"], 2, "write the column and row as X,Y");
    fails(&["route", m, wj, "--to", "1,1"], 2, "route needs --from X,Y");
    // A world of another map, and labels of another size.
    let other = Path::new(env!("CARGO_MANIFEST_DIR")).join("samples/two-corridors/truth.json");
    fails(&["route", m, other.to_str().unwrap(), "--from", "1,1", "--to", "2,2"], 1, "explains a");
    let small = tmp("small").join("labels.pgm");
    std::fs::write(&small, ksmcmc::grid::pgm::encode_u16(3, 3, &[0; 9])).unwrap();
    let e = ["--from", "1,1", "--to", "2,2", "--labels", small.to_str().unwrap()];
    fails(&[&["route", m, wj][..], &e].concat(), 1, "labels are 3x3 but the map is");
}
