//! The chain's bookkeeping, determinism and input checks.

#![allow(clippy::field_reassign_with_default)] // configs are built by adjusting defaults, field by field

use ksmcmc::floorplan::{Chain, ChainConfig, ChainError};
use ksmcmc::floorplan::{KernelWeights, Schedule};
use ksmcmc::grid::{Cell, Grid, OccupancyMap};

/// Three rooms in a row with doors between them and a corridor below; walls 2 cells thick.
fn rooms_map() -> Grid<Cell> {
    let (w, h) = (64, 40);
    let mut g = Grid::new(w, h, Cell::Unknown);
    let mut room = |x0: usize, y0: usize, x1: usize, y1: usize| {
        for y in y0..=y1 {
            for x in x0..=x1 {
                let edge = x <= x0 + 1 || x >= x1 - 1 || y <= y0 + 1 || y >= y1 - 1;
                *g.at_mut(x, y) = if edge { Cell::Occupied } else { Cell::Free };
            }
        }
    };
    room(0, 0, 21, 25);
    room(20, 0, 41, 25);
    room(40, 0, 63, 25);
    room(0, 24, 63, 39);
    // Doors: between rooms, and from each room to the corridor.
    for y in 10..16 {
        for x in 20..22 {
            *g.at_mut(x, y) = Cell::Free;
            *g.at_mut(x + 20, y) = Cell::Free;
        }
    }
    for x in [8usize, 28, 50] {
        for dx in 0..6 {
            for y in 24..26 {
                *g.at_mut(x + dx, y) = Cell::Free;
            }
        }
    }
    // Clutter.
    *g.at_mut(10, 10) = Cell::Unknown;
    *g.at_mut(30, 30) = Cell::Occupied;
    g
}

fn all_kernels_config() -> ChainConfig {
    let mut c = ChainConfig::default();
    c.schedule = Schedule::constant(KernelWeights([0.15, 0.1, 0.1, 0.1, 0.1, 0.1, 0.1, 0.15, 0.1]));
    c.doors.min_m = 0.2;
    c.detectors.free_space_start = 200;
    c.detectors.free_space_every = 150;
    // Hot, so that the chain keeps moving and every kernel applies and undoes many moves.
    c.posterior.temperature = 30.0;
    c.kernels.min_side_m = 0.3;
    c.detectors.rotation_deg = Some(0.0);
    c
}

#[test]
fn incremental_posterior_equals_full_recomputation_after_every_step() {
    let map = OccupancyMap::from_classified(rooms_map());
    for seed in 0..4 {
        let mut config = all_kernels_config();
        // Thin rings (the dissertation's model, one 5 cm cell) and thick ones (two).
        config.wall_thickness_m = Some(0.05 * (1 + seed % 2) as f64);
        let mut chain = Chain::new(&map, config, seed).unwrap();
        let mut doors_seen = 0;
        for i in 0..2500 {
            chain.step(1);
            assert!(chain.check_consistency(), "seed {seed}: bookkeeping diverged at step {i}");
            doors_seen = doors_seen.max(chain.current_rects().1.len());
        }
        let t = chain.trace();
        for k in ksmcmc::floorplan::Kernel::ALL {
            assert!(t.proposed[k.index()] > 0, "seed {seed}: {} never proposed", k.name());
        }
        assert!(t.total_accepted() > 50, "seed {seed}: the chain barely moved: {:?}", t.accepted);
        assert!(doors_seen > 0, "seed {seed}: no door was ever allocated");
    }
}

#[test]
fn explains_a_clean_map_well() {
    let map = OccupancyMap::from_classified(rooms_map());
    let mut chain = Chain::new(&map, ChainConfig::default(), 3).unwrap();
    chain.step(8000);
    let k = chain.best_prediction_rate();
    assert!(k > 0.95, "K(W,M) = {k}");
    let best = chain.best_world();
    assert!((3..=6).contains(&best.units.len()), "{} units", best.units.len());
    best.validate().unwrap();
    // The best world is never worse than the current one.
    assert!(chain.best_log_posterior() >= chain.log_posterior());
}

#[test]
fn same_seed_same_chain_different_seed_different_chain() {
    let map = OccupancyMap::from_classified(rooms_map());
    let run = |seed| {
        let mut c = Chain::new(&map, all_kernels_config(), seed).unwrap();
        c.step(3000);
        (c.world().to_json(), c.log_posterior(), c.trace().accepted)
    };
    assert_eq!(run(42), run(42));
    assert_ne!(run(42).0, run(43).0);
}

#[test]
fn run_for_respects_its_budget_and_clock() {
    let map = OccupancyMap::from_classified(rooms_map());
    let mut chain = Chain::new(&map, ChainConfig::default(), 1).unwrap();
    // A fake clock advancing 1 ms per reading: a 10 ms budget allows about ten 16-step rounds.
    let mut t = 0.0;
    let n = chain.run_for(10.0, &mut || {
        t += 1.0;
        t
    });
    assert_eq!(n % 16, 0);
    assert!((16..=16 * 11).contains(&n), "{n}");
    assert_eq!(chain.iteration(), n);
}

#[test]
fn bad_maps_and_configs_are_errors() {
    let free = OccupancyMap::from_classified(Grid::new(40, 30, Cell::Occupied));
    let e = Chain::new(&free, ChainConfig::default(), 1).unwrap_err();
    assert!(matches!(e, ChainError::Map(_)) && e.to_string().contains("no free cells"), "{e}");
    let one = OccupancyMap::from_classified(Grid::new(1, 1, Cell::Free));
    let e = Chain::new(&one, ChainConfig::default(), 1).unwrap_err();
    assert!(e.to_string().contains("1x1"), "{e}");
    let map = OccupancyMap::from_classified(rooms_map());
    // Each bad setting is named by its path in the configuration's JSON, with what it must be.
    let mut cases: Vec<(ChainConfig, &str, &str)> = Vec::new();
    let mut c = ChainConfig::default();
    c.posterior.temperature = f64::NAN;
    cases.push((c, "posterior.temperature", "a positive number"));
    let mut c = ChainConfig::default();
    c.posterior.overlap_penalty = -1.0;
    cases.push((c, "posterior.overlap_penalty", "in (0, 1]"));
    let mut c = ChainConfig::default();
    c.posterior.sensor.table[0][0] = 0.0;
    cases.push((c, "posterior.sensor.table", "a probability in (0, 1]"));
    let mut c = ChainConfig::default();
    c.kernels.shift_sigma_m = f64::INFINITY;
    cases.push((c, "kernels.shift_sigma_m", "metres above 0, at most 50"));
    let mut c = ChainConfig::default();
    c.kernels.min_side_m = 0.0;
    cases.push((c, "kernels.min_side_m", "metres above 0, at most 100"));
    let mut c = ChainConfig::default();
    c.schedule = Schedule::constant(KernelWeights([0.0; 9]));
    cases.push((c, "schedule.phases.weights", "positive for at least one kernel"));
    let mut c = ChainConfig::default();
    c.schedule = Schedule::constant(KernelWeights([1.0, -1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]));
    cases.push((c, "schedule.phases.weights", "finite and non-negative"));
    let mut c = ChainConfig::default();
    c.doors.min_m = 2.5;
    cases.push((c, "doors.min_m", "metres above 0, at most max_m"));
    let mut c = ChainConfig::default();
    c.detectors.rotation_deg = Some(f64::NAN);
    cases.push((c, "detectors.rotation_deg", "a number of degrees"));
    let mut c = ChainConfig::default();
    c.knowledge.time_share = 0.0;
    cases.push((c, "knowledge.time_share", "in (0, 1]"));
    let mut c = ChainConfig::default();
    c.output.trace_every = 0;
    cases.push((c, "output.trace_every", "at least 1"));
    for (c, field, expected) in cases {
        let e = Chain::new(&map, c, 1).unwrap_err();
        let ChainError::Config(s) = &e else { panic!("{field}: {e}") };
        assert_eq!((s.field(), s.expected()), (field, expected), "{e}");
        assert!(e.to_string().starts_with(&format!("invalid chain configuration: {field} ")), "{e}");
        assert!(std::error::Error::source(&e).is_some(), "{e}");
    }
}

#[test]
fn config_json_accepts_partial_objects() {
    let c: ChainConfig =
        serde_json::from_str(r#"{"posterior": {"temperature": 2.0}, "kernels": {"min_side_m": 0.2}}"#).unwrap();
    assert_eq!(c.posterior.temperature, 2.0);
    assert_eq!(c.kernels.min_side_cells(0.05), 4);
    assert_eq!(c.posterior.overlap_penalty, ChainConfig::default().posterior.overlap_penalty);
}

/// `ChainConfig::from_json`, which the CLI's `--config` and the browser's `configJson` share:
/// blank text is the defaults, and every refusal says what is wrong.
#[test]
fn config_json_errors_name_the_problem() {
    assert_eq!(ChainConfig::from_json(" ").unwrap(), ChainConfig::default());
    assert_eq!(ChainConfig::from_json("{}").unwrap(), ChainConfig::default());
    let c = ChainConfig::from_json(r#"{"posterior": {"temperature": 2.0}, "kernels": {"min_side_m": 0.2}}"#).unwrap();
    assert_eq!((c.posterior.temperature, c.kernels.min_side_cells(0.05)), (2.0, 4));
    let err = |json: &str| ChainConfig::from_json(json).unwrap_err().to_string();
    for (json, needle) in [
        ("{", "chain config"),
        ("[1, 2]", "JSON object"),
        (r#"{"posterior": {"temperature": NaN}}"#, "NaN"),
        (r#"{"posterior": {"temperature": -1}}"#, "temperature -1"),
        (r#"{"posterior": {"temprature": 2}}"#, "unknown field `posterior.temprature`"),
        (r#"{"iterations": 5}"#, "unknown field `iterations`"),
        (r#"{"kernels": {"min_side": "big"}}"#, "chain config"),
    ] {
        let e = err(json);
        assert!(e.contains(needle), "{json}: {e}");
    }
}

#[test]
fn knowledge_types_units_and_stays_deterministic() {
    let map = OccupancyMap::from_classified(rooms_map());
    let mut c = ChainConfig::default();
    c.knowledge.enabled = true;
    c.knowledge.every = 200;
    let run = |seed| {
        let mut chain = Chain::new(&map, c.clone(), seed).unwrap();
        chain.step(4000);
        assert!(chain.knowledge_error().is_none(), "{:?}", chain.knowledge_error());
        assert!(chain.inferences() > 0, "inference never ran");
        (chain.best_world().to_json(), chain.inferred().types.len())
    };
    let (a, typed) = run(5);
    assert!(typed > 0);
    let world = ksmcmc::floorplan::World::from_json(&a).unwrap();
    assert!(world.units.iter().any(|u| u.kind != ksmcmc::floorplan::UnitType::Unknown), "no unit got a type");
    assert_eq!(run(5).0, a, "same seed, same world with knowledge");
}

#[test]
fn a_broken_knowledge_base_is_a_clear_error() {
    let map = OccupancyMap::from_classified(rooms_map());
    let mut c = ChainConfig::default();
    c.knowledge.enabled = true;
    c.knowledge.kb = Some("Room(unit)\nRoom(x) => Corr(x)\n".into());
    let e = Chain::new(&map, c, 1).unwrap_err();
    assert!(matches!(e, ChainError::Knowledge(_)), "{e}");
    assert!(e.to_string().contains("line 2"), "{e}");
    let mut c = ChainConfig::default();
    c.knowledge.object_share = f64::NAN;
    assert!(matches!(Chain::new(&map, c, 1).unwrap_err(), ChainError::Config(_)));
}

#[test]
fn config_json_refuses_misspelt_fields() {
    for text in
        [r#"{"posterior": {"temprature": 2.0}}"#, r#"{"kernel": {}}"#, r#"{"detectors": {"walls": {"min_segmnt": 3}}}"#]
    {
        let e = serde_json::from_str::<ChainConfig>(text).unwrap_err().to_string();
        assert!(e.contains("unknown field"), "{text}: {e}");
    }
}

/// The world's unexplained areas ("N") are exactly the free cells outside every unit and door,
/// in components of at least `MIN_UNEXPLAINED_CELLS`, counted here the slow way.
#[test]
fn unexplained_areas_list_every_uncovered_free_cell() {
    use ksmcmc::floorplan::unexplained::MIN_UNEXPLAINED_CELLS;
    // The building, with a patch of free space beside it (5x5, below the free-space detector's
    // 60 cells, without walls) that no unit explains.
    let rooms = rooms_map();
    let mut grid = Grid::new(rooms.width() + 16, rooms.height(), Cell::Unknown);
    for y in 0..rooms.height() {
        for x in 0..rooms.width() {
            *grid.at_mut(x, y) = *rooms.at(x, y);
        }
    }
    for y in 10..15 {
        for x in 70..75 {
            *grid.at_mut(x, y) = Cell::Free;
        }
    }
    let map = OccupancyMap::from_classified(grid.clone());
    for (seed, steps) in [(1, 0), (2, 300), (3, 6000)] {
        let mut config = ChainConfig::default();
        config.detectors.rotation_deg = Some(0.0);
        let mut chain = Chain::new(&map, config, seed).unwrap();
        chain.step(steps);
        let world = chain.best_world();
        world.validate().unwrap();
        let mut covered = Grid::new(grid.width(), grid.height(), false);
        for r in world.units.iter().map(|u| u.rect()).chain(world.doors.iter().map(|d| d.rect())) {
            for y in r.y..r.bottom() {
                for x in r.x..r.right() {
                    *covered.at_mut(x as usize, y as usize) = true;
                }
            }
        }
        let mut listed = Grid::new(grid.width(), grid.height(), false);
        for a in &world.unexplained {
            assert!(a.cells as usize >= MIN_UNEXPLAINED_CELLS);
            for &[y, x0, x1] in &a.runs {
                for x in x0..=x1 {
                    let (x, y) = (x as usize, y as usize);
                    assert_eq!(*grid.at(x, y), Cell::Free, "seed {seed}: listed cell ({x},{y}) is not free");
                    assert!(!*covered.at(x, y), "seed {seed}: listed cell ({x},{y}) is inside a unit or door");
                    assert!(!*listed.at(x, y), "seed {seed}: cell ({x},{y}) listed twice");
                    *listed.at_mut(x, y) = true;
                }
            }
        }
        let uncovered_free = (0..grid.height())
            .flat_map(|y| (0..grid.width()).map(move |x| (x, y)))
            .filter(|&(x, y)| *grid.at(x, y) == Cell::Free && !*covered.at(x, y))
            .count();
        let listed_cells: usize = world.unexplained.iter().map(|a| a.cells as usize).sum();
        if steps == 0 {
            // The empty world explains nothing: one area per room-sized component, all cells.
            assert!(world.units.is_empty());
            assert_eq!(listed_cells, uncovered_free, "seed {seed}");
        } else {
            // Whatever is not listed is in components below the size floor.
            assert!(uncovered_free - listed_cells < MIN_UNEXPLAINED_CELLS * 8, "seed {seed}");
        }
        // The patch beside the building is listed, exactly.
        if steps == 6000 {
            assert!(
                world.unexplained.iter().any(|a| (a.x0, a.y0, a.x1, a.y1, a.cells) == (70, 10, 74, 14, 25)),
                "seed {seed}: the patch is not listed: {:?}",
                world.unexplained.iter().map(|a| (a.x0, a.y0, a.x1, a.y1)).collect::<Vec<_>>()
            );
        }
    }
}

/// Door sizes are metres, turned into cells from the map's resolution; the cell names of
/// older versions are refused by name rather than read as metres.
#[test]
fn door_sizes_are_metres_and_cell_names_are_refused() {
    let c = ChainConfig::from_json(r#"{"doors": {"min_m": 0.8}}"#).unwrap();
    assert_eq!((c.doors.cells(0.05).min_len, c.doors.cells(0.1).min_len, c.doors.cells(0.025).min_len), (16, 8, 32));
    let e = ChainConfig::from_json(r#"{"doors": {"min_len": 10}}"#).unwrap_err().to_string();
    assert!(e.contains("min_len"), "{e}");
    let e = ChainConfig::from_json(r#"{"doors": {"min_m": 0}}"#).unwrap_err().to_string();
    assert!(e.contains("doors"), "{e}");
}

#[test]
fn the_wall_ring_is_configured_in_metres_and_turned_into_cells_by_the_resolution() {
    // Issue 31: lengths in metres. 0.15 m of wall is three 5 cm cells, two 10 cm cells (1.5
    // rounds up) and one 25 cm cell; the ring is at least one cell whatever the resolution.
    let at = |resolution: f64, m: f64| {
        let mut yaml = ksmcmc::grid::MapYaml::for_image("map.pgm");
        yaml.resolution = resolution;
        let map = OccupancyMap::from_classified(rooms_map()).with_yaml(yaml);
        let config = ChainConfig { wall_thickness_m: Some(m), ..ChainConfig::default() };
        Chain::new(&map, config, 1).unwrap().wall_thickness()
    };
    assert_eq!([at(0.05, 0.15), at(0.1, 0.15), at(0.25, 0.15), at(0.5, 0.05)], [3, 2, 1, 1]);
    // Bad thicknesses are refused, saying the unit.
    for bad in [0.0, -0.1, f64::NAN, f64::INFINITY, 1.5] {
        let config = ChainConfig { wall_thickness_m: Some(bad), ..ChainConfig::default() };
        let err = config.validate().expect_err("a bad thickness").to_string();
        assert!(err.contains("wall_thickness_m") && err.contains("metres"), "{err}");
    }
    // The old field in cells is refused by name, with the fields that exist.
    let err = serde_json::from_str::<ChainConfig>(r#"{"wall_thickness": 3}"#).unwrap_err().to_string();
    assert!(err.contains("wall_thickness") && err.contains("wall_thickness_m"), "{err}");
}
