//! `ksmcmc explore MAP --out DIR`: a simulated robot explores MAP and the floor plan follows.

use crate::args::{self, CliError};
use crate::floorplan::chain_config_from;
use ksmcmc::floorplan::frontier::Goal;
use ksmcmc::floorplan::online::{self, GoalGuide, Guide, Nearest, OnlineConfig};
use ksmcmc::floorplan::rooms::RoomConfig;
use ksmcmc::floorplan::{export, metrics, Chain, ChainConfig};
use ksmcmc::grid::Cell;
use std::ffi::OsString;
use std::path::PathBuf;
use std::time::Instant;

const HELP: &str = "\
Usage: ksmcmc explore MAP --out DIR [options]

Simulates a robot exploring MAP (PGM, PNG or map.yaml) with a 2D range sensor: rays cast over
the true map reveal it, and the robot drives to the nearest frontier of what it has seen
until none is left. Every --update-every metres the floor-plan chain takes the robot's map and
goes on from its world (online operation), and a cold chain starts on the same snapshot to
compare: each notes the iterations it needed to come within 0.1 % of the better best log
posterior. Writes:
  DIR/world.json     the chain's final best world, on the robot's last map
  DIR/labels.pgm     its room segmentation
  DIR/overlay.png    the world drawn over the robot's last map
  DIR/map.pgm, DIR/map.yaml  the robot's last map, as a ROS map (ksmcmc floorplan reads it)
  DIR/timeline.json  one record per update: robot, metres driven, cells seen and changed,
                     warm and cold iterations, log posteriors, units, K(W,M), scan positions
  DIR/report.json    updates, warm_iterations and cold_iterations (summed), the final
                     cell_prediction_rate, and a cold run on the full map to compare

Options:
  --iterations N     iterations after each update (default 20000)
  --update-every M   metres driven between updates (default 10)
  --max-updates N    stop after N updates even if frontiers remain (default 200)
  --range M          the sensor's range, metres (default 8)
  --start X,Y        the start cell (column, row); default: a free cell drawn from the seed
  --no-cold          do not run the cold chains (cold_iterations is then null)
  --no-renew         keep the warm chain at the end; by default, once no frontier is left a
                     fresh chain climbs on the last map for the cold budget and replaces the
                     warm one if its best log posterior is higher (report.json: renewal)
  --cold-budget N    iterations each cold chain may run, at least --iterations (default: five
                     times --iterations); a cold chain that never comes back counts them all
  --goal G           look for G (new-room, room, corridor, hall or other) and stop when the
                     plan holds a new one: the robot drives to the placeholder with the
                     most probability of reaching G per metre of the way there. A second
                     exploration that follows the nearest frontier (no cold chains) looks
                     for the same; report.json gives both under \"goal\"
  --seed S           random seed (default 1); same seed, same result
  --config FILE      chain configuration JSON, as for ksmcmc floorplan; the fields it does
                     not give keep the online defaults (ChainConfig::online: the floorplan
                     defaults with the range-sensor table, under which a wall's ring lies in
                     the wall behind the face the robot saw)
  --knowledge KB     builtin (default), handset, a knowledge base file, or none
  --rotation DEG     map rotation in degrees instead of estimating it from the first map
  --classify RULE    auto (default) or fixed, as for ksmcmc floorplan
";

struct Opts {
    map: PathBuf,
    out: PathBuf,
    seed: u64,
    online: OnlineConfig,
    config: Option<PathBuf>,
    knowledge: Option<String>,
    rotation: Option<f64>,
    classify: String,
    goal: Option<Goal>,
}

/// One line on stderr per map update, as the robot explores.
fn print_update(r: &online::UpdateRecord) {
    eprintln!(
        "update {:>3}: {:>6.1} m, {:>7} cells changed, warm {:>6} / cold {:>6} iterations, K(W,M) {:.4}",
        r.update,
        r.travelled_m,
        r.changed_cells,
        r.warm_iterations,
        r.cold_iterations.map_or("-".into(), |c| c.to_string()),
        r.cell_prediction_rate
    )
}

pub fn run(argv: Vec<OsString>) -> Result<(), CliError> {
    let Some(o) = parse(argv)? else { return Ok(()) };
    let config = chain_config_from(ChainConfig::online(), o.config.as_deref(), o.rotation, o.knowledge.as_deref())?;
    let truth = args::load_classified(&o.map, &o.classify)?;
    let t0 = Instant::now();
    let mut log = print_update;
    let mut steered = o.goal.map(|g| GoalGuide::new(g, true, RoomConfig::default()));
    let guide: &mut dyn Guide = match steered.as_mut() {
        Some(g) => g,
        None => &mut Nearest,
    };
    let mut run = online::explore_guided(&truth, &config, &o.online, o.seed, &mut log, guide)
        .map_err(|e| args::failed(o.map.display(), e))?;
    let seconds = t0.elapsed().as_secs_f64();
    let goal = match &steered {
        Some(g) => Some(compare_goal(g, &run, &truth, &config, &o)?),
        None => None,
    };
    // A cold chain on the whole true map, with as many iterations as one update: the final
    // world should explain what the robot saw as well as that explains everything.
    let mut cold = Chain::new(&truth, config, o.seed).map_err(|e| args::failed(o.map.display(), e))?;
    cold.step(o.online.iterations);
    let cold_k = metrics::prediction_rate(truth.classified(), &cold.best_world());
    let snapshot = run.explorer.snapshot();
    let input = export::RoomInput::of(&mut run.chain);
    let (world, labels) = input.explain(&RoomConfig::default()).map_err(|e| args::failed("finding the rooms", e))?;
    let k = metrics::prediction_rate(snapshot.classified(), &world);
    let report = serde_json::json!({
        "map": o.map.display().to_string(),
        "seed": o.seed,
        "updates": run.updates(),
        "warm_iterations": run.warm_iterations(),
        "cold_iterations": run.cold_iterations(),
        "iterations_per_update": o.online.iterations,
        "cold_budget": o.online.cold_iterations(),
        "update_every_m": o.online.update_every_m,
        "travelled_m": run.explorer.travelled_m(),
        "scans": run.explorer.scans().len(),
        "explored_free_share": run.explorer.seen_count(Cell::Free) as f64 / truth.count(Cell::Free).max(1) as f64,
        "cell_prediction_rate": k,
        "cell_prediction_rate_on_full_map": metrics::prediction_rate(truth.classified(), &world),
        "cold_full_map": { "iterations": o.online.iterations, "cell_prediction_rate": cold_k },
        "units": world.units.len(),
        "doors": world.doors.len(),
        "rooms": world.rooms.len(),
        "seconds": seconds,
        "renewal": run.renewal,
        "goal": goal,
    });
    let overlay =
        ksmcmc::render::overlay_png(snapshot.classified(), &world).map_err(|e| args::failed(o.out.display(), e))?;
    let timeline = serde_json::to_string_pretty(&run.timeline).expect("records serialise");
    args::write(&o.out.join("world.json"), world.to_json().as_bytes())?;
    args::write(&o.out.join("labels.pgm"), &export::labels_pgm(&labels))?;
    args::write(&o.out.join("overlay.png"), &overlay)?;
    args::write(&o.out.join("timeline.json"), timeline.as_bytes())?;
    args::write(&o.out.join("map.pgm"), &snapshot.to_pgm())?;
    args::write(&o.out.join("map.yaml"), snapshot.to_yaml("map.pgm").as_bytes())?;
    args::write(&o.out.join("report.json"), export::report_json(&report).as_bytes())?;
    println!(
        "{}: {} updates over {:.0} m in {:.1} s; warm {} / cold {} iterations; K(W,M) {:.4} (cold on the full map {:.4}) -> {}",
        o.map.display(),
        run.updates(),
        run.explorer.travelled_m(),
        seconds,
        run.warm_iterations(),
        run.cold_iterations().map_or("-".into(), |c| c.to_string()),
        k,
        cold_k,
        o.out.display()
    );
    Ok(())
}

fn parse(argv: Vec<OsString>) -> Result<Option<Opts>, CliError> {
    use lexopt::prelude::*;
    let mut parser = lexopt::Parser::from_args(argv);
    let (mut map, mut out, mut config, mut knowledge, mut rotation) = (None, None, None, None, None);
    let (mut seed, mut online, mut classify) = (1u64, OnlineConfig::default(), String::from("auto"));
    let mut goal = None;
    while let Some(arg) = parser.next()? {
        match arg {
            Value(v) if map.is_none() => map = Some(args::path(v)),
            Long("out") => out = Some(args::path(parser.value()?)),
            Long("seed") => seed = args::value("--seed", parser.value()?)?,
            Long("iterations") => online.iterations = args::value("--iterations", parser.value()?)?,
            Long("update-every") => online.update_every_m = args::value("--update-every", parser.value()?)?,
            Long("max-updates") => online.max_updates = args::value("--max-updates", parser.value()?)?,
            Long("range") => online.explore.range_m = args::value("--range", parser.value()?)?,
            Long("start") => online.explore.start = Some(start(parser.value()?)?),
            Long("no-cold") => online.measure_cold = false,
            Long("no-renew") => online.renew = false,
            Long("cold-budget") => online.cold_budget = args::value("--cold-budget", parser.value()?)?,
            Long("config") => config = Some(args::path(parser.value()?)),
            Long("knowledge") => knowledge = Some(args::value("--knowledge", parser.value()?)?),
            Long("rotation") => rotation = Some(args::value("--rotation", parser.value()?)?),
            Long("classify") => classify = args::value("--classify", parser.value()?)?,
            Long("goal") => {
                let name: String = args::value("--goal", parser.value()?)?;
                goal = Some(Goal::parse(&name).map_err(|e| CliError::Usage(e.to_string()))?);
            }
            Long("help") | Short('h') => {
                print!("{HELP}");
                return Ok(None);
            }
            _ => return Err(arg.unexpected().into()),
        }
    }
    online.validate().map_err(|e| CliError::Usage(e.to_string()))?;
    Ok(Some(Opts {
        map: args::required(map, "a MAP", "explore")?,
        out: args::required(out, "--out DIR", "explore")?,
        seed,
        online,
        config,
        knowledge,
        rotation,
        classify,
        goal,
    }))
}

/// The goal-driven run's `g` finding against a second exploration of the same map from the
/// same start that follows the nearest frontier and looks for the same goal by the same rule.
fn compare_goal(
    g: &GoalGuide,
    run: &online::Exploration,
    truth: &ksmcmc::grid::OccupancyMap,
    config: &ChainConfig,
    o: &Opts,
) -> Result<serde_json::Value, CliError> {
    let mut watch = GoalGuide::new(g.goal(), false, RoomConfig::default());
    let plain = OnlineConfig { measure_cold: false, renew: false, ..o.online };
    let near = online::explore_guided(truth, config, &plain, o.seed, &mut |_| {}, &mut watch)
        .map_err(|e| args::failed(o.map.display(), e))?;
    let policy = |name: &str, found: Option<f64>, e: &online::Exploration| {
        serde_json::json!({
            "policy": name,
            "found_at_m": found,
            "travelled_m": e.explorer.travelled_m(),
            "goals": e.explorer.goals(),
            "updates": e.updates(),
        })
    };
    Ok(serde_json::json!({
        "goal": g.goal().name(),
        "expected_value": policy("expected value", g.found_at_m(), run),
        "nearest_frontier": policy("nearest frontier", watch.found_at_m(), &near),
    }))
}

/// `--start X,Y`.
fn start(v: OsString) -> Result<[u32; 2], CliError> {
    let s: String = args::value("--start", v)?;
    let bad = || CliError::Usage(format!("--start must be X,Y in map cells, not {s:?}"));
    let (x, y) = s.split_once(',').ok_or_else(bad)?;
    Ok([x.trim().parse().map_err(|_| bad())?, y.trim().parse().map_err(|_| bad())?])
}
