//! `ksmcmc mln` end to end: output format, exit codes, positioned errors.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

const KB: &str = "samples/knowledge/indoor.mln";
const DB: &str = "samples/knowledge/indoor.db";
const QUERY: &str = "Room,Corr,Hall,Other,SaLe";

fn ksmcmc(args: &[&str]) -> Output {
    let out = Command::new(env!("CARGO_BIN_EXE_ksmcmc"))
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .args(args)
        .output()
        .expect("run ksmcmc");
    let text = format!("{}{}", String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
    assert!(!text.contains("panicked"), "ksmcmc {args:?} panicked: {text}");
    out
}

fn run_ok(args: &[&str]) -> String {
    let out = ksmcmc(args);
    assert!(out.status.success(), "ksmcmc {args:?} failed: {}", String::from_utf8_lossy(&out.stderr));
    String::from_utf8(out.stdout).unwrap()
}

fn run_err(args: &[&str], code: i32) -> String {
    let out = ksmcmc(args);
    assert_eq!(out.status.code(), Some(code), "ksmcmc {args:?}: {}", String::from_utf8_lossy(&out.stderr));
    String::from_utf8(out.stderr).unwrap()
}

fn scratch(name: &str, text: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("mln_cli");
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

#[test]
fn query_prints_one_sorted_line_per_ground_query_atom() {
    let out = run_ok(&["mln", "query", "--mln", KB, "--db", DB, "--query", QUERY]);
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(lines.len(), 4 * 4 + 4 * 4, "{out}");
    let mut sorted = lines.clone();
    sorted.sort();
    assert_eq!(lines, sorted);
    for line in &lines {
        let (atom, p) = line.rsplit_once(' ').unwrap();
        assert!(atom.ends_with(')'), "{line}");
        let p: f64 = p.parse().unwrap();
        assert!((0.0..=1.0).contains(&p) && p.to_string().len() <= 6, "{line}");
    }
    assert!(lines.contains(&"SaLe(U1,U4) 0.0000"), "not adjacent");
    // The methods agree.
    let exact = run_ok(&["mln", "query", "--mln", KB, "--db", DB, "--query", QUERY, "--method", "exact"]);
    assert_eq!(out, exact, "auto is exact on this small network");
    let gibbs = run_ok(&[
        "mln",
        "query",
        "--mln",
        KB,
        "--db",
        DB,
        "--query",
        QUERY,
        "--method",
        "gibbs",
        "--samples",
        "20000",
        "--seed",
        "3",
    ]);
    for (a, b) in exact.lines().zip(gibbs.lines()) {
        let (pa, pb): (f64, f64) =
            (a.rsplit_once(' ').unwrap().1.parse().unwrap(), b.rsplit_once(' ').unwrap().1.parse().unwrap());
        assert!((pa - pb).abs() < 0.02, "{a} vs {b}");
    }
    // Same seed, same output.
    let mcsat = |seed| {
        run_ok(&[
            "mln",
            "query",
            "--mln",
            KB,
            "--db",
            DB,
            "--query",
            "Hall",
            "--method",
            "mcsat",
            "--samples",
            "500",
            "--seed",
            seed,
        ])
    };
    assert_eq!(mcsat("5"), mcsat("5"));
}

#[test]
fn map_prints_the_most_probable_world() {
    let all = run_ok(&["mln", "map", "--mln", KB, "--db", DB, "--query", "Room,Hall"]);
    assert_eq!(all.lines().count(), 8);
    assert!(all.lines().all(|l| l.ends_with(" 0") || l.ends_with(" 1")), "{all}");
    assert!(all.contains("Hall(U4) 1\n") && all.contains("Room(U1) 1\n"), "{all}");
    let true_only = run_ok(&["mln", "map", "--mln", KB, "--db", DB, "--query", "Room,Hall", "--true-only"]);
    let expected: String = all.lines().filter_map(|l| l.strip_suffix(" 1")).map(|a| format!("{a}\n")).collect();
    assert_eq!(true_only, expected);
    let exact = run_ok(&["mln", "map", "--mln", KB, "--db", DB, "--query", "Room,Hall", "--method", "exact"]);
    assert_eq!(exact, all);
    let table = run_ok(&[
        "mln",
        "map",
        "--mln",
        "samples/knowledge/tabletop.mln",
        "--db",
        "samples/knowledge/tabletop.db",
        "--query",
        "false",
        "--true-only",
    ]);
    assert!(table.contains("false(O6)"), "{table}");
}

#[test]
fn info_describes_the_network() {
    let out = run_ok(&["mln", "info", "--mln", KB, "--db", DB, "--query", QUERY]);
    assert!(out.contains("Adj(unit, unit)"), "{out}");
    assert!(out.contains("hard  SaLe(p, q) => SaLe(q, p)"), "{out}");
    assert!(out.contains("ground network: 24 unknown atoms"), "{out}");
}

#[test]
fn bad_knowledge_bases_and_evidence_fail_with_positions() {
    let kb = scratch("bad.mln", "RoLi(unit)\nAdj(unit,unit)\n1.0 RoLi(x) ^ Adj(x, y ^ RoLi(y)\n");
    let e = run_err(&["mln", "query", "--mln", kb.to_str().unwrap(), "--query", "RoLi"], 1);
    assert_eq!(
        e,
        format!("ksmcmc: {}: line 3, column 24: expected ')' after the arguments of Adj, found '^'\n", kb.display())
    );
    let db = scratch("bad.db", "RoLi(U1)\nAdj(U1,U2)\nAdj(U2,U1)\nHall(U1\n");
    let e = run_err(&["mln", "query", "--mln", KB, "--db", db.to_str().unwrap(), "--query", "Hall"], 1);
    assert_eq!(
        e,
        format!(
            "ksmcmc: {}: line 4, column 8: expected ')' after the arguments of Hall, found end of line\n",
            db.display()
        )
    );
    // Evidence breaking a hard formula points into the knowledge base.
    let db = scratch("asym.db", "Adj(U1,U2)\n");
    let e = run_err(&["mln", "query", "--mln", KB, "--db", db.to_str().unwrap(), "--query", "Hall"], 1);
    assert!(e.starts_with(&format!("ksmcmc: {KB}: line ")) && e.contains("violates the hard formula"), "{e}");
    // Too large for exact inference, and a size limit.
    let e = run_err(&["mln", "query", "--mln", KB, "--db", DB, "--query", QUERY, "--max-atoms", "5"], 1);
    assert!(e.contains("more than 5 ground atoms"), "{e}");
    let e = run_err(&["mln", "query", "--mln", KB, "--query", "Kitchen"], 1);
    assert_eq!(e, "ksmcmc: grounding: Kitchen is not a declared predicate (declare it first, e.g. `Kitchen(type)`)\n");
    let wide = scratch("wide.mln", "P(t)\n1 EXIST x P(x)\n");
    let consts: Vec<String> = (0..30).map(|i| format!("C{i}")).collect();
    let domain = format!("t={}", consts.join(","));
    let e = run_err(
        &["mln", "query", "--mln", wide.to_str().unwrap(), "--query", "P", "--domain", &domain, "--method", "exact"],
        1,
    );
    assert!(e.starts_with("ksmcmc: inference: exact inference enumerates 2^n worlds"), "{e}");
    let e = run_err(&["mln", "query", "--mln", "no/such.mln", "--query", "A"], 1);
    assert!(e.contains("no/such.mln"), "{e}");
}

#[test]
fn bad_usage_exits_2() {
    for args in [
        vec!["mln"],
        vec!["mln", "frobnicate", "--mln", KB],
        vec!["mln", "query", "--db", DB, "--query", "Hall"],
        vec!["mln", "query", "--mln", KB, "--db", DB],
        vec!["mln", "query", "--mln", KB, "--query", "Hall", "--method", "magic"],
        vec!["mln", "map", "--mln", KB, "--method", "gibbs"],
        vec!["mln", "query", "--mln", KB, "--query", "Hall", "--samples", "many"],
        vec!["mln", "query", "--mln", KB, "--query", "Hall", "--domain", "unit"],
        vec!["mln", "query", "--mln", KB, "--query", "Hall", "--bogus"],
    ] {
        run_err(&args, 2);
    }
    let help = run_ok(&["mln", "--help"]);
    assert!(help.contains("ksmcmc mln query"));
}

#[test]
fn domains_and_world_assumptions_from_the_command_line() {
    // No evidence: the caller names the units; RoLi etc. are then open world too unless
    // declared closed.
    let out = run_ok(&[
        "mln",
        "query",
        "--mln",
        KB,
        "--query",
        "Hall",
        "--domain",
        "unit=A,B",
        "--closed",
        "RoLi,CoLi,HaLi,MulDoor,Adj",
    ]);
    assert_eq!(out, "Hall(A) 0.5000\nHall(B) 0.5000\n");
    let db = scratch("hall.db", "HaLi(C)\n");
    let e = run_err(
        &["mln", "query", "--mln", KB, "--db", db.to_str().unwrap(), "--query", "Hall", "--domain", "unit=A,B"],
        1,
    );
    assert!(e.contains("line 1, column 1: constant C is not in the declared domain of type unit"), "{e}");
}

/// The learned weight of the only soft formula in a `mln learn` output.
fn learned_weight(text: &str) -> f64 {
    let line = text.lines().find(|l| l.contains("Smokes(x) => Cancer(x)")).expect("the formula");
    line.split_whitespace().next().unwrap().parse().unwrap()
}

#[test]
fn learn_writes_a_knowledge_base_with_the_optimal_weights() {
    let kb = scratch("smoking.mln", "Smokes(person)\nCancer(person)\n1.5 Smokes(x) => Cancer(x)\n");
    // Smokers: A, B, C with cancer, D without (database 1); E with, F without (database 2).
    let db1 = scratch("smoking1.db", "Smokes(A)\nCancer(A)\nSmokes(B)\nCancer(B)\nSmokes(C)\nCancer(C)\nSmokes(D)\n");
    let db2 = scratch("smoking2.db", "Smokes(E)\nCancer(E)\nSmokes(F)\n");
    let out = scratch("smoking-learned.mln", "");
    let (kb, db1, db2, out) =
        (kb.to_str().unwrap(), db1.to_str().unwrap(), db2.to_str().unwrap(), out.to_str().unwrap());
    let common = ["mln", "learn", "--mln", kb, "--db", db1, "--db", db2, "--query", "Cancer", "--prior-sigma", "inf"];
    // P(Cancer | Smokes) = 4 / 6 in the pooled data: w = log 2, by both methods here (each
    // smoker's Cancer atom is its own Markov blanket's only unknown).
    for method in ["discriminative", "pll"] {
        let mut args = common.to_vec();
        args.extend(["--method", method, "--out", out]);
        run_ok(&args);
        let text = std::fs::read_to_string(out).unwrap();
        assert!(text.starts_with("// Weights learned by `ksmcmc mln learn`"), "{text}");
        assert!((learned_weight(&text) - 2f64.ln()).abs() < 1e-6, "{method}: {text}");
        let info = run_ok(&["mln", "info", "--mln", out]);
        assert!(info.contains("Smokes(x) => Cancer(x)"), "{info}");
    }
    // Standard output without --out; deterministic; a prior pulls the weight toward 0.
    let a = run_ok(&common);
    assert_eq!(a, run_ok(&common));
    let mut tight = common.to_vec();
    let last = tight.len() - 1;
    tight[last] = "0.3";
    let w = learned_weight(&run_ok(&tight));
    assert!(w > 0.0 && w < 2f64.ln() - 0.1, "{w}");
    // Discriminative with MC-SAT estimates (forced by --max-exact 0): near log 2, within 0.1
    // at this seed and sample size.
    let mut sampled = common.to_vec();
    sampled.extend(["--method", "discriminative", "--max-exact", "0", "--samples", "2000", "--seed", "3"]);
    let text = run_ok(&sampled);
    assert!(text.contains("Expected counts by MC-SAT (2000 samples, seed 3)"), "{text}");
    assert!((learned_weight(&text) - 2f64.ln()).abs() < 0.1, "{text}");
}

#[test]
fn training_worlds_from_synthetic_floor_plans() {
    let world = "samples/office-small/truth.json";
    let map = "samples/office-small/map.yaml";
    let all = run_ok(&["mln", "evidence", "--world", world, "--map", map, "--truth"]);
    assert!(all.contains("Small("), "the default classifier marks small units: {all}");
    // For Tab. 3.5's knowledge base, which has no Small, only what it declares.
    let train = run_ok(&["mln", "evidence", "--world", world, "--map", map, "--truth", "--mln", KB]);
    assert!(!train.contains("Small("), "{train}");
    assert!(train.contains("\nCorr(U1)\n") && train.contains("\nRoom(U2)\n"), "{train}");
    assert!(train.contains("\nSaLe(U2,U3)\nSaLe(U3,U2)\n"), "{train}");
    let evidence = run_ok(&["mln", "evidence", "--world", world, "--resolution", "0.05"]);
    assert!(evidence.contains("CoLi(U1)") && !evidence.contains("Corr(U1)"), "{evidence}");
    let db = scratch("office-small.db", &train);
    let learned = run_ok(&["mln", "learn", "--mln", KB, "--db", db.to_str().unwrap(), "--query", QUERY]);
    let kb = scratch("indoor-learned.mln", &learned);
    // The learned knowledge base answers queries on the sample evidence.
    let out = run_ok(&["mln", "query", "--mln", kb.to_str().unwrap(), "--db", DB, "--query", "Room"]);
    assert_eq!(out.lines().count(), 4, "{out}");
}

#[test]
fn learn_and_evidence_usage_and_errors() {
    for args in [
        vec!["mln", "learn", "--mln", KB],
        vec!["mln", "learn", "--mln", KB, "--db", DB, "--method", "magic"],
        vec!["mln", "learn", "--mln", KB, "--db", DB, "--closed", "Adj"],
        vec!["mln", "learn", "--mln", KB, "--db", DB, "--prior-sigma", "wide"],
        vec!["mln", "query", "--mln", KB, "--db", DB, "--db", DB, "--query", "Hall"],
        vec!["mln", "evidence", "--map", "samples/office-small/map.yaml"],
        vec!["mln", "evidence", "--world", "samples/office-small/truth.json"],
        vec!["mln", "evidence", "--world", "samples/office-small/truth.json", "--resolution", "-1"],
    ] {
        run_err(&args, 2);
    }
    let e = run_err(&["mln", "learn", "--mln", KB, "--db", DB, "--method", "discriminative"], 1);
    assert_eq!(
        e,
        "ksmcmc: learning: discriminative learning needs the query (non-evidence) predicates, e.g. --query Room,Corr\n"
    );
    // The sample evidence has no SaLe atoms: as a training world all are false, which the
    // hard formulas allow; but a one-sided Adj breaks one.
    let asym = scratch("asym-train.db", "RoLi(U1)\nAdj(U1,U2)\n");
    let e = run_err(&["mln", "learn", "--mln", KB, "--db", asym.to_str().unwrap()], 1);
    assert!(e.contains("the training world violates the hard formula `Adj(p, q) => Adj(q, p)`"), "{e}");
    // A constant outside a declared domain: the error names the database and the line.
    let kb = scratch("closed.mln", "person = {A, B}\nSmokes(person)\n1 Smokes(x)\n");
    let (good, bad) = (scratch("good.db", "Smokes(A)\n"), scratch("bad-const.db", "Smokes(B)\nSmokes(C)\n"));
    let e = run_err(
        &["mln", "learn", "--mln", kb.to_str().unwrap(), "--db", good.to_str().unwrap(), "--db", bad.to_str().unwrap()],
        1,
    );
    assert_eq!(
        e,
        format!(
            "ksmcmc: {}: line 2, column 1: constant C is not in the declared domain of type person\n",
            bad.display()
        )
    );
    let e = run_err(&["mln", "evidence", "--world", "no/such.json", "--resolution", "0.05"], 1);
    assert!(e.contains("no/such.json"), "{e}");
    let help = run_ok(&["mln", "--help"]);
    assert!(help.contains("ksmcmc mln learn") && help.contains("ksmcmc mln evidence"));
}

/// `samples/knowledge/indoor-learned.mln` is what `learn-indoor.sh` makes: the same synthetic
/// floors (the seed list is read from the script), the same evidence, the same weights.
#[test]
fn the_learned_indoor_knowledge_base_is_reproducible() {
    let script = std::fs::read_to_string("samples/knowledge/learn-indoor.sh").unwrap();
    let seeds = script.split("<<SEEDS\n").nth(1).unwrap().split("\nSEEDS").next().unwrap();
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("indoor-train");
    let mut args: Vec<String> = [
        "mln",
        "learn",
        "--mln",
        "samples/knowledge/indoor-rules.mln",
        "--query",
        QUERY,
        "--method",
        "discriminative",
        "--iterations",
        "50",
        "--samples",
        "500",
        "--prior-sigma",
        "2",
    ]
    .map(String::from)
    .to_vec();
    for line in seeds.lines() {
        let mut words = line.split_whitespace();
        let seed = words.next().unwrap();
        let out = dir.join(seed);
        let mut synth = vec!["synth", "--seed", seed, "--out", out.to_str().unwrap()];
        synth.extend(words);
        run_ok(&synth);
        let db = dir.join(format!("{seed}.db"));
        let (world, map) = (out.join("truth.json"), out.join("map.yaml"));
        let (world, map, db_path) = (world.to_str().unwrap(), map.to_str().unwrap(), db.to_str().unwrap());
        run_ok(&["mln", "evidence", "--world", world, "--map", map, "--truth", "--out", db_path]);
        args.extend(["--db".to_string(), db_path.to_string()]);
    }
    assert_eq!(seeds.lines().count(), 14);
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let learned = run_ok(&args);
    let committed = std::fs::read_to_string("samples/knowledge/indoor-learned.mln").unwrap();
    let body = |t: &str| t.lines().filter(|l| !l.starts_with("//")).map(String::from).collect::<Vec<_>>();
    assert_eq!(body(&learned), body(&committed), "rerun samples/knowledge/learn-indoor.sh");
    // It keeps the hand-set file's formulas, hard ones hard, and a query runs on it.
    let info = run_ok(&["mln", "info", "--mln", "samples/knowledge/indoor-learned.mln"]);
    assert_eq!(info.matches("    hard  ").count(), 3, "{info}");
    assert_eq!(info.lines().filter(|l| l.starts_with("  ") && l.contains("=>")).count(), 38, "{info}");
    run_ok(&["mln", "query", "--mln", "samples/knowledge/indoor-learned.mln", "--db", DB, "--query", QUERY]);
}

/// `mln evidence --rooms`: a chain's world of a synthetic floor as a training world of the room
/// rules, its SameRoom atoms on open pairs only, counted in the header.
#[test]
fn room_training_worlds_from_chain_worlds() {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("rooms-train");
    let s = dir.join("synth");
    let (s, run) = (s.to_str().unwrap(), dir.join("run"));
    run_ok(&["synth", "--seed", "2031", "--clutter", "0.1", "--out", s]);
    let map = format!("{s}/map.yaml");
    run_ok(&["floorplan", &map, "--seed", "1", "--out", run.to_str().unwrap()]);
    let world = run.join("world.json");
    let world = world.to_str().unwrap();
    let labels = format!("{s}/truth_labels.pgm");
    let db = run_ok(&["mln", "evidence", "--rooms", "--world", world, "--map", &map, "--truth-labels", &labels]);
    let header = db.lines().next().unwrap();
    assert!(header.starts_with("// Room-layer training world"), "{db}");
    let lines: Vec<&str> = db.lines().filter(|l| !l.starts_with("//")).collect();
    let same: Vec<&str> = lines.iter().copied().filter(|l| l.starts_with("SameRoom(")).collect();
    assert!(!same.is_empty(), "a cluttered floor has rooms the chain cuts in two: {db}");
    for l in &same {
        let open = l.replace("SameRoom(", "Open(");
        assert!(lines.contains(&open.as_str()), "{l} without {open}");
    }
    assert!(header.contains(&format!(", {} in one truth room", same.len() / 2)), "{header}");
    // Without truth: the evidence alone, as the room layer gives it to the rules.
    let evidence = run_ok(&["mln", "evidence", "--rooms", "--world", world, "--map", &map]);
    assert!(!evidence.contains("SameRoom(") && evidence.contains("\nOpen("), "{evidence}");
    // A training world learns.
    let path = scratch("rooms-train.db", &db);
    let learned = run_ok(&[
        "mln",
        "learn",
        "--mln",
        "samples/knowledge/rooms.mln",
        "--db",
        path.to_str().unwrap(),
        "--query",
        "SameRoom",
        "--method",
        "discriminative",
    ]);
    assert!(learned.contains("Flush(p, q) => SameRoom(p, q)"), "{learned}");
    // Errors: usage (2), and labels of another map or no PGM at all (1).
    for args in [
        vec!["mln", "evidence", "--rooms", "--world", world],
        vec!["mln", "evidence", "--rooms", "--world", world, "--map", &map, "--truth"],
        vec!["mln", "evidence", "--rooms", "--world", world, "--resolution", "0.05"],
        vec!["mln", "evidence", "--world", world, "--map", &map, "--truth-labels", &labels],
    ] {
        run_err(&args, 2);
    }
    let small = scratch("small-labels.pgm", "P2\n2 2\n65535\n0 1 1 0\n");
    let e = run_err(
        &["mln", "evidence", "--rooms", "--world", world, "--map", &map, "--truth-labels", small.to_str().unwrap()],
        1,
    );
    assert!(e.contains("small-labels.pgm") && e.contains("truth labels are 2x2"), "{e}");
    let junk = scratch("junk-labels.pgm", "not an image");
    let e = run_err(
        &["mln", "evidence", "--rooms", "--world", world, "--map", &map, "--truth-labels", junk.to_str().unwrap()],
        1,
    );
    assert!(e.contains("junk-labels.pgm") && e.contains("truth labels"), "{e}");
    let narrow = dir.join("narrow");
    run_ok(&["synth", "--seed", "1", "--width", "300", "--out", narrow.to_str().unwrap()]);
    let narrow = format!("{}/map.yaml", narrow.display());
    let other = run_err(&["mln", "evidence", "--rooms", "--world", world, "--map", &narrow], 1);
    assert!(other.contains("world.json") && other.contains("different map"), "{other}");
}

/// `samples/knowledge/rooms-learned.mln` is what `learn-rooms.sh` makes.
#[test]
fn the_learned_room_rules_are_reproducible() {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("rooms-recipe");
    let learned = dir.join("rooms-learned.mln");
    let out = Command::new("sh")
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .arg("samples/knowledge/learn-rooms.sh")
        .env("KSMCMC", env!("CARGO_BIN_EXE_ksmcmc"))
        .env("OUT", &dir)
        .env("LEARNED", &learned)
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let body = |t: &str| t.lines().filter(|l| !l.starts_with("//")).map(String::from).collect::<Vec<_>>();
    let committed = std::fs::read_to_string("samples/knowledge/rooms-learned.mln").unwrap();
    assert_eq!(body(&std::fs::read_to_string(&learned).unwrap()), body(&committed), "rerun learn-rooms.sh");
    // The same formulas as the hand-set rules, hard ones hard.
    let info = run_ok(&["mln", "info", "--mln", "samples/knowledge/rooms-learned.mln"]);
    let hand = run_ok(&["mln", "info", "--mln", "samples/knowledge/rooms.mln"]);
    let formulas =
        |t: &str| t.lines().filter(|l| l.contains("=>")).map(|l| l.split_at(12).1.to_string()).collect::<Vec<_>>();
    assert_eq!(formulas(&info), formulas(&hand));
    assert_eq!(info.matches("    hard  ").count(), 2, "{info}");
}
