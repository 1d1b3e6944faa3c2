//! `ksmcmc evaluate --only settle`: which settle rule (floorplan::settled) stops a chain as soon
//! as its plan is as good as the command's default budget makes it.
//!
//! The live mapper stops when the best world has settled; `ksmcmc floorplan` runs 20,000
//! iterations, the budget whose quality BENCHMARKS reports. A rule that waits longer than the
//! plan needs makes the page slow for nothing; one that stops sooner gives a worse plan. Each
//! map's chain runs once, to [`CAP`] iterations, watched by every candidate rule at once; the
//! plan is scored when the chain passes 20,000 iterations and where each rule would have
//! stopped. The rule is chosen on generated floors, whose truth is known, by a criterion fixed
//! before looking at the benchmark floors (the fewest iterations among rules whose plans are on
//! average as good as at 20,000 within [`TOLERANCE`]); the benchmark floors and Cartesium,
//! scored the same way, are the held-out figures.

use crate::args::{self, CliError};
use crate::score::truth_regions;
use ksmcmc::floorplan::metrics::{prediction_rate, score_segmentation};
use ksmcmc::floorplan::rooms::RoomConfig;
use ksmcmc::floorplan::settled::{Settled, STRIDE};
use ksmcmc::floorplan::synth::{generate, SynthConfig};
use ksmcmc::floorplan::{Chain, ChainConfig};
use ksmcmc::grid::{Cell, Classifier, Grid, OccupancyMap};
use std::collections::BTreeMap;
use std::path::Path;

/// The most iterations a chain runs; a rule that has not stopped by then counts as stopping
/// here.
const CAP: u64 = 150_000;
/// The command's default budget, the reference.
const REFERENCE: u64 = 20_000;
/// How far a rule's mean precision, recall (and K(W,M) / 4) may fall below the reference's.
const TOLERANCE: f64 = 0.005;
/// How far any one map's precision or recall may fall below its reference.
const WORST: f64 = 0.02;

/// A candidate rule: iterations of window per square metre of free floor, the fewest
/// iterations of window, and the relative threshold of the best log posterior.
#[derive(Clone, Copy, Debug)]
pub struct Rule {
    pub per_m2: f64,
    pub min_window: u64,
    pub relative: f64,
}

impl Rule {
    fn watcher(&self, free_cells: usize, resolution: f64) -> Settled {
        Settled::scaled(free_cells, resolution, self.per_m2, self.min_window, self.relative)
    }

    fn name(&self) -> String {
        format!("{} / m2, at least {}, {:e}", self.per_m2, self.min_window, self.relative)
    }
}

/// The candidates: the rule before this set first (a quarter of the free cells at 0.05 m is
/// 100 iterations per m2, at least 5,000; 1e-4), then shorter windows and coarser thresholds.
fn rules() -> Vec<Rule> {
    let mut v = vec![Rule { per_m2: 100.0, min_window: 5_000, relative: 1e-4 }];
    for (per_m2, min_window) in [(20.0, 2_000), (10.0, 2_000), (5.0, 2_000), (5.0, 1_000), (2.5, 1_000)] {
        for relative in [3e-4, 1e-3, 3e-3] {
            v.push(Rule { per_m2, min_window, relative });
        }
    }
    v
}

/// The plan's figures: precision, recall and K(W,M).
type Figures = [f64; 3];

/// One map's run: the reference figures and, per rule, the stop and the figures there.
struct MapRun {
    reference: Figures,
    stops: Vec<(u64, Figures)>,
}

/// Runs `map`'s chain to [`CAP`] under every rule, scoring with `score` at the reference and
/// at each rule's stop.
fn run_map(
    map: &OccupancyMap,
    config: &ChainConfig,
    seed: u64,
    score: &mut dyn FnMut(&mut Chain) -> Result<Figures, CliError>,
) -> Result<MapRun, CliError> {
    let mut chain = Chain::new(map, config.clone(), seed).map_err(|e| CliError::Failed(e.to_string()))?;
    let free = map.count(Cell::Free);
    let rules = rules();
    let mut watchers: Vec<Settled> = rules.iter().map(|r| r.watcher(free, chain.resolution())).collect();
    let mut stop: Vec<Option<u64>> = vec![None; rules.len()];
    let mut scored: BTreeMap<u64, Figures> = BTreeMap::new();
    for w in &mut watchers {
        w.look(&chain);
    }
    while chain.iteration() < CAP && (stop.iter().any(Option::is_none) || chain.iteration() < REFERENCE) {
        chain.step(STRIDE);
        let it = chain.iteration();
        let mut want = it == REFERENCE;
        for (w, s) in watchers.iter_mut().zip(stop.iter_mut()) {
            w.look(&chain);
            if s.is_none() && (w.settled_at().is_some() || it >= CAP) {
                *s = Some(it);
                want = true;
            }
        }
        if want && !scored.contains_key(&it) {
            scored.insert(it, score(&mut chain)?);
        }
    }
    let stops = stop.iter().map(|s| s.unwrap_or(CAP)).map(|s| (s, scored[&s])).collect();
    Ok(MapRun { reference: scored[&REFERENCE], stops })
}

fn mean(v: impl Iterator<Item = f64>) -> f64 {
    let (s, n) = v.fold((0.0, 0usize), |(s, n), x| (s + x, n + 1));
    s / n.max(1) as f64
}

/// Per rule over `runs`: mean stop iteration, mean figures minus the reference's, and the
/// worst map's fall in precision or recall.
fn table(title: &str, runs: &[(String, MapRun)]) {
    println!("\n#### {title} ({} maps)\n", runs.len());
    let r = |k: usize| mean(runs.iter().map(|(_, m)| m.reference[k]));
    println!("Reference ({REFERENCE} iterations): precision {:.4}, recall {:.4}, K(W,M) {:.4}\n", r(0), r(1), r(2));
    println!("| rule | mean iterations | max | precision - ref | recall - ref | K - ref | worst map fall |");
    println!("|---|---|---|---|---|---|---|");
    for (i, rule) in rules().iter().enumerate() {
        let its = runs.iter().map(|(_, m)| m.stops[i].0 as f64);
        let max = runs.iter().map(|(_, m)| m.stops[i].0).max().unwrap_or(0);
        let d = |k: usize| mean(runs.iter().map(|(_, m)| m.stops[i].1[k] - m.reference[k]));
        let worst = runs
            .iter()
            .map(|(_, m)| (m.reference[0] - m.stops[i].1[0]).max(m.reference[1] - m.stops[i].1[1]))
            .fold(f64::NEG_INFINITY, f64::max);
        println!(
            "| {} | {:.0} | {max} | {:+.4} | {:+.4} | {:+.4} | {:.3} |",
            rule.name(),
            mean(its),
            d(0),
            d(1),
            d(2),
            worst
        );
    }
}

/// The index of the rule the criterion chooses on `runs`: the fewest mean iterations among
/// those within [`TOLERANCE`] of the reference in mean precision and recall, K(W,M) within a
/// quarter of it, and no map's precision or recall more than [`WORST`] below its own.
fn choose(runs: &[&(String, MapRun)]) -> Option<usize> {
    let ok = |i: usize| {
        let d = |k: usize| mean(runs.iter().map(|(_, m)| m.stops[i].1[k] - m.reference[k]));
        let worst = runs.iter().all(|(_, m)| (0..2).all(|k| m.stops[i].1[k] >= m.reference[k] - WORST));
        d(0) >= -TOLERANCE && d(1) >= -TOLERANCE && d(2) >= -TOLERANCE / 4.0 && worst
    };
    let its = |i: usize| mean(runs.iter().map(|(_, m)| m.stops[i].0 as f64));
    (0..rules().len()).filter(|&i| ok(i)).min_by(|&a, &b| its(a).total_cmp(&its(b)))
}

/// Leave one floor out: for each benchmark floor (plain and furnished together), the rule
/// chosen on the generated floors and the other floors, and the held-out floor's figures
/// under it beside its reference.
fn leave_one_floor_out(generated: &[(String, MapRun)], held: &[(String, MapRun)]) {
    println!("\n#### Leave one floor out: the rule chosen without the floor, on the floor\n");
    println!("| held-out floor | rule chosen on the others | stops at (plain, furnished) | precision / recall there | at {REFERENCE} |");
    println!("|---|---|---|---|---|");
    let floor = |n: &str| n.trim_end_matches("_furnitures").to_string();
    let mut floors: Vec<String> = held.iter().map(|(n, _)| floor(n)).collect();
    floors.dedup();
    let (mut its, mut d) = (Vec::new(), [Vec::new(), Vec::new()]);
    for f in &floors {
        let pool: Vec<&(String, MapRun)> =
            generated.iter().chain(held.iter().filter(|(n, _)| floor(n) != *f)).collect();
        let Some(i) = choose(&pool) else {
            println!("| {f} | none within the tolerance | | | |");
            continue;
        };
        let out: Vec<&(String, MapRun)> = held.iter().filter(|(n, _)| floor(n) == *f).collect();
        let at: Vec<String> = out.iter().map(|(_, m)| m.stops[i].0.to_string()).collect();
        let there: Vec<String> =
            out.iter().map(|(_, m)| format!("{:.3} / {:.3}", m.stops[i].1[0], m.stops[i].1[1])).collect();
        let refs: Vec<String> =
            out.iter().map(|(_, m)| format!("{:.3} / {:.3}", m.reference[0], m.reference[1])).collect();
        for (_, m) in &out {
            its.push(m.stops[i].0 as f64);
            for (k, dk) in d.iter_mut().enumerate() {
                dk.push(m.stops[i].1[k] - m.reference[k]);
            }
        }
        println!("| {f} | {} | {} | {} | {} |", rules()[i].name(), at.join(", "), there.join(", "), refs.join(", "));
    }
    println!(
        "\nHeld out, over the floors' maps: mean stop {:.0} iterations, precision {:+.4} and recall {:+.4} against {REFERENCE}.",
        mean(its.into_iter()),
        mean(d[0].iter().copied()),
        mean(d[1].iter().copied())
    );
}

/// Per map, each rule's stop (for the chosen rule and the rule before this set).
fn per_map(runs: &[(String, MapRun)], chosen: Option<usize>) {
    let Some(c) = chosen else { return };
    println!("\n| map | precision / recall / K at {REFERENCE} | chosen rule stops at | precision / recall / K there | old rule stops at |");
    println!("|---|---|---|---|---|");
    for (name, m) in runs {
        let f = |x: Figures| format!("{:.3} / {:.3} / {:.4}", x[0], x[1], x[2]);
        println!("| {name} | {} | {} | {} | {} |", f(m.reference), m.stops[c].0, f(m.stops[c].1), m.stops[0].0);
    }
}

/// The generated floors the rule is chosen on.
fn kinds() -> Vec<(&'static str, SynthConfig)> {
    let d = SynthConfig::default();
    vec![
        ("office", d.clone()),
        ("furnished", SynthConfig { clutter: 0.1, ..d.clone() }),
        ("hall", SynthConfig { halls: 1, ..d.clone() }),
        ("two corridors", SynthConfig { corridors: Some(2), width: 480, height: 400, ..d.clone() }),
        ("large 1237x672", SynthConfig { width: 1237, height: 672, halls: 1, ..d.clone() }),
        ("rotated 20 deg", SynthConfig { rotation_deg: 20.0, ..d }),
    ]
}

pub fn settle(dir: &Path, config: &ChainConfig, rooms: &RoomConfig, seeds: u64) -> Result<(), CliError> {
    println!("\n### Settle rules: where each stops and the plan there (`evaluate --only settle`)");
    let mut generated = Vec::new();
    for (name, synth) in kinds() {
        for seed in 0..seeds {
            let s = generate(&synth, 600 + seed).map_err(|e| args::failed(name, e))?;
            let truth: Grid<u32> = s.labels.map(|&l| l as u32);
            let mut score = |chain: &mut Chain| -> Result<Figures, CliError> {
                let (world, labels) = chain.best_world_with_rooms(rooms).map_err(|e| args::failed("rooms", e))?;
                let seg = score_segmentation(&labels.map(|&l| l as u32), &truth);
                Ok([seg.precision, seg.recall, prediction_rate(s.map.classified(), &world)])
            };
            generated.push((format!("{name} {}", 600 + seed), run_map(&s.map, config, 1, &mut score)?));
        }
    }
    table("Generated floors", &generated);
    let index = choose(&generated.iter().collect::<Vec<_>>());
    println!(
        "\nChosen on the generated floors alone: {}",
        index.map_or("none within the tolerance".into(), |i| rules()[i].name())
    );
    per_map(&generated, index);

    let mut held = Vec::new();
    let bormann = dir.join("bormann2016");
    let mut names: Vec<String> = std::fs::read_dir(&bormann)
        .map_err(|e| args::failed(bormann.display(), e))?
        .filter_map(|e| e.ok()?.file_name().into_string().ok())
        .filter_map(|n| n.strip_suffix("_gt_segmentation.png").map(str::to_string))
        .collect();
    names.sort();
    for name in &names {
        let truth = truth_regions(&bormann.join(format!("{name}_gt_segmentation.png")))?;
        for suffix in ["", "_furnitures"] {
            let mut map = args::load_map(&bormann.join(format!("{name}{suffix}.png")))?;
            map.set_classifier(Classifier::auto()).map_err(|e| args::failed("classifier", e))?;
            let mut score = |chain: &mut Chain| -> Result<Figures, CliError> {
                let (world, labels) = chain.best_world_with_rooms(rooms).map_err(|e| args::failed("rooms", e))?;
                let seg = score_segmentation(&labels.map(|&l| l as u32), &truth);
                Ok([seg.precision, seg.recall, prediction_rate(map.classified(), &world)])
            };
            held.push((format!("{name}{suffix}"), run_map(&map, config, 1, &mut score)?));
        }
    }
    let path = dir.join("radish/ubremen-cartesium.png");
    let map = args::load_classified(&path, "auto")?;
    let mut score = |chain: &mut Chain| -> Result<Figures, CliError> {
        let world = chain.best_world();
        let rooms = chain.best_world_with_rooms(rooms).map_err(|e| args::failed("rooms", e))?.0.rooms.len();
        // No room truth: precision stands for K(W,M) and recall for the rooms' count.
        Ok([0.0, rooms as f64, prediction_rate(map.classified(), &world)])
    };
    let cartesium = run_map(&map, config, 1, &mut score)?;
    table("Benchmark floors, plain and furnished", &held);
    per_map(&held, index);
    leave_one_floor_out(&generated, &held);
    let all: Vec<&(String, MapRun)> = generated.iter().chain(held.iter()).collect();
    let index = choose(&all);
    println!(
        "\nChosen on all of them (the shipped rule): {}",
        index.map_or("none within the tolerance".into(), |i| rules()[i].name())
    );
    println!(
        "\nCartesium (no room truth; rooms and K(W,M)): at {REFERENCE} {} rooms, K {:.4}",
        cartesium.reference[1], cartesium.reference[2]
    );
    for (i, rule) in rules().iter().enumerate() {
        let (at, f) = cartesium.stops[i];
        println!("- {}: stops at {at}, {} rooms, K {:.4}", rule.name(), f[1], f[2]);
    }
    Ok(())
}
