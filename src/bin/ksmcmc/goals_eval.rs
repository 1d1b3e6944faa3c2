//! `ksmcmc evaluate --only goals`: how far the simulated robot drives to find a new hall, or
//! any new room, when it follows the nearest frontier and when it drives to the placeholder
//! with the most probability of reaching its goal per metre (`floorplan::online::GoalGuide`).
//!
//! Each floor is generated with the test seeds of the frontier set (the frontier rules'
//! weights were learned on other seeds), and explored from the middle of one of its rooms
//! (offices, the run seed choosing which; a robot that starts in a hall has found one), once
//! with each policy, with the chain following as in `ksmcmc explore`. A goal is
//! found when a truth unit of its type (any type for a new room) that was less than half seen
//! after the first scan is at least half seen ([`NEW_ROOM_SEEN`]); the robot stops there. The
//! metres driven and the goals chosen until then are compared on the runs where both policies
//! found it.

use crate::args::{self, CliError};
use ksmcmc::explore::Target;
use ksmcmc::explore::{ExploreConfig, Explorer};
use ksmcmc::floorplan::frontier::{seen_shares, Goal, NEW_ROOM_SEEN};
use ksmcmc::floorplan::online::{self, GoalGuide, Guide, OnlineConfig};
use ksmcmc::floorplan::rooms::RoomConfig;
use ksmcmc::floorplan::synth::{generate, SynthConfig, Synthetic};
use ksmcmc::floorplan::{Chain, ChainConfig, UnitType};
use ksmcmc::grid::Cell;
use std::time::Instant;

/// Seeds of the floors (the frontier set's test seeds).
const FLOOR_SEEDS: [u64; 3] = [4101, 4102, 4103];
/// Seeds of the runs: each draws the robot's start and seeds the chain.
const RUN_SEEDS: [u64; 3] = [1, 2, 3];

/// The goals and the kinds of generated floor each is looked for on.
fn cases() -> Vec<(Goal, &'static str, SynthConfig)> {
    let d = SynthConfig::default();
    let hall = SynthConfig { width: 600, halls: 1, ..d.clone() };
    let halls = SynthConfig { width: 700, halls: 2, ..d.clone() };
    vec![
        (Goal::Find(UnitType::Hall), "hall", hall.clone()),
        (Goal::Find(UnitType::Hall), "two halls", halls),
        (Goal::NewRoom, "office", d.clone()),
        (Goal::NewRoom, "hall", hall),
        (Goal::NewRoom, "two corridors", SynthConfig { width: 500, height: 400, corridors: Some(2), ..d.clone() }),
        (Goal::NewRoom, "many storage", SynthConfig { width: 500, others: 6, ..d }),
    ]
}

/// Where a run found its goal: metres driven and goals chosen.
type Found = (f64, usize);

/// A guide that steers (or watches) as [`GoalGuide`] and finds by the floor's truth.
struct ByTruth<'a> {
    plan: GoalGuide,
    goal: Goal,
    floor: &'a Synthetic,
    /// Truth units already at least half seen after the first scan.
    seen_at_start: Option<Vec<bool>>,
    found_at_m: Option<f64>,
    goals: usize,
}

impl ByTruth<'_> {
    /// Whether truth unit `k` (0-based) is of the goal's type.
    fn wanted(&self, k: usize) -> bool {
        self.goal.wants(self.floor.truth.units[k].kind)
    }
}

impl Guide for ByTruth<'_> {
    fn targets(
        &mut self,
        chain: &mut Chain,
        explorer: &Explorer,
    ) -> Result<Vec<Target>, ksmcmc::floorplan::ChainError> {
        self.plan.targets(chain, explorer)
    }

    fn found(&mut self, explorer: &Explorer) -> bool {
        if self.found_at_m.is_some() {
            return true;
        }
        let units = self.floor.truth.units.len();
        let shares = seen_shares(explorer.seen(), &self.floor.labels, units);
        let half: Vec<bool> = (0..units).map(|k| shares[k + 1] >= NEW_ROOM_SEEN).collect();
        let Some(start) = &self.seen_at_start else {
            self.seen_at_start = Some(half);
            return false;
        };
        if (0..units).any(|k| half[k] && !start[k] && self.wanted(k)) {
            self.found_at_m = Some(explorer.travelled_m());
            self.goals = explorer.goals();
        }
        self.found_at_m.is_some()
    }
}

/// The middle cell of the truth room (type room) the run seed picks, if it is free.
fn start_in_room(floor: &Synthetic, seed: u64) -> Option<[u32; 2]> {
    let rooms: Vec<_> = floor.truth.units.iter().filter(|u| u.kind == UnitType::Room).collect();
    let u = rooms.get((seed as usize * 7) % rooms.len().max(1))?;
    let (x, y) = (u.x + u.w / 2, u.y + u.h / 2);
    let free = floor.map.classified().get(i64::from(x), i64::from(y)) == Some(&Cell::Free);
    free.then_some([x as u32, y as u32])
}

/// One exploration's finding: metres and goals when found (`None`: never found).
fn explore_for(
    floor: &Synthetic,
    goal: Goal,
    steer: bool,
    seed: u64,
    chain: &ChainConfig,
    online: &OnlineConfig,
) -> Result<Option<Found>, CliError> {
    let online =
        OnlineConfig { explore: ExploreConfig { start: start_in_room(floor, seed), ..online.explore }, ..*online };
    let online = &online;
    let mut guide = ByTruth {
        plan: GoalGuide::new(goal, steer, RoomConfig::default()),
        goal,
        floor,
        seen_at_start: None,
        found_at_m: None,
        goals: 0,
    };
    online::explore_guided(&floor.map, chain, online, seed, &mut |_| {}, &mut guide)
        .map_err(|e| args::failed("an exploration", e))?;
    Ok(guide.found_at_m.map(|m| (m, guide.goals)))
}

/// The middle of `v` (the mean of the two middle values of an even count; 0 if empty).
fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    match v.len() {
        0 => 0.0,
        n if n % 2 == 1 => v[n / 2],
        n => (v[n / 2 - 1] + v[n / 2]) / 2.0,
    }
}

/// The goals set (module docs), with `iterations` per update, at the default update interval
/// (10 m) and at half of it.
pub fn goals(iterations: u64) -> Result<(), CliError> {
    for every in [OnlineConfig::default().update_every_m, OnlineConfig::default().update_every_m / 2.0] {
        goals_every(iterations, every)?;
    }
    Ok(())
}

/// The goals set with updates every `every` metres.
fn goals_every(iterations: u64, every: f64) -> Result<(), CliError> {
    let chain = ChainConfig::online();
    let online =
        OnlineConfig { iterations, update_every_m: every, measure_cold: false, renew: false, ..Default::default() };
    println!(
        "\n### Goal-driven exploration ({iterations} iterations per update, every {} m; floors {FLOOR_SEEDS:?}, runs {RUN_SEEDS:?})\n",
        online.update_every_m
    );
    println!("| goal | kind | runs | found (nearest / expected value) | both found | mean m (nearest / expected value) | median m | mean goals | expected value shorter / longer / same |");
    println!("|---|---|---|---|---|---|---|---|---|");
    let t0 = Instant::now();
    let mut all: Vec<(f64, f64)> = Vec::new();
    for (goal, kind, synth) in cases() {
        let (mut runs, mut found, mut both) = (0, [0usize; 2], Vec::new());
        for floor_seed in FLOOR_SEEDS {
            let floor = generate(&synth, floor_seed).map_err(|e| args::failed(kind, e))?;
            for seed in RUN_SEEDS {
                runs += 1;
                let near = explore_for(&floor, goal, false, seed, &chain, &online)?;
                let ev = explore_for(&floor, goal, true, seed, &chain, &online)?;
                found[0] += usize::from(near.is_some());
                found[1] += usize::from(ev.is_some());
                if let (Some(a), Some(b)) = (near, ev) {
                    both.push((a, b));
                }
            }
        }
        let n = both.len().max(1) as f64;
        let mean = |f: &dyn Fn(&(Found, Found)) -> f64| both.iter().map(f).sum::<f64>() / n;
        let shorter = both.iter().filter(|(a, b)| b.0 < a.0).count();
        let longer = both.iter().filter(|(a, b)| b.0 > a.0).count();
        println!(
            "| {} | {kind} | {runs} | {} / {} | {} | {:.1} / {:.1} | {:.1} / {:.1} | {:.1} / {:.1} | {shorter} / {longer} / {} |",
            goal.name(),
            found[0],
            found[1],
            both.len(),
            mean(&|p| p.0 .0),
            mean(&|p| p.1 .0),
            median(both.iter().map(|p| p.0 .0).collect()),
            median(both.iter().map(|p| p.1 .0).collect()),
            mean(&|p| p.0 .1 as f64),
            mean(&|p| p.1 .1 as f64),
            both.len() - shorter - longer
        );
        if matches!(goal, Goal::Find(UnitType::Hall)) {
            all.extend(both.iter().map(|(a, b)| (a.0, b.0)));
        }
    }
    let n = all.len().max(1) as f64;
    println!(
        "\nFinding a hall, over {} runs both found it in: nearest frontier {:.1} m, expected value {:.1} m on average ({:.0} s).",
        all.len(),
        all.iter().map(|p| p.0).sum::<f64>() / n,
        all.iter().map(|p| p.1).sum::<f64>() / n,
        t0.elapsed().as_secs_f64()
    );
    Ok(())
}
