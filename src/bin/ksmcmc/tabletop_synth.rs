//! `ksmcmc tabletop-synth --seed N --out scene.json`: a synthetic table-top scene with truth.

use crate::args::{self, CliError};
use ksmcmc::tabletop::synth::{generate, SynthConfig};
use std::ffi::OsString;
use std::path::Path;

const HELP: &str = "\
Usage: ksmcmc tabletop-synth --seed N --out scene.json [options]

Generates a table-top scene: boxes resting on the table, stacks, planks leaning on boxes,
boxes hovering because their support is hidden, and false estimates cutting into other
objects, seen by a stereo camera; keypoints with pixel noise, estimated poses with pose noise,
and the truth per object (hidden, false, true pose). The same seed and options give the same
bytes on every platform.

Options (override the config file, whose fields are the library's SynthConfig):
  --seed N              random seed (required)
  --out FILE            the scene JSON to write (required)
  --config FILE         JSON config; missing fields take their defaults
  --objects MIN-MAX     visible objects, e.g. 3-10 (default 3-10)
  --hovering N          exactly N boxes with a hidden support
  --false N             exactly N false estimates
  --keypoints N         keypoints per object (default 40)
  --pixel-noise PX      keypoint noise, pixels (default 1)
  --pose-noise M        estimated position noise per axis, metres (default 0.002)
  --mono                a single camera instead of a stereo pair
  --print-config        print the effective config as JSON and exit
  -h, --help            this text
";

type Override = Box<dyn FnOnce(&mut SynthConfig)>;

pub fn run(argv: Vec<OsString>) -> Result<(), CliError> {
    use lexopt::prelude::*;
    let mut parser = lexopt::Parser::from_args(argv);
    let (mut seed, mut out, mut config_path, mut print_config) = (None, None, None, false);
    let mut overrides: Vec<Override> = Vec::new();
    while let Some(arg) = parser.next()? {
        match arg {
            Long("seed") => seed = Some(args::value::<u64>("--seed", parser.value()?)?),
            Long("out") => out = Some(args::path(parser.value()?)),
            Long("config") => config_path = Some(args::path(parser.value()?)),
            Long("objects") => {
                let v: String = args::value("--objects", parser.value()?)?;
                overrides.push(objects_override(&v)?);
            }
            Long("hovering") => {
                let v = args::value("--hovering", parser.value()?)?;
                overrides.push(Box::new(move |c| c.hovering = Some(v)));
            }
            Long("false") => {
                let v = args::value("--false", parser.value()?)?;
                overrides.push(Box::new(move |c| c.false_estimates = Some(v)));
            }
            Long("keypoints") => {
                let v = args::value("--keypoints", parser.value()?)?;
                overrides.push(Box::new(move |c| c.keypoints = v));
            }
            Long("pixel-noise") => {
                let v = args::value("--pixel-noise", parser.value()?)?;
                overrides.push(Box::new(move |c| c.pixel_noise = v));
            }
            Long("pose-noise") => {
                let v = args::value("--pose-noise", parser.value()?)?;
                overrides.push(Box::new(move |c| c.pose_noise_t = v));
            }
            Long("mono") => overrides.push(Box::new(|c| c.baseline = None)),
            Long("print-config") => print_config = true,
            Long("help") | Short('h') => {
                print!("{HELP}");
                return Ok(());
            }
            _ => return Err(arg.unexpected().into()),
        }
    }
    let config = effective_config(config_path.as_deref(), overrides)?;
    if print_config {
        println!("{}", serde_json::to_string_pretty(&config).unwrap_or_default());
        return Ok(());
    }
    let seed = args::required(seed, "--seed N", "tabletop-synth")?;
    let out = args::required(out, "--out scene.json", "tabletop-synth")?;
    let scene = generate(&config, seed).map_err(|e| CliError::Failed(e.to_string()))?;
    args::write(&out, (scene.to_json() + "\n").as_bytes())?;
    let count = |f: fn(&ksmcmc::tabletop::scene::Truth) -> bool| {
        scene.objects.iter().filter(|o| o.truth.as_ref().is_some_and(f)).count()
    };
    println!(
        "{} objects ({} hiding another, {} false estimates) -> {}",
        scene.objects.len(),
        count(|t| t.hidden),
        count(|t| t.false_estimate),
        out.display()
    );
    Ok(())
}

/// The override of `--objects MIN-MAX`: the least and the most visible objects.
fn objects_override(v: &str) -> Result<Override, CliError> {
    let bad = || CliError::Usage(format!("--objects: {v:?} is not MIN-MAX, e.g. 3-10"));
    let (lo, hi) = v.split_once('-').ok_or_else(bad)?;
    let (lo, hi): (u32, u32) = (lo.trim().parse().map_err(|_| bad())?, hi.trim().parse().map_err(|_| bad())?);
    Ok(Box::new(move |c| {
        c.min_objects = lo;
        c.max_objects = hi;
    }))
}

/// The config to generate with: the file's (or the defaults), then the command line's
/// overrides in order, validated.
fn effective_config(config_path: Option<&Path>, overrides: Vec<Override>) -> Result<SynthConfig, CliError> {
    let mut config = match config_path {
        Some(p) => {
            let text = std::fs::read_to_string(p).map_err(|e| args::failed(p.display(), e))?;
            SynthConfig::parse_json(&text).map_err(|e| args::failed(p.display(), e))?
        }
        None => SynthConfig::default(),
    };
    for o in overrides {
        o(&mut config);
    }
    config.validate().map_err(|m| CliError::Usage(format!("invalid configuration: {m}")))?;
    Ok(config)
}
