//! `ksmcmc mln query|map|info`: Markov logic inference on a knowledge base and evidence.

use crate::args::{self, CliError};
use ksmcmc::mln::{Database, GroundConfig, InferenceConfig, MapConfig, MapMethod, Mln, MlnError, Network, Source};
use std::ffi::OsString;
use std::path::{Path, PathBuf};

const HELP: &str = "\
Usage:
  ksmcmc mln query --mln KB.mln [--db EVIDENCE.db] --query PRED[,PRED...] [options]
      marginal probability of every ground query atom, one per line: `Pred(A,B) 0.8731`
  ksmcmc mln map --mln KB.mln [--db EVIDENCE.db] [--query PRED,...] [options]
      the most probable world: every ground query atom with 1 (true) or 0 (false),
      or with --true-only just the true ones
  ksmcmc mln info --mln KB.mln [--db EVIDENCE.db] [--query PRED,...]
      declarations, formulas and the size of the ground network

Knowledge bases use the Alchemy / ProbCog format (see samples/knowledge/*.mln); evidence has
one ground atom per line: Pred(A,B), !Pred(A,B), or 0.8 Pred(A) for soft evidence.
Lines are sorted by predicate, then constants.

Options:
  --query P,Q           query predicates (open world); map and info default to every
                        predicate the evidence does not mention
  --method M            query: auto (default: exact when the network is thin, else mcsat),
                        exact (junction tree or enumeration), enumerate, mcsat, gibbs
                        map: maxwalksat (default) or exact (enumeration)
  --samples N           MC-SAT steps / Gibbs sweeps (default 5000)
  --burn-in N           steps discarded first (default 100)
  --seed S              random seed (default 1)
  --domain TYPE=A,B,C   constants of a type (closes its domain); repeatable
  --open P,Q            further open-world (hidden) predicates
  --closed P,Q          closed-world predicates (unlisted atoms false)
  --max-atoms N         refuse ground networks with more unknown atoms (default 1000000)
  --max-clauses N       refuse ground networks with more clauses (default 4000000)
  --flips N             map: MaxWalkSAT flips per try (default 10000)
  --tries N             map: MaxWalkSAT restarts (default 3)
  --true-only           map: print only the true query atoms
";

struct Options {
    command: String,
    kb: Option<PathBuf>,
    db: Option<PathBuf>,
    ground: GroundConfig,
    method: Option<String>,
    inference: InferenceConfig,
    map: MapConfig,
    true_only: bool,
}

fn list(name: &str, v: OsString) -> Result<Vec<String>, CliError> {
    let s: String = args::value(name, v)?;
    let items: Vec<String> = s.split(',').map(|p| p.trim().to_string()).filter(|p| !p.is_empty()).collect();
    if items.is_empty() {
        return Err(CliError::Usage(format!("{name} needs at least one name")));
    }
    Ok(items)
}

fn parse_options(argv: Vec<OsString>) -> Result<Option<Options>, CliError> {
    use lexopt::prelude::*;
    let mut parser = lexopt::Parser::from_args(argv);
    let mut o = Options {
        command: String::new(),
        kb: None,
        db: None,
        ground: GroundConfig::default(),
        method: None,
        inference: InferenceConfig::default(),
        map: MapConfig::default(),
        true_only: false,
    };
    while let Some(arg) = parser.next()? {
        match arg {
            Value(v) if o.command.is_empty() => o.command = args::value("command", v)?,
            Long("help") | Short('h') => {
                print!("{HELP}");
                return Ok(None);
            }
            Long("mln") => o.kb = Some(args::path(parser.value()?)),
            Long("db") => o.db = Some(args::path(parser.value()?)),
            Long("query") => o.ground.query.extend(list("--query", parser.value()?)?),
            Long("open") => o.ground.open_world.extend(list("--open", parser.value()?)?),
            Long("closed") => o.ground.closed_world.extend(list("--closed", parser.value()?)?),
            Long("domain") => {
                let s: String = args::value("--domain", parser.value()?)?;
                let Some((ty, consts)) = s.split_once('=') else {
                    return Err(CliError::Usage(format!("--domain {s:?}: expected TYPE=A,B,C")));
                };
                let consts: Vec<String> =
                    consts.split(',').map(|c| c.trim().to_string()).filter(|c| !c.is_empty()).collect();
                o.ground.domains.push((ty.trim().to_string(), consts));
            }
            Long("method") => o.method = Some(args::value("--method", parser.value()?)?),
            Long("samples") => o.inference.samples = args::value("--samples", parser.value()?)?,
            Long("burn-in") => o.inference.burn_in = args::value("--burn-in", parser.value()?)?,
            Long("seed") => {
                let seed = args::value("--seed", parser.value()?)?;
                o.inference.seed = seed;
                o.map.seed = seed;
            }
            Long("max-atoms") => o.ground.max_atoms = args::value("--max-atoms", parser.value()?)?,
            Long("max-clauses") => o.ground.max_clauses = args::value("--max-clauses", parser.value()?)?,
            Long("flips") => o.map.max_flips = args::value("--flips", parser.value()?)?,
            Long("tries") => o.map.tries = args::value("--tries", parser.value()?)?,
            Long("true-only") => o.true_only = true,
            _ => return Err(arg.unexpected().into()),
        }
    }
    Ok(Some(o))
}

pub fn run(argv: Vec<OsString>) -> Result<(), CliError> {
    let Some(mut o) = parse_options(argv)? else {
        return Ok(());
    };
    let command = match o.command.as_str() {
        "" => return Err(CliError::Usage("mln needs a command: query, map or info; run `ksmcmc mln --help`".into())),
        c @ ("query" | "map" | "info") => c.to_string(),
        c => return Err(CliError::Usage(format!("unknown mln command {c:?}: query, map or info"))),
    };
    let kb_path = args::required(o.kb.take(), "--mln KB.mln", "mln")?;
    if command == "query" && o.ground.query.is_empty() {
        return Err(CliError::Usage("mln query needs --query PRED[,PRED...]".into()));
    }
    match (command.as_str(), o.method.as_deref()) {
        (_, None) => {}
        ("query", Some(m)) => o.inference.method = m.parse().map_err(CliError::Usage)?,
        ("map", Some("maxwalksat")) => o.map.method = MapMethod::MaxWalkSat,
        ("map", Some("exact")) => o.map.method = MapMethod::Exact,
        (c, Some(m)) => return Err(CliError::Usage(format!("--method {m:?} does not apply to mln {c}"))),
    }

    let kb_text = read(&kb_path)?;
    // Name the file a positioned error is in; otherwise the step that failed.
    let locate = |step: &str, e: MlnError| -> CliError {
        let file = match e.source {
            Some(Source::KnowledgeBase) => kb_path.display().to_string(),
            Some(Source::Evidence) => o.db.as_deref().map_or("evidence".into(), |p| p.display().to_string()),
            None => step.to_string(),
        };
        args::failed(file, e)
    };
    let mln = Mln::parse(&kb_text).map_err(|e| locate("", e))?;
    let db = match &o.db {
        Some(p) => Database::parse(&read(p)?, &mln).map_err(|e| locate("", e))?,
        None => Database::new(),
    };
    let net = Network::ground(&mln, &db, &o.ground).map_err(|e| locate("grounding", e))?;
    match command.as_str() {
        "query" => {
            let m = net.infer_marginals(&o.inference).map_err(|e| locate("inference", e))?;
            let mut out = String::new();
            for (atom, p) in m.iter() {
                out.push_str(&format!("{atom} {p:.4}\n"));
            }
            print!("{out}");
        }
        "map" => {
            let w = net.map(&o.map).map_err(|e| locate("MAP inference", e))?;
            let mut out = String::new();
            for (atom, v) in w.iter() {
                if !o.true_only {
                    out.push_str(&format!("{atom} {}\n", v as u8));
                } else if v {
                    out.push_str(&format!("{atom}\n"));
                }
            }
            print!("{out}");
        }
        _ => {
            println!("{}:", kb_path.display());
            for p in mln.predicates() {
                println!("  {}({})", p.name(), mln.argument_types(p).join(", "));
            }
            for f in mln.formulas() {
                let w = match f.weight() {
                    ksmcmc::mln::Weight::Hard => "hard".to_string(),
                    ksmcmc::mln::Weight::Soft(w) => format!("{w:.4}"),
                };
                println!("  {w:>8}  {}", f.text());
            }
            println!(
                "ground network: {} unknown atoms, {} clauses, {} features ({} hard), {} query atoms",
                net.atom_count(),
                net.clause_count(),
                net.feature_count(),
                net.hard_feature_count(),
                net.query_count()
            );
        }
    }
    Ok(())
}

fn read(path: &Path) -> Result<String, CliError> {
    std::fs::read_to_string(path).map_err(|e| args::failed(path.display(), e))
}
