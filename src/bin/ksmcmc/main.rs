//! The `ksmcmc` command-line tool: a thin front end over the library.
//!
//! Exit codes: 0 success, 1 the work failed (bad map, unreadable file), 2 the command line is
//! wrong.

mod args;
mod bench;
mod evaluate;
mod explore;
mod floorplan;
mod frontier_eval;
mod goals_eval;
mod info;
mod mln;
mod realistic_eval;
mod render;
mod route;
mod score;
mod settle_eval;
mod synth;
mod tabletop;
mod tabletop_synth;

use std::process::ExitCode;

const USAGE: &str = "\
ksmcmc: semantic floor plans from occupancy grids by knowledge-supervised MCMC

Usage:
  ksmcmc info MAP                          size and cell classes of a map
  ksmcmc render MAP [--world world.json] --out out.png
                                           draw a classified map, optionally with a world over it
  ksmcmc floorplan MAP --out DIR [--iterations N] [--seed S] [--time-limit SEC]
                                           explain a map with a semantic floor plan
  ksmcmc route MAP WORLD.json --from X,Y --to X,Y
                                           a route through the world's rooms and doors (JSON)
  ksmcmc explore MAP --out DIR [--seed S]  a simulated robot explores MAP; the floor plan
                                           follows it online (warm against cold chains)
  ksmcmc score LABELS TRUTH                segmentation precision and recall
  ksmcmc bench                             speed of the engine (for BENCHMARKS.md)
  ksmcmc evaluate                          quality on real and synthetic maps (BENCHMARKS.md)
  ksmcmc synth --seed N --out DIR [options]
                                           generate a synthetic floor plan with ground truth
  ksmcmc mln query|map|info --mln KB.mln [--db EVIDENCE.db] [--query P,Q]
                                           Markov logic marginals, most probable world, network size
  ksmcmc mln learn --mln KB.mln --db TRAIN.db [--db ...] [--out LEARNED.mln]
                                           learn formula weights from complete training worlds
  ksmcmc mln evidence --world truth.json --map map.yaml [--truth]
                                           indoor evidence (and training world) of a floor plan
  ksmcmc tabletop SCENE.json --out DIR [--iterations N] [--seed S]
                                           scene graph of a table-top scene from 6D poses
  ksmcmc tabletop-synth --seed N --out scene.json
                                           generate a table-top scene with ground truth
  ksmcmc tabletop-eval [--scenes N]        table-top accuracy and speed (BENCHMARKS.md)
  ksmcmc help                              this text

MAP is a PGM (P2/P5, 8 or 16 bits), a PNG of any colour type, or a ROS map.yaml.
Run `ksmcmc COMMAND --help` for a command's options.
";

fn main() -> ExitCode {
    // Bugs must not print a Rust backtrace at users; say what happened and where to report it.
    std::panic::set_hook(Box::new(|info| {
        eprintln!("ksmcmc: internal error (this is a bug, please report it): {info}");
    }));
    tune_malloc();
    quiet_on_closed_pipe();
    let mut argv = std::env::args_os().skip(1);
    let Some(command) = argv.next() else {
        eprint!("{USAGE}");
        return ExitCode::from(2);
    };
    let rest: Vec<_> = argv.collect();
    let result = match command.to_str() {
        Some("info") => info::run(rest),
        Some("render") => render::run(rest),
        Some("floorplan") => floorplan::run(rest),
        Some("score") => score::run(rest),
        Some("route") => route::run(rest),
        Some("explore") => explore::run(rest),
        Some("bench") => bench::run(rest),
        Some("evaluate") => evaluate::run(rest),
        Some("synth") => synth::run(rest),
        Some("tabletop") => tabletop::run(rest),
        Some("tabletop-synth") => tabletop_synth::run(rest),
        Some("tabletop-eval") => tabletop::eval(rest),
        Some("mln") => mln::run(rest),
        Some("help" | "--help" | "-h") => {
            print!("{USAGE}");
            Ok(())
        }
        Some("--version" | "-V") => {
            println!("ksmcmc {}", env!("CARGO_PKG_VERSION"));
            Ok(())
        }
        _ => Err(args::CliError::Usage(format!(
            "unknown command {:?}; run `ksmcmc help` for the list",
            command.to_string_lossy()
        ))),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(args::CliError::Usage(m)) => {
            eprintln!("ksmcmc: {m}");
            ExitCode::from(2)
        }
        Err(args::CliError::Failed(m)) => {
            eprintln!("ksmcmc: {m}");
            ExitCode::from(1)
        }
    }
}

/// Ends the process quietly, as other command-line tools do, when what reads its output
/// closes the pipe (`ksmcmc info MAP | head -1`): Rust ignores SIGPIPE, so the next print
/// would fail with "Broken pipe" and report an internal error. With the signal's default
/// action restored the shell sees the usual exit status 141. Elsewhere a no-op.
fn quiet_on_closed_pipe() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    // SAFETY: restores a signal's default disposition before any threads start.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
}

/// Sets glibc's malloc for a run that allocates and frees map-sized tables over and over.
///
/// * The mmap threshold fixed at glibc's default (128 KiB): the chain's setup allocates and
///   frees buffers of a few MB, and glibc would raise its threshold to their size, so later
///   buffers of that size would come from a heap it rarely gives back; the resident set of a
///   `floorplan` run on a 1237x672 map ended up 20 MB above the live heap (70.9 MB against
///   65.3 MB with the threshold fixed; BENCHMARKS.md).
/// * One arena, and 64 MiB kept at the top of the heap when it is trimmed (a few map-sized
///   tables: a 1237x672 map's 4-byte tables are 3.3 MB, office_g's 19 MB): the stages free
///   what the next one allocates again, and glibc gave the freed top of the heap back to the
///   system each time, so every new table touched fresh pages. Cartesium took 85,000 page
///   faults and 800 ms of CPU, now 16,000 and 660 ms, with the resident set 62.9 → 63.6 MB;
///   without the one arena each thread's arena kept its own pad (92 MB).
///
/// Only the binary: a library does not set its host's allocator. A no-op on other platforms
/// and C libraries.
fn tune_malloc() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    // SAFETY: mallopt only changes allocator parameters; it is called before any threads start.
    unsafe {
        libc::mallopt(libc::M_MMAP_THRESHOLD, 128 * 1024);
        libc::mallopt(libc::M_ARENA_MAX, 1);
        libc::mallopt(libc::M_TOP_PAD, 64 << 20);
    }
}
