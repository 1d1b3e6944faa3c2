//! `ksmcmc bench`: speed of the engine on fixed inputs, for BENCHMARKS.md.
//!
//! Speed lives here, not in timed tests: numbers depend on the machine, so the command prints
//! them with the machine's description and they are recorded by hand.

use crate::args::{self, CliError};
use ksmcmc::floorplan::synth::{generate, SynthConfig};
use ksmcmc::floorplan::{metrics, Chain, ChainConfig};
use ksmcmc::grid::{Classifier, OccupancyMap};
use std::ffi::OsString;
use std::path::PathBuf;
use std::time::Instant;

const HELP: &str = "\
Usage: ksmcmc bench [--iterations N] [--datasets DIR] [--seed S]

Runs the floor-plan chain on the Radish Cartesium map (from DIR, default ../shared/datasets)
and on synthetic maps of 556x322 and 1237x672 cells, and prints for each: iterations per
second over the whole chain (N iterations, default 20000), the setup time (orientation,
detectors), the time and iteration at which the chain first came within 0.1 % of its final
best log posterior (time to convergence), and K(W,M); then how long `ksmcmc synth` takes to
generate the two synthetic maps (the rotated 1237x672 office of the synth tests among them).
";

struct Row {
    name: String,
    cells: (usize, usize),
    setup: f64,
    seconds: f64,
    iterations: u64,
    converged_at: u64,
    converged_s: f64,
    k: f64,
}

fn run_one(name: &str, map: &OccupancyMap, iterations: u64, seed: u64) -> Result<Row, CliError> {
    let t0 = Instant::now();
    let mut chain = Chain::new(map, ChainConfig::default(), seed).map_err(|e| args::failed(name, e))?;
    let setup = t0.elapsed().as_secs_f64();
    let start = chain.log_posterior();
    let t1 = Instant::now();
    // Record (iteration, seconds, best) every 250 iterations to find the convergence point.
    let mut marks = Vec::new();
    while chain.iteration() < iterations {
        chain.step(250.min(iterations - chain.iteration()));
        marks.push((chain.iteration(), t1.elapsed().as_secs_f64(), chain.best_log_posterior()));
    }
    let seconds = t1.elapsed().as_secs_f64();
    let best = chain.best_log_posterior();
    let target = best - 0.001 * (best - start).abs();
    let (converged_at, converged_s) =
        marks.iter().find(|m| m.2 >= target).map(|m| (m.0, m.1)).unwrap_or((iterations, seconds));
    Ok(Row {
        name: name.to_string(),
        cells: (map.width(), map.height()),
        setup,
        seconds,
        iterations: chain.iteration(),
        converged_at,
        converged_s,
        k: metrics::prediction_rate(map.classified(), &chain.best_world()),
    })
}

/// Median wall time of `f` over `runs` runs, milliseconds.
fn median_ms(runs: usize, mut f: impl FnMut()) -> f64 {
    let mut t: Vec<f64> = (0..runs)
        .map(|_| {
            let t0 = Instant::now();
            f();
            t0.elapsed().as_secs_f64() * 1000.0
        })
        .collect();
    t.sort_by(f64::total_cmp);
    t[runs / 2]
}

/// Markov logic: ground and infer all query marginals (default method: exact when the junction
/// tree is small, MC-SAT otherwise).
fn bench_mln() -> Result<(), CliError> {
    use ksmcmc::floorplan::knowledge::{evidence, GeometryClassifier, BUILTIN_INDOOR};
    use ksmcmc::floorplan::{Unit, UnitType, World};
    use ksmcmc::mln::{Database, Evidence, GroundConfig, InferenceConfig, Mln, Network};
    let fail = |e: ksmcmc::mln::MlnError| args::failed("mln", e);
    // A 20-unit world: a corridor with two rows of nine rooms and a hall at its end.
    let mut w = World::empty(1400, 300);
    let room = |id, x, y, kind| Unit::new(id, x, y, 81, 101, kind);
    w.units.push(Unit::new(1, 0, 100, 721, 41, UnitType::Unknown));
    for i in 0..9 {
        w.units.push(room(2 + i, i as i32 * 80, 0, UnitType::Unknown));
        w.units.push(room(11 + i, i as i32 * 80, 140, UnitType::Unknown));
    }
    w.units.push(Unit::new(20, 720, 0, 300, 241, UnitType::Unknown));
    let indoor = Mln::parse(BUILTIN_INDOOR).map_err(fail)?;
    let facts = evidence(&w, 0.05, &GeometryClassifier::default());
    let mut db = Database::new();
    for (p, a, v) in &facts {
        let a: Vec<&str> = a.iter().map(String::as_str).collect();
        db.insert(&indoor, p, &a, if *v { Evidence::True } else { Evidence::False }).map_err(fail)?;
    }
    let mut gc = GroundConfig::query(&["Room", "Corr", "Hall", "Other", "SaLe"]);
    gc.closed_world = ["RoLi", "CoLi", "HaLi", "MulDoor", "Adj"].map(String::from).to_vec();
    let tabletop = Mln::parse(include_str!("../../../samples/knowledge/tabletop.mln")).map_err(fail)?;
    let tdb = Database::parse(include_str!("../../../samples/knowledge/tabletop.db"), &tabletop).map_err(fail)?;
    let tgc = GroundConfig::query(&["supported", "supportive", "hidden", "false"]);
    println!("\n| knowledge base | unknown atoms | ground clauses | ground + infer all marginals (median of 21) |");
    println!("|---|---|---|---|");
    for (name, mln, db, gc) in [
        ("indoor (Tab. 3.5), 20 units", &indoor, &db, &gc),
        ("table-top (Tab. 4.3), shipped scene", &tabletop, &tdb, &tgc),
    ] {
        let net = Network::ground(mln, db, gc).map_err(fail)?;
        let mut err = None;
        let ms = median_ms(21, || {
            if let Err(e) = Network::ground(mln, db, gc).and_then(|n| n.infer_marginals(&InferenceConfig::default())) {
                err = Some(e);
            }
        });
        if let Some(e) = err {
            return Err(fail(e));
        }
        println!("| {name} | {} | {} | {ms:.3} ms |", net.atom_count(), net.clause_count());
    }
    Ok(())
}

pub fn run(argv: Vec<OsString>) -> Result<(), CliError> {
    use lexopt::prelude::*;
    let mut parser = lexopt::Parser::from_args(argv);
    let (mut iterations, mut seed) = (20_000u64, 1u64);
    let mut datasets = PathBuf::from("../shared/datasets");
    while let Some(arg) = parser.next()? {
        match arg {
            Long("iterations") => iterations = args::value("--iterations", parser.value()?)?,
            Long("seed") => seed = args::value("--seed", parser.value()?)?,
            Long("datasets") => datasets = args::path(parser.value()?),
            Long("help") | Short('h') => {
                print!("{HELP}");
                return Ok(());
            }
            _ => return Err(arg.unexpected().into()),
        }
    }
    let mut rows = Vec::new();
    let radish = datasets.join("radish/ubremen-cartesium.png");
    if radish.exists() {
        let mut map = args::load_map(&radish)?;
        map.set_classifier(Classifier::default()).map_err(|e| args::failed("classifier", e))?;
        rows.push(run_one("ubremen-cartesium (Radish)", &map, iterations, seed)?);
    } else {
        eprintln!("ksmcmc: {} not found; skipping the Cartesium map", radish.display());
    }
    for (w, h) in [(556u32, 322u32), (1237, 672)] {
        let config = SynthConfig { width: w, height: h, ..SynthConfig::default() };
        let s = generate(&config, 7).map_err(|e| args::failed("synth", e))?;
        rows.push(run_one(&format!("synthetic {w}x{h} (seed 7)"), &s.map, iterations, seed)?);
    }
    let synth_ms = bench_synth();
    println!("| map | cells | setup s | iterations | seconds | iterations/s | converged (it / s) | K(W,M) |");
    println!("|---|---|---|---|---|---|---|---|");
    for r in &rows {
        println!(
            "| {} | {}x{} | {:.3} | {} | {:.2} | {:.0} | {} / {:.2} | {:.4} |",
            r.name,
            r.cells.0,
            r.cells.1,
            r.setup,
            r.iterations,
            r.seconds,
            r.iterations as f64 / r.seconds.max(1e-9),
            r.converged_at,
            r.converged_s,
            r.k
        );
    }
    println!();
    println!("| synthetic map generated | median ms |");
    println!("|---|---|");
    for (name, ms) in synth_ms {
        println!("| {name} | {ms:.1} |");
    }
    bench_mln()
}

/// Generation time of two synthetic maps, the small office of the chain rows and the large rotated one the
/// synth tests check (timed here, not asserted there: a test is no stopwatch).
fn bench_synth() -> Vec<(&'static str, f64)> {
    let large = SynthConfig {
        width: 1237,
        height: 672,
        halls: 1,
        others: 4,
        clutter: 0.05,
        unexplored: 0.1,
        rotation_deg: 20.0,
        ..SynthConfig::default()
    };
    [
        ("556x322, seed 7", SynthConfig { width: 556, height: 322, ..SynthConfig::default() }, 7),
        ("1237x672 rotated 20 degrees, seed 11", large, 11),
    ]
    .into_iter()
    .map(|(name, config, seed)| {
        (name, median_ms(5, || drop(generate(&config, seed).expect("a valid synth configuration"))))
    })
    .collect()
}
