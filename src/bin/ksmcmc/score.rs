//! `ksmcmc score LABELS TRUTH`: segmentation precision and recall by the benchmark's scoring.

use crate::args::{self, CliError};
use ksmcmc::floorplan::metrics::{regions, score_segmentation};
use ksmcmc::grid::{decode_image, white_cells, Grid, Limits};
use std::ffi::OsString;
use std::path::Path;

const HELP: &str = "\
Usage: ksmcmc score LABELS TRUTH [--truth regions|labels] [--json]

Scores a room segmentation as the room-segmentation benchmark (Bormann et al. 2016) does:
segments of 100 cells or fewer are dropped; precision is the mean over predicted segments of
their largest overlap with a truth segment over their size, recall the same the other way.

  LABELS   an image of segment ids (e.g. labels.pgm from `ksmcmc floorplan`), 0 = none
  TRUTH    a ground-truth image: by default its white regions (all channels >= 250) are the
           segments, as in the benchmark's *_gt_segmentation.png files; with --truth labels it
           is an image of segment ids like LABELS (e.g. truth_labels.pgm from `ksmcmc synth`)
";

/// Segment ids from an image: every distinct gray value is a segment, 0 none.
pub fn label_image(path: &Path) -> Result<Grid<u32>, CliError> {
    let bytes = std::fs::read(path).map_err(|e| args::failed(path.display(), e))?;
    let raster = decode_image(&bytes, &Limits::default()).map_err(|e| args::failed(path.display(), e))?;
    Ok(raster.gray.map(|&v| v as u32))
}

/// The benchmark's truth segments: 4-connected regions whose every channel is at least 250.
pub fn truth_regions(path: &Path) -> Result<Grid<u32>, CliError> {
    let bytes = std::fs::read(path).map_err(|e| args::failed(path.display(), e))?;
    let white = white_cells(&bytes, &Limits::default()).map_err(|e| args::failed(path.display(), e))?;
    Ok(regions(&white))
}

pub fn run(argv: Vec<OsString>) -> Result<(), CliError> {
    use lexopt::prelude::*;
    let mut parser = lexopt::Parser::from_args(argv);
    let (mut labels, mut truth, mut kind, mut json) = (None, None, String::from("regions"), false);
    while let Some(arg) = parser.next()? {
        match arg {
            Value(v) if labels.is_none() => labels = Some(args::path(v)),
            Value(v) if truth.is_none() => truth = Some(args::path(v)),
            Long("truth") => kind = args::value("--truth", parser.value()?)?,
            Long("json") => json = true,
            Long("help") | Short('h') => {
                print!("{HELP}");
                return Ok(());
            }
            _ => return Err(arg.unexpected().into()),
        }
    }
    let labels = args::required(labels, "LABELS", "score")?;
    let truth = args::required(truth, "TRUTH", "score")?;
    let predicted = label_image(&labels)?;
    let truth_grid = match kind.as_str() {
        "regions" => truth_regions(&truth)?,
        "labels" => label_image(&truth)?,
        other => return Err(CliError::Usage(format!("--truth must be regions or labels, not {other:?}"))),
    };
    if (predicted.width(), predicted.height()) != (truth_grid.width(), truth_grid.height()) {
        return Err(CliError::Failed(format!(
            "{} is {}x{} but {} is {}x{}: score a segmentation against the truth of the same map",
            labels.display(),
            predicted.width(),
            predicted.height(),
            truth.display(),
            truth_grid.width(),
            truth_grid.height()
        )));
    }
    let s = score_segmentation(&predicted, &truth_grid);
    if json {
        println!("{}", serde_json::to_string(&s).expect("json"));
    } else {
        println!(
            "precision {:.4} recall {:.4} ({} predicted segments, {} truth segments)",
            s.precision, s.recall, s.predicted, s.truth
        );
    }
    Ok(())
}
