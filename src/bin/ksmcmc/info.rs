//! `ksmcmc info MAP`: what a map is, as the loader sees it.

use crate::args::{self, CliError};
use ksmcmc::grid::Cell;
use std::ffi::OsString;

const HELP: &str = "Usage: ksmcmc info MAP\n\nPrints the size, resolution and cell classes of a map.\n";

pub fn run(argv: Vec<OsString>) -> Result<(), CliError> {
    use lexopt::prelude::*;
    let mut parser = lexopt::Parser::from_args(argv);
    let mut map = None;
    while let Some(arg) = parser.next()? {
        match arg {
            Value(v) if map.is_none() => map = Some(args::path(v)),
            Long("help") | Short('h') => {
                print!("{HELP}");
                return Ok(());
            }
            _ => return Err(arg.unexpected().into()),
        }
    }
    let path = args::required(map, "a MAP", "info")?;
    let m = args::load_map(&path)?;
    let n = (m.width() * m.height()) as f64;
    println!("{}: {} x {} cells, {} m/cell", path.display(), m.width(), m.height(), m.yaml().resolution);
    for c in [Cell::Free, Cell::Unknown, Cell::Occupied] {
        let k = m.count(c);
        println!("  {:<9} {:>9} ({:.1} %)", format!("{c:?}").to_lowercase(), k, 100.0 * k as f64 / n);
    }
    Ok(())
}
