//! The Markov logic engine against exact answers.
//!
//! Three independent exact references: brute force over worlds with `Mln::log_weight` (which
//! evaluates the first-order formulas directly, no grounding or clausal form), enumeration of
//! the ground network, and the junction tree. MC-SAT and Gibbs sampling must land within 0.02
//! of them on every query atom with the fixed seeds used here. Knowledge bases: a smokers
//! example, the table-top rules of Tab. 4.3 on several scenes, the indoor rules of Tab. 3.5 on
//! worlds of 3 - 5 units.

use ksmcmc::mln::{
    Database, ErrorKind, Evidence, GroundConfig, InferenceConfig, MapConfig, MapMethod, Marginals, Method, Mln,
    Network, SliceMoves, Source,
};

const INDOOR: &str = include_str!("../../samples/knowledge/indoor.mln");
const TABLETOP: &str = include_str!("../../samples/knowledge/tabletop.mln");
const INDOOR_QUERY: [&str; 5] = ["Room", "Corr", "Hall", "Other", "SaLe"];
const INDOOR_EVIDENCE: [&str; 5] = ["RoLi", "CoLi", "HaLi", "MulDoor", "Adj"];
const TABLETOP_QUERY: [&str; 4] = ["hidden", "false", "supportive", "supported"];
const TABLETOP_EVIDENCE: [&str; 6] = ["stable", "table", "contact", "intersect", "hover", "higher"];

const SMOKERS: &str = "\
// Richardson and Domingos' smokers, with a few extras that exercise the grammar.
Smokes(person)
Cancer(person)
Friends(person, person)

1.5 Smokes(x) => Cancer(x)
1.1 Friends(x, y) => (Smokes(x) <=> Smokes(y))   // two clauses, one feature
-0.7 Cancer(x) ^ !Smokes(x)                      // negative weight
0.8 Smokes(x) => EXIST y (Friends(x, y) ^ x != y)
-0.4 FORALL y (Friends(x, y) => Smokes(y))
0.6 Friends(x, y) ^ Friends(y, z) => Friends(x, z)
0.3 Smokes(Anna) v Cancer(Bob)
Friends(x, x).
";

/// Evidence for the smokers: Friends is closed world, so its reflexive atoms (hard) are listed.
const SMOKERS_DB: &str =
    "Friends(Anna,Bob)\nFriends(Bob,Chris)\nSmokes(Anna)\nFriends(Anna,Anna)\nFriends(Bob,Bob)\nFriends(Chris,Chris)\n";

fn ground(kb: &str, db: &str, config: &GroundConfig) -> Network {
    let mln = Mln::parse(kb).unwrap_or_else(|e| panic!("knowledge base: {e}"));
    let db = Database::parse(db, &mln).unwrap_or_else(|e| panic!("evidence: {e}"));
    Network::ground(&mln, &db, config).unwrap_or_else(|e| panic!("grounding: {e}"))
}

fn config(query: &[&str], closed: &[&str]) -> GroundConfig {
    GroundConfig { closed_world: closed.iter().map(|s| s.to_string()).collect(), ..GroundConfig::query(query) }
}

fn infer(net: &Network, method: Method, samples: u32, seed: u64) -> Marginals {
    let c = InferenceConfig { method, samples, seed, ..Default::default() };
    net.infer_marginals(&c).unwrap_or_else(|e| panic!("{method:?}: {e}"))
}

/// Largest difference between two sets of marginals over the same atoms.
fn max_diff(a: &Marginals, b: &Marginals) -> (f64, String) {
    assert_eq!(a.len(), b.len());
    let mut worst = (0.0, String::new());
    for ((x, p), (y, q)) in a.iter().zip(b.iter()) {
        assert_eq!(x, y);
        if (p - q).abs() >= worst.0 {
            worst = ((p - q).abs(), format!("{x}: {p:.4} vs {q:.4}"));
        }
    }
    worst
}

/// Exact by junction tree (and by enumeration if `enumerate`), then MC-SAT and Gibbs within
/// 0.02 of it.
fn check_samplers(label: &str, net: &Network, enumerate: bool) -> Marginals {
    let exact = infer(net, Method::Exact, 1, 1);
    if enumerate {
        let e = infer(net, Method::Enumerate, 1, 1);
        let (d, at) = max_diff(&exact, &e);
        assert!(d < 1e-9, "{label}: junction tree vs enumeration differ by {d} at {at}");
    }
    for (method, samples) in [(Method::McSat, 10_000), (Method::Gibbs, 10_000)] {
        let m = infer(net, method, samples, 7);
        let (d, at) = max_diff(&m, &exact);
        assert!(d < 0.02, "{label}: {method:?} off by {d:.4} at {at}");
    }
    // Pure MC-SAT, without the interleaved Gibbs sweeps, mixes more slowly.
    let pure =
        InferenceConfig { method: Method::McSat, samples: 40_000, seed: 7, gibbs_sweeps: 0, ..Default::default() };
    let (d, at) = max_diff(&net.infer_marginals(&pure).unwrap(), &exact);
    assert!(d < 0.02, "{label}: pure MC-SAT off by {d:.4} at {at}");
    exact
}

// ---------------------------------------------------------------- brute force

/// Marginals of every atom of the `open` predicates by brute force over all worlds, weighing
/// each with `Mln::log_weight` (direct evaluation of the formulas).
fn brute_force(
    kb: &str,
    evidence_true: &[(&str, Vec<&str>)],
    unknown: &[(&str, Vec<&str>)],
    domains: &GroundConfig,
) -> Vec<f64> {
    let mln = Mln::parse(kb).unwrap();
    let k = unknown.len();
    assert!(k <= 16);
    let mut logw = Vec::with_capacity(1 << k);
    for x in 0u32..1 << k {
        let mut world = Database::new();
        for (p, args) in evidence_true {
            world.insert(&mln, p, args, Evidence::True).unwrap();
        }
        for (j, (p, args)) in unknown.iter().enumerate() {
            if x >> j & 1 == 1 {
                world.insert(&mln, p, args, Evidence::True).unwrap();
            }
        }
        logw.push(mln.log_weight(&world, domains).unwrap());
    }
    let top = logw.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
    let w: Vec<f64> = logw.iter().map(|l| (l - top).exp()).collect();
    let z: f64 = w.iter().sum();
    (0..k).map(|j| w.iter().enumerate().filter(|(x, _)| x >> j & 1 == 1).map(|(_, w)| w).sum::<f64>() / z).collect()
}

#[test]
fn smokers_match_brute_force_and_samplers_match_exact() {
    let people = ["Anna", "Bob", "Chris"];
    let domains = GroundConfig {
        domains: vec![("person".into(), people.iter().map(|s| s.to_string()).collect())],
        ..Default::default()
    };
    let evidence_true = vec![
        ("Friends", vec!["Anna", "Bob"]),
        ("Friends", vec!["Anna", "Anna"]),
        ("Friends", vec!["Bob", "Bob"]),
        ("Friends", vec!["Chris", "Chris"]),
    ];
    let mut unknown = Vec::new();
    for p in people {
        unknown.push(("Smokes", vec![p]));
        unknown.push(("Cancer", vec![p]));
        for q in people {
            if p != q && !(p == "Anna" && q == "Bob") && !(p == "Bob" && q == "Chris") {
                unknown.push(("Friends", vec![p, q]));
            }
        }
    }
    let reference = brute_force(SMOKERS, &evidence_true, &unknown, &domains);
    let db = "Friends(Anna,Bob)\n!Friends(Bob,Chris)\n";
    for simplify in [true, false] {
        let cfg = GroundConfig {
            simplify,
            domains: domains.domains.clone(),
            ..GroundConfig::query(&["Smokes", "Cancer", "Friends"])
        };
        let net = ground(SMOKERS, db, &cfg);
        let exact = check_samplers(&format!("smokers (simplify {simplify})"), &net, true);
        for ((p, args), r) in unknown.iter().zip(&reference) {
            let got = exact.get(p, args).unwrap();
            assert!((got - r).abs() < 1e-9, "{p}({args:?}): network {got} vs brute force {r}");
        }
        assert_eq!(exact.get("Friends", &["Anna", "Bob"]), Some(1.0));
        assert_eq!(exact.get("Friends", &["Bob", "Chris"]), Some(0.0));
        assert_eq!(exact.get("Friends", &["Chris", "Chris"]), Some(1.0), "hard unit clause");
    }
}

#[test]
fn network_log_weight_is_the_formula_count_of_eq_2_4() {
    // Every atom open and the hard clauses kept, so the network's atoms are all the atoms.
    let mln = Mln::parse(SMOKERS).unwrap();
    let people: Vec<String> = ["Anna", "Bob"].iter().map(|s| s.to_string()).collect();
    let cfg = GroundConfig {
        simplify: false,
        domains: vec![("person".into(), people)],
        ..GroundConfig::query(&["Smokes", "Cancer", "Friends"])
    };
    let net = Network::ground(&mln, &Database::new(), &cfg).unwrap();
    assert_eq!(net.atom_count(), 8);
    let mut seen_infinite = false;
    for x in 0u32..1 << 8 {
        let state: Vec<bool> = (0..8).map(|j| x >> j & 1 == 1).collect();
        let mut world = Database::new();
        for (j, &v) in state.iter().enumerate() {
            if v {
                let a = net.atom(j);
                let args: Vec<&str> = a.args.iter().map(String::as_str).collect();
                world.insert(&mln, &a.predicate, &args, Evidence::True).unwrap();
            }
        }
        let direct = mln.log_weight(&world, &cfg).unwrap();
        let via_network = net.log_weight(&state);
        if direct.is_infinite() {
            seen_infinite = true;
            assert_eq!(via_network, f64::NEG_INFINITY);
        } else {
            assert!((direct - via_network).abs() < 1e-9, "world {x:08b}: {direct} vs {via_network}");
        }
    }
    assert!(seen_infinite, "some worlds violate Friends(x,x).");
}

#[test]
fn tabletop_prior_of_eq_4_3() {
    let mln = Mln::parse(TABLETOP).unwrap();
    let world_text =
        "table(T)\nstable(T)\nstable(O1)\ncontact(O1,T)\ncontact(T,O1)\nhigher(O1,T)\nsupportive(T)\nsupported(O1)\n";
    let world = Database::parse(world_text, &mln).unwrap();
    // r11 and r15 hold for both objects (2 x log(0.7/0.3) each); r12, r13, r16 for both and
    // r14 for all four pairs (10 x log(0.9/0.1)). All hard rules hold.
    let expected = 4.0 * (0.7f64 / 0.3).ln() + 10.0 * 9f64.ln();
    let got = mln.log_weight(&world, &GroundConfig::default()).unwrap();
    assert!((got - expected).abs() < 1e-9, "{got} vs {expected}");
    // Without supported(O1), hard rule r10 fails: probability zero.
    let world = Database::parse(&world_text.replace("supported(O1)\n", ""), &mln).unwrap();
    assert_eq!(mln.log_weight(&world, &GroundConfig::default()).unwrap(), f64::NEG_INFINITY);
    // And hidden(O1) costs exactly the weight of r11 (supported => !hidden).
    let world = Database::parse(&format!("{world_text}hidden(O1)\n"), &mln).unwrap();
    let got = mln.log_weight(&world, &GroundConfig::default()).unwrap();
    assert!((got - (expected - (0.7f64 / 0.3).ln())).abs() < 1e-9);
}

// ---------------------------------------------------------------- the dissertation's KBs

const SCENES: [&str; 3] = [
    // A on the table, B stacked on A.
    "table(T)\nstable(T)\nstable(A)\nstable(B)\ncontact(A,T)\ncontact(T,A)\ncontact(A,B)\ncontact(B,A)\n\
     higher(A,T)\nhigher(B,T)\nhigher(B,A)\n",
    // A on the table, B hovering, C unstable and intersecting A.
    "table(T)\nstable(T)\nstable(A)\nstable(B)\ncontact(A,T)\ncontact(T,A)\nhover(B)\n\
     intersect(A,C)\nintersect(C,A)\nhigher(A,T)\nhigher(B,T)\nhigher(C,T)\nhigher(B,A)\n",
    // Fig. 4.9-b without O6: three on the table, O4 leaning on O2 and O3, O5 hovering.
    "table(T)\nstable(T)\nstable(O1)\nstable(O2)\nstable(O3)\nstable(O5)\n\
     contact(O1,T)\ncontact(T,O1)\ncontact(O2,T)\ncontact(T,O2)\ncontact(O3,T)\ncontact(T,O3)\n\
     contact(O4,O2)\ncontact(O2,O4)\ncontact(O4,O3)\ncontact(O3,O4)\nhover(O5)\n\
     higher(O1,T)\nhigher(O2,T)\nhigher(O3,T)\nhigher(O4,T)\nhigher(O5,T)\nhigher(O4,O2)\nhigher(O4,O3)\nhigher(O5,O2)\n",
];

#[test]
fn tabletop_scenes() {
    for (i, scene) in SCENES.iter().enumerate() {
        for simplify in [true, false] {
            let cfg = GroundConfig { simplify, ..config(&TABLETOP_QUERY, &TABLETOP_EVIDENCE) };
            let net = ground(TABLETOP, scene, &cfg);
            let m = check_samplers(&format!("scene {i} (simplify {simplify})"), &net, true);
            // The table is never a false estimate and hides nothing (hard r7, r8).
            assert_eq!(m.get("false", &["T"]), Some(0.0));
            assert_eq!(m.get("hidden", &["T"]), Some(0.0));
        }
    }
    // The shipped scene: O6 intersects O1 and is not stable, so it is the likely false
    // estimate; O5 hovers, so something is probably hidden under it.
    let mln = Mln::parse(TABLETOP).unwrap();
    let db = Database::parse(include_str!("../../samples/knowledge/tabletop.db"), &mln).unwrap();
    let net = Network::ground(&mln, &db, &GroundConfig::query(&TABLETOP_QUERY)).unwrap();
    let m = check_samplers("tabletop.db", &net, true);
    assert!(m.get("false", &["O6"]).unwrap() > 0.85);
    assert!(m.get("hidden", &["O5"]).unwrap() > 0.75);
    assert!(m.get("false", &["O1"]).unwrap() < 0.2);
    assert_eq!(m.get("supported", &["O1"]), Some(1.0), "r10 makes it certain");
}

const WORLDS: [&str; 3] = [
    // A room, a corridor and a hall in a row.
    "RoLi(A)\nCoLi(B)\nMulDoor(B)\nHaLi(C)\nAdj(A,B)\nAdj(B,A)\nAdj(B,C)\nAdj(C,B)\n",
    // samples/knowledge/indoor.db with other names: two rooms off a corridor, a hall at its end.
    "RoLi(A)\nRoLi(B)\nCoLi(C)\nMulDoor(C)\nHaLi(D)\n\
     Adj(A,B)\nAdj(B,A)\nAdj(A,C)\nAdj(C,A)\nAdj(B,C)\nAdj(C,B)\nAdj(C,D)\nAdj(D,C)\n",
    // Five units in a ring; a room with several doors, a corridor with one.
    "RoLi(A)\nMulDoor(A)\nRoLi(B)\nCoLi(C)\nHaLi(D)\nRoLi(E)\n\
     Adj(A,B)\nAdj(B,A)\nAdj(B,C)\nAdj(C,B)\nAdj(C,D)\nAdj(D,C)\nAdj(D,E)\nAdj(E,D)\nAdj(E,A)\nAdj(A,E)\n",
];

#[test]
fn indoor_worlds() {
    for (i, world) in WORLDS.iter().enumerate() {
        let net = ground(INDOOR, world, &config(&INDOOR_QUERY, &INDOOR_EVIDENCE));
        // Enumeration is 2^16 worlds for the first, too slow in debug builds for the others,
        // whose reference is the junction tree (checked against enumeration elsewhere).
        let m = check_samplers(&format!("indoor world {i}"), &net, i == 0);
        for (a, p) in m.iter() {
            if a.predicate == "SaLe" {
                let back = m.get("SaLe", &[&a.args[1], &a.args[0]]).unwrap();
                assert!((p - back).abs() < 1e-9, "SaLe is symmetric (hard): {a} {p} vs {back}");
            }
        }
        assert_eq!(m.get("SaLe", &["A", "A"]), Some(0.0), "a unit is not adjacent to itself");
    }
    // The hall-like unit is most likely a hall, and not a room.
    let net = ground(INDOOR, WORLDS[0], &config(&INDOOR_QUERY, &INDOOR_EVIDENCE));
    let m = infer(&net, Method::Exact, 1, 1);
    assert!(m.get("Hall", &["C"]).unwrap() > 0.8);
    assert!(m.get("Room", &["C"]).unwrap() < 0.2);
    assert!(m.get("Corr", &["B"]).unwrap() > 0.7);
}

#[test]
fn shipped_indoor_example_grounds_and_is_sensible() {
    let mln = Mln::parse(INDOOR).unwrap();
    let db = Database::parse(include_str!("../../samples/knowledge/indoor.db"), &mln).unwrap();
    let net = Network::ground(&mln, &db, &GroundConfig::query(&INDOOR_QUERY)).unwrap();
    assert_eq!(net.query_count(), 4 * 4 + 16);
    let m = infer(&net, Method::Auto, 1, 1);
    assert!(m.get("Room", &["U1"]).unwrap() > 0.6);
    assert!(m.get("Hall", &["U4"]).unwrap() > 0.8);
    assert_eq!(m.get("SaLe", &["U1", "U4"]), Some(0.0), "not adjacent");
    // Its evidence must list adjacency both ways: the hard symmetry rejects anything else.
    let e = Network::ground(&mln, &Database::parse("Adj(U1,U2)", &mln).unwrap(), &GroundConfig::query(&INDOOR_QUERY))
        .unwrap_err();
    assert!(matches!(e.kind, ErrorKind::Unsatisfiable { .. }));
    assert_eq!(e.source, Some(Source::KnowledgeBase));
    assert_eq!(
        e.position.unwrap().line,
        INDOOR.lines().position(|l| l.starts_with("Adj(p, q) => Adj(q, p).")).unwrap() as u32 + 1
    );
    assert!(
        e.to_string().contains("the evidence violates the hard formula `Adj(p, q) => Adj(q, p)` with p = U1, q = U2"),
        "{e}"
    );
}

// ---------------------------------------------------------------- hard formulas

const HARD: &str = "A(t)\nB(t)\n1 A(x)\nA(x) => B(x).\n";

#[test]
fn hard_formulas_give_violating_worlds_probability_zero() {
    // Worlds of (A, B): 00 -> 1, 01 -> 1, 11 -> e, and 10 is impossible.
    let e = 1f64.exp();
    let (pa, pb) = (e / (2.0 + e), (1.0 + e) / (2.0 + e));
    for simplify in [false, true] {
        let cfg = GroundConfig {
            simplify,
            domains: vec![("t".into(), vec!["X".into()])],
            ..GroundConfig::query(&["A", "B"])
        };
        let net = ground(HARD, "", &cfg);
        assert_eq!(net.hard_feature_count(), 1);
        assert_eq!(net.log_weight(&[true, false]), f64::NEG_INFINITY);
        assert_eq!(net.log_weight(&[true, true]), 1.0);
        for method in [Method::Exact, Method::Enumerate] {
            let m = infer(&net, method, 1, 1);
            assert!((m.get("A", &["X"]).unwrap() - pa).abs() < 1e-12, "{method:?}");
            assert!((m.get("B", &["X"]).unwrap() - pb).abs() < 1e-12, "{method:?}");
        }
        for method in [Method::McSat, Method::Gibbs] {
            let m = infer(&net, method, 5_000, 3);
            assert!((m.get("A", &["X"]).unwrap() - pa).abs() < 0.02, "{method:?}");
            assert!((m.get("B", &["X"]).unwrap() - pb).abs() < 0.02, "{method:?}");
        }
    }
    // Exactly one of A, B (hard), with soft weights pulling both ways: the samplers' estimates
    // of the two must add up to one exactly, as no sampled world breaks the constraint.
    let kb = "A(t)\nB(t)\nA(x) <=> !B(x).\n2 A(x)\n1.5 B(x)\n";
    let cfg =
        GroundConfig { domains: vec![("t".into(), vec!["X".into(), "Y".into()])], ..GroundConfig::query(&["A", "B"]) };
    let net = ground(kb, "", &cfg);
    let exact = 1.0 / (1.0 + (-0.5f64).exp());
    for method in [Method::McSat, Method::Gibbs] {
        let m = infer(&net, method, 2_000, 5);
        let (a, b) = (m.get("A", &["X"]).unwrap(), m.get("B", &["X"]).unwrap());
        assert!((a + b - 1.0).abs() < 1e-9, "{method:?}: {a} + {b}");
        assert!((a - exact).abs() < 0.02, "{method:?}: {a} vs {exact}");
    }
}

#[test]
fn contradictory_hard_formulas_are_reported() {
    let kb = "A(t)\nB(t)\nA(x).\nA(x) => B(x).\nB(x) => !A(x).\n";
    let mln = Mln::parse(kb).unwrap();
    let db = Database::parse("A(X)", &mln).unwrap();
    let e = Network::ground(&mln, &db, &GroundConfig::query(&["B"])).unwrap_err();
    assert!(matches!(e.kind, ErrorKind::Unsatisfiable { .. }), "{e}");
    // Without propagation, the contradiction surfaces at inference instead.
    let cfg = GroundConfig { simplify: false, ..GroundConfig::query(&["B"]) };
    let net = Network::ground(&mln, &db, &cfg).unwrap();
    for method in [Method::Exact, Method::Enumerate, Method::McSat, Method::Gibbs] {
        let c = InferenceConfig { method, walksat_flips: 1_000, ..Default::default() };
        let e = net.infer_marginals(&c).unwrap_err();
        assert!(
            matches!(e.kind, ErrorKind::Unsatisfiable { .. } | ErrorKind::NoSatisfyingWorld { .. }),
            "{method:?}: {e}"
        );
    }
}

// ---------------------------------------------------------------- MAP

#[test]
fn maxwalksat_finds_the_exact_map() {
    let mut cases = vec![
        ("smokers", ground(SMOKERS, SMOKERS_DB, &GroundConfig::query(&["Smokes", "Cancer"]))),
        (
            "hard",
            ground(
                HARD,
                "",
                &GroundConfig {
                    simplify: false,
                    domains: vec![("t".into(), vec!["X".into(), "Y".into()])],
                    ..GroundConfig::query(&["A", "B"])
                },
            ),
        ),
        ("indoor", ground(INDOOR, WORLDS[0], &config(&INDOOR_QUERY, &INDOOR_EVIDENCE))),
    ];
    for s in SCENES {
        cases.push(("scene", ground(TABLETOP, s, &config(&TABLETOP_QUERY, &TABLETOP_EVIDENCE))));
    }
    for (label, net) in &cases {
        let exact = net.map(&MapConfig { method: MapMethod::Exact, ..Default::default() }).unwrap();
        let found = net.map(&MapConfig::default()).unwrap();
        assert!(found.log_weight().is_finite(), "{label}: MaxWalkSAT must satisfy the hard formulas");
        assert!(
            (found.log_weight() - exact.log_weight()).abs() < 1e-9,
            "{label}: MaxWalkSAT {} vs exact {}",
            found.log_weight(),
            exact.log_weight()
        );
        // The exact MAP world really is the best: no single flip improves it.
        let mut state = exact.state().to_vec();
        for a in 0..state.len() {
            state[a] = !state[a];
            assert!(net.log_weight(&state) <= exact.log_weight() + 1e-9, "{label}");
            state[a] = !state[a];
        }
    }
    // Reported for the query atoms, sorted.
    let net = ground(TABLETOP, SCENES[1], &config(&TABLETOP_QUERY, &TABLETOP_EVIDENCE));
    let map = net.map(&MapConfig::default()).unwrap();
    let names: Vec<String> = map.iter().map(|(a, _)| a.to_string()).collect();
    let mut sorted = names.clone();
    sorted.sort();
    assert_eq!(names, sorted);
    assert_eq!(names.len(), 4 * 4);
    assert!(map.iter().any(|(a, v)| a.to_string() == "false(C)" && v), "C intersects A and is unstable");
}

// ---------------------------------------------------------------- soft evidence

#[test]
fn soft_evidence_is_a_log_odds_unit_clause() {
    let kb = "P(t)\nQ(t)\n";
    let net = ground(kb, "0.8 P(A)\n0.3 !Q(A)\n", &GroundConfig::query(&["P", "Q"]));
    let m = infer(&net, Method::Exact, 1, 1);
    assert!((m.get("P", &["A"]).unwrap() - 0.8).abs() < 1e-12);
    assert!((m.get("Q", &["A"]).unwrap() - 0.7).abs() < 1e-12);
    // With a formula, the prior odds are updated: 0.8 and P => Q (weight log 4) give
    // P(P) = 0.8 * 4 / (0.8 * 4 + 0.2 * 1 + ...) by enumeration of (P, Q):
    // 11: 4 * 4 = 16, 10: 4 * 1, 01: 1 * 4, 00: 1 * 4 (P's odds 4, the rule 4 when true).
    let net = ground("P(t)\nQ(t)\nlog(4) P(x) => Q(x)\n", "0.8 P(A)\n", &GroundConfig::query(&["P", "Q"]));
    for method in [Method::Exact, Method::Enumerate] {
        let m = infer(&net, method, 1, 1);
        assert!((m.get("P", &["A"]).unwrap() - 20.0 / 28.0).abs() < 1e-12, "{method:?}");
        assert!((m.get("Q", &["A"]).unwrap() - 20.0 / 28.0).abs() < 1e-12, "{method:?}");
    }
}

// ---------------------------------------------------------------- determinism

#[test]
fn equal_seeds_give_equal_results() {
    let net = ground(TABLETOP, SCENES[2], &config(&TABLETOP_QUERY, &TABLETOP_EVIDENCE));
    let slice = SliceMoves::SampleSat { steps: 0, temperature: 0.5, walksat_probability: 0.5 };
    for (method, slice) in
        [(Method::McSat, SliceMoves::Uniform), (Method::McSat, slice), (Method::Gibbs, SliceMoves::Uniform)]
    {
        let c = |seed| InferenceConfig { method, samples: 300, seed, slice, ..Default::default() };
        let a: Vec<f64> = net.infer_marginals(&c(11)).unwrap().iter().map(|x| x.1).collect();
        let b: Vec<f64> = net.infer_marginals(&c(11)).unwrap().iter().map(|x| x.1).collect();
        let d: Vec<f64> = net.infer_marginals(&c(12)).unwrap().iter().map(|x| x.1).collect();
        assert_eq!(a, b, "{method:?}");
        assert_ne!(a, d, "{method:?}: the seed matters");
    }
    let m = |seed| net.map(&MapConfig { seed, ..Default::default() }).unwrap().state().to_vec();
    assert_eq!(m(3), m(3));
}

#[test]
fn poon_domingos_samplesat_runs_and_is_roughly_right() {
    // Poon and Domingos' SampleSAT is not exactly uniform on the slice; on the smokers
    // network its bias is small.
    let net = ground(SMOKERS, SMOKERS_DB, &GroundConfig::query(&["Smokes", "Cancer"]));
    let exact = infer(&net, Method::Exact, 1, 1);
    let slice = SliceMoves::SampleSat { steps: 0, temperature: 0.5, walksat_probability: 0.5 };
    let m = net
        .infer_marginals(&InferenceConfig { method: Method::McSat, samples: 3_000, slice, ..Default::default() })
        .unwrap();
    let (d, at) = max_diff(&m, &exact);
    assert!(d < 0.05, "{d} at {at}");
}

// ---------------------------------------------------------------- errors

fn kb_error(text: &str) -> String {
    Mln::parse(text).unwrap_err().to_string()
}

#[test]
fn parse_errors_say_where_and_what() {
    let decl = "RoLi(unit)\nAdj(unit,unit)\n";
    let cases = [
        (format!("{decl}1.0 RoLi(x) ^ Adj(x, y ^ RoLi(y)"), "line 3, column 24: expected ')' after the arguments of Adj, found '^'"),
        (format!("{decl}// fine\n\n1 (RoLi(x) v RoLi(y)"), "line 5, column 21: expected a connective or ')' to close the '(' at line 5, column 3, found end of input"),
        (format!("{decl}1 RoLi(x))"), "line 3, column 10: expected a connective (^ v => <=>), '.' or the end of the line, found ')'"),
        (format!("{decl}2 Room(x) => RoLi(x)"), "line 3, column 3: Room is not a declared predicate (declare it first, e.g. `Room(type)`)"),
        (format!("{decl}2 Adj(x) => RoLi(x)"), "line 3, column 3: Adj takes 2 arguments, found 1"),
        (format!("{decl}1,5 RoLi(x)"), "line 3, column 2: expected an arithmetic operator (+ - * /) or a formula after the weight, found ','"),
        (format!("{decl}log(0.9/0) RoLi(x)"), "line 3, column 8: bad weight: division by zero"),
        (format!("{decl}log(0.9/0.1 RoLi(x)"), "line 3, column 13: expected an arithmetic operator (+ - * /) or ')' in the weight, found 'RoLi'"),
        (format!("{decl}RoLi(x) ^ RoLi(y)"), "line 3, column 1: expected a weight before the formula or a '.' after it (a hard formula), found a formula with neither"),
        (format!("{decl}0.5 RoLi(x)."), "line 3, column 12: expected no '.' after a weighted formula (a hard formula ends in '.' and has no weight), found '.'"),
        (format!("{decl}1 EXIST Y RoLi(Y)"), "line 3, column 9: expected a variable (lower case) after the quantifier, found 'Y'"),
        (format!("{decl}1 RoLi(x) ^ Adj(x, x) ^ x = "), "line 3, column 29: expected a variable or constant after the equality sign, found end of input"),
        (format!("{decl}Size(unit, real)\n1 Size(x, y) ^ RoLi(y)"), "line 4, column 21: y is used both as a real and as a unit"),
        ("unit = {A, b}".to_string(), "line 1, column 12: expected a constant (starting with a capital letter or a digit), found 'b'"),
        ("unit = {A}\nunit = {B}".to_string(), "line 2, column 1: the domain of type unit is already declared at line 1, column 1"),
        ("unit = {A}\nR(unit)\n1 R(B)".to_string(), "line 3, column 5: constant B is not in the declared domain of type unit"),
        ("R(unit) & S(unit)".to_string(), "line 1, column 9: expected a name, a number, a connective (! ^ v => <=>) or a parenthesis, found '&'"),
    ];
    for (text, expected) in &cases {
        assert_eq!(&kb_error(text), expected, "for {text:?}");
        assert_eq!(Mln::parse(text).unwrap_err().source, Some(Source::KnowledgeBase));
    }
}

#[test]
fn evidence_errors_say_where_and_what() {
    let mln = Mln::parse("unit = {U1, U2}\nRoLi(unit)\nAdj(unit,unit)\nname(thing)\n").unwrap();
    let db_error = |text: &str| Database::parse(text, &mln).unwrap_err();
    let cases = [
        ("RoLi(U1)\n\n!RoLi(U1)", "line 3, column 2: contradictory evidence for RoLi(U1) (see line 1, column 1)"),
        ("0.3 RoLi(U1)\n0.4 RoLi(U1)", "line 2, column 5: contradictory evidence for RoLi(U1) (see line 1, column 5)"),
        ("Adj(U1, u2)", "line 1, column 9: evidence must be ground, but u2 is a variable (constants start with a capital letter or a digit)"),
        ("Adj(U1)", "line 1, column 1: Adj takes 2 arguments, found 1"),
        ("Room(U1)", "line 1, column 1: Room is not a declared predicate (declare it first, e.g. `Room(type)`)"),
        ("RoLi(U1) RoLi(U2)", "line 1, column 10: expected the end of the line after the atom (one atom per line), found 'RoLi'"),
        ("1.2 RoLi(U1)", "line 1, column 1: soft evidence must be a probability strictly between 0 and 1, found 1.2"),
        ("RoLi U1", "line 1, column 6: expected '(' and the arguments of RoLi, found 'U1'"),
        ("RoLi((U1)", "line 1, column 6: expected a variable or constant as argument of RoLi, found '('"),
    ];
    for (text, expected) in cases {
        let e = db_error(text);
        assert_eq!(e.to_string(), expected, "for {text:?}");
        assert_eq!(e.source, Some(Source::Evidence));
    }
    // A constant outside a declared domain is caught when the evidence meets the domains.
    let db = Database::parse("RoLi(U1)\nAdj(U1,U3)\n", &mln).unwrap();
    let e = Network::ground(&mln, &db, &GroundConfig::default()).unwrap_err();
    assert_eq!(e.to_string(), "line 2, column 1: constant U3 is not in the declared domain of type unit");
    assert_eq!(e.source, Some(Source::Evidence));
    // An open type grows with the evidence instead.
    let db = Database::parse("name(Cup)\n", &mln).unwrap();
    assert!(Network::ground(&mln, &db, &GroundConfig::default()).is_ok());
    // A domain given by the caller closes the type too.
    let cfg = GroundConfig { domains: vec![("thing".into(), vec!["Plate".into()])], ..Default::default() };
    let e = Network::ground(&mln, &db, &cfg).unwrap_err();
    assert!(matches!(e.kind, ErrorKind::UnknownConstant { .. }), "{e}");
    // Configuration mistakes.
    for cfg in [
        GroundConfig::query(&["Room"]),
        GroundConfig { domains: vec![("place".into(), vec!["X".into()])], ..Default::default() },
        GroundConfig { closed_world: vec!["RoLi".into()], ..GroundConfig::query(&["RoLi"]) },
    ] {
        assert!(Network::ground(&mln, &Database::new(), &cfg).is_err());
    }
}

#[test]
fn size_limits_are_errors_not_exhaustion() {
    let mln = Mln::parse("P(t)\nR(t,t)\n1 P(x) ^ R(x,y) => P(y)\n").unwrap();
    let many: Vec<String> = (0..200).map(|i| format!("C{i}")).collect();
    let base = GroundConfig { domains: vec![("t".into(), many)], ..GroundConfig::query(&["P", "R"]) };
    let limit = |what: &str, e: ksmcmc::mln::MlnError| match e.kind {
        ErrorKind::TooLarge { what: w, .. } => assert_eq!(w, what),
        k => panic!("expected a size error, got {k:?}"),
    };
    limit(
        "ground atoms",
        Network::ground(&mln, &Database::new(), &GroundConfig { max_atoms: 10_000, ..base.clone() }).unwrap_err(),
    );
    limit(
        "ground clauses",
        Network::ground(&mln, &Database::new(), &GroundConfig { max_clauses: 5_000, ..base.clone() }).unwrap_err(),
    );
    limit(
        "groundings",
        Network::ground(&mln, &Database::new(), &GroundConfig { max_groundings: 1_000, ..base.clone() }).unwrap_err(),
    );
    assert!(Network::ground(&mln, &Database::new(), &GroundConfig { max_atoms: 40_200, ..base.clone() }).is_ok());
    // Exact inference refuses what it cannot enumerate: one feature over 30 atoms.
    let mln = Mln::parse("P(t)\n1 EXIST x P(x)\n").unwrap();
    let consts: Vec<String> = (0..30).map(|i| format!("C{i}")).collect();
    let cfg = GroundConfig { domains: vec![("t".into(), consts)], ..GroundConfig::query(&["P"]) };
    let net = Network::ground(&mln, &Database::new(), &cfg).unwrap();
    for method in [Method::Exact, Method::Enumerate] {
        let e = net.infer_marginals(&InferenceConfig { method, ..Default::default() }).unwrap_err();
        assert!(matches!(e.kind, ErrorKind::TooManyUnknownAtoms { atoms: 30, limit: 24 }), "{method:?}: {e}");
    }
    // Auto falls back to MC-SAT: P(x) is true unless all 30 are false.
    let m = infer(&net, Method::Auto, 2_000, 1);
    assert!((m.get("P", &["C0"]).unwrap() - 0.5).abs() < 0.03);
}

// ---------------------------------------------------------------- hostile input

#[test]
fn hostile_input_gives_errors_not_panics() {
    let deep = [
        format!("A(t)\n1 {}A(x){}", "(".repeat(100_000), ")".repeat(100_000)),
        format!("A(t)\n1 {}A(x)", "!".repeat(100_000)),
        format!("A(t)\n1 {}A(x)", "A(x) => ".repeat(100_000)),
        format!("A(t)\n{}1{} A(x)", "(".repeat(100_000), ")".repeat(100_000)),
        format!("A(t)\n{}1 A(x)", "-".repeat(100_000)),
        format!("A(t)\n1 {}A(x)", "EXIST y ".repeat(100_000)),
    ];
    for text in &deep {
        let e = Mln::parse(text).unwrap_err();
        assert!(e.to_string().contains("less nesting"), "{e}");
    }
    assert!(Mln::parse("A(t)\n1 /* never closed").is_err());
    assert!(Mln::parse("A(t)\n1e999 A(x)").is_err(), "infinite weight");
    assert!(Mln::parse("A(t)\nexp(1000) A(x)").is_err(), "infinite weight");

    // Random statements from a vocabulary of fragments: whatever parses must ground and infer
    // (or fail with an error) without panicking.
    let kb_bits = [
        "P(t)",
        "Q(t,t)",
        "R(t)",
        "t = {A, B}",
        "1",
        "-2",
        "log(0.9/0.1)",
        "0",
        "P(x)",
        "Q(x,y)",
        "R(y)",
        "!",
        "^",
        " v ",
        "=>",
        "<=>",
        "(",
        ")",
        ".",
        "EXIST z",
        "FORALL z",
        "Q(z,x)",
        "x = y",
        "x != A",
        "P(A)",
        "//",
        "\n",
        "\n",
        ",",
    ];
    let db_bits =
        ["P(A)", "!P(B)", "0.7 R(A)", "Q(A,B)", "Q(B,A)", "!Q(A,A)", "P(C)", "\n", "\n", "\n", "R(x)", "0.2 !P(A)"];
    fn formula(rng: &mut ksmcmc::mcmc::Rng, depth: u32) -> String {
        const ATOMS: [&str; 9] = ["P(x)", "P(A)", "Q(x,y)", "Q(y,x)", "R(y)", "x = y", "x != A", "R(x)", "R(B)"];
        if depth == 0 || rng.below(3) == 0 {
            return ATOMS[rng.below(ATOMS.len() as u32) as usize].to_string();
        }
        let (a, b) = (formula(rng, depth - 1), formula(rng, depth - 1));
        match rng.below(7) {
            0 => format!("!{a}"),
            1 => format!("({a} ^ {b})"),
            2 => format!("({a} v {b})"),
            3 => format!("({a} => {b})"),
            4 => format!("({a} <=> {b})"),
            5 => format!("EXIST z (Q(z,x) ^ {a})"),
            _ => format!("FORALL z (Q(x,z) => {a} v {b})"),
        }
    }
    let mut rng = ksmcmc::mcmc::Rng::seed(2024);
    let mut parsed = 0;
    for round in 0..3_000 {
        let mut kb = String::from("P(t)\nQ(t,t)\nR(t)\n");
        if round % 4 == 0 {
            for _ in 0..rng.below(25) {
                kb.push_str(kb_bits[rng.below(kb_bits.len() as u32) as usize]);
                kb.push(' ');
            }
        } else {
            if rng.below(2) == 0 {
                kb.push_str("t = {A, B, C}\n");
            }
            for _ in 0..1 + rng.below(4) {
                let f = formula(&mut rng, 3);
                let line = match rng.below(4) {
                    0 => format!("{f}.\n"),
                    1 => format!("-1.5 {f}\n"),
                    2 => format!("log(0.9/0.1) {f}\n"),
                    _ => format!("0.7 {f}\n"),
                };
                kb.push_str(&line);
            }
        }
        let Ok(mln) = Mln::parse(&kb) else { continue };
        let mut db = String::new();
        for _ in 0..rng.below(8) {
            db.push_str(db_bits[rng.below(db_bits.len() as u32) as usize]);
            db.push('\n');
        }
        let Ok(db) = Database::parse(&db, &mln) else { continue };
        let cfg = GroundConfig { max_atoms: 64, max_clauses: 500, max_groundings: 5_000, ..GroundConfig::default() };
        let Ok(net) = Network::ground(&mln, &db, &cfg) else { continue };
        parsed += 1;
        let mut exact = Vec::new();
        for method in [Method::Auto, Method::Exact, Method::Enumerate, Method::McSat, Method::Gibbs] {
            let c = InferenceConfig { method, samples: 20, burn_in: 2, walksat_flips: 2_000, ..Default::default() };
            if let Ok(m) = net.infer_marginals(&c) {
                assert!(m.iter().all(|(_, p)| (0.0..=1.0).contains(&p)), "{kb}");
                if matches!(method, Method::Exact | Method::Enumerate) {
                    exact.push(m);
                }
            }
        }
        if let [tree, enumerated] = &exact[..] {
            let (d, at) = max_diff(tree, enumerated);
            assert!(d < 1e-9, "junction tree and enumeration differ by {d} at {at} for\n{kb}");
        }
        let _ = net.map(&MapConfig { max_flips: 200, ..Default::default() });
    }
    assert!(parsed > 100, "the vocabulary makes enough valid knowledge bases ({parsed})");
}
