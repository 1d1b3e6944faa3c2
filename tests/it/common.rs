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

/// An empty folder for one test's files, `ksmcmc-PREFIX-PID-NAME` in the system's temporary
/// folder (emptied first if an earlier run left it).
pub fn tmp_dir(prefix: &str, name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("ksmcmc-{prefix}-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Runs the `ksmcmc` command line and fails the test if it panicked (whatever its exit code).
pub fn run_cli(args: &[&str]) -> std::process::Output {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_ksmcmc")).args(args).output().unwrap();
    let text = format!("{}{}", String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
    assert!(!text.contains("panicked"), "{args:?}: {text}");
    out
}
