//! The detectors on real maps nobody on this project drew (../shared/datasets; the tests skip
//! without them), and on drawn fixtures with the same features.

use ksmcmc::grid::{Cell, Classifier, Grid, Limits, OccupancyMap};
use ksmcmc::vision::orientation;

/// A Bormann map with the automatic classifier, or `None` (skip) without the datasets.
fn load(test: &str, name: &str) -> Option<OccupancyMap> {
    let path = crate::common::datasets(test)?.join("bormann2016").join(name);
    let mut map = OccupancyMap::load(&path, &Limits::default()).unwrap();
    map.set_classifier(Classifier::auto()).unwrap();
    Some(map)
}

/// A drawn floor like lab_ipa: three upright rooms with 3-cell walls in a solid occupied
/// outside, a 45-degree wall across one room, and small furniture outlines in another.
fn solid_outside_fixture() -> Grid<Cell> {
    let (w, h) = (200usize, 160usize);
    let mut g = Grid::new(w, h, Cell::Occupied);
    for (x0, y0, x1, y1) in [(10, 10, 70, 60), (73, 10, 150, 60), (10, 63, 150, 110)] {
        for y in y0..y1 {
            for x in x0..x1 {
                *g.at_mut(x, y) = Cell::Free;
            }
        }
    }
    for i in 0..30 {
        *g.at_mut(20 + i, 20 + i) = Cell::Occupied;
    }
    for (fx, fy) in [(90, 20), (110, 30), (130, 40)] {
        for d in 0..4 {
            *g.at_mut(fx + d, fy) = Cell::Occupied;
            *g.at_mut(fx, fy + d) = Cell::Occupied;
        }
    }
    g
}

#[test]
fn on_a_fixture_the_dominant_angle_follows_the_walls_and_the_solid_outside_is_hidden() {
    let c = solid_outside_fixture();
    let deg = orientation::dominant_angle(&c).to_degrees();
    assert!(deg.abs() < 3.0, "the walls are upright, found {deg:.2} degrees");
    let out = ksmcmc::grid::hidden::hide_interior(&c, 3);
    let occupied = |g: &Grid<Cell>| g.cells().iter().filter(|&&k| k == Cell::Occupied).count();
    assert!(occupied(&out) * 3 < occupied(&c), "{} of {} occupied cells kept", occupied(&out), occupied(&c));
    let faces = orientation::wall_surface(&c);
    for (i, (&f, &o)) in faces.cells().iter().zip(out.cells()).enumerate() {
        assert!(f != Cell::Occupied || o == Cell::Occupied, "wall face {i} hidden");
    }
    // With unknown space around it instead, the building keeps every wall.
    let mut open = c.clone();
    for (i, k) in open.cells_mut().iter_mut().enumerate() {
        let (x, y) = (i % 200, i / 200);
        if !(7..153).contains(&x) || !(7..113).contains(&y) {
            *k = Cell::Unknown;
        }
    }
    assert_eq!(ksmcmc::grid::hidden::hide_interior(&open, 3), open);
}

/// lab_ipa is drawn with the outside filled in as occupied, and its free space has 45-degree
/// walls; Freiburg101 with furniture has many small furniture outlines. Their walls are
/// (nearly) upright in the image.
#[test]
fn the_dominant_angle_follows_the_walls_not_the_solid_outside() {
    for name in ["lab_ipa.png", "lab_ipa_furnitures.png", "Freiburg101_scan_furnitures.png"] {
        let Some(map) = load("the_dominant_angle_follows_the_walls_not_the_solid_outside", name) else { return };
        let deg = orientation::dominant_angle(map.classified()).to_degrees();
        assert!(deg.abs() < 3.0, "{name}: the walls are upright, found {deg:.2} degrees");
    }
}

/// The solid outside of lab_ipa is not wall: the map keeps all but a wall's depth of it
/// occupied, and every occupied cell next to free space (a wall face) stays occupied.
#[test]
fn the_inside_of_a_solid_outside_is_hidden() {
    let Some(map) = load("the_inside_of_a_solid_outside_is_hidden", "lab_ipa.png") else { return };
    let raw = map.classifier().classify_raster(map.raster());
    let out = map.classified();
    let occupied = |g: &ksmcmc::grid::Grid<Cell>| g.cells().iter().filter(|&&k| k == Cell::Occupied).count();
    assert!(occupied(out) * 5 < occupied(&raw), "{} of {} occupied cells kept", occupied(out), occupied(&raw));
    let faces = orientation::wall_surface(&raw);
    for (i, (&f, &o)) in faces.cells().iter().zip(out.cells()).enumerate() {
        assert!(f != Cell::Occupied || o == Cell::Occupied, "wall face {i} hidden");
    }
}

/// Maps with unknown space around the building keep their walls: nothing of lab_c is hidden.
#[test]
fn walls_beside_unexplored_space_are_kept() {
    let Some(map) = load("walls_beside_unexplored_space_are_kept", "lab_c_scan.png") else { return };
    assert_eq!(&map.classifier().classify_raster(map.raster()), map.classified());
}

/// The pentagon office_e has walls in five directions, 18 degrees apart modulo 90; lab_ipa
/// has upright walls and 45-degree ones; office_c only upright walls. The CLI's report lists
/// them and says that the units follow only the first.
#[test]
fn wall_directions_of_a_pentagon_a_45_degree_wing_and_an_upright_floor() {
    let degrees = |name: &str| -> Option<Vec<f64>> {
        let map = load("wall_directions_of_a_pentagon_a_45_degree_wing_and_an_upright_floor", name)?;
        let mut d: Vec<f64> =
            orientation::wall_directions(map.classified(), 0.3).iter().map(|d| d.angle.to_degrees()).collect();
        d.sort_by(f64::total_cmp);
        Some(d)
    };
    let close = |found: &[f64], want: &[f64]| {
        found.len() == want.len() && found.iter().zip(want).all(|(f, w)| (f - w).abs() < 1.5)
    };
    let Some(e) = degrees("office_e.png") else { return };
    assert!(close(&e, &[-36.0, -18.0, 0.0, 18.0, 36.0]), "office_e: {e:?}");
    let ipa = degrees("lab_ipa.png").unwrap();
    assert!(close(&ipa, &[-43.5, 1.8]), "lab_ipa: {ipa:?}");
    let c = degrees("office_c.png").unwrap();
    assert!(close(&c, &[0.0]), "office_c: {c:?}");
    let dir = crate::common::tmp_dir("wall-directions", "office_e");
    let path = crate::common::datasets("").unwrap().join("bormann2016/office_e.png");
    let out = crate::common::run_cli(&[
        "floorplan",
        path.to_str().unwrap(),
        "--iterations",
        "200",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(out.status.success());
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("follow 5 directions"), "{stderr}");
    let report: serde_json::Value = serde_json::from_slice(&std::fs::read(dir.join("report.json")).unwrap()).unwrap();
    assert_eq!(report["wall_directions"].as_array().unwrap().len(), 5);
}

/// Direction regions (issue 13): on two buildings at an angle, each wing's floor takes its
/// own wing's direction; a one-direction building is one region.
#[test]
fn each_wing_of_a_building_is_a_region_of_its_direction() {
    use ksmcmc::floorplan::synth::{generate, SynthConfig};
    use ksmcmc::vision::regions::{direction_regions, RegionConfig};
    // The difference of two angles modulo 90 degrees, in degrees.
    let apart = |a: f64, b: f64| {
        let d = (a - b).to_degrees().rem_euclid(90.0);
        d.min(90.0 - d)
    };
    for (wing, seed) in [(30.0, 1), (-45.0, 2), (60.0, 3), (20.0, 4)] {
        let s = generate(&SynthConfig { wing_deg: wing, ..SynthConfig::default() }, seed).unwrap();
        let found = direction_regions(s.map.classified(), &RegionConfig::default(), s.map.yaml().resolution);
        let index_of = |a: f64| found.directions.iter().position(|d| apart(d.angle, a) < 1.0);
        let first =
            index_of(0.0).unwrap_or_else(|| panic!("wing {wing}: no upright direction in {:?}", found.directions));
        let second = index_of(f64::to_radians(wing)).unwrap_or_else(|| panic!("wing {wing}: {:?}", found.directions));
        let (mut right, mut total) = (0usize, 0usize);
        for (i, &l) in s.labels.cells().iter().enumerate() {
            if l == 0 || s.map.classified().cells()[i] != Cell::Free {
                continue;
            }
            let turned = s.truth.units[l as usize - 1].angle.is_some();
            total += 1;
            right += usize::from(found.region.cells()[i] as usize == if turned { second } else { first });
        }
        let rate = right as f64 / total as f64;
        assert!(rate > 0.95, "wing {wing}: {rate:.3} of the floor in its wing's region");
    }
    let s = generate(&SynthConfig { rotation_deg: 20.0, ..SynthConfig::default() }, 5).unwrap();
    let found = direction_regions(s.map.classified(), &RegionConfig::default(), s.map.yaml().resolution);
    let shares = found.shares();
    assert!(shares[0] > 0.99, "one building, {shares:?}");
}
