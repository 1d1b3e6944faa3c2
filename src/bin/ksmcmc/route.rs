//! `ksmcmc route MAP WORLD.json --from X,Y --to X,Y|--to-placeholder ID`: a route through
//! rooms and doors, to a cell or to one of the world's placeholders.

use crate::args::{self, CliError};
use ksmcmc::floorplan::route::{saved_labels, RoutePlanner};
use ksmcmc::grid::Grid;
use std::ffi::OsString;
use std::path::{Path, PathBuf};

const HELP: &str = "\
Usage: ksmcmc route MAP WORLD.json --from X,Y (--to X,Y | --to-placeholder ID) [--labels labels.pgm]
                    [--classify RULE]

Plans a route from one map cell to another (X column, Y row, from 0 at the top left) through
the rooms and doors of a floor plan: first on the room graph (rooms joined where world.json
says they open onto each other), then on the cells of the rooms it passes. Prints JSON:
  {\"rooms\": [ids], \"doors\": [ids], \"path\": [[x, y], ...], \"length_m\": metres}
rooms and doors are those the path passes, in order (room ids are labels.pgm's values, door
ids world.json's); path is every cell from start to goal, 8-connected, all free, cutting no
occupied corner; length_m uses the map's resolution (map.yaml, else 0.05 m per cell).

Options:
  --from X,Y       the start cell (required)
  --to X,Y         the goal cell (this or --to-placeholder is required)
  --to-placeholder ID
                   the goal is placeholder ID of world.json: its cell on the frontier, where
                   seen space meets unseen space (floorplan::frontier)
  --labels FILE    the room labels written with the world (labels.pgm of ksmcmc floorplan);
                   without it they are found again from the map and the world, which needs
                   the world's rooms to be those of the default room settings
  --classify RULE  how a plain image becomes cells, as for ksmcmc floorplan: auto (default) or
                   fixed; a map.yaml uses its own thresholds
  -h, --help       this text

Exit codes: 0 a route was found, 1 no route (an end off the map or not free, or no free path
to the goal) or a file could not be read, 2 the command line is wrong.
";

struct Opts {
    map: PathBuf,
    world: PathBuf,
    from: (i64, i64),
    to: Goal,
    labels: Option<PathBuf>,
    classify: String,
}

/// Where the route goes.
enum Goal {
    /// A map cell (column, row).
    Cell((i64, i64)),
    /// The cell of a placeholder of the world, by its id.
    Placeholder(u32),
}

pub fn run(argv: Vec<OsString>) -> Result<(), CliError> {
    let Some(o) = parse(argv)? else { return Ok(()) };
    let map = args::load_classified(&o.map, &o.classify)?;
    let world = args::load_world(&o.world, &map)?;
    let to = match o.to {
        Goal::Cell(c) => c,
        Goal::Placeholder(id) => match world.placeholders.iter().find(|p| p.id == id) {
            Some(p) => (i64::from(p.x), i64::from(p.y)),
            None => {
                return Err(CliError::Failed(format!(
                    "{}: no placeholder {id}; the world has {} (ids 1 to {0}, where the map has frontiers)",
                    o.world.display(),
                    world.placeholders.len()
                )))
            }
        },
    };
    let labels = match &o.labels {
        Some(p) => label_image(p)?,
        None => saved_labels(&world, &map).map_err(|e| args::failed(o.world.display(), e))?,
    };
    let resolution = map.yaml().resolution;
    let mut planner = RoutePlanner::new(map.classified().clone(), labels, &world, resolution)
        .map_err(|e| args::failed(o.labels.as_deref().unwrap_or(&o.world).display(), e))?;
    let route = planner.route(o.from, to).map_err(|e| CliError::Failed(e.to_string()))?;
    // A long path piped into `head` closes the pipe early: that is no failure.
    use std::io::Write;
    match writeln!(std::io::stdout().lock(), "{}", route.to_json()) {
        Err(e) if e.kind() != std::io::ErrorKind::BrokenPipe => Err(args::failed("stdout", e)),
        _ => Ok(()),
    }
}

fn parse(argv: Vec<OsString>) -> Result<Option<Opts>, CliError> {
    use lexopt::prelude::*;
    let mut parser = lexopt::Parser::from_args(argv);
    let (mut map, mut world, mut from, mut to, mut labels) = (None, None, None, None, None);
    let mut classify = String::from("auto");
    while let Some(arg) = parser.next()? {
        match arg {
            Value(v) if map.is_none() => map = Some(args::path(v)),
            Value(v) if world.is_none() => world = Some(args::path(v)),
            Long("from") => from = Some(cell("--from", parser.value()?)?),
            Long("to") => to = Some(Goal::Cell(cell("--to", parser.value()?)?)),
            Long("to-placeholder") => to = Some(Goal::Placeholder(args::value("--to-placeholder", parser.value()?)?)),
            Long("labels") => labels = Some(args::path(parser.value()?)),
            Long("classify") => classify = args::value("--classify", parser.value()?)?,
            Long("help") | Short('h') => {
                print!("{HELP}");
                return Ok(None);
            }
            _ => return Err(arg.unexpected().into()),
        }
    }
    Ok(Some(Opts {
        map: args::required(map, "a MAP", "route")?,
        world: args::required(world, "a WORLD.json", "route")?,
        from: args::required(from, "--from X,Y", "route")?,
        to: args::required(to, "--to X,Y or --to-placeholder ID", "route")?,
        labels,
        classify,
    }))
}

/// A cell `X,Y`: two whole numbers.
fn cell(name: &str, v: OsString) -> Result<(i64, i64), CliError> {
    let s: String = args::value(name, v)?;
    let bad = || CliError::Usage(format!("{name}: {s:?} is not a cell; write the column and row as X,Y (e.g. 120,45)"));
    let (x, y) = s.split_once(',').ok_or_else(bad)?;
    Ok((x.trim().parse().map_err(|_| bad())?, y.trim().parse().map_err(|_| bad())?))
}

/// A 16-bit label image (labels.pgm): room id per cell.
fn label_image(path: &Path) -> Result<Grid<u16>, CliError> {
    let bytes = std::fs::read(path).map_err(|e| args::failed(path.display(), e))?;
    let raster =
        ksmcmc::grid::decode_image(&bytes, &Default::default()).map_err(|e| args::failed(path.display(), e))?;
    Ok(raster.gray)
}
