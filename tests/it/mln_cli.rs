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
