//! Online updates (`Chain::update_map`): a chain that follows a growing map keeps its world,
//! and what it redoes equals what a chain started on the new map computes.

use ksmcmc::floorplan::{synth, Chain, ChainConfig, Rect};
use ksmcmc::grid::{Cell, Grid, OccupancyMap};
use std::collections::BTreeMap;

fn floor(seed: u64) -> synth::Synthetic {
    synth::generate(&synth::SynthConfig { width: 260, height: 180, ..Default::default() }, seed).unwrap()
}

/// `map` with every cell outside `keep` unknown: what a robot has seen of it.
fn seen(map: &Grid<Cell>, keep: impl Fn(usize, usize) -> bool) -> OccupancyMap {
    let mut g = map.clone();
    for y in 0..g.height() {
        for x in 0..g.width() {
            if !keep(x, y) {
                *g.at_mut(x, y) = Cell::Unknown;
            }
        }
    }
    OccupancyMap::from_classified(g)
}

/// Upright, fixed wall depth, and no free-space detector, so that the candidate pool is the
/// wall detector's alone.
fn config() -> ChainConfig {
    let mut c = ChainConfig::default();
    c.detectors.rotation_deg = Some(0.0);
    c.detectors.free_space_start = u64::MAX / 2;
    c.wall_thickness_m = Some(0.15);
    c
}

/// The pool's rectangles and weights. The pool gives back a weight as the difference of two
/// cumulative sums, so a weight differs in its last bits with its place in the pool: weights
/// are compared to 1e-9 of the larger.
fn pool(chain: &Chain) -> BTreeMap<(i32, i32, i32, i32), f64> {
    chain.candidates().iter().map(|(r, w): (Rect, f64)| ((r.x, r.y, r.w, r.h), w)).collect()
}

fn same(a: f64, b: Option<&f64>) -> bool {
    b.is_some_and(|&b| (a - b).abs() <= 1e-9 * a.abs().max(b.abs()))
}

#[test]
fn rescored_candidates_equal_a_fresh_detector_run() {
    let mut added = 0;
    for seed in 1..=4 {
        let s = floor(seed);
        let full = s.map.classified();
        let (w, h) = (full.width(), full.height());
        // Three snapshots: the left part, then a quadrant more, then everything.
        let snapshots = [
            seen(full, |x, _| x < w * 2 / 5),
            seen(full, |x, y| x < w * 2 / 5 || (x < w * 3 / 4 && y < h / 2)),
            s.map.clone(),
        ];
        let mut chain = Chain::new(&snapshots[0], config(), seed).unwrap();
        chain.step(1500);
        for snap in &snapshots[1..] {
            let update = chain.update_map(snap).unwrap();
            assert!(update.changed_cells > 0, "seed {seed}: {update:?}");
            added += update.candidates_added;
            let fresh = Chain::new(snap, config(), seed).unwrap();
            assert!(fresh.candidates().len() < 60_000, "the detector truncated its list");
            let (a, b) = (pool(&chain), pool(&fresh));
            let only_a: Vec<_> = a.iter().filter(|(k, v)| !same(**v, b.get(k))).take(5).collect();
            let only_b: Vec<_> = b.iter().filter(|(k, v)| !same(**v, a.get(k))).take(5).collect();
            assert!(only_a.is_empty() && only_b.is_empty(), "seed {seed}: kept {only_a:?}, fresh {only_b:?}");
            assert!(chain.check_consistency(), "seed {seed}");
            chain.step(1500);
            assert!(chain.check_consistency(), "seed {seed}");
        }
    }
    // The updates did rescore: the comparison is not between two untouched pools.
    assert!(added > 100, "{added}");
}

#[test]
fn an_update_rescores_the_current_and_best_worlds_on_the_new_map() {
    let s = floor(7);
    let full = s.map.classified();
    let half = seen(full, |x, _| x < full.width() / 2);
    let mut chain = Chain::new(&half, config(), 7).unwrap();
    chain.step(4000);
    let before = (chain.log_posterior(), chain.best_log_posterior(), chain.iteration());
    let best_units = chain.best_world().units.len();
    chain.update_map(&s.map).unwrap();
    // The units stay; the map they explain changed, so the log posteriors did too.
    assert_eq!(chain.iteration(), before.2);
    assert_ne!(chain.log_posterior(), before.0);
    assert!(chain.best_log_posterior() >= chain.log_posterior());
    assert!(chain.best_world().units.len() >= best_units.min(1));
    // A chain on the full map with the same units in it scores them the same: compare
    // through K(W, M), which the explanation gives exactly.
    let k = ksmcmc::floorplan::metrics::prediction_rate(s.map.classified(), &chain.world());
    assert!((chain.prediction_rate() - k).abs() < 1e-12, "{} vs {k}", chain.prediction_rate());
    // The same snapshot again changes nothing.
    let lp = chain.log_posterior();
    let again = chain.update_map(&s.map).unwrap();
    assert_eq!(again.changed_cells, 0);
    assert_eq!(again.window, None);
    assert_eq!(chain.log_posterior(), lp);
}

#[test]
fn a_map_of_another_size_is_refused_and_nothing_changes() {
    let s = floor(3);
    let mut chain = Chain::new(&s.map, config(), 3).unwrap();
    chain.step(500);
    let lp = chain.log_posterior();
    let small = OccupancyMap::from_classified(Grid::new(100, 80, Cell::Free));
    let e = chain.update_map(&small).unwrap_err().to_string();
    assert!(e.contains("100x80") && e.contains("keep the map's size"), "{e}");
    assert_eq!(chain.log_posterior(), lp);
    assert!(chain.check_consistency());
}

#[test]
fn updates_are_deterministic() {
    let s = floor(5);
    let full = s.map.classified();
    let run = || {
        let mut chain = Chain::new(&seen(full, |x, _| x < 120), ChainConfig::default(), 11).unwrap();
        chain.step(3000);
        chain.update_map(&s.map).unwrap();
        chain.step(3000);
        serde_json::to_string(&chain.best_world()).unwrap()
    };
    assert_eq!(run(), run());
}

/// A cold chain may run longer than the warm one (`cold_budget`): it then counts the
/// iterations it needed where it would have counted the warm chain's budget, and one that
/// never comes back counts all of its own.
#[test]
fn a_cold_budget_counts_what_the_cold_chains_need() {
    use ksmcmc::floorplan::online::{explore, OnlineConfig};
    let s = synth::generate(&synth::SynthConfig { width: 200, height: 140, ..Default::default() }, 2).unwrap();
    let short = OnlineConfig { update_every_m: 6.0, iterations: 1000, cold_budget: 1000, ..Default::default() };
    let long = OnlineConfig { cold_budget: 4000, ..short };
    assert_eq!(OnlineConfig { cold_budget: 0, ..short }.cold_iterations(), 5000, "five times by default");
    let (a, b) = (
        explore(&s.map, &ChainConfig::default(), &short, 1, &mut |_| {}).unwrap(),
        explore(&s.map, &ChainConfig::default(), &long, 1, &mut |_| {}).unwrap(),
    );
    assert_eq!(a.updates(), b.updates(), "the robot drives the same way");
    for r in &a.timeline {
        assert!(r.cold_iterations.unwrap() <= 1000);
    }
    for r in &b.timeline {
        let c = r.cold_iterations.unwrap();
        assert!(c <= 4000);
        if r.cold_reached == Some(false) {
            assert_eq!(c, 4000, "update {}", r.update);
        }
    }
    assert!(
        b.timeline.iter().any(|r| r.cold_iterations.unwrap() > 1000),
        "some cold chain needs more than the warm chain's budget"
    );
}

/// Finds what it looks for once the robot has driven `metres`, and steers nowhere.
struct After {
    metres: f64,
    plans: usize,
}

impl ksmcmc::floorplan::online::Guide for After {
    fn targets(
        &mut self,
        _: &mut Chain,
        _: &ksmcmc::explore::Explorer,
    ) -> Result<Vec<ksmcmc::explore::Target>, ksmcmc::floorplan::ChainError> {
        self.plans += 1;
        Ok(Vec::new())
    }

    fn found(&mut self, e: &ksmcmc::explore::Explorer) -> bool {
        e.travelled_m() >= self.metres
    }
}

#[test]
fn a_guide_that_finds_what_it_looks_for_ends_the_exploration() {
    use ksmcmc::floorplan::online::{explore, explore_guided, OnlineConfig};
    let s = floor(3);
    let online = OnlineConfig { update_every_m: 3.0, iterations: 500, measure_cold: false, ..Default::default() };
    let full = explore(&s.map, &config(), &online, 1, &mut |_| {}).unwrap();
    assert!(full.explorer.travelled_m() > 12.0, "{}", full.explorer.travelled_m());
    let mut guide = After { metres: 7.0, plans: 0 };
    let short = explore_guided(&s.map, &config(), &online, 1, &mut |_| {}, &mut guide).unwrap();
    // It stops within one drive of 16 cells (at most 16 diagonal steps, 1.13 m) past 7 m.
    let m = short.explorer.travelled_m();
    assert!((7.0..7.0 + 16.0 * 1.5 * 0.05).contains(&m), "{m}");
    assert!(!short.explorer.is_done());
    // The guide saw the first plan and every update but the last (found before it).
    assert_eq!(guide.plans, short.updates(), "{} updates", short.updates());
    // Until then it drove as the nearest-frontier robot drives: the same cells.
    assert_eq!(short.explorer.scans(), &full.explorer.scans()[..short.explorer.scans().len()]);
}

#[test]
fn the_goal_guide_hands_the_robot_the_plans_placeholders_weighed_for_its_goal() {
    use ksmcmc::floorplan::frontier::Goal;
    use ksmcmc::floorplan::online::{GoalGuide, Guide, OnlineConfig};
    use ksmcmc::floorplan::rooms::RoomConfig;
    let s = floor(5);
    let online = OnlineConfig {
        update_every_m: 4.0,
        iterations: 2000,
        max_updates: 1,
        measure_cold: false,
        ..Default::default()
    };
    let robot = ksmcmc::explore::Explorer::new(&s.map, online.explore, 1).unwrap();
    let mut chain = Chain::new(&robot.snapshot(), ChainConfig::online(), 1).unwrap();
    chain.step(2000);
    let (world, _) = chain.best_world_with_rooms(&RoomConfig::default()).unwrap();
    assert!(!world.placeholders.is_empty(), "a first scan leaves frontiers");
    for goal in [Goal::NewRoom, Goal::Find(ksmcmc::floorplan::UnitType::Hall)] {
        let targets = GoalGuide::new(goal, true, RoomConfig::default()).targets(&mut chain, &robot).unwrap();
        assert_eq!(targets.len(), world.placeholders.len());
        for (t, p) in targets.iter().zip(&world.placeholders) {
            assert_eq!(t.cell, (p.x as usize, p.y as usize));
            assert!((0.0..=p.p_new_room).contains(&t.value), "{t:?} {p:?}");
        }
        if goal == Goal::NewRoom {
            assert!(targets.iter().zip(&world.placeholders).all(|(t, p)| t.value == p.p_new_room));
        }
        // Watching, it steers nowhere; and the first plan is what later ones are judged by.
        let mut watch = GoalGuide::new(goal, false, RoomConfig::default());
        assert!(watch.targets(&mut chain, &robot).unwrap().is_empty());
        assert!(!watch.found(&robot) && watch.found_at_m().is_none() && watch.plans() == 1);
    }
}

#[test]
fn a_finished_exploration_ends_under_the_whole_map_table_with_the_better_chain() {
    use ksmcmc::floorplan::online::{explore, OnlineConfig};
    use ksmcmc::floorplan::posterior::SensorModel;
    let s = floor(2);
    let online = OnlineConfig { update_every_m: 6.0, iterations: 1500, measure_cold: false, ..Default::default() };
    let run = explore(&s.map, &ChainConfig::online(), &online, 1, &mut |_| {}).unwrap();
    assert!(run.explorer.is_done());
    let r = run.renewal.clone().expect("a finished exploration is renewed");
    assert_eq!(r.iterations, online.cold_iterations());
    // The chain kept is the one with the higher best log posterior, under the whole-map table.
    assert_eq!(r.adopted, r.fresh_log_posterior > r.warm_log_posterior);
    assert_eq!(run.chain.best_log_posterior(), r.warm_log_posterior.max(r.fresh_log_posterior));
    assert_eq!(run.chain.config().posterior.sensor, SensorModel::default());
    let last = run.explorer.snapshot();
    let k = ksmcmc::floorplan::metrics::prediction_rate(last.classified(), &run.chain.best_world());
    let kept = if r.adopted { r.fresh_cell_prediction_rate } else { r.warm_cell_prediction_rate };
    assert_eq!(k, kept);
    assert!(run.chain.check_consistency());
    // Without renewal the warm chain stays as it was, under the range-sensor table.
    let plain = OnlineConfig { renew: false, ..online };
    let warm = explore(&s.map, &ChainConfig::online(), &plain, 1, &mut |_| {}).unwrap();
    assert!(warm.renewal.is_none());
    assert_eq!(warm.chain.config().posterior.sensor, SensorModel::range_sensor());
    assert_eq!(warm.chain.best_log_posterior(), r.range_sensor_log_posterior);
}
