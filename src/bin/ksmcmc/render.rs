//! `ksmcmc render MAP [--world world.json] --out out.png`: draw a map, optionally with a world.

use crate::args::{self, CliError};
use ksmcmc::render::{self, RenderOptions};
use std::ffi::OsString;

/// The largest `--scale`.
const MAX_SCALE: u32 = 16;

const HELP: &str = "\
Usage: ksmcmc render MAP [--world world.json] --out out.png [--scale N] [--no-labels] [--no-legend]

Draws the classified map (occupied black, unknown gray, free white) and, with --world, a
semantic world over it in the papers' colours: walls blue, doors cyan, object cells green,
unit interiors tinted by type, each room's (or unit's) type and id inside it where it fits,
and a legend of the colours in a corner.

MAP is a PGM (P2/P5), a PNG, or a ROS map.yaml.

Options:
  --world FILE    a world.json made for this map (its frame.map_size must be the map's size)
  --out FILE      where to write the PNG (required)
  --scale N       output pixels per map cell, 1 to 16 (default 1)
  --no-labels     leave out the unit labels
  --no-legend     leave out the legend
  -h, --help      this text
";

pub fn run(argv: Vec<OsString>) -> Result<(), CliError> {
    use lexopt::prelude::*;
    let mut parser = lexopt::Parser::from_args(argv);
    let mut map = None;
    let mut world = None;
    let mut out = None;
    let mut options = RenderOptions::default();
    while let Some(arg) = parser.next()? {
        match arg {
            Value(v) if map.is_none() => map = Some(args::path(v)),
            Long("world") => world = Some(args::path(parser.value()?)),
            Long("out") | Short('o') => out = Some(args::path(parser.value()?)),
            Long("scale") => options.scale = scale(parser.value()?)?,
            Long("no-labels") => options.labels = false,
            Long("no-legend") => options.legend = false,
            Long("help") | Short('h') => {
                print!("{HELP}");
                return Ok(());
            }
            _ => return Err(arg.unexpected().into()),
        }
    }
    let map_path = args::required(map, "a MAP", "render")?;
    let out = args::required(out, "--out FILE", "render")?;

    let map = args::load_map(&map_path)?;
    let world = match &world {
        Some(path) => Some(args::load_world(path, &map)?),
        None => None,
    };
    let pixmap = render::try_render(map.classified(), world.as_ref(), &options)
        .map_err(|e| args::failed(map_path.display(), e))?;
    let png = render::encode_png(&pixmap);
    if png.is_empty() {
        return Err(CliError::Failed(format!("{}: the PNG encoder failed", out.display())));
    }
    args::write(&out, &png)?;
    println!("{}: {} x {} pixels", out.display(), pixmap.width(), pixmap.height());
    Ok(())
}

/// Parses `--scale`: a whole number from 1 to [`MAX_SCALE`].
fn scale(v: OsString) -> Result<u32, CliError> {
    let s: u32 = args::value("--scale", v)?;
    if !(1..=MAX_SCALE).contains(&s) {
        return Err(CliError::Usage(format!(
            "--scale: {s} is out of range; use 1 to {MAX_SCALE} output pixels per map cell"
        )));
    }
    Ok(s)
}
