//! The synthetic generator: determinism, truth consistency, noise statistics, validation.

use ksmcmc::floorplan::synth::{generate, SynthConfig, Synthetic};
use ksmcmc::floorplan::{Rect, Unit, UnitType, World};
use ksmcmc::grid::{Cell, Grid};
use std::collections::HashSet;

/// No noise at all: every cell reads what the layout says.
fn quiet() -> SynthConfig {
    SynthConfig {
        speckle_occupied: 0.0,
        speckle_unknown: 0.0,
        wall_roughness: 0.0,
        wall_gaps: 0.0,
        clutter: 0.0,
        ..SynthConfig::default()
    }
}

fn interior(u: &Unit) -> Rect {
    Rect::new(u.x + 1, u.y + 1, u.w - 2, u.h - 2)
}

fn gen(c: &SynthConfig, seed: u64) -> Synthetic {
    generate(c, seed).unwrap_or_else(|e| panic!("seed {seed}: {e}"))
}

/// The map cell under world cell `(x, y)`'s centre.
fn map_cell(s: &Synthetic, x: i32, y: i32) -> Option<Cell> {
    let (mx, my) = s.truth.frame.to_map(x as f64 + 0.5, y as f64 + 0.5);
    s.map.classified().get(mx.floor() as i64, my.floor() as i64).copied()
}

/// The world cell under map cell `(x, y)`'s centre.
fn world_cell(s: &Synthetic, x: usize, y: usize) -> (i32, i32) {
    let (wx, wy) = s.truth.frame.to_world(x as f64 + 0.5, y as f64 + 0.5);
    (wx.floor() as i32, wy.floor() as i32)
}

fn connected(w: &World) -> bool {
    let n = w.units.len();
    let index = |id: u32| w.units.iter().position(|u| u.id == id).unwrap();
    let mut seen = vec![false; n];
    let mut stack = vec![0];
    seen[0] = true;
    while let Some(i) = stack.pop() {
        for d in &w.doors {
            let [a, b] = [index(d.units[0]), index(d.units[1])];
            for (p, q) in [(a, b), (b, a)] {
                if p == i && !seen[q] {
                    seen[q] = true;
                    stack.push(q);
                }
            }
        }
    }
    seen.iter().all(|&s| s)
}

/// Every structural promise of the module docs, for one generated map.
fn check_truth(s: &Synthetic, c: &SynthConfig, seed: u64) {
    let w = &s.truth;
    let t = c.wall_thickness as i32;
    let ctx = |m: &str| format!("seed {seed}: {m}");
    w.validate().unwrap_or_else(|e| panic!("{}", ctx(&e.to_string())));
    assert_eq!(World::from_json(&s.truth_json()).unwrap(), *w, "{}", ctx("truth.json round trip"));
    assert_eq!(w.frame.world_size, [c.width, c.height]);
    assert_eq!(w.frame.map_size, [s.map.width() as u32, s.map.height() as u32]);
    assert_eq!((s.labels.width(), s.labels.height()), (s.map.width(), s.map.height()));
    assert_eq!(s.explored.len(), w.units.len());
    let (ww, wh) = (c.width as usize, c.height as usize);

    // Ids 1..n in order, units inside the world, interiors disjoint.
    let mut owner = Grid::new(ww, wh, 0usize);
    for (i, u) in w.units.iter().enumerate() {
        assert_eq!(u.id, i as u32 + 1);
        assert!(u.x >= 0 && u.y >= 0 && u.x + u.w <= c.width as i32 && u.y + u.h <= c.height as i32);
        assert!(u.w >= 3 && u.h >= 3);
        assert_ne!(u.kind, UnitType::Unknown);
        let r = interior(u);
        for y in r.y..r.bottom() {
            for x in r.x..r.right() {
                let o = owner.at_mut(x as usize, y as usize);
                assert_eq!(*o, 0, "{}", ctx(&format!("units {} and {} overlap at ({x},{y})", *o, u.id)));
                *o = i + 1;
            }
        }
    }

    // Doors sit in the wall between their two units, on the centre line, inside both rings.
    let mut pairs = HashSet::new();
    for d in &w.doors {
        let (a, b) = (w.unit(d.units[0]).unwrap(), w.unit(d.units[1]).unwrap());
        assert!(pairs.insert(d.units), "{}", ctx("two doors join the same units"));
        let (ra, rb) = (a.rect(), b.rect());
        let vertical = d.x0 == d.x1;
        // Across the wall: a's ring, then t - 1 cells on to b's ring.
        let (ring_a, ring_b, across) =
            if vertical { (ra.right() - 1, rb.x, d.x0) } else { (ra.bottom() - 1, rb.y, d.y0) };
        assert_eq!(ring_b - ring_a, t - 1, "{}", ctx(&format!("door {} joins units not sharing a wall", d.id)));
        assert_eq!(across, ring_a + (t - 1) / 2, "{}", ctx("door off the wall's centre line"));
        for (x, y) in d.cells() {
            let along = if vertical { y } else { x };
            for r in [ra, rb] {
                let (lo, hi) = if vertical { (r.y, r.bottom() - 1) } else { (r.x, r.right() - 1) };
                assert!(along > lo && along < hi, "{}", ctx(&format!("door {} leaves its wall at ({x},{y})", d.id)));
            }
            if t == 1 {
                assert!(ra.on_border(x, y) && rb.on_border(x, y), "{}", ctx("door not on both rings"));
            } else if t == 2 {
                assert!(ra.on_border(x, y), "{}", ctx("door not on a's ring"));
            }
        }
        let dl = d.len() as f64 * c.resolution;
        assert!(dl <= c.door_width[1] + 1e-9, "{}", ctx(&format!("door {} is {dl} m wide", d.id)));
    }
    assert!(connected(w), "{}", ctx("door graph not connected"));

    // Labels: unit index + 1 exactly on interiors, as sampled from the map cell centres.
    for y in 0..s.map.height() {
        for x in 0..s.map.width() {
            let (wx, wy) = world_cell(s, x, y);
            let expected = owner.get(wx as i64, wy as i64).map_or(0, |&o| o as u16);
            assert_eq!(*s.labels.at(x, y), expected, "{}", ctx(&format!("label at map ({x},{y})")));
        }
    }

    // Furniture only in explored rooms and halls, never read free.
    let objects: HashSet<(i32, i32)> = w.object_cells.iter().map(|c| (c[0], c[1])).collect();
    for &(x, y) in &objects {
        let o = *owner.at(x as usize, y as usize);
        assert!(o > 0, "{}", ctx("object cell outside every unit"));
        assert!(matches!(w.units[o - 1].kind, UnitType::Room | UnitType::Hall) && s.explored[o - 1]);
        if w.frame.angle == 0.0 {
            assert_ne!(map_cell(s, x, y), Some(Cell::Free), "{}", ctx("object cell reads free"));
        }
    }

    // Explored interiors read free but for speckle (and what rotation blurs at the edges).
    let mut free = vec![0usize; w.units.len()];
    let mut total = vec![0usize; w.units.len()];
    for y in 0..s.map.height() {
        for x in 0..s.map.width() {
            let l = *s.labels.at(x, y) as usize;
            if l > 0 && !objects.contains(&world_cell(s, x, y)) {
                total[l - 1] += 1;
                free[l - 1] += usize::from(s.map.classified().at(x, y) == &Cell::Free);
            }
        }
    }
    let noise = c.speckle_occupied + c.speckle_unknown;
    for i in 0..w.units.len() {
        if s.explored[i] && total[i] > 0 {
            let f = free[i] as f64 / total[i] as f64;
            assert!(f >= 1.0 - noise - 0.03, "{}", ctx(&format!("explored unit {} only {f:.3} free", i + 1)));
        }
    }

    // Outside the building (more than a wall away from every unit) is unknown.
    let mut near = Grid::new(ww, wh, false);
    let reach = t + i32::from(w.frame.angle != 0.0);
    for u in &w.units {
        for y in (u.y - reach).max(0)..(u.y + u.h + reach).min(wh as i32) {
            for x in (u.x - reach).max(0)..(u.x + u.w + reach).min(ww as i32) {
                *near.at_mut(x as usize, y as usize) = true;
            }
        }
    }
    for y in 0..s.map.height() {
        for x in 0..s.map.width() {
            let (wx, wy) = world_cell(s, x, y);
            if !near.get(wx as i64, wy as i64).copied().unwrap_or(false) {
                assert_eq!(s.map.classified().at(x, y), &Cell::Unknown, "{}", ctx(&format!("outside at ({x},{y})")));
            }
        }
    }
}

#[test]
fn same_seed_same_bytes_different_seed_different_map() {
    let c = SynthConfig { rotation_deg: 12.5, clutter: 0.08, unexplored: 0.3, ..SynthConfig::default() };
    let (a, b) = (gen(&c, 99), gen(&c, 99));
    assert_eq!(a.map_pgm(), b.map_pgm());
    assert_eq!(a.map_yaml(), b.map_yaml());
    assert_eq!(a.truth_json(), b.truth_json());
    assert_eq!(a.labels_pgm(), b.labels_pgm());
    let maps: HashSet<Vec<u8>> = (0..6).map(|seed| gen(&c, seed).map_pgm()).collect();
    assert_eq!(maps.len(), 6, "different seeds gave identical maps");
    let truths: HashSet<String> = (0..6).map(|seed| gen(&c, seed).truth_json()).collect();
    assert_eq!(truths.len(), 6, "different seeds gave identical truths");
}

#[test]
fn truth_is_consistent_for_many_seeds() {
    let c = SynthConfig::default();
    for seed in 0..30 {
        check_truth(&gen(&c, seed), &c, seed);
    }
}

#[test]
fn truth_is_consistent_across_layouts() {
    let cases = [
        SynthConfig { wall_thickness: 1, ..quiet() },
        SynthConfig { wall_thickness: 2, unexplored: 0.4, ..SynthConfig::default() },
        SynthConfig { width: 700, height: 600, corridors: Some(2), others: 3, ..SynthConfig::default() },
        SynthConfig { width: 900, height: 600, halls: 2, clutter: 0.15, ..SynthConfig::default() },
        SynthConfig { width: 500, height: 160, halls: 1, unexplored: 0.5, peek: 1.0, ..SynthConfig::default() },
        SynthConfig { width: 260, height: 520, rotation_deg: -33.0, ..SynthConfig::default() },
        SynthConfig { rotation_deg: 20.0, wall_thickness: 4, unexplored: 0.2, clutter: 0.1, ..SynthConfig::default() },
        SynthConfig { resolution: 0.1, wall_thickness: 2, ..SynthConfig::default() },
    ];
    for (k, c) in cases.iter().enumerate() {
        for seed in 0..6 {
            check_truth(&gen(c, seed), c, 1000 * k as u64 + seed);
        }
    }
}

#[test]
fn noise_free_map_is_exactly_the_layout() {
    let c = quiet();
    for seed in 0..10 {
        let s = gen(&c, seed);
        let cells = s.map.classified();
        for u in &s.truth.units {
            let r = u.rect();
            for y in r.y..r.bottom() {
                for x in r.x..r.right() {
                    let cell = *cells.at(x as usize, y as usize);
                    if interior(u).contains(x, y) {
                        assert_eq!(cell, Cell::Free, "seed {seed}: interior ({x},{y})");
                    } else if cell != Cell::Occupied {
                        // A ring cell that is not wall must be a door opening.
                        assert_eq!(cell, Cell::Free, "seed {seed}: ring ({x},{y})");
                        assert!(
                            s.truth.doors.iter().any(|d| d.units.contains(&u.id)
                                && d.cells()
                                    .any(|(dx, dy)| (dx - x).abs() + (dy - y).abs() <= c.wall_thickness as i32)),
                            "seed {seed}: free ring cell ({x},{y}) of unit {} away from its doors",
                            u.id
                        );
                    }
                }
            }
        }
        for d in &s.truth.doors {
            for (x, y) in d.cells() {
                assert_eq!(*cells.at(x as usize, y as usize), Cell::Free, "seed {seed}: door {} closed", d.id);
            }
        }
    }
}

#[test]
fn layout_matches_the_config() {
    let cm = |m: f64| (m / 0.05).round() as i32;
    for seed in 0..10 {
        let c = SynthConfig { width: 900, height: 500, halls: 2, others: 3, ..SynthConfig::default() };
        let s = gen(&c, seed);
        let count = |k| s.truth.units.iter().filter(|u| u.kind == k).count();
        assert_eq!(count(UnitType::Hall), 2);
        assert_eq!(count(UnitType::Other), 3);
        assert!((1..=2).contains(&count(UnitType::Corridor)));
        assert!(count(UnitType::Room) >= 4);
        for u in &s.truth.units {
            let (short, long) = ((u.w - 2).min(u.h - 2), (u.w - 2).max(u.h - 2));
            match u.kind {
                UnitType::Corridor => {
                    assert!(short >= cm(1.5) && short <= cm(2.5), "corridor {short} cells wide");
                    assert!(long >= 2 * short, "corridor {short} x {long} is not long and narrow");
                }
                UnitType::Hall => assert!(short >= cm(8.0) || long >= cm(8.0)),
                UnitType::Other => assert!(short <= cm(2.5), "other unit {short} cells wide"),
                UnitType::Room => assert!(short >= cm(3.0), "room {short} cells wide"),
                UnitType::Unknown => unreachable!(),
            }
        }
        // Every room and other unit opens onto a corridor or a hall it touches.
        for u in s.truth.units.iter().filter(|u| matches!(u.kind, UnitType::Room | UnitType::Other)) {
            let hub_door = s.truth.doors.iter().any(|d| {
                d.units.contains(&u.id)
                    && d.units
                        .iter()
                        .any(|&v| matches!(s.truth.unit(v).unwrap().kind, UnitType::Corridor | UnitType::Hall))
            });
            assert!(hub_door, "seed {seed}: unit {} has no door to a corridor or hall", u.id);
        }
    }
    // Two corridors and no hall: a connecting corridor joins them.
    let c = SynthConfig { width: 800, height: 640, corridors: Some(2), ..SynthConfig::default() };
    for seed in 0..5 {
        let s = gen(&c, seed);
        assert_eq!(s.truth.units.iter().filter(|u| u.kind == UnitType::Corridor).count(), 3);
        assert!(connected(&s.truth));
    }
    // A portrait canvas turns the layout: corridors run vertically.
    let c = SynthConfig { width: 300, height: 500, ..SynthConfig::default() };
    let s = gen(&c, 3);
    assert_eq!((s.map.width(), s.map.height()), (300, 500));
    for u in s.truth.units.iter().filter(|u| u.kind == UnitType::Corridor) {
        assert!(u.h > u.w);
    }
    // The room count range is honoured.
    for seed in 0..5 {
        let s = gen(&SynthConfig { rooms: [8, 8], ..SynthConfig::default() }, seed);
        assert_eq!(s.truth.units.iter().filter(|u| u.kind == UnitType::Room).count(), 8);
    }
    let err = generate(&SynthConfig { rooms: [40, 50], ..SynthConfig::default() }, 1).unwrap_err();
    assert!(err.to_string().contains("rooms"), "{err}");
}

#[test]
fn rotation_keeps_walls_on_the_truth() {
    let c = SynthConfig { rotation_deg: 20.0, ..quiet() };
    for seed in 0..5 {
        let s = gen(&c, seed);
        assert!((s.truth.frame.angle - 0.349_065_850_4).abs() < 1e-9);
        assert!(s.map.width() > 400 && s.map.height() > 300);
        let (mut on_wall, mut rings, mut free, mut inside) = (0, 0, 0, 0);
        for u in &s.truth.units {
            let r = u.rect();
            for y in r.y..r.bottom() {
                for x in r.x..r.right() {
                    let cell = map_cell(&s, x, y);
                    if r.on_border(x, y) {
                        rings += 1;
                        on_wall += usize::from(cell == Some(Cell::Occupied));
                    } else {
                        inside += 1;
                        free += usize::from(cell == Some(Cell::Free));
                    }
                }
            }
        }
        let (wall_rate, free_rate) = (on_wall as f64 / rings as f64, free as f64 / inside as f64);
        assert!(wall_rate > 0.8, "seed {seed}: only {wall_rate:.3} of the truth walls read occupied");
        assert!(free_rate > 0.98, "seed {seed}: only {free_rate:.3} of the truth interiors read free");
        check_truth(&s, &c, seed);
    }
}

/// Two wings at an angle (issue 13): the second wing's units carry their angle, lie in the
/// frame that angle gives, and land on the map's walls and floor there; the labels agree; the
/// passage joins the wings.
#[test]
fn two_wings_at_an_angle_keep_their_units_on_the_map() {
    for (wing, seed) in [(30.0, 1), (-45.0, 2), (60.0, 3)] {
        let c = SynthConfig { wing_deg: wing, ..quiet() };
        let s = gen(&c, seed);
        let w = &s.truth;
        w.validate().unwrap();
        assert!(!w.is_one_direction());
        let second = w.units.iter().filter(|u| u.angle.is_some()).count();
        assert!(second >= 3 && second < w.units.len(), "wing {wing}: {second} of {} units turned", w.units.len());
        for u in w.units.iter().filter(|u| u.angle.is_some()) {
            assert!((u.angle.unwrap() - f64::to_radians(wing)).abs() < 1e-12);
        }
        let (mut on_wall, mut rings, mut free, mut inside, mut labelled) = (0, 0, 0, 0, 0);
        for (i, u) in w.units.iter().enumerate() {
            let frame = w.unit_frame(u);
            let r = u.rect();
            for y in r.y..r.bottom() {
                for x in r.x..r.right() {
                    let (mx, my) = frame.to_map(x as f64 + 0.5, y as f64 + 0.5);
                    let (mx, my) = (mx.floor() as i64, my.floor() as i64);
                    let cell = s.map.classified().get(mx, my).copied();
                    if r.on_border(x, y) {
                        rings += 1;
                        on_wall += usize::from(cell == Some(Cell::Occupied));
                    } else {
                        inside += 1;
                        free += usize::from(cell == Some(Cell::Free));
                        labelled += usize::from(s.labels.get(mx, my) == Some(&(i as u16 + 1)));
                    }
                }
            }
        }
        let rates = (on_wall as f64 / rings as f64, free as f64 / inside as f64, labelled as f64 / inside as f64);
        assert!(rates.0 > 0.8 && rates.1 > 0.97 && rates.2 > 0.97, "wing {wing}: wall, free, label rates {rates:?}");
        // One building: the free cells are 8-connected through the passage.
        let g = s.map.classified();
        let free_cells = g.cells().iter().filter(|&&c| c == Cell::Free).count();
        let start = g.cells().iter().position(|&c| c == Cell::Free).unwrap();
        let (gw, gh) = (g.width() as i64, g.height() as i64);
        let mut seen = vec![false; g.cells().len()];
        let mut stack = vec![start];
        seen[start] = true;
        let mut reached = 0;
        while let Some(i) = stack.pop() {
            reached += 1;
            let (x, y) = (i as i64 % gw, i as i64 / gw);
            for (dx, dy) in [(-1, 0), (1, 0), (0, -1), (0, 1), (-1, -1), (1, 1), (-1, 1), (1, -1)] {
                let (nx, ny) = (x + dx, y + dy);
                if nx >= 0 && ny >= 0 && nx < gw && ny < gh {
                    let j = (ny * gw + nx) as usize;
                    if !seen[j] && g.cells()[j] == Cell::Free {
                        seen[j] = true;
                        stack.push(j);
                    }
                }
            }
        }
        assert_eq!(reached, free_cells, "wing {wing}: the wings are not joined");
        assert_eq!(gen(&c, seed).map_pgm(), s.map_pgm());
        assert_eq!(World::from_json(&s.truth_json()).unwrap(), s.truth);
    }
    let bad = SynthConfig { wing_deg: 5.0, ..quiet() };
    assert!(generate(&bad, 1).unwrap_err().to_string().contains("wing_deg"));
}

#[test]
fn speckle_rates_match_the_config() {
    let c = SynthConfig { speckle_occupied: 0.05, speckle_unknown: 0.1, ..quiet() };
    let (mut occ, mut unk, mut n) = (0usize, 0usize, 0usize);
    for seed in 0..4 {
        let s = gen(&c, seed);
        for (cell, l) in s.map.classified().cells().iter().zip(s.labels.cells()) {
            if *l > 0 {
                n += 1;
                occ += usize::from(*cell == Cell::Occupied);
                unk += usize::from(*cell == Cell::Unknown);
            }
        }
    }
    let (po, pu) = (occ as f64 / n as f64, unk as f64 / n as f64);
    assert!((po - 0.05).abs() < 0.005, "occupied speckle {po}");
    assert!((pu - 0.1).abs() < 0.007, "unknown speckle {pu}");
}

#[test]
fn unexplored_units_read_unknown() {
    let c = SynthConfig { unexplored: 0.5, peek: 0.0, ..quiet() };
    for seed in 0..8 {
        let s = gen(&c, seed);
        let pool = s.truth.units.iter().filter(|u| u.kind != UnitType::Corridor).count();
        let dark: Vec<usize> = (0..s.explored.len()).filter(|&i| !s.explored[i]).collect();
        assert_eq!(dark.len(), (pool as f64 * 0.5).round() as usize);
        for &i in &dark {
            let u = &s.truth.units[i];
            assert_ne!(u.kind, UnitType::Corridor);
            let r = interior(u);
            for y in r.y..r.bottom() {
                for x in r.x..r.right() {
                    assert_eq!(s.map.classified().at(x as usize, y as usize), &Cell::Unknown);
                }
            }
        }
    }
    // Peeking through doors reveals part, never all, of an unexplored unit.
    let c = SynthConfig { unexplored: 0.5, peek: 1.0, ..quiet() };
    let (mut seen, mut total) = (0usize, 0usize);
    for seed in 0..8 {
        let s = gen(&c, seed);
        let n = s.truth.units.len();
        let (mut unit_seen, mut unit_total) = (vec![0usize; n], vec![0usize; n]);
        for (cell, l) in s.map.classified().cells().iter().zip(s.labels.cells()) {
            if *l > 0 {
                unit_total[*l as usize - 1] += 1;
                unit_seen[*l as usize - 1] += usize::from(*cell == Cell::Free);
            }
        }
        let dark: Vec<usize> = (0..n).filter(|&i| !s.explored[i]).collect();
        // A narrow storage room may be seen whole through its door, but not every unit.
        assert!(dark.iter().any(|&i| unit_seen[i] < unit_total[i] * 9 / 10), "seed {seed}: all seen by peeking");
        for i in dark {
            seen += unit_seen[i];
            total += unit_total[i];
        }
    }
    let f = seen as f64 / total as f64;
    assert!(f > 0.05 && f < 0.9, "peeking revealed {f:.3} of unexplored space");
}

#[test]
fn clutter_and_wall_gaps_follow_the_config() {
    let area = |s: &Synthetic| -> usize {
        s.truth
            .units
            .iter()
            .filter(|u| matches!(u.kind, UnitType::Room | UnitType::Hall))
            .map(|u| interior(u).area() as usize)
            .sum()
    };
    for clutter in [0.05, 0.15] {
        let c = SynthConfig { clutter, ..quiet() };
        let (mut cells, mut total) = (0, 0);
        for seed in 0..5 {
            let s = gen(&c, seed);
            cells += s.truth.object_cells.len();
            total += area(&s);
        }
        let f = cells as f64 / total as f64;
        assert!(f > 0.6 * clutter && f < 1.3 * clutter, "clutter {clutter}: covered {f:.3}");
    }
    assert!(gen(&quiet(), 1).truth.object_cells.is_empty());

    // Gaps make some wall cells read unknown; without them every seen wall cell is occupied.
    let ring_unknown = |c: &SynthConfig| -> f64 {
        let (mut unknown, mut n) = (0, 0);
        for seed in 0..4 {
            let s = gen(c, seed);
            for u in &s.truth.units {
                let r = u.rect();
                for y in r.y..r.bottom() {
                    for x in r.x..r.right() {
                        if r.on_border(x, y) {
                            n += 1;
                            unknown += usize::from(map_cell(&s, x, y) == Some(Cell::Unknown));
                        }
                    }
                }
            }
        }
        unknown as f64 / n as f64
    };
    assert_eq!(ring_unknown(&quiet()), 0.0);
    // Ragged faces: cells just inside the walls read occupied at about the configured rate.
    let c = SynthConfig { wall_roughness: 0.3, ..quiet() };
    let (mut rough, mut n) = (0, 0);
    for seed in 0..4 {
        let s = gen(&c, seed);
        for u in &s.truth.units {
            let r = interior(u);
            for y in r.y..r.bottom() {
                for x in r.x..r.right() {
                    if r.on_border(x, y) {
                        n += 1;
                        rough += usize::from(map_cell(&s, x, y) == Some(Cell::Occupied));
                    }
                }
            }
        }
    }
    let f = rough as f64 / n as f64;
    assert!(f > 0.22 && f < 0.32, "roughness 0.3 made {f:.3} of the wall faces occupied");
    let gappy = ring_unknown(&SynthConfig { wall_gaps: 0.02, ..quiet() });
    assert!(gappy > 0.03 && gappy < 0.3, "gaps left {gappy:.3} of the rings unknown");
}

/// The same 20 x 15 m building at `resolution` metres per cell, walls 0.15 m, no noise but
/// `extra`.
fn building_at(resolution: f64, extra: SynthConfig) -> SynthConfig {
    let cells = |m: f64| (m / resolution).round() as u32;
    SynthConfig {
        width: cells(20.0),
        height: cells(15.0),
        margin: cells(0.5),
        wall_thickness: cells(0.15).max(1),
        resolution,
        ..extra
    }
}

/// Runs of unknown cells along the cell row or column just inside each unit's wall ring, in
/// metres: their count per metre of wall and their mean length.
fn wall_gap_runs(s: &Synthetic, resolution: f64) -> (f64, f64) {
    let (mut runs, mut cells, mut along) = (0usize, 0usize, 0usize);
    for u in &s.truth.units {
        let r = u.rect();
        let sides: [Vec<(i32, i32)>; 2] =
            [(r.x..r.right()).map(|x| (x, r.y)).collect(), (r.y..r.bottom()).map(|y| (r.x, y)).collect()];
        for side in sides {
            along += side.len();
            let mut inside = false;
            for (x, y) in side {
                let unknown = map_cell(s, x, y) == Some(Cell::Unknown);
                runs += usize::from(unknown && !inside);
                cells += usize::from(unknown);
                inside = unknown;
            }
        }
    }
    let metres = along as f64 * resolution;
    (runs as f64 / metres, cells as f64 * resolution / runs.max(1) as f64)
}

#[test]
fn wall_gaps_are_as_long_and_as_frequent_in_metres_at_any_resolution() {
    // The rate is per 5 cm of wall and the length 0.1 - 0.4 m, so a building has the same
    // holes at 2.5 and 10 cm as at 5 cm (within 30 %: the 10 cm runs round to whole cells).
    let measure = |resolution: f64| {
        let (mut per_m, mut len, n) = (0.0, 0.0, 6);
        for seed in 0..n {
            let s = gen(&building_at(resolution, SynthConfig { wall_gaps: 0.01, ..quiet() }), seed);
            let (p, l) = wall_gap_runs(&s, resolution);
            per_m += p / n as f64;
            len += l / n as f64;
        }
        (per_m, len)
    };
    let (per_m, len) = measure(0.05);
    assert!(per_m > 0.05 && len > 0.15 && len < 0.35, "at 5 cm: {per_m:.3} gaps a metre, {len:.3} m long");
    for resolution in [0.025, 0.10] {
        let (p, l) = measure(resolution);
        assert!((p / per_m - 1.0).abs() < 0.3, "{resolution} m: {p:.3} gaps a metre against {per_m:.3} at 5 cm");
        assert!((l / len - 1.0).abs() < 0.3, "{resolution} m: gaps {l:.3} m long against {len:.3} at 5 cm");
    }
}

#[test]
fn glass_lets_rays_through_and_out_and_leaves_the_truth() {
    // Quiet maps with a margin of 1.5 m outside the building, so rays have room to fan out.
    let base = SynthConfig { margin: 30, ..quiet() };
    let glazed = SynthConfig { glass: 0.5, ..base.clone() };
    let (mut outside_free, mut ring_free, mut ring) = (0usize, 0usize, 0usize);
    for seed in 0..4 {
        let (plain, glass) = (gen(&base, seed), gen(&glazed, seed));
        // The layout is drawn before the scan: the truth is the same, only the map differs.
        assert_eq!(plain.truth, glass.truth, "seed {seed}");
        let inside = |s: &Synthetic, x: i32, y: i32| s.truth.units.iter().any(|u| u.rect().contains(x, y));
        let building = glass.truth.units.iter().fold(glass.truth.units[0].rect(), |a, u| {
            let r = u.rect();
            let (x0, y0) = (a.x.min(r.x), a.y.min(r.y));
            Rect::new(x0, y0, a.right().max(r.right()) - x0, a.bottom().max(r.bottom()) - y0)
        });
        for y in 0..glass.labels.height() as i32 {
            for x in 0..glass.labels.width() as i32 {
                let beyond =
                    x < building.x - 2 || y < building.y - 2 || x > building.right() + 1 || y > building.bottom() + 1;
                if beyond {
                    assert_ne!(map_cell(&plain, x, y), Some(Cell::Free), "seed {seed}: free outside without glass");
                    outside_free += usize::from(map_cell(&glass, x, y) == Some(Cell::Free));
                }
            }
        }
        // Wall cells next to a unit's ring (one cell outwards): free only where glass is,
        // or a door.
        for u in &glass.truth.units {
            let r = u.rect();
            for x in r.x..r.right() {
                for y in [r.y - 1, r.bottom()] {
                    if !inside(&glass, x, y) {
                        ring += 1;
                        ring_free += usize::from(map_cell(&glass, x, y) == Some(Cell::Free));
                    }
                }
            }
        }
    }
    assert!(outside_free > 200, "glass let {outside_free} cells outside read free");
    let f = ring_free as f64 / ring as f64;
    // Doors alone free a few per cent of the walls; half a pane per metre of 1 - 3 m, every
    // other column crossed, frees far more.
    assert!(f > 0.2 && f < 0.95, "glass freed {f:.3} of the wall cells beside the units");
}

#[test]
fn open_hubs_are_arches_as_wide_as_the_shared_wall() {
    let c = SynthConfig { width: 600, halls: 1, ..quiet() };
    let arches = SynthConfig { open_hubs: 1.0, ..c.clone() };
    for seed in 0..4 {
        let (doors, open) = (gen(&c, seed), gen(&arches, seed));
        let hubs = |s: &Synthetic, d: &ksmcmc::floorplan::Door| {
            d.units.iter().all(|&u| matches!(s.truth.units[u as usize - 1].kind, UnitType::Corridor | UnitType::Hall))
        };
        let len = |d: &ksmcmc::floorplan::Door| (d.x1 - d.x0).abs().max((d.y1 - d.y0).abs()) + 1;
        let mut seen = 0;
        for (a, b) in doors.truth.doors.iter().zip(&open.truth.doors).filter(|(a, _)| hubs(&doors, a)) {
            assert_eq!(a.units, b.units);
            // A door is at most 1.2 m (24 cells); the arch spans the corridor's width (at least
            // 1.5 m) but the two cells kept at either end.
            assert!(len(a) <= 24, "seed {seed}: door {a:?}");
            assert!(len(b) >= 30 - 4 && len(b) > len(a), "seed {seed}: arch {b:?} against door {a:?}");
            seen += 1;
        }
        assert!(seen >= 1, "seed {seed}: no opening between hubs");
    }
}

#[test]
fn outputs_have_the_promised_formats() {
    let c = SynthConfig { resolution: 0.1, ..SynthConfig::default() };
    let s = gen(&c, 4);
    let (w, h) = (s.map.width(), s.map.height());
    let pgm = s.map_pgm();
    let head = format!("P5\n{w} {h}\n255\n");
    assert!(pgm.starts_with(head.as_bytes()));
    assert_eq!(pgm.len(), head.len() + w * h);
    assert!(pgm[head.len()..].iter().all(|v| [0, 205, 254].contains(v)));
    let labels = s.labels_pgm();
    let head = format!("P5\n{w} {h}\n65535\n");
    assert!(labels.starts_with(head.as_bytes()));
    assert_eq!(labels.len(), head.len() + 2 * w * h);
    let max = s.labels.cells().iter().max().copied().unwrap();
    assert_eq!(max as usize, s.truth.units.len());
    let yaml = s.map_yaml();
    assert!(yaml.contains("image: map.pgm") && yaml.contains("resolution: 0.1"), "{yaml}");
    // The map reads back to the same classes through its own YAML.
    let back = ksmcmc::grid::OccupancyMap::from_yaml_and_image(&yaml, &pgm, &Default::default()).unwrap();
    assert_eq!(back.classified(), s.map.classified());
    // Config JSON round trip.
    assert_eq!(SynthConfig::from_json(&c.to_json()).unwrap(), c);
}

#[test]
fn bad_configs_are_errors_naming_the_field() {
    let d = SynthConfig::default;
    let cases: Vec<(SynthConfig, &str)> = vec![
        (SynthConfig { width: 0, ..d() }, "width"),
        (SynthConfig { height: 5, ..d() }, "height"),
        (SynthConfig { width: 60_000, height: 60_000, ..d() }, "width x height"),
        (SynthConfig { width: 8000, height: 4000, rotation_deg: 45.0, ..d() }, "rotation_deg"),
        (SynthConfig { resolution: f64::NAN, ..d() }, "resolution"),
        (SynthConfig { resolution: -0.05, ..d() }, "resolution"),
        (SynthConfig { resolution: 0.0, ..d() }, "resolution"),
        (SynthConfig { rotation_deg: f64::INFINITY, ..d() }, "rotation_deg"),
        (SynthConfig { wall_thickness: 0, ..d() }, "wall_thickness"),
        (SynthConfig { wall_thickness: 20, ..d() }, "wall_thickness"),
        (SynthConfig { margin: 200, ..d() }, "margin"),
        (SynthConfig { corridors: Some(3), ..d() }, "corridors"),
        (SynthConfig { corridors: Some(0), ..d() }, "corridors"),
        (SynthConfig { halls: 5, ..d() }, "halls"),
        (SynthConfig { others: 1000, ..d() }, "others"),
        (SynthConfig { rooms: [5, 2], ..d() }, "rooms"),
        (SynthConfig { room_width: [f64::NAN, 6.0], ..d() }, "room_width"),
        (SynthConfig { room_width: [-3.0, 6.0], ..d() }, "room_width"),
        (SynthConfig { corridor_width: [2.5, 1.5], ..d() }, "corridor_width"),
        (SynthConfig { hall_width: [0.0, 10.0], ..d() }, "hall_width"),
        (SynthConfig { door_width: [2.0, 2.5], ..d() }, "door_width"),
        (SynthConfig { door_width: [0.01, 1.0], ..d() }, "door_width"),
        (SynthConfig { other_width: [1e9, 1e9], ..d() }, "other_width"),
        (SynthConfig { speckle_occupied: -0.1, ..d() }, "speckle_occupied"),
        (SynthConfig { speckle_unknown: f64::NAN, ..d() }, "speckle_unknown"),
        (SynthConfig { speckle_occupied: 0.6, speckle_unknown: 0.6, ..d() }, "speckle_occupied + speckle_unknown"),
        (SynthConfig { wall_gaps: 2.0, ..d() }, "wall_gaps"),
        (SynthConfig { clutter: 0.9, ..d() }, "clutter"),
        (SynthConfig { unexplored: -1.0, ..d() }, "unexplored"),
        (SynthConfig { peek: 1.5, ..d() }, "peek"),
        (SynthConfig { extra_doors: f64::NAN, ..d() }, "extra_doors"),
        // Valid fields, but the building cannot hold the layout.
        (SynthConfig { height: 100, corridors: Some(2), ..d() }, "height"),
        (SynthConfig { width: 300, halls: 2, ..d() }, "width"),
        (SynthConfig { height: 60, ..d() }, "height"),
        (SynthConfig { others: 100, ..d() }, "others"),
    ];
    for (c, field) in cases {
        let e = generate(&c, 1).err().unwrap_or_else(|| panic!("{field}: accepted {c:?}")).to_string();
        assert!(e.contains(field), "error for {field} does not name it: {e}");
        assert!(e.contains("accepted") || e.contains("holds") || e.contains("held"), "no accepted range: {e}");
    }
    let e = SynthConfig::from_json(r#"{"widht": 3}"#).unwrap_err().to_string();
    assert!(e.contains("widht"), "{e}");
    assert!(SynthConfig::from_json(r#"{"width": -3}"#).is_err());
}

#[test]
fn large_building_is_consistent() {
    let c = SynthConfig {
        width: 1237,
        height: 672,
        halls: 1,
        others: 4,
        clutter: 0.05,
        unexplored: 0.1,
        rotation_deg: 20.0,
        ..SynthConfig::default()
    };
    // Its generation time is measured by `ksmcmc bench` ("synthetic map generated"), not here.
    let s = gen(&c, 11);
    assert!(s.truth.units.iter().filter(|u| u.kind == UnitType::Room).count() >= 20);
    check_truth(&s, &c, 11);
}

/// FNV-1a over all four outputs.
fn fingerprint(s: &Synthetic) -> u64 {
    let mut h = 0xcbf2_9ce4_8422_2325u64;
    for bytes in [s.map_pgm(), s.map_yaml().into_bytes(), s.truth_json().into_bytes(), s.labels_pgm()] {
        for b in bytes {
            h ^= b as u64;
            h = h.wrapping_mul(0x0100_0000_01b3);
        }
    }
    h
}

/// The outputs are pinned: these fingerprints were computed natively on x86_64 and, with the
/// same code compiled to wasm32-unknown-unknown and run under node, gave the same numbers. A
/// change to the generator that alters them must update them and regenerate `samples/`.
#[test]
fn fingerprints_are_pinned() {
    let d = SynthConfig::default;
    let configs = [
        d(),
        SynthConfig { rotation_deg: 20.0, clutter: 0.1, unexplored: 0.3, ..d() },
        SynthConfig {
            width: 1217,
            height: 272,
            rotation_deg: 20.0,
            halls: 2,
            others: 3,
            clutter: 0.03,
            unexplored: 0.1,
            ..d()
        },
        SynthConfig {
            width: 440,
            height: 640,
            rotation_deg: -33.3,
            corridors: Some(2),
            wall_thickness: 2,
            resolution: 0.04,
            ..d()
        },
    ];
    let expected: [[u64; 2]; 4] = [
        [12862689927821811755, 14947760121836810273],
        [1941061354947554788, 13551425407517875875],
        [5700757946609970258, 5228937568162246352],
        [10726154137505864526, 1403276544415481367],
    ];
    for (k, c) in configs.iter().enumerate() {
        for (j, seed) in [0, 42].into_iter().enumerate() {
            assert_eq!(fingerprint(&gen(c, seed)), expected[k][j], "config {k}, seed {seed}");
        }
    }
}
