//! `ksmcmc tabletop`, `tabletop-synth` and `tabletop-eval` end to end: files, formats,
//! determinism, errors and exit codes, and the shipped samples.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn ksmcmc(args: &[&str]) -> Output {
    let out = Command::new(env!("CARGO_BIN_EXE_ksmcmc"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("run ksmcmc");
    let text = format!("{}{}", String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
    assert!(!text.contains("panicked") && !text.contains("internal error"), "ksmcmc {args:?} panicked: {text}");
    out
}

fn scratch(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("tabletop_cli").join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn run_ok(args: &[&str]) -> String {
    let out = ksmcmc(args);
    assert!(out.status.success(), "ksmcmc {args:?} failed: {}", String::from_utf8_lossy(&out.stderr));
    String::from_utf8(out.stdout).unwrap()
}

/// Runs a failing command: its exit code and what it said on stderr.
fn run_err(args: &[&str]) -> (i32, String) {
    let out = ksmcmc(args);
    assert!(!out.status.success(), "ksmcmc {args:?} should fail");
    (out.status.code().unwrap(), String::from_utf8(out.stderr).unwrap())
}

fn json(path: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

fn sample(rel: &str) -> String {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("samples/tabletop").join(rel).to_str().unwrap().to_string()
}

#[test]
fn synth_writes_a_scene_deterministically() {
    let dir = scratch("synth");
    let (a, b, c) = (dir.join("a.json"), dir.join("b.json"), dir.join("c.json"));
    let said =
        run_ok(&["tabletop-synth", "--seed", "9", "--hovering", "1", "--false", "1", "--out", a.to_str().unwrap()]);
    assert!(said.contains("1 hiding another, 1 false estimates"), "{said}");
    run_ok(&["tabletop-synth", "--seed", "9", "--hovering", "1", "--false", "1", "--out", b.to_str().unwrap()]);
    run_ok(&["tabletop-synth", "--seed", "10", "--out", c.to_str().unwrap()]);
    let (ta, tb, tc) = (std::fs::read(&a).unwrap(), std::fs::read(&b).unwrap(), std::fs::read(&c).unwrap());
    assert_eq!(ta, tb);
    assert_ne!(ta, tc);
    let scene = ksmcmc::tabletop::scene::Scene::from_json(std::str::from_utf8(&ta).unwrap()).unwrap();
    assert!(scene.objects.iter().all(|o| o.truth.is_some() && !o.keypoints.is_empty()));
    let config = run_ok(&["tabletop-synth", "--print-config", "--keypoints", "12"]);
    let v: serde_json::Value = serde_json::from_str(&config).unwrap();
    assert_eq!(v["keypoints"], 12);
}

#[test]
fn synth_command_line_errors() {
    assert_eq!(run_err(&["tabletop-synth", "--out", "x.json"]).0, 2);
    let (code, msg) = run_err(&["tabletop-synth", "--seed", "1", "--objects", "lots", "--out", "x.json"]);
    assert_eq!(code, 2);
    assert!(msg.contains("MIN-MAX"), "{msg}");
    let (code, msg) = run_err(&["tabletop-synth", "--seed", "1", "--objects", "5-3", "--out", "x.json"]);
    assert_eq!(code, 2);
    assert!(msg.contains("min_objects"), "{msg}");
    assert_eq!(run_err(&["tabletop-synth", "--seed", "1", "--bogus"]).0, 2);
    assert_eq!(run_err(&["tabletop-synth", "--seed", "x", "--out", "x.json"]).0, 2);
}

#[test]
fn tabletop_writes_graph_pictures_and_report() {
    let dir = scratch("fig");
    let out = dir.join("out");
    let said = run_ok(&["tabletop", &sample("fig-4-9.json"), "--out", out.to_str().unwrap()]);
    assert!(said.contains("FALSE-ESTIMATE") && said.contains("HIDES-AN-OBJECT"), "{said}");
    let graph = json(&out.join("graph.json"));
    let nodes = graph["nodes"].as_array().unwrap();
    assert_eq!(nodes.len(), 7);
    for n in nodes {
        for key in ["id", "p_hidden", "p_false", "hidden", "false"] {
            assert!(!n[key].is_null(), "{key} missing in {n}");
        }
    }
    let table = nodes.iter().find(|n| n["id"] == "table").unwrap();
    assert_eq!((table["hidden"].as_bool(), table["false"].as_bool()), (Some(false), Some(false)));
    let edges = graph["edges"].as_array().unwrap();
    assert!(edges.iter().all(|e| e["kind"] == "support" || e["kind"] == "contact"));
    assert!(edges.iter().any(|e| e["from"] == "table" && e["to"] == "1" && e["kind"] == "support"));
    let report = json(&out.join("report.json"));
    assert_eq!(report["iterations"], 100);
    assert!(report["seconds"].as_f64().unwrap() > 0.0);
    assert!(report["ms_per_iteration"].as_f64().unwrap() > 0.0);
    assert_eq!(report["score"]["flags_correct"], 12);
    for png in ["graph.png", "view.png"] {
        assert!(std::fs::read(out.join(png)).unwrap().starts_with(b"\x89PNG"));
    }
    // Same seed, same result; another seed, the same graph for this clear-cut scene.
    let again = dir.join("again");
    run_ok(&["tabletop", &sample("fig-4-9.json"), "--out", again.to_str().unwrap(), "--seed", "1"]);
    assert_eq!(std::fs::read(out.join("view.png")).unwrap(), std::fs::read(again.join("view.png")).unwrap());
    let other = dir.join("other");
    run_ok(&[
        "tabletop",
        &sample("fig-4-9.json"),
        "--out",
        other.to_str().unwrap(),
        "--seed",
        "7",
        "--iterations",
        "20",
    ]);
    let flags = |g: &serde_json::Value| -> Vec<(String, bool, bool)> {
        g["nodes"]
            .as_array()
            .unwrap()
            .iter()
            .map(|n| (n["id"].to_string(), n["hidden"].as_bool().unwrap(), n["false"].as_bool().unwrap()))
            .collect()
    };
    assert_eq!(flags(&graph), flags(&json(&other.join("graph.json"))));
    assert_eq!(json(&other.join("report.json"))["iterations"], 20);
}

#[test]
fn tabletop_errors_say_what_is_wrong() {
    let dir = scratch("errors");
    let out = dir.join("out");
    let o = out.to_str().unwrap();
    let (code, msg) = run_err(&["tabletop", "no/such/scene.json", "--out", o]);
    assert_eq!(code, 1);
    assert!(msg.contains("no/such/scene.json"), "{msg}");
    let bad = dir.join("bad.json");
    let text = std::fs::read_to_string(sample("fig-4-9.json")).unwrap().replacen("0.1,", "-0.1,", 1);
    std::fs::write(&bad, text).unwrap();
    let (code, msg) = run_err(&["tabletop", bad.to_str().unwrap(), "--out", o]);
    assert_eq!(code, 1);
    assert!(msg.contains("must be positive") && msg.contains("objects["), "{msg}");
    let (code, msg) = run_err(&["tabletop", &sample("fig-4-9.json")]);
    assert_eq!(code, 2);
    assert!(msg.contains("--out"), "{msg}");
    assert_eq!(run_err(&["tabletop", &sample("fig-4-9.json"), "--out", o, "--iterations", "many"]).0, 2);
    assert_eq!(run_err(&["tabletop", &sample("fig-4-9.json"), "--out", o, "--frobnicate"]).0, 2);
    let config = dir.join("config.json");
    std::fs::write(&config, r#"{"proposal": {"candidates": 0}}"#).unwrap();
    let (code, msg) = run_err(&["tabletop", &sample("fig-4-9.json"), "--out", o, "--config", config.to_str().unwrap()]);
    assert_eq!(code, 2);
    assert!(msg.contains("candidates"), "{msg}");
    assert!(!out.join("graph.json").exists(), "nothing is written on failure");
}

#[test]
fn eval_reports_accuracy_and_speed() {
    let dir = scratch("eval");
    let j = dir.join("eval.json");
    let said = run_ok(&[
        "tabletop-eval",
        "--quick",
        "--scenes",
        "3",
        "--speed",
        "1",
        "--iterations",
        "10",
        "--json",
        j.to_str().unwrap(),
    ]);
    assert!(said.contains("flags correct") && said.contains("ms per iteration"), "{said}");
    let v = json(&j);
    assert_eq!(v["generated"]["scenes"], 3);
    assert!(v["generated"]["flag_accuracy"].as_f64().unwrap() <= 1.0);
    assert!(v["speed"]["ms_per_iteration"].as_f64().unwrap() > 0.0);
    assert!(v["dissertation"].is_null());
}

#[test]
fn help_lists_the_commands() {
    let usage = run_ok(&["help"]);
    for c in ["tabletop SCENE.json", "tabletop-synth", "tabletop-eval"] {
        assert!(usage.contains(c), "{c}");
    }
    for c in ["tabletop", "tabletop-synth", "tabletop-eval"] {
        assert!(run_ok(&[c, "--help"]).starts_with("Usage:"));
    }
}

#[test]
fn samples_are_reproduced_byte_for_byte() {
    let readme = std::fs::read_to_string(sample("README.md")).unwrap();
    let dir = scratch("samples");
    let mut checked = 0;
    for line in readme.lines().filter(|l| l.starts_with("ksmcmc ")) {
        let mut args: Vec<String> = line.split_whitespace().skip(1).map(String::from).collect();
        let at = args.iter().position(|a| a == "--out").unwrap() + 1;
        let target = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(&args[at]);
        let fresh = dir.join(format!("out{checked}"));
        args[at] = fresh.to_str().unwrap().to_string();
        let refs: Vec<&str> = args.iter().map(String::as_str).collect();
        run_ok(&refs);
        if target.is_dir() {
            for f in ["graph.json", "graph.png", "view.png"] {
                assert_eq!(
                    std::fs::read(fresh.join(f)).unwrap(),
                    std::fs::read(target.join(f)).unwrap(),
                    "{line}: {f}"
                );
            }
        } else {
            assert_eq!(std::fs::read(&fresh).unwrap(), std::fs::read(&target).unwrap(), "{line}");
        }
        checked += 1;
    }
    assert_eq!(checked, 4);
}
