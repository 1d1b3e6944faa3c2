//! `ksmcmc mln query|map|info|learn|evidence`: Markov logic inference on a knowledge base and
//! evidence, weight learning from training worlds, and evidence from floor-plan worlds.

use crate::args::{self, CliError};
use ksmcmc::floorplan::knowledge::{self, GeometryClassifier};
use ksmcmc::floorplan::World;
use ksmcmc::mln::{
    learn_weights, Database, GroundConfig, InferenceConfig, LearnConfig, MapConfig, MapMethod, Mln, MlnError, Network,
    Source,
};
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
  ksmcmc mln learn --mln KB.mln --db TRAIN.db [--db TRAIN2.db ...] [--out LEARNED.mln] [options]
      learn the weights of the soft formulas from complete training worlds (atoms a database
      does not list are false; each database has its own constants) and write the knowledge
      base with them (to standard output without --out); hard formulas stay hard
  ksmcmc mln evidence --world truth.json (--map map.yaml | --resolution M) [--truth] [--mln KB]
                      [--out FILE]
      the indoor evidence (RoLi, CoLi, HaLi, MulDoor, Adj, Small, Narrow, Circ) of a floor-plan world as a
      database; with --truth also its true Room/Corr/Hall/Other types and SaLe pairs
      (connecting walls within 10 % of each other), a training world for `mln learn`;
      geometry classes by the default classifier of Tab. 3.6 (halls from 60 m²,
      corridors 3.5 times as long as wide, small under 10 m², narrow under 2.5 m; Circ:
      doors to three spaces or to two corridor- or hall-like ones); with --mln only the
      predicates that knowledge base declares (Tab. 3.5's indoor.mln has no Small)
  ksmcmc mln evidence --rooms --world world.json --map MAP [--truth-labels LABELS.pgm]
                      [--mln KB] [--out FILE]
      the room layer's evidence (Open, Flush, Closed, Room/Corr/Hall/Other) of a chain's world.json
      (from `ksmcmc floorplan MAP`) as the room rules (samples/knowledge/rooms.mln) are given
      it; with --truth-labels (the truth_labels.pgm of `ksmcmc synth`) also SameRoom for each
      open pair whose units lie mostly in the same truth room: a training world for
      `mln learn --query SameRoom`

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

Learning (mln learn):
  --method M            pll (default): pseudo-log-likelihood, the sum over ground atoms of
                        log P(atom | its Markov blanket), over the --query predicates' atoms
                        given the others, or over all atoms without --query;
                        discriminative: conditional log-likelihood of the --query predicates
                        given the others (needs --query); expected counts exact, or by
                        MC-SAT for a database whose query atoms form a connected part of
                        more than --max-exact atoms
  --prior-sigma S       standard deviation of the Gaussian prior on each weight (default 2,
                        Alchemy's for discriminative learning); `inf` for none
  --iterations N        most L-BFGS iterations (default 200)
  --max-exact N         discriminative: largest connected part of query atoms enumerated
                        (default 16); larger ones are sampled
  --samples N, --seed S discriminative with MC-SAT: samples per database and iteration
                        (default 500) and seed (default 1); learning is otherwise
                        deterministic and draws no random numbers
";

struct Options {
    command: String,
    kb: Option<PathBuf>,
    dbs: Vec<PathBuf>,
    ground: GroundConfig,
    method: Option<String>,
    inference: InferenceConfig,
    map: MapConfig,
    learn: LearnConfig,
    samples: Option<u32>,
    true_only: bool,
    out: Option<PathBuf>,
    world: Option<PathBuf>,
    map_yaml: Option<PathBuf>,
    resolution: Option<f64>,
    truth: bool,
    rooms: bool,
    truth_labels: Option<PathBuf>,
}

fn list(name: &str, v: OsString) -> Result<Vec<String>, CliError> {
    let s: String = args::value(name, v)?;
    let items: Vec<String> = s.split(',').map(|p| p.trim().to_string()).filter(|p| !p.is_empty()).collect();
    if items.is_empty() {
        return Err(CliError::Usage(format!("{name} needs at least one name")));
    }
    Ok(items)
}

fn domain(v: OsString) -> Result<(String, Vec<String>), CliError> {
    let s: String = args::value("--domain", v)?;
    let Some((ty, consts)) = s.split_once('=') else {
        return Err(CliError::Usage(format!("--domain {s:?}: expected TYPE=A,B,C")));
    };
    let consts: Vec<String> = consts.split(',').map(|c| c.trim().to_string()).filter(|c| !c.is_empty()).collect();
    Ok((ty.trim().to_string(), consts))
}

fn parse_options(argv: Vec<OsString>) -> Result<Option<Options>, CliError> {
    use lexopt::prelude::*;
    let mut parser = lexopt::Parser::from_args(argv);
    let mut o = Options {
        command: String::new(),
        kb: None,
        dbs: Vec::new(),
        ground: GroundConfig::default(),
        method: None,
        inference: InferenceConfig::default(),
        map: MapConfig::default(),
        learn: LearnConfig::default(),
        samples: None,
        true_only: false,
        out: None,
        world: None,
        map_yaml: None,
        resolution: None,
        truth: false,
        rooms: false,
        truth_labels: None,
    };
    while let Some(arg) = parser.next()? {
        match arg {
            Value(v) if o.command.is_empty() => o.command = args::value("command", v)?,
            Long("help") | Short('h') => {
                print!("{HELP}");
                return Ok(None);
            }
            Long("mln") => o.kb = Some(args::path(parser.value()?)),
            Long("db") => o.dbs.push(args::path(parser.value()?)),
            Long("query") => o.ground.query.extend(list("--query", parser.value()?)?),
            Long("open") => o.ground.open_world.extend(list("--open", parser.value()?)?),
            Long("closed") => o.ground.closed_world.extend(list("--closed", parser.value()?)?),
            Long("domain") => o.ground.domains.push(domain(parser.value()?)?),
            Long("method") => o.method = Some(args::value("--method", parser.value()?)?),
            Long("samples") => {
                let n = args::value("--samples", parser.value()?)?;
                o.inference.samples = n;
                o.samples = Some(n);
            }
            Long("burn-in") => o.inference.burn_in = args::value("--burn-in", parser.value()?)?,
            Long("seed") => {
                let seed = args::value("--seed", parser.value()?)?;
                o.inference.seed = seed;
                o.map.seed = seed;
                o.learn.seed = seed;
            }
            Long("max-atoms") => o.ground.max_atoms = args::value("--max-atoms", parser.value()?)?,
            Long("max-clauses") => o.ground.max_clauses = args::value("--max-clauses", parser.value()?)?,
            Long("flips") => o.map.max_flips = args::value("--flips", parser.value()?)?,
            Long("tries") => o.map.tries = args::value("--tries", parser.value()?)?,
            Long("true-only") => o.true_only = true,
            Long("prior-sigma") => o.learn.prior_sigma = args::value("--prior-sigma", parser.value()?)?,
            Long("iterations") => o.learn.iterations = args::value("--iterations", parser.value()?)?,
            Long("max-exact") => o.learn.max_exact_atoms = args::value("--max-exact", parser.value()?)?,
            Long("out") => o.out = Some(args::path(parser.value()?)),
            Long("world") => o.world = Some(args::path(parser.value()?)),
            Long("map") => o.map_yaml = Some(args::path(parser.value()?)),
            Long("resolution") => o.resolution = Some(args::value("--resolution", parser.value()?)?),
            Long("truth") => o.truth = true,
            Long("rooms") => o.rooms = true,
            Long("truth-labels") => o.truth_labels = Some(args::path(parser.value()?)),
            _ => return Err(arg.unexpected().into()),
        }
    }
    Ok(Some(o))
}

const COMMANDS: &str = "query, map, info, learn or evidence";

pub fn run(argv: Vec<OsString>) -> Result<(), CliError> {
    let Some(mut o) = parse_options(argv)? else {
        return Ok(());
    };
    let command = match o.command.as_str() {
        "" => return Err(CliError::Usage(format!("mln needs a command: {COMMANDS}; run `ksmcmc mln --help`"))),
        c @ ("query" | "map" | "info" | "learn" | "evidence") => c.to_string(),
        c => return Err(CliError::Usage(format!("unknown mln command {c:?}: {COMMANDS}"))),
    };
    if command == "evidence" {
        return evidence(&o);
    }
    let kb_path = args::required(o.kb.take(), "--mln KB.mln", "mln")?;
    if command == "learn" {
        return learn(o, &kb_path);
    }
    if o.dbs.len() > 1 {
        return Err(CliError::Usage(format!("mln {command} takes one --db (only learn takes several)")));
    }
    if command == "query" && o.ground.query.is_empty() {
        return Err(CliError::Usage("mln query needs --query PRED[,PRED...]".into()));
    }
    match (command.as_str(), o.method.as_deref()) {
        (_, None) => {}
        ("query", Some(m)) => {
            o.inference.method = m.parse().map_err(|e: ksmcmc::mln::UnknownMethod| CliError::Usage(e.to_string()))?
        }
        ("map", Some("maxwalksat")) => o.map.method = MapMethod::MaxWalkSat,
        ("map", Some("exact")) => o.map.method = MapMethod::Exact,
        (c, Some(m)) => return Err(CliError::Usage(format!("--method {m:?} does not apply to mln {c}"))),
    }

    let kb_text = read(&kb_path)?;
    let db_path = o.dbs.first().cloned();
    let locate = |step: &str, e: MlnError| locate(&kb_path, db_path.as_deref(), step, e);
    let mln = Mln::parse(&kb_text).map_err(|e| locate("", e))?;
    let db = match &db_path {
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
        _ => info(&kb_path, &mln, &net),
    }
    Ok(())
}

/// Names the file a positioned error is in; otherwise the step that failed.
fn locate(kb: &Path, db: Option<&Path>, step: &str, e: MlnError) -> CliError {
    let file = match e.source {
        Some(Source::KnowledgeBase) => kb.display().to_string(),
        Some(Source::Evidence) => db.map_or("evidence".into(), |p| p.display().to_string()),
        None => step.to_string(),
    };
    args::failed(file, e)
}

fn info(kb_path: &Path, mln: &Mln, net: &Network) {
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

/// `mln learn`: reads the knowledge base and the training worlds, learns, writes the result.
fn learn(mut o: Options, kb_path: &Path) -> Result<(), CliError> {
    if o.dbs.is_empty() {
        return Err(CliError::Usage("mln learn needs at least one --db TRAIN.db".into()));
    }
    if !o.ground.open_world.is_empty() || !o.ground.closed_world.is_empty() {
        return Err(CliError::Usage(
            "--open and --closed do not apply to mln learn: training worlds are complete".into(),
        ));
    }
    if let Some(m) = &o.method {
        o.learn.method = m.parse().map_err(|e| CliError::Usage(format!("--method: {e}")))?;
    }
    o.learn.query = std::mem::take(&mut o.ground.query);
    if let Some(n) = o.samples {
        o.learn.samples = n;
    }
    o.learn.ground = o.ground.clone();
    let mln = Mln::parse(&read(kb_path)?).map_err(|e| locate(kb_path, None, "", e))?;
    let mut dbs = Vec::new();
    for p in &o.dbs {
        dbs.push(Database::parse(&read(p)?, &mln).map_err(|e| locate(kb_path, Some(p), "", e))?);
    }
    let learned = learn_weights(&mln, &dbs, &o.learn).map_err(|e| {
        // An error positioned in evidence names no database: find the first that fails alone.
        let culprit = match e.source {
            Some(Source::Evidence) => {
                (0..dbs.len()).find(|&i| ksmcmc::mln::Learner::new(&mln, &dbs[i..=i], &o.learn).is_err())
            }
            _ => None,
        };
        locate(kb_path, culprit.map(|i| o.dbs[i].as_path()), "learning", e)
    })?;
    let method = match o.learn.method {
        ksmcmc::mln::LearnMethod::PseudoLikelihood => "pseudo-log-likelihood",
        ksmcmc::mln::LearnMethod::Discriminative => "discriminative (conditional log-likelihood)",
    };
    let query = if o.learn.query.is_empty() { "all predicates".to_string() } else { o.learn.query.join(", ") };
    let files: Vec<String> = o.dbs.iter().map(|p| p.display().to_string()).collect();
    let header = format!(
        "Weights learned by `ksmcmc mln learn` from {kb}.\nMethod: {method}; query predicates: {query}; \
         Gaussian prior sigma {sigma}.\nTraining worlds ({n}): {files}.\n{progress}\nFormulas ending in '.' are \
         hard and were not learned; `// was` gives each soft formula's former weight.",
        kb = kb_path.display(),
        sigma = o.learn.prior_sigma,
        n = files.len(),
        files = files.join(", "),
        progress = progress(&learned, &o.learn),
    );
    let text = learned.to_mln(&mln, &header);
    eprintln!("{}", header.replace('\n', " "));
    match &o.out {
        Some(p) => args::write(p, text.as_bytes()),
        None => {
            print!("{text}");
            Ok(())
        }
    }
}

fn progress(learned: &ksmcmc::mln::Learned, config: &LearnConfig) -> String {
    if learned.sampled {
        return format!(
            "Expected counts by MC-SAT ({} samples, seed {}): {} diagonal Newton iterations, weights averaged \
             over the second half; last largest gradient component {:.2e}.",
            config.samples, config.seed, learned.iterations, learned.gradient
        );
    }
    format!(
        "Objective {:.6}, largest gradient component {:.2e} after {} L-BFGS iterations{}.",
        learned.objective,
        learned.gradient,
        learned.iterations,
        if learned.converged { "" } else { " (not converged: raise --iterations)" }
    )
}

/// `mln evidence --rooms`: the room layer's evidence of a chain's world (and with
/// --truth-labels the SameRoom atoms).
fn room_evidence(o: &Options) -> Result<(), CliError> {
    use ksmcmc::floorplan::{export::RoomInput, rooms};
    if o.truth || o.resolution.is_some() {
        return Err(CliError::Usage(
            "mln evidence --rooms takes --truth-labels, not --truth, and the map itself (--map), not --resolution"
                .into(),
        ));
    }
    let world_path = args::required(o.world.as_ref(), "--world world.json", "mln evidence")?;
    let map_path = args::required(o.map_yaml.as_ref(), "--map MAP (the map the world explains)", "mln evidence")?;
    let map = args::load_classified(map_path, "auto")?;
    let world = args::load_world(world_path, &map)?;
    let units = world.units.len();
    let input =
        RoomInput::for_map(world, &map, true, Default::default()).map_err(|e| args::failed(world_path.display(), e))?;
    let truth = match &o.truth_labels {
        Some(p) => {
            let bytes = std::fs::read(p).map_err(|e| args::failed(p.display(), e))?;
            rooms::truth_labels_from_pgm(&bytes).map_err(|e| args::failed(p.display(), e))?
        }
        // Without truth no unit lies in a truth room: the SameRoom atoms are dropped below.
        None => ksmcmc::grid::Grid::new(map.width(), map.height(), 0),
    };
    let t = input
        .room_training(&truth, &rooms::RoomConfig::default())
        .map_err(|e| args::failed(o.truth_labels.as_ref().map_or(world_path.display(), |p| p.display()), e))?;
    let mut facts = t.facts;
    if o.truth_labels.is_none() {
        facts.retain(|f| f.0 != "SameRoom");
    }
    if let Some(kb) = &o.kb {
        let mln = Mln::parse(&read(kb)?).map_err(|e| args::failed(kb.display(), e))?;
        facts.retain(|f| mln.predicate(f.0).is_some());
    }
    let what = if o.truth_labels.is_some() { "training world (evidence and true SameRoom atoms)" } else { "evidence" };
    let stray = t.truth_rooms.iter().filter(|r| r.is_none()).count();
    let mut text =
        format!("// Room-layer {what} of {}, {units} units, {} open pairs", world_path.display(), t.open_pairs);
    if o.truth_labels.is_some() {
        text.push_str(&format!(", {} in one truth room; {stray} units in no truth room", t.same_room));
    }
    text.push_str(&format!(".\n// Closed world: atoms not listed are false.\n{}", knowledge::database_text(&facts)));
    match &o.out {
        Some(p) => args::write(p, text.as_bytes()),
        None => {
            print!("{text}");
            Ok(())
        }
    }
}

/// `mln evidence`: the indoor evidence (and with --truth the query atoms) of a world.
fn evidence(o: &Options) -> Result<(), CliError> {
    if o.rooms {
        return room_evidence(o);
    }
    if o.truth_labels.is_some() {
        return Err(CliError::Usage("--truth-labels needs --rooms (the room layer's training world)".into()));
    }
    let world_path = args::required(o.world.as_ref(), "--world truth.json", "mln evidence")?;
    let resolution = match (o.resolution, &o.map_yaml) {
        (Some(r), None) => r,
        (None, Some(p)) => {
            let yaml = ksmcmc::grid::MapYaml::parse(&read(p)?).map_err(|e| args::failed(p.display(), e))?;
            yaml.resolution
        }
        _ => return Err(CliError::Usage("mln evidence needs one of --map map.yaml and --resolution M".into())),
    };
    if !(resolution.is_finite() && resolution > 0.0) {
        return Err(CliError::Usage(format!("--resolution {resolution}: must be a positive number of metres")));
    }
    let world = World::from_json(&read(world_path)?).map_err(|e| args::failed(world_path.display(), e))?;
    let classifier = GeometryClassifier::default();
    let untyped = world.units.iter().filter(|u| u.kind == ksmcmc::floorplan::UnitType::Unknown).count();
    if o.truth && untyped > 0 {
        eprintln!(
            "warning: {}: {untyped} units have no type; as training data they are neither rooms, corridors, \
             halls nor others",
            world_path.display()
        );
    }
    let mut facts = if o.truth {
        knowledge::training_facts(&world, resolution, &classifier)
    } else {
        knowledge::evidence(&world, resolution, &classifier)
    };
    if let Some(kb) = &o.kb {
        let mln = Mln::parse(&read(kb)?).map_err(|e| args::failed(kb.display(), e))?;
        facts.retain(|f| mln.predicate(f.0).is_some());
    }
    let what = if o.truth { "training world (evidence and true query atoms)" } else { "evidence" };
    let text = format!(
        "// Indoor {what} of {}, {} units, {resolution} m per cell.\n\
         // Closed world: atoms not listed are false.\n{}",
        world_path.display(),
        world.units.len(),
        knowledge::database_text(&facts)
    );
    match &o.out {
        Some(p) => args::write(p, text.as_bytes()),
        None => {
            print!("{text}");
            Ok(())
        }
    }
}

fn read(path: &Path) -> Result<String, CliError> {
    std::fs::read_to_string(path).map_err(|e| args::failed(path.display(), e))
}
