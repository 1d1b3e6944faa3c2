//! Helpers the test modules share: where the real maps are.

use std::path::{Path, PathBuf};

/// The real maps (`radish/`, `bormann2016/`): `$KSMCMC_DATASETS`, or `../shared/datasets` beside
/// the checkout. `None`, after printing why, when they are absent: tests that need them then
/// skip, so that `cargo test` passes on a fresh clone. A `KSMCMC_DATASETS` that names no
/// folder is a mistake and fails the test.
pub fn datasets(test: &str) -> Option<PathBuf> {
    if let Some(dir) = std::env::var_os("KSMCMC_DATASETS") {
        let dir = PathBuf::from(dir);
        assert!(dir.is_dir(), "KSMCMC_DATASETS={} is not a folder", dir.display());
        return Some(dir);
    }
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/datasets");
    if dir.is_dir() {
        Some(dir)
    } else {
        println!("skipped: {test} needs the real maps in ../shared/datasets (set KSMCMC_DATASETS)");
        None
    }
}
