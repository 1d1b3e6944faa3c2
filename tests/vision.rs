//! The detectors on real maps nobody on this project drew (../shared/datasets).

use ksmcmc::grid::{Cell, Classifier, Limits, OccupancyMap};
use ksmcmc::vision::{hidden, orientation};
use std::path::{Path, PathBuf};

fn bormann(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/datasets/bormann2016").join(name)
}

fn load(name: &str) -> OccupancyMap {
    let mut map = OccupancyMap::load(&bormann(name), &Limits::default()).unwrap();
    map.set_classifier(Classifier::auto()).unwrap();
    map
}

/// lab_ipa is drawn with the outside filled in as occupied, and its free space has 45-degree
/// walls; Freiburg101 with furniture has many small furniture outlines. Their walls are
/// (nearly) upright in the image.
#[test]
fn the_dominant_angle_follows_the_walls_not_the_solid_outside() {
    for name in ["lab_ipa.png", "lab_ipa_furnitures.png", "Freiburg101_scan_furnitures.png"] {
        let map = load(name);
        let deg = orientation::dominant_angle(map.classified()).to_degrees();
        assert!(deg.abs() < 3.0, "{name}: the walls are upright, found {deg:.2} degrees");
    }
}

/// The solid outside of lab_ipa is not wall: all but a wall's depth of it is hidden, while
/// every occupied cell next to free space (a wall face) stays occupied.
#[test]
fn the_inside_of_a_solid_outside_is_hidden() {
    let map = load("lab_ipa.png");
    let c = map.classified();
    let out = hidden::hide_interior(c, hidden::depth_cells(map.yaml().resolution));
    let occupied = |g: &ksmcmc::grid::Grid<Cell>| g.cells().iter().filter(|&&k| k == Cell::Occupied).count();
    assert!(occupied(&out) * 5 < occupied(c), "{} of {} occupied cells kept", occupied(&out), occupied(c));
    let faces = orientation::wall_surface(c);
    for (i, (&f, &o)) in faces.cells().iter().zip(out.cells()).enumerate() {
        assert!(f != Cell::Occupied || o == Cell::Occupied, "wall face {i} hidden");
    }
}

/// Maps with unknown space around the building keep their walls: nothing of lab_c is hidden.
#[test]
fn walls_beside_unexplored_space_are_kept() {
    let map = load("lab_c_scan.png");
    let out = hidden::hide_interior(map.classified(), hidden::depth_cells(map.yaml().resolution));
    assert_eq!(&out, map.classified());
}
