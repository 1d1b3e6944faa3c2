//! `ksmcmc synth`: a synthetic floor plan with its ground truth, written as four files.

use crate::args::{self, CliError};
use ksmcmc::floorplan::synth::{generate, SynthConfig};
use std::ffi::OsString;

const HELP: &str = "\
Usage: ksmcmc synth --seed N --out DIR [--config config.json] [options]

Generates a synthetic office floor mapped as by a 2D laser SLAM system, with its ground truth,
and writes
  DIR/map.pgm           the occupancy map (occupied 0, unknown 205, free 254)
  DIR/map.yaml          its ROS map_server description
  DIR/truth.json        the true world (world.json: units, types, doors, furniture cells)
  DIR/truth_labels.pgm  16-bit PGM: index + 1 of the truth unit whose interior holds each cell
The same seed and options give the same bytes on every platform.

Options (override the config file, whose fields are documented in the library's SynthConfig):
  --seed N              random seed (required)
  --out DIR             output folder, created if missing (required)
  --config FILE         JSON config; missing fields take their defaults
  --width W             canvas width, cells (default 400)
  --height H            canvas height, cells (default 300)
  --resolution M        metres per cell (default 0.05)
  --rotation DEG        rotate the building against the image axes (default 0)
  --wing DEG            a second wing turned DEG more (10 to 80 either way) to the right
                        of the first, joined by a passage (default 0: one building)
  --corridors N         1 or 2 (default: chosen by the building's depth)
  --halls N             halls at the ends of the building, 0 to 2 (default 0)
  --others N            small \"other\" units such as storage (default 1)
  --wall-thickness N    cells (default 3)
  --clutter F           fraction of room and hall floor covered by furniture (default 0.03)
  --unexplored F        fraction of rooms, halls and others never entered (default 0)
  --speckle P           probability of a free cell reading occupied, and twice P of reading
                        unknown (default 0.002)
  --wall-roughness P    probability of a free cell beside an occupied one reading
                        occupied (default 0.05)
  --wall-gaps P         probability per 5 cm of wall of a gap starting (default 0.004)
  --glass F             glass panes per metre of wall the laser sees through, rays fanning
                        out of the building through outer ones (default 0)
  --open-hubs P         probability of an open arch, not a door, between two corridors or a
                        corridor and a hall (default 0)
  --print-config        print the effective config as JSON and exit
  -h, --help            this text
";

/// A command-line option that changes one config field, applied over the config file.
type Override = Box<dyn FnOnce(&mut SynthConfig)>;

pub fn run(argv: Vec<OsString>) -> Result<(), CliError> {
    use lexopt::prelude::*;
    let mut parser = lexopt::Parser::from_args(argv);
    let (mut seed, mut out, mut config_path) = (None, None, None);
    let mut overrides: Vec<Override> = Vec::new();
    let mut print_config = false;
    while let Some(arg) = parser.next()? {
        match arg {
            Long("seed") => seed = Some(args::value::<u64>("--seed", parser.value()?)?),
            Long("out") => out = Some(args::path(parser.value()?)),
            Long("config") => config_path = Some(args::path(parser.value()?)),
            Long(name) if OVERRIDES.contains(&name) => {
                let name = name.to_owned();
                overrides.push(field_override(&name, parser.value()?)?);
            }
            Long("print-config") => print_config = true,
            Long("help") | Short('h') => {
                print!("{HELP}");
                return Ok(());
            }
            _ => return Err(arg.unexpected().into()),
        }
    }
    let mut config = match &config_path {
        Some(p) => {
            let text = std::fs::read_to_string(p).map_err(|e| args::failed(p.display(), e))?;
            SynthConfig::parse_json(&text).map_err(|e| args::failed(p.display(), e))?
        }
        None => SynthConfig::default(),
    };
    for apply in overrides {
        apply(&mut config);
    }
    config.validate().map_err(|e| CliError::Failed(e.to_string()))?;
    if print_config {
        println!("{}", config.to_json());
        return Ok(());
    }
    let seed = args::required(seed, "--seed N", "synth")?;
    let out = args::required(out, "--out DIR", "synth")?;
    let s = generate(&config, seed).map_err(|e| CliError::Failed(e.to_string()))?;
    args::write(&out.join("map.pgm"), &s.map_pgm())?;
    args::write(&out.join("map.yaml"), s.map_yaml().as_bytes())?;
    args::write(&out.join("truth.json"), s.truth_json().as_bytes())?;
    args::write(&out.join("truth_labels.pgm"), &s.labels_pgm())?;
    let count = |k| s.truth.units.iter().filter(|u| u.kind == k).count();
    use ksmcmc::floorplan::UnitType::*;
    println!(
        "{}: {} x {} map, {} units ({} rooms, {} corridors, {} halls, {} other), {} doors, {} unexplored",
        out.display(),
        s.map.width(),
        s.map.height(),
        s.truth.units.len(),
        count(Room),
        count(Corridor),
        count(Hall),
        count(Other),
        s.truth.doors.len(),
        s.explored.iter().filter(|e| !**e).count()
    );
    Ok(())
}

/// The options that override one config field.
const OVERRIDES: [&str; 16] = [
    "width",
    "height",
    "resolution",
    "rotation",
    "wing",
    "corridors",
    "halls",
    "others",
    "wall-thickness",
    "clutter",
    "unexplored",
    "speckle",
    "wall-roughness",
    "wall-gaps",
    "glass",
    "open-hubs",
];

/// The override of option `--name` (one of [`OVERRIDES`]) with value `v`.
fn field_override(name: &str, v: OsString) -> Result<Override, CliError> {
    let flag = format!("--{name}");
    Ok(match name {
        "width" => {
            let v = args::value(&flag, v)?;
            Box::new(move |c| c.width = v)
        }
        "height" => {
            let v = args::value(&flag, v)?;
            Box::new(move |c| c.height = v)
        }
        "resolution" => {
            let v = args::value(&flag, v)?;
            Box::new(move |c| c.resolution = v)
        }
        "rotation" => {
            let v = args::value(&flag, v)?;
            Box::new(move |c| c.rotation_deg = v)
        }
        "wing" => {
            let v = args::value(&flag, v)?;
            Box::new(move |c| c.wing_deg = v)
        }
        "corridors" => {
            let v = args::value(&flag, v)?;
            Box::new(move |c| c.corridors = Some(v))
        }
        "halls" => {
            let v = args::value(&flag, v)?;
            Box::new(move |c| c.halls = v)
        }
        "others" => {
            let v = args::value(&flag, v)?;
            Box::new(move |c| c.others = v)
        }
        "wall-thickness" => {
            let v = args::value(&flag, v)?;
            Box::new(move |c| c.wall_thickness = v)
        }
        "clutter" => {
            let v = args::value(&flag, v)?;
            Box::new(move |c| c.clutter = v)
        }
        "unexplored" => {
            let v = args::value(&flag, v)?;
            Box::new(move |c| c.unexplored = v)
        }
        "speckle" => {
            let v: f64 = args::value(&flag, v)?;
            Box::new(move |c| {
                c.speckle_occupied = v;
                c.speckle_unknown = 2.0 * v;
            })
        }
        "wall-roughness" => {
            let v = args::value(&flag, v)?;
            Box::new(move |c| c.wall_roughness = v)
        }
        "wall-gaps" => {
            let v = args::value(&flag, v)?;
            Box::new(move |c| c.wall_gaps = v)
        }
        "glass" => {
            let v = args::value(&flag, v)?;
            Box::new(move |c| c.glass = v)
        }
        "open-hubs" => {
            let v = args::value(&flag, v)?;
            Box::new(move |c| c.open_hubs = v)
        }
        other => unreachable!("--{other} is not in OVERRIDES"),
    })
}
