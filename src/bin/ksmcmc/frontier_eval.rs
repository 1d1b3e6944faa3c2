//! `ksmcmc evaluate --only frontier`: placeholders on generated floors seen in part, scored
//! against what truly lies behind them, and the frontier rules' weights learned from other
//! such floors (`--learn FILE` writes them: `samples/knowledge/frontier-learned.mln`).
//!
//! A simulated robot ([`ksmcmc::explore`]) explores each generated floor; its map is taken when
//! it has seen 30, 55 and 80 % of the free space; the same floor is also generated with three
//! in ten rooms never entered (`synth --unexplored 0.3`: their walls seen from outside, a peek
//! through some doors). Each map is explained as `ksmcmc floorplan` does, and each placeholder
//! of the plan labelled by [`frontier_truth`]. The weights are learned on the
//! training seeds and scored on the test seeds, which they never saw.

use crate::args::{self, CliError};
use ksmcmc::explore::{ExploreConfig, Explorer};
use ksmcmc::floorplan::frontier::{
    evidence, frontier_truth, placeholders, unentered_doors, FrontierCase, FrontierRules, Stretch, FRONTIER_EVIDENCE,
    FRONTIER_QUERY, FRONTIER_RULES,
};
use ksmcmc::floorplan::run::{run, RunOptions};
use ksmcmc::floorplan::synth::{generate, SynthConfig, Synthetic};
use ksmcmc::floorplan::{ChainConfig, World};
use ksmcmc::grid::{Cell, OccupancyMap};
use ksmcmc::mln::{learn_weights, LearnConfig, LearnMethod};
use std::fmt::Write as _;
use std::path::Path;
use std::time::Instant;

/// Seeds of the floors the weights are learned on (none is a seed of another evaluation or of
/// a learning script).
/// Thirty-six, 4001 - 4036: on three, what the weights learned moved with the floors (a hall
/// floor's rooms led to new rooms in 12 % of its training placeholders and 46 % of its test
/// ones), and the combinations of evidence in `frontier.mln` need more cases than a few floors
/// of a kind give (held-out AUC 0.776 on 3, 0.849 on 18, 0.851 on 36 with the same rules).
const TRAIN_SEEDS: [u64; 36] = {
    let mut seeds = [0; 36];
    let mut i = 0;
    while i < seeds.len() {
        seeds[i] = 4001 + i as u64;
        i += 1;
    }
    seeds
};
/// Seeds of the floors the weights are scored on.
const TEST_SEEDS: [u64; 3] = [4101, 4102, 4103];
/// Shares of the free space seen at which the robot's map is taken.
const SEEN: [f64; 3] = [0.3, 0.55, 0.8];
/// Share of the rooms never entered on the floor of each kind generated with rooms unexplored.
const UNEXPLORED: f64 = 0.3;
/// A placeholder stands at an unentered room's door when it lies this close to it, m.
const AT_DOOR_M: f64 = 1.5;

/// The kinds of generated floor.
fn kinds() -> Vec<(&'static str, SynthConfig)> {
    let d = SynthConfig::default();
    vec![
        ("office", d.clone()),
        ("hall", SynthConfig { width: 600, halls: 1, ..d.clone() }),
        ("two corridors", SynthConfig { width: 500, height: 400, corridors: Some(2), ..d.clone() }),
        ("cluttered", SynthConfig { clutter: 0.1, ..d.clone() }),
        ("rotated 20 deg", SynthConfig { rotation_deg: 20.0, ..d.clone() }),
        ("many storage", SynthConfig { width: 500, others: 6, ..d }),
    ]
}

/// One partial map explained: its world, its cases, the unentered rooms' doors, and the time
/// of the run and of its placeholders.
struct Explained {
    kind: &'static str,
    /// The floor's seed.
    seed: u64,
    world: World,
    cases: Vec<FrontierCase>,
    doors: Vec<(f64, f64)>,
    resolution: f64,
    run_s: f64,
    placeholders_s: f64,
}

/// Explores floor `seed` of `kind` and explains the robot's map at each share of [`SEEN`].
fn explain(kind: &'static str, synth: &SynthConfig, seed: u64, o: &Options) -> Result<Vec<Explained>, CliError> {
    let s = generate(synth, seed).map_err(|e| args::failed(kind, e))?;
    let free = s.map.count(Cell::Free) as f64;
    let mut robot = Explorer::new(&s.map, ExploreConfig::default(), seed).map_err(|e| args::failed(kind, e))?;
    let mut out = Vec::new();
    for share in SEEN {
        while (robot.seen_count(Cell::Free) as f64) < share * free && robot.advance(100) {}
        out.push(explain_partial(kind, seed, &robot.snapshot(), &s, o)?);
    }
    // The same floor with rooms never entered, their walls seen from outside.
    let unexplored = SynthConfig { unexplored: UNEXPLORED, ..synth.clone() };
    let u = generate(&unexplored, seed).map_err(|e| args::failed(kind, e))?;
    out.push(explain_partial(kind, seed, &u.map, &u, o)?);
    Ok(out)
}

/// `partial`, a map of the generated floor `s` seen in part, explained and its placeholders
/// labelled.
fn explain_partial(
    kind: &'static str,
    seed: u64,
    partial: &OccupancyMap,
    s: &Synthetic,
    o: &Options,
) -> Result<Explained, CliError> {
    let options = RunOptions { seed: 1, iterations: o.iterations, config: o.config.clone(), ..Default::default() };
    let r = run(partial, &options).map_err(|e| args::failed(kind, e))?;
    let resolution = partial.yaml().resolution;
    let t = Instant::now();
    let again = placeholders(&r.world, partial.classified(), &r.labels, resolution, &FrontierRules::builtin())
        .map_err(|e| args::failed(kind, e))?;
    let placeholders_s = t.elapsed().as_secs_f64();
    assert_eq!(again, r.world.placeholders, "the run's placeholders are the layer's");
    let (map, truth) = (partial.classified(), s.map.classified());
    let cases = frontier_truth(&r.world, map, &r.labels, resolution, &s.truth, truth, &s.labels);
    let doors = unentered_doors(&s.truth, map, &s.labels, resolution);
    Ok(Explained { kind, seed, world: r.world, cases, doors, resolution, run_s: r.seconds, placeholders_s })
}

/// What `evaluate --only frontier` is given.
pub struct Options<'a> {
    /// Iterations per chain.
    pub iterations: u64,
    /// The chain's settings.
    pub config: ChainConfig,
    /// Where to write the learned rules, if anywhere.
    pub learn: Option<&'a Path>,
    /// Where to write every placeholder's measures and truth ([`cases_csv`]), if anywhere.
    pub cases: Option<&'a Path>,
}

/// The frontier set (module docs).
pub fn frontier(o: &Options) -> Result<(), CliError> {
    let mut train = Vec::new();
    let mut test = Vec::new();
    for (kind, synth) in kinds() {
        for seed in TRAIN_SEEDS {
            train.extend(explain(kind, &synth, seed, o)?);
        }
        for seed in TEST_SEEDS {
            test.extend(explain(kind, &synth, seed, o)?);
        }
    }
    if let Some(path) = o.cases {
        args::write(path, cases_csv(&train, &test).as_bytes())?;
    }
    let hand = FrontierRules::parse(FRONTIER_RULES).map_err(|e| args::failed("frontier.mln", e))?;
    let learned_text = learn(&hand, &train)?;
    let learned = FrontierRules::parse(&learned_text).map_err(|e| args::failed("the learned rules", e))?;
    if let Some(path) = o.learn {
        args::write(path, learned_text.as_bytes())?;
    }
    let base = base_rates(&train);
    evidence_table(&train);
    println!(
        "\n### Placeholders on generated floors seen in part ({} iterations; learned on seeds {:?}, scored on {:?}; maps at {:?} of the free space seen, and with {} of the rooms never entered)\n",
        o.iterations, TRAIN_SEEDS, TEST_SEEDS, SEEN, UNEXPLORED
    );
    println!("| rules | kind | placeholders (new rooms) | AUC | Brier (base rate) | type accuracy | log loss (class frequencies) | unentered doors covered |");
    println!("|---|---|---|---|---|---|---|---|");
    for (name, rules) in [("hand-set", &hand), ("built-in", &FrontierRules::builtin()), ("learned here", &learned)] {
        let mut names: Vec<&str> = kinds().iter().map(|k| k.0).collect();
        names.push("all kinds");
        for kind in names {
            let part: Vec<&Explained> = test.iter().filter(|e| kind == "all kinds" || e.kind == kind).collect();
            let s = score(rules, &part, &base)?;
            println!("| {name} | {kind} | {s} |");
        }
    }
    let run_s: f64 = test.iter().map(|e| e.run_s).sum();
    let ph_s: f64 = test.iter().map(|e| e.placeholders_s).sum();
    println!(
        "\nPlaceholders took {:.3} s of {:.1} s of runs on the test maps ({:.2} %).",
        ph_s,
        run_s,
        100.0 * ph_s / run_s.max(1e-9)
    );
    Ok(())
}

/// Per evidence predicate, on the training maps: how many placeholders have it, the share of
/// them that lead to a new room and to nothing, and the kinds beyond them.
fn evidence_table(train: &[Explained]) {
    println!(
        "\n| evidence (training maps) | placeholders | new room | nothing beyond | room / corridor / hall / other |"
    );
    println!("|---|---|---|---|---|");
    for pred in FRONTIER_EVIDENCE.iter().copied().chain(["(all)"]) {
        let (mut n, mut new, mut nothing, mut kinds) = (0usize, 0usize, 0usize, [0usize; 4]);
        for e in train {
            for c in &e.cases {
                if pred != "(all)" && !evidence(&e.world, &c.stretch).contains(&pred) {
                    continue;
                }
                n += 1;
                new += usize::from(c.beyond.is_new());
                match c.beyond.kind_index() {
                    Some(k) => kinds[k] += 1,
                    None => nothing += 1,
                }
            }
        }
        let share = |k: usize| k as f64 / n.max(1) as f64;
        let [a, b, c, d] = kinds.map(share);
        println!("| {pred} | {n} | {:.2} | {:.2} | {a:.2} / {b:.2} / {c:.2} / {d:.2} |", share(new), share(nothing));
    }
}

/// Every placeholder of the training and test maps as a line of CSV, for looking at the
/// evidence outside the project: which set, the floor's kind and seed, the stretch's measures
/// ([`Stretch`]; lengths in m, areas in m²), the room it opens from (area, type), whether a new
/// room lies behind and the kind of space behind (0 - 3: room, corridor, hall, other; -1:
/// nothing).
fn cases_csv(train: &[Explained], test: &[Explained]) -> String {
    let mut csv = String::from(
        "set,kind,seed,width_m,behind_m2,pocket,inside,at_door,jambs,planned,own,ways,room_m2,room_type,new,beyond\n",
    );
    for (set, maps) in [("train", train), ("test", test)] {
        for e in maps {
            for c in &e.cases {
                let s = &c.stretch;
                let room = e.world.rooms.iter().find(|r| r.id == s.room);
                let beyond = c.beyond.kind_index().map_or(-1, |k| k as i64);
                let _ = writeln!(
                    csv,
                    "{set},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{beyond}",
                    e.kind,
                    e.seed,
                    s.width_m,
                    s.behind_m2,
                    u8::from(s.pocket),
                    s.inside,
                    u8::from(s.at_door),
                    u8::from(s.jambs),
                    s.planned,
                    s.own,
                    s.ways,
                    room.map_or(0.0, |r| r.area_m2),
                    room.map_or("none", |r| r.kind.name()),
                    u8::from(c.beyond.is_new()),
                );
            }
        }
    }
    csv
}

/// Widths of the weights' Gaussian prior tried: each is learned on one half of the training
/// seeds and scored (AUC) on the other, both ways, and the best is learned on all of them.
const PRIOR_SIGMAS: [f64; 3] = [0.5, 1.0, 2.0];

/// The hand-set rules' weights learned from the training maps' cases, as rules text, with the
/// prior's width chosen by two-fold cross-validation over the training seeds
/// ([`PRIOR_SIGMAS`]; the folds printed).
fn learn(hand: &FrontierRules, train: &[Explained]) -> Result<String, CliError> {
    let half = TRAIN_SEEDS[TRAIN_SEEDS.len() / 2];
    let (a, b): (Vec<&Explained>, Vec<&Explained>) = train.iter().partition(|e| e.seed < half);
    println!("\n| prior sigma | AUC, learned on seeds below {half} and scored on the rest | the other way | mean |");
    println!("|---|---|---|---|");
    let mut best = (f64::NEG_INFINITY, PRIOR_SIGMAS[0]);
    for sigma in PRIOR_SIGMAS {
        let mut aucs = [0.0; 2];
        for (k, (fit, check)) in [(&a, &b), (&b, &a)].into_iter().enumerate() {
            let rules = FrontierRules::parse(&learn_with(hand, fit, sigma)?)
                .map_err(|e| args::failed("the learned rules", e))?;
            let (p, y) = p_new_room(&rules, check)?;
            aucs[k] = auc(&p, &y);
        }
        let mean = (aucs[0] + aucs[1]) / 2.0;
        println!("| {sigma} | {:.3} | {:.3} | {mean:.3} |", aucs[0], aucs[1]);
        if mean > best.0 {
            best = (mean, sigma);
        }
    }
    learn_with(hand, &train.iter().collect::<Vec<_>>(), best.1)
}

/// The hand-set rules' weights learned from `train`'s cases with a Gaussian prior of width
/// `sigma`, as rules text.
fn learn_with(hand: &FrontierRules, train: &[&Explained], sigma: f64) -> Result<String, CliError> {
    let mut dbs = Vec::new();
    for e in train.iter().filter(|e| !e.cases.is_empty()) {
        dbs.push(hand.training_database(&e.world, &e.cases).map_err(|e| args::failed("a training world", e))?);
    }
    let config = LearnConfig {
        method: LearnMethod::Discriminative,
        query: FRONTIER_QUERY.iter().map(|q| q.to_string()).collect(),
        prior_sigma: sigma,
        ..Default::default()
    };
    let learned = learn_weights(hand.mln(), &dbs, &config).map_err(|e| args::failed("learning", e))?;
    let cases: usize = train.iter().map(|e| e.cases.len()).sum();
    let header = format!(
        "The frontier rules (frontier.mln, where each rule is explained) with weights learned\n\
         discriminatively (Gaussian prior sigma {sigma}, the best of {PRIOR_SIGMAS:?} by two-fold\n\
         cross-validation over the training seeds) from {cases} placeholders of {} partial maps:\n\
         generated floors of six kinds, seeds {} - {}, explored by `ksmcmc::explore` to\n\
         {SEEN:?} of their free space, and the same floors with {UNEXPLORED} of their rooms never\n\
         entered, explained at seed 1. Written by\n\
         `ksmcmc evaluate --only frontier --learn samples/knowledge/frontier-learned.mln`;\n\
         the same binary writes the same bytes.",
        train.len(),
        TRAIN_SEEDS[0],
        TRAIN_SEEDS[TRAIN_SEEDS.len() - 1],
    );
    Ok(learned.to_mln(hand.mln(), &header))
}

/// `P(NewRoom)` of every placeholder of `maps` under `rules`, and whether a new room truly
/// lies behind it.
fn p_new_room(rules: &FrontierRules, maps: &[&Explained]) -> Result<(Vec<f64>, Vec<bool>), CliError> {
    let (mut p, mut y) = (Vec::new(), Vec::new());
    for e in maps {
        let (_, answers) = weigh(rules, e)?;
        for (c, (pn, _)) in e.cases.iter().zip(&answers) {
            p.push(*pn);
            y.push(c.beyond.is_new());
        }
    }
    Ok((p, y))
}

/// The training maps' share of placeholders into new rooms and frequency of each kind of
/// space beyond (room, corridor, hall, other), the baselines of the scores.
fn base_rates(train: &[Explained]) -> (f64, [f64; 4]) {
    let cases = train.iter().flat_map(|e| &e.cases);
    let (mut n, mut new, mut kinds) = (0usize, 0usize, [1usize; 4]);
    for c in cases {
        n += 1;
        new += usize::from(c.beyond.is_new());
        if let Some(k) = c.beyond.kind_index() {
            kinds[k] += 1;
        }
    }
    let total: usize = kinds.iter().sum();
    (new as f64 / n.max(1) as f64, kinds.map(|k| k as f64 / total as f64))
}

/// The stretches of `e`'s cases and what `rules` say of each ([`FrontierRules::weigh`]).
type Weighed = (Vec<Stretch>, Vec<(f64, [f64; 4])>);
fn weigh(rules: &FrontierRules, e: &Explained) -> Result<Weighed, CliError> {
    let stretches: Vec<Stretch> = e.cases.iter().map(|c| c.stretch.clone()).collect();
    let answers = rules.weigh(&e.world, &stretches).map_err(|err| args::failed(e.kind, err))?;
    Ok((stretches, answers))
}

/// One table row's figures for `rules` on `maps`.
fn score(rules: &FrontierRules, maps: &[&Explained], base: &(f64, [f64; 4])) -> Result<String, CliError> {
    let (mut p_new, mut is_new) = (Vec::new(), Vec::new());
    let (mut typed, mut right, mut loss, mut base_loss) = (0usize, 0usize, 0.0, 0.0);
    let (mut doors, mut covered, mut any) = (0usize, 0usize, 0usize);
    for e in maps {
        let (stretches, answers) = weigh(rules, e)?;
        for (c, (p, types)) in e.cases.iter().zip(&answers) {
            p_new.push(*p);
            is_new.push(c.beyond.is_new());
            if let Some(k) = c.beyond.kind_index() {
                typed += 1;
                let best = (0..4).max_by(|&a, &b| types[a].total_cmp(&types[b])).unwrap_or(0);
                right += usize::from(best == k);
                loss -= types[k].max(1e-6).ln();
                base_loss -= base.1[k].ln();
            }
        }
        let reach = AT_DOOR_M / e.resolution;
        for &(dx, dy) in &e.doors {
            doors += 1;
            let near = |s: &Stretch| {
                s.cells.iter().any(|&i| {
                    let w = e.world.frame.map_size[0] as usize;
                    libm::hypot((i % w) as f64 + 0.5 - dx, (i / w) as f64 + 0.5 - dy) <= reach
                })
            };
            covered += usize::from(stretches.iter().zip(&answers).any(|(s, (p, _))| *p >= 0.5 && near(s)));
            any += usize::from(stretches.iter().any(near));
        }
    }
    let brier: f64 = p_new.iter().zip(&is_new).map(|(p, &y)| (p - f64::from(u8::from(y))).powi(2)).sum::<f64>();
    let base_brier: f64 = is_new.iter().map(|&y| (base.0 - f64::from(u8::from(y))).powi(2)).sum::<f64>();
    let n = p_new.len().max(1) as f64;
    let t = typed.max(1) as f64;
    Ok(format!(
        "{} ({}) | {:.3} | {:.3} ({:.3}) | {:.3} ({typed}) | {:.3} ({:.3}) | {covered} of {doors} ({any} with one at any P)",
        p_new.len(),
        is_new.iter().filter(|&&y| y).count(),
        auc(&p_new, &is_new),
        brier / n,
        base_brier / n,
        right as f64 / t,
        loss / t,
        base_loss / t,
    ))
}

/// The area under the ROC curve of scores `p` for labels `y`: the chance that a random
/// positive scores above a random negative, ties counting half (NaN without both).
fn auc(p: &[f64], y: &[bool]) -> f64 {
    let pos: Vec<f64> = p.iter().zip(y).filter(|t| *t.1).map(|t| *t.0).collect();
    let neg: Vec<f64> = p.iter().zip(y).filter(|t| !*t.1).map(|t| *t.0).collect();
    if pos.is_empty() || neg.is_empty() {
        return f64::NAN;
    }
    let mut wins = 0.0;
    for a in &pos {
        for b in &neg {
            wins += if a > b {
                1.0
            } else if a == b {
                0.5
            } else {
                0.0
            };
        }
    }
    wins / (pos.len() * neg.len()) as f64
}

#[cfg(test)]
mod tests {
    use super::{auc, cases_csv, Explained};
    use ksmcmc::floorplan::frontier::{Beyond, FrontierCase, Stretch};
    use ksmcmc::floorplan::{Room, UnitType, World};

    #[test]
    fn cases_are_one_line_each_with_the_room_and_the_truth() {
        let mut world = World::empty(10, 10);
        let room = Room {
            id: 2,
            kind: UnitType::Hall,
            units: vec![],
            area_m2: 120.0,
            doors: vec![],
            opens_to: vec![],
            name: None,
        };
        world.rooms = vec![room];
        let stretch = Stretch {
            cells: vec![0],
            at: (0, 0),
            width_m: 1.25,
            behind_m2: 6.0,
            pocket: true,
            inside: 0.5,
            room: 2,
            at_door: false,
            jambs: true,
            planned: 0.0,
            own: 0.25,
            ways: 3,
        };
        let beyond = Beyond::Space { kind: UnitType::Room, new: true };
        let cases = vec![
            FrontierCase { stretch: stretch.clone(), beyond },
            FrontierCase { stretch: Stretch { room: 0, ..stretch }, beyond: Beyond::Nothing },
        ];
        let e = Explained {
            kind: "hall",
            seed: 4001,
            world,
            cases,
            doors: vec![],
            resolution: 0.05,
            run_s: 1.0,
            placeholders_s: 0.1,
        };
        let csv = cases_csv(&[e], &[]);
        let lines: Vec<&str> = csv.lines().collect();
        assert_eq!(lines.len(), 3, "{csv}");
        assert_eq!(lines[0].split(',').count(), lines[1].split(',').count());
        assert_eq!(lines[1], "train,hall,4001,1.25,6,1,0.5,0,1,0,0.25,3,120,hall,1,0");
        assert_eq!(lines[2], "train,hall,4001,1.25,6,1,0.5,0,1,0,0.25,3,0,none,0,-1");
    }

    #[test]
    fn auc_counts_ordered_pairs_and_half_ties() {
        assert_eq!(auc(&[0.9, 0.8, 0.1], &[true, false, false]), 1.0);
        assert_eq!(auc(&[0.1, 0.9], &[true, false]), 0.0);
        assert_eq!(auc(&[0.5, 0.5, 0.7, 0.2], &[true, false, true, false]), 0.875);
        assert!(auc(&[0.5], &[true]).is_nan());
    }
}
