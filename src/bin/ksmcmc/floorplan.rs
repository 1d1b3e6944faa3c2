//! `ksmcmc floorplan MAP --out DIR`: explain a map with a semantic floor plan.

use crate::args::{self, CliError};
use ksmcmc::floorplan::georef::Georef;
use ksmcmc::floorplan::run::{Run, RunOptions};
use ksmcmc::floorplan::settled::{self, Settled};
use ksmcmc::floorplan::{metrics, Chain, ChainConfig, ChainError};
use ksmcmc::grid::Cell;
use ksmcmc::render::model3d::Model3dOptions;
use std::ffi::OsString;
use std::path::PathBuf;
use std::time::Instant;

const HELP: &str = "\
Usage: ksmcmc floorplan MAP --out DIR [options]

Explains an occupancy map (PGM, PNG or map.yaml) with a semantic floor plan found by
data-driven MCMC, and writes:
  DIR/world.json    the best world found (units, doors, object cells, rooms)
  DIR/overlay.png   the world drawn over the classified map
  DIR/graph.json    the scene graph (units joined by doors and walls) and the rooms
  DIR/trace.csv     log posterior, acceptance rate and unit count over the run
  DIR/labels.pgm    16-bit room segmentation (room id per free cell, 0 elsewhere)
  DIR/report.json   iterations, time, K(W,M), counts, log posterior, seed
  DIR/world.geojson the rooms (IMDF `unit`s: room, walkway, lobby or unspecified), doors
                    (`opening`s) and the floor (`level`) as GeoJSON, in metres of the map
                    frame (the map.yaml origin applied), or longitude/latitude with --georef
  DIR/world.svg     the floor plan as a vector drawing in layers (rooms by type, walls,
                    doors, labels), in map cells
  DIR/world.glb     the 3D world (glTF 2.0 binary, metres, Y up): walls with openings at the
                    doors, a floor slab per room in its type's colour

Options:
  --iterations N     iterations to run (default 20000)
  --time-limit SEC   stop after this many seconds even if iterations remain
  --until-settled    stop once the best world has settled (floorplan::settled; the live
                     mapper's rule), at most --iterations; report.json gives settled_at
  --seed S           random seed (default 1); same seed, same result
  --config FILE      chain configuration JSON (any subset of fields; see the docs)
      --rotation DEG     map rotation in degrees instead of estimating it
      --knowledge KB     knowledge supervision during the chain: `builtin` (default: the indoor
                     rules of Tab. 3.5 and more, weights learned from labelled floors),
                     `handset` (Tab. 3.5 with the hand-set weights), a knowledge base file
                     (Alchemy format), or `none`
                     (the weak prior of the first paper; types are then inferred on the final
                     world with the built-in rules)
  --room-rules FILE  the rules that decide which units are one room when knowledge is on
                     (Alchemy format, query SameRoom; default: the built-in
                     samples/knowledge/rooms.mln; rooms-learned.mln has its rules with
                     weights learned from generated floors)
  --region FILE      an image the size of the map whose non-black cells are a region of
                     interest: report.json then also gives K(W,M) inside it
  --georef LAT,LON,BEARING
                     where the map lies on the Earth, for world.geojson: latitude and
                     longitude (degrees, WGS 84) of the map frame's origin and the compass
                     bearing of its y axis (0: the map's up is north); coordinates are then
                     longitude/latitude on the local tangent plane
  --edits FILE       a person's corrections as hard evidence: a JSON list of merges
                     (the rooms at two points are one), splits (a wall runs along a line),
                     types and names of the room at a point, in map cells (column, row);
                     see docs/formats.md, \"Correcting a floor plan\"
  --wall-height M    height of the walls in world.glb, metres (default 2.5)
  --door-height M    height of the door openings in world.glb, metres (default 2.0; at most
                     the wall height)
  --no-wings         one chain in the dominant direction even where the walls follow
                     several (by default a map whose walls follow several directions, such as
                     a pentagon or wings at an angle, is explained again wing by wing, each in
                     its own direction: world.json's units then carry their angles; see
                     floorplan::wings; the iterations are per chain, and --edits,
                     --until-settled, --time-limit and --rotation keep one chain)
  --classify RULE    how pixels become cells: auto (default; background grays found from
                     the histogram, anti-aliased walls occupied, the same rule for a PNG, a
                     PGM and a map.yaml, so the same pixels give the same rooms) or fixed
                     (a map.yaml's own thresholds; eq. 3.7's for a plain image)
  --resolution M     metres per cell of the map (default: the map.yaml's; a plain image
                     without one is read at 0.05 m, the benchmark maps' cell, with a note)
";

/// The command line, parsed.
struct Opts {
    map: PathBuf,
    out: PathBuf,
    config: Option<PathBuf>,
    iterations: u64,
    seed: u64,
    time_limit: Option<f64>,
    rotation: Option<f64>,
    classify: String,
    resolution: Option<f64>,
    region: Option<PathBuf>,
    knowledge: Option<String>,
    room_rules: Option<PathBuf>,
    until_settled: bool,
    georef: Option<Georef>,
    edits: Option<PathBuf>,
    model: Model3dOptions,
    wings: bool,
}

pub fn run(argv: Vec<OsString>) -> Result<(), CliError> {
    let Some(o) = parse(argv)? else { return Ok(()) };
    let config = chain_config(&o)?;
    let map = args::at_resolution(args::load_classified(&o.map, &o.classify)?, &o.map, o.resolution);
    let region = load_region(&o, &map)?;
    let edits = o.edits.as_deref().map(load_edits).transpose()?;
    // A failure names the file at fault: the edits where they do not fit the map.
    let failed = |e: ChainError| match (&e, &o.edits) {
        (ChainError::Edits(_), Some(path)) => args::failed(path.display(), e),
        _ => args::failed(o.map.display(), e),
    };
    // The run of the library (a chain per wing where the walls follow several directions),
    // unless a setting asks for what only the one chain does so far: stopping by a time
    // limit or the settle rule.
    if !o.until_settled && o.time_limit.is_none() {
        let wings = o.wings && o.rotation.is_none();
        let options = RunOptions { seed: o.seed, iterations: o.iterations, config, edits, wings };
        return write_run(&o, &map, ksmcmc::floorplan::run::run(&map, &options).map_err(failed)?, region.as_ref());
    }
    let t0 = Instant::now();
    let mut chain = Chain::new(&map, config, o.seed).map_err(failed)?;
    if let Some(edits) = edits {
        chain.set_edits(edits).map_err(failed)?;
    }
    let deadline = o.time_limit.map(|t| t0 + std::time::Duration::from_secs_f64(t));
    let mut settled = Settled::for_floor(map.count(Cell::Free), chain.resolution());
    let chunk = if o.until_settled { settled::STRIDE } else { 500 };
    while chain.iteration() < o.iterations {
        if deadline.is_some_and(|d| Instant::now() >= d) || (o.until_settled && settled.settled_at().is_some()) {
            break;
        }
        let n = (o.iterations - chain.iteration()).min(chunk);
        settled.step(&mut chain, n);
    }
    let mut result = Run::of_chain(chain, &map, t0.elapsed().as_secs_f64()).map_err(failed)?;
    if o.until_settled {
        result.report["settled_at"] = serde_json::json!(settled.settled_at());
    }
    write_run(&o, &map, result, region.as_ref())
}

/// Writes the run's nine files to `o.out` and prints its summary line (with the number of
/// wings, when there were several) and the note on several wall directions.
fn write_run(
    o: &Opts,
    map: &ksmcmc::grid::OccupancyMap,
    run: Run,
    region: Option<&ksmcmc::grid::Grid<bool>>,
) -> Result<(), CliError> {
    let Run { world, labels, mut report, trace, iterations, seconds, wings } = run;
    report["map"] = o.map.display().to_string().into();
    report["cell_prediction_rate_region"] =
        region.map(|r| metrics::prediction_rate_in(map.classified(), &world, Some(r))).into();
    let k = report["cell_prediction_rate"].as_f64().unwrap_or(0.0);
    let outputs = ksmcmc::render::Outputs::new(map, &world, &labels, &report, trace, o.georef.as_ref(), &o.model)
        .map_err(|e| args::failed(o.out.display(), e))?;
    for (name, bytes) in outputs.files() {
        args::write(&o.out.join(name), bytes)?;
    }
    println!(
        "{}: {iterations} iterations in {seconds:.2} s ({:.0}/s), K(W,M) = {k:.4}, {} units, {} doors, {} rooms{} -> {}",
        o.map.display(),
        iterations as f64 / seconds.max(1e-9),
        world.units.len(),
        world.doors.len(),
        world.rooms.len(),
        wings.map_or(String::new(), |n| format!(", {n} wings")),
        o.out.display()
    );
    if let Some(note) = ksmcmc::floorplan::report::several_directions_note(&report) {
        eprintln!("{note}");
    }
    Ok(())
}

/// Parses and checks the arguments; `None` when `--help` was answered.
fn parse(argv: Vec<OsString>) -> Result<Option<Opts>, CliError> {
    use lexopt::prelude::*;
    let mut parser = lexopt::Parser::from_args(argv);
    let (mut map, mut out, mut config_path) = (None, None, None::<PathBuf>);
    let (mut iterations, mut seed, mut time_limit, mut rotation) = (20_000u64, 1u64, None::<f64>, None::<f64>);
    let mut classify = String::from("auto");
    let mut resolution = None::<f64>;
    let mut region_path: Option<PathBuf> = None;
    let mut knowledge: Option<String> = None;
    let mut room_rules: Option<PathBuf> = None;
    let mut until_settled = false;
    let mut georef = None;
    let mut edits: Option<PathBuf> = None;
    let mut model = Model3dOptions::default();
    let mut wings = true;
    while let Some(arg) = parser.next()? {
        match arg {
            Value(v) if map.is_none() => map = Some(args::path(v)),
            Long("out") => out = Some(args::path(parser.value()?)),
            Long("iterations") => iterations = args::value("--iterations", parser.value()?)?,
            Long("seed") => seed = args::value("--seed", parser.value()?)?,
            Long("time-limit") => time_limit = Some(args::value("--time-limit", parser.value()?)?),
            Long("config") => config_path = Some(args::path(parser.value()?)),
            Long("rotation") => rotation = Some(args::value("--rotation", parser.value()?)?),
            Long("classify") => classify = args::value("--classify", parser.value()?)?,
            Long("resolution") => resolution = Some(args::value("--resolution", parser.value()?)?),
            Long("region") => region_path = Some(args::path(parser.value()?)),
            Long("knowledge") => knowledge = Some(args::value("--knowledge", parser.value()?)?),
            Long("room-rules") => room_rules = Some(args::path(parser.value()?)),
            Long("until-settled") => until_settled = true,
            Long("no-wings") => wings = false,
            Long("georef") => georef = Some(args::value::<Georef>("--georef", parser.value()?)?),
            Long("edits") => edits = Some(args::path(parser.value()?)),
            Long("wall-height") => model.wall_height = args::value("--wall-height", parser.value()?)?,
            Long("door-height") => model.door_height = args::value("--door-height", parser.value()?)?,
            Long("help") | Short('h') => {
                print!("{HELP}");
                return Ok(None);
            }
            _ => return Err(arg.unexpected().into()),
        }
    }
    let map = args::required(map, "a MAP", "floorplan")?;
    let out = args::required(out, "--out DIR", "floorplan")?;
    if let Some(t) = time_limit {
        if !(t.is_finite() && t > 0.0) {
            return Err(CliError::Usage(format!("--time-limit must be a positive number of seconds, not {t}")));
        }
    }
    model.validate().map_err(|e| CliError::Usage(format!("--wall-height/--door-height: {e}")))?;
    if let Some(r) = resolution.filter(|r| !(r.is_finite() && *r > 0.0 && *r <= 10.0)) {
        return Err(CliError::Usage(format!(
            "--resolution must be the metres per cell, above 0 and at most 10, not {r}"
        )));
    }
    if let Some(r) = rotation {
        if !r.is_finite() {
            return Err(CliError::Usage(format!("--rotation must be a number of degrees, not {r}")));
        }
    }
    Ok(Some(Opts {
        map,
        out,
        config: config_path,
        iterations,
        seed,
        time_limit,
        rotation,
        classify,
        resolution,
        region: region_path,
        knowledge,
        room_rules,
        until_settled,
        georef,
        edits,
        model,
        wings,
    }))
}

/// The edits of `--edits`, size-checked before reading.
fn load_edits(path: &std::path::Path) -> Result<ksmcmc::floorplan::edits::Edits, CliError> {
    use ksmcmc::floorplan::edits::{Edits, MAX_EDITS_TEXT};
    let len = std::fs::metadata(path).map_err(|e| args::failed(path.display(), e))?.len();
    if len > MAX_EDITS_TEXT as u64 {
        return Err(args::failed(path.display(), format!("{len} bytes, over the cap of {MAX_EDITS_TEXT} for edits")));
    }
    let text = std::fs::read_to_string(path).map_err(|e| args::failed(path.display(), e))?;
    Edits::parse(&text).map_err(|e| args::failed(path.display(), e))
}

/// The chain configuration: `--config`, then `--rotation` and `--knowledge` over it.
fn chain_config(o: &Opts) -> Result<ChainConfig, CliError> {
    let mut config =
        chain_config_from(ChainConfig::default(), o.config.as_deref(), o.rotation, o.knowledge.as_deref())?;
    if let Some(p) = &o.room_rules {
        config.knowledge.room_kb = Some(room_rules(p)?);
    }
    Ok(config)
}

/// The room rules of `--room-rules`, parsed now so that a broken file is named.
pub fn room_rules(path: &std::path::Path) -> Result<String, CliError> {
    let text = std::fs::read_to_string(path).map_err(|e| args::failed(path.display(), e))?;
    ksmcmc::floorplan::rooms::RoomKnowledge::parse(&text).map_err(|e| args::failed(path.display(), e))?;
    Ok(text)
}

/// The chain configuration from a `--config` file, then `--rotation` and `--knowledge` over
/// it (`ksmcmc explore` takes the same options).
pub fn chain_config_from(
    base: ChainConfig,
    path: Option<&std::path::Path>,
    rotation: Option<f64>,
    knowledge: Option<&str>,
) -> Result<ChainConfig, CliError> {
    let mut config = match path {
        Some(p) => {
            let text = std::fs::read_to_string(p).map_err(|e| args::failed(p.display(), e))?;
            ChainConfig::from_json_over(&base, &text).map_err(|e| args::failed(p.display(), e))?
        }
        None => base,
    };
    if rotation.is_some() {
        config.detectors.rotation_deg = rotation;
    }
    if let Some(name) = knowledge {
        ksmcmc::floorplan::knowledge::IndoorKnowledge::named(name, |path| std::fs::read_to_string(path))
            .map_err(|e| CliError::Failed(e.to_string()))?
            .apply_to(&mut config.knowledge);
    }
    Ok(config)
}

/// The `--region` mask (non-black cells), which must be the map's size.
fn load_region(o: &Opts, map: &ksmcmc::grid::OccupancyMap) -> Result<Option<ksmcmc::grid::Grid<bool>>, CliError> {
    let Some(p) = &o.region else { return Ok(None) };
    let bytes = std::fs::read(p).map_err(|e| args::failed(p.display(), e))?;
    let raster = ksmcmc::grid::decode_image(&bytes, &Default::default()).map_err(|e| args::failed(p.display(), e))?;
    if (raster.width(), raster.height()) != (map.width(), map.height()) {
        return Err(CliError::Failed(format!(
            "{}: the region is {}x{} but the map is {}x{}",
            p.display(),
            raster.width(),
            raster.height(),
            map.width(),
            map.height()
        )));
    }
    Ok(Some(raster.gray.map(|&g| g > 0)))
}
