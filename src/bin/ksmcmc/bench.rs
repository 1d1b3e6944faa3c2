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
best log posterior (time to convergence), and K(W,M).
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
    Ok(())
}
