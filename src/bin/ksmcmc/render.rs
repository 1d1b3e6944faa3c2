//! `ksmcmc render` (being written).

use crate::args::CliError;
use std::ffi::OsString;

pub fn run(_argv: Vec<OsString>) -> Result<(), CliError> {
    Err(CliError::Failed("render is not implemented yet".into()))
}
