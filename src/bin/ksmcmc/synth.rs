//! `ksmcmc synth` (being written).

use crate::args::CliError;
use std::ffi::OsString;

pub fn run(_argv: Vec<OsString>) -> Result<(), CliError> {
    Err(CliError::Failed("synth is not implemented yet".into()))
}
